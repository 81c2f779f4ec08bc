"""The progress bar's rate is the points this call computed over its time: a resumed run's
points already done are where the bar starts, not work done in the first instant (which
showed rates of millions of points per second on short or resumed runs)."""

import re
import time

import pytest

pytest.importorskip("tqdm")


def test_a_resumed_runs_rate_counts_only_its_own_points(capsys):
    from batstudy._api import _progress_bar

    update = _progress_bar(True, unit="points")
    update(900, 1000)  # resumed: 900 done before
    time.sleep(0.2)
    update(1000, 1000)
    update.close()
    err = capsys.readouterr().err
    rates = [float(x) for x in re.findall(r"([0-9.]+)points/s", err)]
    assert rates, err
    # 100 points in about 0.2 s: some 500 points/s, not 1000 points / 0.2 s = 5000
    assert rates[-1] < 1500, err
