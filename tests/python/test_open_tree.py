"""`batstudy.open_results` shows the whole file: `/uncertainty` of a sampled study, and
`/optimize` of a design search in tidy form, whose best design is the one the search reports
and whose BBCOR constraint is the BBCOR `/bat` stores for that design (one protocol, one
ball: docs/layout.md, `/bat`). Needs BATSTUDY_BIN."""
import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "python"))
BIN = os.environ.get("BATSTUDY_BIN")
pytestmark = pytest.mark.skipif(not BIN, reason="BATSTUDY_BIN not set (scripts/test.sh sets it)")

SEARCH = """name: tree_search
model: wave
base:
  bat: {preset: aluminum}
  ball: {preset: mlb, speed: 40.0}
  hoop: {from_geometry: true}
grid:
  impact.z: [0.66, 0.70]
optimize:
  max_evaluations: 6
  variables:
    bat.shell.thickness: {min: 0.0025, max: 0.0040, start: 0.0030}
  objective: {maximize: sweet_spot.exit_speed}
  constraints:
    - {quantity: bat.bbcor, max: 0.70}
"""

SAMPLED = """name: tree_sample
model: rigid
base: {impact: {z: 0.7}, ball: {preset: mlb}}
sample:
  n: 8
  ball_spread: ball
"""


def run(tmp_path, text, command):
    study, out = tmp_path / "s.yaml", tmp_path / "s.h5"
    study.write_text(text)
    r = subprocess.run([BIN, command, str(study), "-o", str(out), "--quiet"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    return out


def test_a_search_is_in_the_tree_in_tidy_form(tmp_path):
    import batstudy
    import h5py

    out = run(tmp_path, SEARCH, "optimize")
    tree = batstudy.open_results(out)
    opt = tree["optimize"].to_dataset()
    assert opt.design.dims == ("candidate", "variable")
    assert opt.constraint_value.dims == ("candidate", "constraint")
    assert list(opt.variable_units.values) == ["m"]
    assert not any(v.startswith(("design_", "constraint_", "margin_")) and v[-1].isdigit() for v in opt.data_vars)
    best = tree["optimize/best"].to_dataset()
    with h5py.File(out) as f:
        attrs = f["optimize"].attrs
        assert int(best.candidate) == int(attrs["best_candidate"])
        np.testing.assert_array_equal(best.design.values, attrs["best_design"])
    bbcor = float(best.constraint_value.sel(constraint="bat.bbcor <= 0.7"))
    stored = tree["bat"].to_dataset()
    assert bbcor == float(stored.bbcor_max[0])
    shot = json.loads(str(stored.bbcor_shot.values[0]))
    assert shot["ball"]["preset"] == "mlb" and shot["hoop"]["from_geometry"] is True


def test_a_samples_uncertainty_is_in_the_tree(tmp_path):
    import batstudy

    tree = batstudy.open_results(run(tmp_path, SAMPLED, "run"))
    assert "uncertainty" in tree.children
    summary = tree["summary"].to_dataset()
    # the measured spread drew the ball's COR shift (the rigid model uses no stiffness)
    assert "ball_law_cor_shift" in summary.coords and "ball_law_k1" not in summary.coords
