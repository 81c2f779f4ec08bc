"""Every bundled study (studies/*.yaml) runs and writes a file with the public layout: the
shared ../shared/tools/check_layout.py passes on each (named swing_omega × impact_z dims, the
/history group, units), and xarray opens every group.

Guards the bundled studies against drifting from the layout the checker defines (several
studies once wrote no /history and no swing_omega dim). Needs BATSTUDY_BIN (set by
scripts/test.sh); skipped without it."""
import os
import subprocess
import sys
from pathlib import Path

import pytest

xr = pytest.importorskip("xarray")

ROOT = Path(__file__).resolve().parents[2]
CHECK = Path(os.environ.get("BATSTUDY_CHECK_LAYOUT", ROOT.parent / "shared/tools/check_layout.py"))
BIN = os.environ.get("BATSTUDY_BIN")
STUDIES = sorted((ROOT / "studies").glob("*.yaml"))
pytestmark = pytest.mark.skipif(not BIN, reason="BATSTUDY_BIN not set (scripts/test.sh sets it)")


@pytest.mark.parametrize("study", STUDIES, ids=[s.stem for s in STUDIES])
def test_bundled_study_has_the_public_layout(study, tmp_path):
    out = tmp_path / f"{study.stem}.h5"
    r = subprocess.run([BIN, "run", str(study), "-o", str(out), "--jobs", "2", "--quiet"],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    for group in ["summary", "sweet_spot", "history", "bat", "errors"]:
        xr.open_dataset(out, engine="h5netcdf", group=group).close()
    if not CHECK.exists():
        pytest.skip(f"{CHECK} not found")
    r = subprocess.run([sys.executable, str(CHECK), str(out)], capture_output=True, text=True)
    assert r.returncode == 0 and "layout ok" in r.stdout, r.stdout + r.stderr
