"""Batted balls as public bat tracking records them, in SI, beside a simulated population.

:func:`read` reads a CSV in Baseball Savant's per-pitch format (its search's CSV download, or
pybaseball's ``statcast`` output; only the columns below are needed) into an
:class:`xarray.Dataset` along ``swing``, one row per swing with a tracked bat speed. Savant's
columns and their units:

=====================  ==========  ==========================================================
column                 unit        meaning
=====================  ==========  ==========================================================
``bat_speed``          mph         speed of the bat's point 6 in from its head at contact
``swing_length``       ft          path length of the bat's head from the start of tracking
``attack_angle``       deg         elevation of the bat's path at contact (up positive)
``attack_direction``   deg         direction of the bat's path at contact, opposite field
                                   positive, pull negative (checked on the file's balls in
                                   play against their spray)
``swing_path_tilt``    deg         tilt of the swing's plane over the last 40 ms
``release_speed``      mph         the pitch's speed at release
``vx0, vy0, vz0``      ft/s        the pitch's velocity at y = 50 ft (x toward the first-base
                                   side, y toward the pitcher, z up)
``ax, ay, az``         ft/s²       its acceleration (constant over the flight)
``launch_speed``       mph         the batted ball's exit speed
``launch_angle``       deg         its launch angle
``stand``              —           the batter's side, ``R`` or ``L``
``type``               —           ``X`` in play, ``S`` a strike (a foul), ``B`` a ball
=====================  ==========  ==========================================================

What :func:`read` returns, all SI (m/s, m, rad):

- ``bat_speed``, ``swing_length``, ``attack_angle``, ``attack_direction`` (batstudy's sign:
  toward the first-base side positive for a right-handed batter, mirrored for a left-handed
  one; that is Savant's opposite-field-positive for both), ``swing_path_tilt``;
- ``release_speed``; ``pitch_speed``, ``descent_angle`` (falling positive) and
  ``horizontal_angle`` (batstudy's ``pitch`` block's, mirrored for a left-handed batter) at the
  front of the plate, y = 17/12 ft, from the pitch's constant-acceleration track;
- ``exit_speed``, ``launch_angle`` (NaN without a tracked batted ball);
- ``collision_efficiency_q`` = (exit − bat)/(pitch at the plate + bat), the field's q;
- ``stand``, ``in_play`` (bool).

:func:`compare` sets a simulated population (a results file's ``/summary``, e.g. of a study
that samples bat speed, attack angle, pitch speed and descent, and the impact point) beside a
measured one.
"""

from __future__ import annotations

import csv
import math

MPH = 0.44704
FT = 0.3048
DEG = math.pi / 180
# the front of home plate, ft from its point (Savant's y = 0 is the plate's point)
PLATE_FRONT_FT = 17 / 12
# where Savant's pitch kinematics are given, ft
KINEMATICS_Y_FT = 50.0

_NEEDED = ("bat_speed", "release_speed", "vx0", "vy0", "vz0", "ax", "ay", "az", "stand")


# the largest CSV :func:`read` opens: a full season of Savant's per-pitch rows (about 750,000
# pitches) is well under it; a larger file, or a device, is refused before it is read
MAX_BYTES = 4 << 30
# tracked bat speeds, mph: bunts and checked swings from about 10, the fastest swings about 90
BAT_SPEED_MPH = (5.0, 110.0)
# the median swing a tracked file holds is about 70 mph; one under this is in another unit
MIN_MEDIAN_BAT_SPEED_MPH = 40.0


def _number(text) -> float:
    try:
        return float(text)
    except (TypeError, ValueError):
        return math.nan


def pitch_at_plate(v0, a):
    """The pitch's velocity (ft/s, Savant's axes) at the front of the plate, from its velocity
    ``v0`` and acceleration ``a`` at y = 50 ft: y(t) = 50 + v_y t + a_y t²/2 reaches 17/12 ft
    at the root with the pitch still moving toward the plate."""
    vx0, vy0, vz0 = v0
    ax, ay, az = a
    dy = PLATE_FRONT_FT - KINEMATICS_Y_FT
    if not all(map(math.isfinite, (*v0, *a))) or vy0 >= 0:
        raise ValueError(f"vy0 {vy0}, ay {ay}: a pitch moving toward the plate (vy0 < 0 ft/s) "
                         "with finite kinematics")
    disc = vy0 * vy0 + 2 * ay * dy
    if disc < 0:
        raise ValueError(f"vy0 {vy0}, ay {ay}: a pitch that reaches the plate")
    t = dy / vy0 if ay == 0 else (-vy0 - math.sqrt(disc)) / ay
    return vx0 + ax * t, vy0 + ay * t, vz0 + az * t


