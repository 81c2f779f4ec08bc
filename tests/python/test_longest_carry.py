"""batstudy.longest_carry: the longest carry of a study over its impact positions and offsets,
checked against the file's own summary read directly (the grid's best point) and against the
sweet spot's refined position. Needs BATSTUDY_BIN (set by scripts/test.sh)."""
import os
import subprocess

import h5py
import numpy as np
import pytest

import batstudy

BIN = os.environ.get("BATSTUDY_BIN")
pytestmark = pytest.mark.skipif(not BIN, reason="BATSTUDY_BIN not set (scripts/test.sh sets it)")

STUDY = """\
name: carry_probe
model: wave
base:
  bat: {preset: r161}
  ball: {preset: mlb}
  batter: {pitch_speed: 40.2, bat_speed: 31.3, reference_moi: 0.319}
  swing: {attack_angle: 0.1745}
  flight: {}
grid:
  impact.offset: [0.0, -0.0125, -0.03]
  impact.z: [0.62, 0.66, 0.70, 0.74, 0.78]
"""


def test_the_longest_carry_is_the_best_point_of_the_summary(tmp_path):
    study = tmp_path / "carry_probe.yaml"
    study.write_text(STUDY)
    out = tmp_path / "carry_probe.h5"
    r = subprocess.run([BIN, "run", str(study), "-o", str(out), "--quiet"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    best = batstudy.longest_carry(out)
    with h5py.File(out, "r") as f:
        carry = f["summary/carry"][()]  # (impact_offset, impact_z)
        offsets = f["summary/impact_offset"][()]
        z = f["summary/impact_z"][()]
    i, j = np.unravel_index(np.nanargmax(carry), carry.shape)
    assert float(best.offset) == offsets[i]
    # the refined maximum along the bat lies within a grid step of the best grid point, and
    # is at least the best grid value
    assert abs(float(best.position) - z[j]) <= 0.04
    assert float(best.carry) >= carry[i, j] - 1e-9
    assert best.carry.attrs["units"] == "m"
