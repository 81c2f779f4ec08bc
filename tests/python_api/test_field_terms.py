"""The field's terms from the installed wheel: one collision with a pitch off the swing's
path gives its q in the field's convention, and a bat-tracking CSV reads into SI.

References independent of the code: q's definition (exit = q pitch + (1 + q) bat, Nathan's
convention) holds of the returned speeds; an on-plane pitch block gives the batter's on-plane
collision (the special case the pitch block contains); a pitch reaches the plate at about
0.92 of its release speed (drag over 55 ft; the tracked file's own 0.917 ± 0.008)."""

import math
from pathlib import Path

import pytest

import batstudy

ROOT = Path(__file__).resolve().parents[2]
BATTER = {"bat_speed": 31.3, "reference_moi": 0.319}


def collision(pitch=None, pitch_speed=None):
    spec = {"ball": {"preset": "mlb"}, "impact": {"z": 0.70, "offset": -0.01},
            "swing": {"attack_angle": 0.15}, "batter": dict(BATTER)}
    if pitch is not None:
        spec["pitch"] = pitch
    else:
        spec["batter"]["pitch_speed"] = pitch_speed
    return batstudy.simulate(spec)


def test_q_is_the_field_formula_of_the_returned_speeds():
    r = collision(pitch={"speed": 37.0, "descent_angle": 0.107})
    q, v, p, b = r["collision_efficiency_q"], r["exit_speed_lab"], r["pitch_speed_plate"], r["bat_speed_6in"]
    assert p == 37.0 and b > 0
    assert math.isclose(v, q * p + (1 + q) * b, rel_tol=1e-12)
    # squared up against the bat's own best q (its card, which simulate returns), as a
    # study's point is: exit >= 80 % of best_q pitch + (1 + best_q) bat speed
    best_q = r["bat"]["best_q"]
    assert r["squared_up"] == float(v >= 0.8 * (best_q * p + (1 + best_q) * b))


def test_an_on_plane_pitch_block_is_the_batters_on_plane_pitch():
    a = collision(pitch={"speed": 37.0, "descent_angle": 0.15})
    b = collision(pitch_speed=37.0)
    for k in ("exit_speed_lab", "launch_angle", "spin"):
        assert a[k] == pytest.approx(b[k], rel=1e-9, abs=1e-9), k


def test_a_bat_tracking_csv_reads_into_si():
    ds = batstudy.tracking.read(ROOT / "data" / "bat_tracking_2025.csv")
    ratio = (ds.pitch_speed / ds.release_speed).values
    assert 0.88 < ratio.mean() < 0.95, ratio.mean()
    assert ds.exit_speed.attrs["units"] == "m/s"


def test_one_collisions_trajectory_on_its_own_time_axis():
    # the flight's frame: the ball starts at the contact height above the origin, and the
    # stored states end at the landing (NaN after), the hang time between the last two
    spec = {"ball": {"preset": "mlb"}, "impact": {"z": 0.70, "offset": -0.012},
            "batter": dict(BATTER, pitch_speed=40.2), "swing": {"attack_angle": 0.17}, "flight": {}}
    r = batstudy.simulate(spec, history={"fields": ["trajectory"], "interval": 1e-5, "duration": 1e-3})
    h = r["history"]
    t, z = h["flight_time"], h["trajectory_z"]
    assert t[1] - t[0] == pytest.approx(0.1) and len(t) == len(z) == 121
    assert z[0] == pytest.approx(0.9144)
    import numpy as np
    last = np.flatnonzero(np.isfinite(z))[-1]
    assert t[last] <= r["hang_time"] < t[last] + 0.1
