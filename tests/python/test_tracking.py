"""batstudy.tracking: public bat-tracking rows read into SI, and two populations compared.

References independent of the code:
- a pitch's constant-acceleration track (Statcast's nine-parameter fit): with no
  acceleration along y it reaches the plate at t = Δy / v_y exactly, and in general the
  track's y(t) at the time found is the front of the plate;
- the sign of Savant's attack direction, which Savant does not state, against the file's own
  spray coordinates of its balls in play (hc_x, hc_y): after mirroring for the batter's side,
  the direction and the spray must go together;
- the distances' definitions: a sample against itself is at distance 0, and against itself
  shifted by d at Wasserstein distance d.
"""
import math
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from batstudy import tracking

ROOT = Path(__file__).resolve().parents[2]
DATA = ROOT / "data" / "bat_tracking_2025.csv"


def test_a_pitch_reaches_the_front_of_the_plate_on_its_track():
    # no acceleration along y: t = (17/12 − 50) / v_y exactly
    v0, a = (5.0, -130.0, -4.0), (-10.0, 0.0, -25.0)
    t = (17 / 12 - 50) / v0[1]
    vx, vy, vz = tracking.pitch_at_plate(v0, a)
    assert (vx, vy, vz) == pytest.approx((v0[0] + a[0] * t, v0[1], v0[2] + a[2] * t), rel=1e-12)
    # a drag-like deceleration: the track's y at the time found is the plate's front
    v0, a = (7.7, -136.1, -2.3), (-20.2, 31.3, -30.7)
    vy = tracking.pitch_at_plate(v0, a)[1]
    t = (vy - v0[1]) / a[1]
    assert 50 + v0[1] * t + 0.5 * a[1] * t * t == pytest.approx(17 / 12, abs=1e-9)


def test_the_file_reads_into_si_with_savants_attack_direction_sign_checked_on_its_spray():
    ds = tracking.read(DATA)
    assert ds.sizes["swing"] == 300
    assert ds.bat_speed.attrs["units"] == "m/s" and ds.descent_angle.attrs["units"] == "rad"
    # every pitch falls at the plate, by 2–14 degrees (the tracked range)
    assert np.all((ds.descent_angle > 2 * math.pi / 180) & (ds.descent_angle < 14 * math.pi / 180))
    # the spray of the balls in play, from Savant's spray-chart pixels (home plate at
    # (125.42, 198.27)), positive toward first base; mirrored like the direction
    import csv
    rows = [r for r in csv.DictReader(open(DATA)) if r["type"] == "X" and r["hc_x"]]
    spray = np.array([math.atan2(float(r["hc_x"]) - 125.42, 198.27 - float(r["hc_y"])) for r in rows])
    mirror = np.array([1.0 if r["stand"] == "R" else -1.0 for r in rows])
    direction = np.array([float(r["attack_direction"]) for r in rows]) * math.pi / 180
    r = np.corrcoef(direction, mirror * spray)[0, 1]
    assert r > 0.3, r
    # read() gives Savant's value unchanged (toward first base for a right-handed batter)
    assert np.allclose(ds.attack_direction.values[:3] * 180 / math.pi,
                       [float(r["attack_direction"]) for r in list(csv.DictReader(open(DATA)))[:3]])


def test_a_population_against_itself_and_shifted():
    ds = tracking.read(DATA)
    sim = xr.Dataset({"exit_speed_lab": ds.exit_speed, "launch_angle": ds.launch_angle,
                      "bat_speed_6in": ds.bat_speed, "collision_efficiency_q": ds.collision_efficiency_q})
    c = tracking.compare(sim, ds)
    assert np.allclose(c.ks.values[:4], 0) and np.allclose(c.wasserstein.values[:4], 0)
    shifted = sim.assign(exit_speed_lab=sim.exit_speed_lab + 1.0)
    c = tracking.compare(shifted, ds)
    assert float(c.wasserstein.sel(quantity="exit_speed")) == pytest.approx(1.0, rel=1e-9)
    assert float(c["mean"].sel(quantity="exit_speed_per_bat_speed", population="simulated")) == pytest.approx(
        float(c["mean"].sel(quantity="exit_speed_per_bat_speed", population="measured")))


