"""A batted ball's trajectory stored per point (`history.fields: [trajectory]`), on the
flight's own time axis, read back with `batstudy.histories`.

References: the flight's frame puts the ball at the contact height above the origin at t = 0
(Nathan's calculator); the apex lies between two samples, so the highest sample is below it
by at most half the vertical deceleration times half a step squared (zero vertical velocity
there; the deceleration is at most gravity plus drag, here bounded by 2 g); the landing lies
between the last sample and the next. The same launch flown by `batstudy fly` on its own
(the command line, which writes its own trajectory) gives the same states. Needs
BATSTUDY_BIN."""
import csv
import math
import os
import subprocess

import numpy as np
import pytest

import batstudy

BIN = os.environ.get("BATSTUDY_BIN")
pytestmark = pytest.mark.skipif(not BIN, reason="BATSTUDY_BIN not set (scripts/test.sh sets it)")

STUDY = """\
name: trajectory_probe
model: wave
base:
  bat: {preset: r161}
  # the flight calculator's ball (5.125 oz, 9.125 in round), as `batstudy fly` flies it
  ball: {preset: mlb, mass: 0.145291306015625, radius: 0.03688813693512404}
  batter: {bat_speed: 31.3, reference_moi: 0.319}
  pitch: {speed: 40.2, descent_angle: 0.107}
  swing: {attack_angle: 0.1745}
  flight: {}
grid:
  impact.offset: [0.0, -0.0125]
  impact.z: [0.66, 0.70]
history:
  fields: [trajectory]
  interval: 1.0e-5
  duration: 1.0e-3
  only: {impact.z: [0.70]}
"""


@pytest.fixture(scope="module")
def stored(tmp_path_factory):
    d = tmp_path_factory.mktemp("trajectory")
    (d / "s.yaml").write_text(STUDY)
    out = d / "s.h5"
    r = subprocess.run([BIN, "run", str(d / "s.yaml"), "-o", str(out), "--quiet"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    return out


def test_the_stored_trajectory_is_the_flights(stored, tmp_path):
    h = batstudy.histories(stored)
    s = batstudy.open_results(stored)["summary"].to_dataset()
    assert h.sizes["history"] == 2 and h.flight_time.attrs["units"] == "s"
    assert h.trajectory_z.attrs["units"] == "m"
    step = float(h.flight_time[1] - h.flight_time[0])
    for k in range(2):
        row = h.isel(history=k)
        point = s.sel(impact_z=float(row.impact_z), impact_offset=float(row.impact_offset))
        x, y, z = (row[f"trajectory_{c}"].values for c in "xyz")
        assert (x[0], y[0]) == (0.0, 0.0) and math.isclose(z[0], 0.9144, rel_tol=1e-7)  # stored as f32
        landed = np.flatnonzero(~np.isfinite(z))[0]
        last = float(h.flight_time[landed - 1])
        hang = float(point.hang_time)
        assert last <= hang < last + step + 1e-9
        apex = float(point.apex)
        assert np.nanmax(z) <= apex + 1e-5
        assert apex - np.nanmax(z) <= 0.5 * 2 * 9.80665 * (step / 2) ** 2
        # the same launch flown on its own by the command line
        path = tmp_path / f"t{k}.csv"
        args = [BIN, "fly", "--exit-speed", repr(float(point.exit_speed_lab)),
                "--launch-angle", repr(float(point.launch_angle)),
                "--spray-angle", repr(float(point.spray_angle)),
                "--backspin", repr(float(point.spin)), "--sidespin", repr(float(point.sidespin)),
                "--trajectory", str(path)]
        r = subprocess.run(args, capture_output=True, text=True)
        assert r.returncode == 0, r.stderr
        rows = list(csv.DictReader(line for line in open(path) if not line.startswith("#")))
        t = np.array([float(r["t_s"]) for r in rows])
        on_grid = np.isclose(t / step, np.round(t / step), atol=1e-9)
        zs = np.array([float(r["z_m"]) for r in rows])[on_grid]
        # f32 storage: 6e-8 of the largest value
        assert np.allclose(zs, z[: len(zs)], rtol=1e-7, atol=1e-6), (zs[:5], z[:5])