def _row(r: dict) -> dict | None:
    values = {k: _number(r.get(k, "")) for k in _NEEDED if k != "stand"}
    if not math.isfinite(values["bat_speed"]):
        return None
    lo, hi = BAT_SPEED_MPH
    if not lo <= values["bat_speed"] <= hi:
        raise ValueError(f"bat_speed {values['bat_speed']}: allowed {lo} to {hi} mph")
    stand = r.get("stand", "")
    if stand not in ("R", "L"):
        raise ValueError(f"stand {stand!r}: allowed R or L")
    mirror = 1.0 if stand == "R" else -1.0
    vx, vy, vz = pitch_at_plate((values["vx0"], values["vy0"], values["vz0"]),
                                (values["ax"], values["ay"], values["az"]))
    horizontal = math.hypot(vx, vy)
    bat = values["bat_speed"] * MPH
    pitch = math.sqrt(vx * vx + vy * vy + vz * vz) * FT
    exit_speed = _number(r.get("launch_speed", "")) * MPH
    return {
        "bat_speed": bat,
        "swing_length": _number(r.get("swing_length", "")) * FT,
        "attack_angle": _number(r.get("attack_angle", "")) * DEG,
        "attack_direction": _number(r.get("attack_direction", "")) * DEG,
        "swing_path_tilt": _number(r.get("swing_path_tilt", "")) * DEG,
        "release_speed": values["release_speed"] * MPH,
        "pitch_speed": pitch,
        "descent_angle": math.atan2(-vz, horizontal),
        "horizontal_angle": mirror * math.atan2(vx, -vy),
        "exit_speed": exit_speed,
        "launch_angle": _number(r.get("launch_angle", "")) * DEG,
        "collision_efficiency_q": (exit_speed - bat) / (pitch + bat),
        "stand": stand,
        "in_play": r.get("type", "") == "X",
    }


_UNITS = {
    "bat_speed": ("m/s", "bat speed 6 in from the bat's head"),
    "swing_length": ("m", "path length of the bat's head"),
    "attack_angle": ("rad", "elevation of the bat's path at contact"),
    "attack_direction": ("rad", "direction of the bat's path, toward first base positive (right-handed)"),
    "swing_path_tilt": ("rad", "tilt of the swing's plane"),
    "release_speed": ("m/s", "the pitch's speed at release"),
    "pitch_speed": ("m/s", "the pitch's speed at the front of the plate"),
    "descent_angle": ("rad", "the pitch's path below the horizontal at the plate"),
    "horizontal_angle": ("rad", "the pitch's path from straight to the catcher, toward first base positive (right-handed)"),
    "exit_speed": ("m/s", "the batted ball's exit speed"),
    "launch_angle": ("rad", "the batted ball's launch angle"),
    "collision_efficiency_q": ("1", "(exit - bat) / (pitch at the plate + bat)"),
    "stand": ("", "the batter's side"),
    "in_play": ("", "the ball was put in play"),
}


def read(path):
    """The swings of a Savant per-pitch CSV with a tracked bat speed, as a Dataset along
    ``swing`` (module docs). ``path`` is the CSV's path, or a pandas DataFrame with its
    columns. A file without Savant's columns, a row that is not a pitch, a bat speed that is
    not in mph, a file larger than ``MAX_BYTES`` or anything but a regular file raises
    ``ValueError`` naming what is wrong."""
    import numpy as np
    import xarray as xr

    if hasattr(path, "columns") and hasattr(path, "to_dict"):
        rows = _rows("DataFrame", list(path.columns), path.to_dict("records"))
        source = "DataFrame"
    else:
        _check_file(path)
        with open(path, newline="", encoding="utf-8") as f:
            reader = csv.DictReader(f)
            rows = _rows(path, reader.fieldnames, reader)
        source = str(path)
    bats = [r["bat_speed"] / MPH for r in rows]
    if bats and float(np.median(bats)) < MIN_MEDIAN_BAT_SPEED_MPH:
        raise ValueError(
            f"{source}: the median bat_speed is {float(np.median(bats)):.1f}, where tracked "
            f"swings' is about 70 mph: Savant's column is in mph (a column in m/s: times 2.237)")
    data = {}
    for name, (units, long_name) in _UNITS.items():
        values = np.array([r[name] for r in rows])
        attrs = {"long_name": long_name} | ({"units": units} if units else {})
        data[name] = xr.Variable(("swing",), values, attrs)
    return xr.Dataset(data, attrs={"source": source})


def _check_file(path):
    """A regular file of at most ``MAX_BYTES``, checked before a byte is read."""
    import os
    import stat

    st = os.stat(path)
    if not stat.S_ISREG(st.st_mode):
        raise ValueError(f"{path}: not a regular file (a CSV is read whole; a device or a pipe "
                         "has no end)")
    if st.st_size > MAX_BYTES:
        raise ValueError(f"{path}: {st.st_size} bytes, more than a season of pitches "
                         f"(at most {MAX_BYTES})")