def test_a_file_without_savants_columns_is_refused_by_name(tmp_path):
    bad = tmp_path / "bad.csv"
    bad.write_text("bat_speed,launch_speed\n70,90\n")
    with pytest.raises(ValueError, match=r"bad.csv: not a bat-tracking CSV: it lacks the column\(s\) release_speed"):
        tracking.read(bad)
    bad.write_text(DATA.read_text().replace(",L,R,", ",X,R,", 1))
    with pytest.raises(ValueError, match=r"bad.csv:\d+: stand 'X': allowed R or L"):
        tracking.read(bad)


def _with_column(text, column, edit):
    """The CSV text with ``edit(value)`` applied to ``column`` of every row."""
    import csv
    import io

    rows = list(csv.DictReader(io.StringIO(text)))
    out = io.StringIO()
    w = csv.DictWriter(out, fieldnames=list(rows[0]), lineterminator="\n")
    w.writeheader()
    for r in rows:
        r[column] = edit(r[column])
        w.writerow(r)
    return out.getvalue()


def test_a_device_or_a_huge_file_is_refused_before_it_is_read(tmp_path, monkeypatch):
    # /dev/zero has no end and no newline: a reader without a bound grows until killed
    with pytest.raises(ValueError, match="not a regular file"):
        tracking.read("/dev/zero")
    monkeypatch.setattr(tracking, "MAX_BYTES", 100)
    with pytest.raises(ValueError, match="more than a season"):
        tracking.read(DATA)


def test_rows_that_are_not_pitches_raise_value_error_with_their_line(tmp_path):
    bad = tmp_path / "bad.csv"
    text = DATA.read_text()
    # a pitch that never reaches the plate (vy0 = 0, ay = 0 divided by zero before)
    bad.write_text(_with_column(_with_column(text, "vy0", lambda v: "0"), "ay", lambda v: "0"))
    with pytest.raises(ValueError, match=r"bad.csv:2: vy0 0.0"):
        tracking.read(bad)
    # a short row: DictReader gives None for its missing columns (a TypeError before)
    header, first = text.splitlines()[:2]
    names, values = header.split(","), first.split(",")
    keep = max(names.index("bat_speed"), names.index("stand")) + 1
    short = [v if n in ("bat_speed", "stand") else "" for n, v in zip(names, values)][:keep]
    bad.write_text(header + "\n" + ",".join(short) + "\n")
    with pytest.raises(ValueError, match=r"bad.csv:2: "):
        tracking.read(bad)


def test_bat_speeds_in_metres_per_second_are_refused():
    # Savant's column is mph; the same swings in m/s are 0.447 of it, a median near 32
    ds = tracking.read(DATA)
    assert 60 < float(np.median(ds.bat_speed)) / tracking.MPH < 80
    import tempfile

    with tempfile.TemporaryDirectory() as d:
        bad = Path(d) / "ms.csv"
        bad.write_text(_with_column(DATA.read_text(), "bat_speed",
                                    lambda v: f"{float(v) * tracking.MPH:.2f}" if v else v))
        with pytest.raises(ValueError, match="median bat_speed is 3[0-9].[0-9], where tracked"):
            tracking.read(bad)


def test_a_dataframe_reads_as_its_csv():
    pd = pytest.importorskip("pandas")
    frame = pd.read_csv(DATA, dtype={"stand": str, "type": str})
    a, b = tracking.read(DATA), tracking.read(frame)
    assert a.sizes == b.sizes
    np.testing.assert_allclose(a.exit_speed.values, b.exit_speed.values, equal_nan=True)
    assert b.attrs["source"] == "DataFrame"


def test_the_figure_draws_both_populations():
    import matplotlib
    matplotlib.use("Agg")
    from batstudy import plot
    ds = tracking.read(DATA)
    sim = xr.Dataset({"exit_speed_lab": ds.exit_speed + 0.5, "launch_angle": ds.launch_angle,
                      "bat_speed_6in": ds.bat_speed, "collision_efficiency_q": ds.collision_efficiency_q})
    ax = plot.tracking(sim, DATA)
    assert len(ax) == 3 and len(ax[2].collections) == 2
    assert ax[0].get_title().startswith("KS ")
