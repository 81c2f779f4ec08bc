"""batstudy.ball_rig against closed forms: a lossless linear ball of stiffness k fired at a rigid
wall peaks at F = v √(k m) (a half-period of the mass on the spring), so ASTM F2845's dynamic
stiffness (F_peak / v)² / m is k itself, its contact lasts π √(m / k), and its COR is 1."""
import math
import os
import subprocess

import pytest

import batstudy

BIN = os.environ.get("BATSTUDY_BIN")
pytestmark = pytest.mark.skipif(not BIN, reason="BATSTUDY_BIN not set (scripts/test.sh sets it)")

STUDY = """
name: rig
model: wave
base:
  bat: {preset: wall}
  impact: {z: 0.0}
  ball: {mass: 0.145, law: {kind: elastic, stiffness: 7.0e5}}
grid:
  ball.speed: [5.0, 26.8, 60.8]
"""


def test_an_elastic_linear_ball_has_its_own_stiffness(tmp_path):
    study, out = tmp_path / "rig.yaml", tmp_path / "rig.h5"
    study.write_text(STUDY)
    r = subprocess.run([BIN, "run", str(study), "-o", str(out), "--quiet"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    rig = batstudy.ball_rig(out)
    k, m = 7.0e5, 0.145
    for v in (5.0, 26.8, 60.8):
        point = rig.sel(ball_speed=v)
        assert float(point.dynamic_stiffness) == pytest.approx(k, rel=1e-3)
        assert float(point.cor) == pytest.approx(1.0, abs=1e-3)
        assert float(point.contact_time) == pytest.approx(math.pi * math.sqrt(m / k), rel=1e-2)
        assert point.dynamic_stiffness.attrs["units"] == "N/m"