def _rows(source, columns, records):
    """Each record with a tracked bat speed as SI values; a bad one raises ``ValueError``
    with its line (the header is line 1)."""
    missing = [c for c in _NEEDED if c not in (columns or [])]
    if missing:
        raise ValueError(f"{source}: not a bat-tracking CSV: it lacks the column(s) {', '.join(missing)}")
    rows = []
    for line, r in enumerate(records, start=2):
        try:
            row = _row(r)
        except (ValueError, ZeroDivisionError, TypeError, OverflowError) as e:
            raise ValueError(f"{source}:{line}: {e}") from None
        if row is not None:
            rows.append(row)
    return rows


def _ks(a, b):
    """The two-sample Kolmogorov–Smirnov distance: the largest gap between the two empirical
    distribution functions."""
    import numpy as np

    a, b = np.sort(a), np.sort(b)
    grid = np.concatenate([a, b])
    return float(np.max(np.abs(np.searchsorted(a, grid, "right") / len(a)
                               - np.searchsorted(b, grid, "right") / len(b))))


def _wasserstein(a, b):
    """The first Wasserstein (earth mover's) distance of two samples, in their units: the
    mean gap between their quantile functions."""
    import numpy as np

    q = (np.arange(512) + 0.5) / 512
    return float(np.mean(np.abs(np.quantile(a, q) - np.quantile(b, q))))


def compare(simulated, measured, quantities=None):
    """A simulated population beside a measured one, as a Dataset along ``quantity``:
    each one's mean, standard deviation, 10th, 50th and 90th percentiles, and two distances
    between the distributions (the Kolmogorov–Smirnov statistic, 0–1, and the first
    Wasserstein distance, in the quantity's units). The slope of exit speed on bat speed
    (least squares, 1) is a row of its own (``exit_speed_per_bat_speed``).

    ``simulated``: a results file's ``/summary`` as a Dataset (``exit_speed_lab``,
    ``launch_angle``, ``bat_speed_6in``, ``collision_efficiency_q`` are read); ``measured``:
    what :func:`read` returns (balls in play and fouls with a tracked exit speed)."""
    import numpy as np
    import xarray as xr

    pairs = quantities or {
        "exit_speed": ("exit_speed_lab", "exit_speed"),
        "launch_angle": ("launch_angle", "launch_angle"),
        "bat_speed": ("bat_speed_6in", "bat_speed"),
        "collision_efficiency_q": ("collision_efficiency_q", "collision_efficiency_q"),
    }

    def finite(x):
        x = np.ravel(np.asarray(x, dtype=float))
        return x[np.isfinite(x)]

    rows = {}
    for name, (sim_name, meas_name) in pairs.items():
        s, m = finite(simulated[sim_name]), finite(measured[meas_name])
        rows[name] = (s, m)

    def slope(bat, exit_speed):
        bat, exit_speed = np.ravel(np.asarray(bat, float)), np.ravel(np.asarray(exit_speed, float))
        ok = np.isfinite(bat) & np.isfinite(exit_speed)
        return float(np.polyfit(bat[ok], exit_speed[ok], 1)[0]) if ok.sum() > 2 else math.nan

    names = list(rows) + ["exit_speed_per_bat_speed"]
    stats = {k: np.full((len(names), 2), np.nan) for k in ("mean", "sd", "p10", "p50", "p90")}
    distance = {"ks": np.full(len(names), np.nan), "wasserstein": np.full(len(names), np.nan)}
    for i, name in enumerate(rows):
        for j, x in enumerate(rows[name]):
            if len(x):
                stats["mean"][i, j], stats["sd"][i, j] = np.mean(x), np.std(x, ddof=1) if len(x) > 1 else np.nan
                stats["p10"][i, j], stats["p50"][i, j], stats["p90"][i, j] = np.percentile(x, [10, 50, 90])
        s, m = rows[name]
        if len(s) and len(m):
            distance["ks"][i], distance["wasserstein"][i] = _ks(s, m), _wasserstein(s, m)
    last = len(names) - 1
    stats["mean"][last, 0] = slope(simulated["bat_speed_6in"], simulated["exit_speed_lab"])
    stats["mean"][last, 1] = slope(measured["bat_speed"], measured["exit_speed"])
    out = xr.Dataset(
        {k: (("quantity", "population"), v) for k, v in stats.items()}
        | {k: (("quantity",), v) for k, v in distance.items()},
        coords={"quantity": names, "population": ["simulated", "measured"]},
    )
    out["ks"].attrs["long_name"] = "Kolmogorov-Smirnov statistic (0: the same distribution)"
    out["wasserstein"].attrs["long_name"] = "first Wasserstein distance, in the quantity's units"
    return out
