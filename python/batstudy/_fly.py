"""One batted ball's flight on its own (the flight of a study's ``flight`` block): the
trajectory as an :class:`xarray.Dataset` with a time axis of its own."""

from typing import Optional, Sequence

import math

import numpy as np
import xarray as xr

from . import _native

_COLUMNS = {
    "x": ("m", "position toward the first-base (right-field) side"),
    "y": ("m", "position toward centre field"),
    "z": ("m", "height above the ground"),
    "vx": ("m/s", "velocity toward the first-base side"),
    "vy": ("m/s", "velocity toward centre field"),
    "vz": ("m/s", "upward velocity"),
}


def _si(value, path: str) -> float:
    """A number (SI) as it is, or text with a unit in SI (the units of `path`'s quantity)."""
    if isinstance(value, str):
        return _native.to_si(value, path)
    return float(value)


def fly(
    exit_speed: float,
    launch_angle: float,
    spin: float,
    spin_axis: float = 0.0,
    *,
    spray_angle: float = 0.0,
    height: float = 0.9144,
    temperature: Optional[float] = None,
    pressure: Optional[float] = None,
    elevation: float = 0.0,
    humidity: float = 0.5,
    wind: Sequence[float] = (0.0, 0.0, 0.0),
) -> xr.Dataset:
    """The flight of a ball leaving the bat, as Nathan's trajectory calculator flies it.

    SI numbers, or text with a unit (``fly("103mph", "27.5deg", "2500rpm")``, as a study file
    takes them; ``batstudy.units`` converts numbers: ``fly(units.mph(103), units.deg(27.5),
    units.rpm(2500))``): ``exit_speed`` m/s; ``launch_angle`` rad above the horizontal;
    ``spin`` rad/s, the spin's magnitude, required (a ball without spin is a knuckleball
    that carries tens of feet less: give 0 for one; batted balls leave with about
    1,000–3,000 rpm); ``spin_axis`` rad, the tilt of the spin axis from
    pure backspin (0) toward sidespin that curves the ball to the left-field side (π/2; −π/2
    curves it to the right-field side, π is topspin): backspin = spin·cos(spin_axis),
    sidespin = spin·sin(spin_axis); ``spray_angle`` rad from straight-away centre field,
    positive toward right field; ``height`` m of the contact point (3 ft). The air:
    ``temperature`` K (70 °F), ``pressure`` Pa reduced to sea level (29.92 inHg),
    ``elevation`` m, ``humidity`` 0–1, ``wind`` (x, y, z) m/s in the flight frame (a tail
    wind to centre field is ``(0, w, 0)``).

    The frame: origin on the ground below the contact point, x toward the first-base
    (right-field) side, y toward centre field, z up. Returns a Dataset over ``time`` (s, every
    integration step and the landing) with ``x``, ``y``, ``z`` (m) and ``vx``, ``vy``, ``vz``
    (m/s), and the scalars ``carry`` (m, from the contact point to where the ball is back on
    the ground), ``apex`` (m), ``apex_time`` (s), ``hang_time`` (s), ``landing_x`` and
    ``landing_y`` (m). Raises ValueError naming an input outside its range.
    """
    standard_temperature, standard_pressure = _native.standard_air()
    # a value with a unit ("100mph", "28deg", "2500rpm", "70F") is converted by definition
    exit_speed, launch_angle, spin, spin_axis, spray_angle, height, elevation = (
        _si(x, path) for x, path in (
            (exit_speed, "launch.exit_speed"), (launch_angle, "launch.launch_angle"), (spin, "launch.spin"),
            (spin_axis, "launch.spin_axis"), (spray_angle, "launch.spray_angle"), (height, "launch.height"),
            (elevation, "flight.elevation"),
        )
    )
    temperature, pressure = (None if x is None else _si(x, path)
                             for x, path in ((temperature, "flight.temperature"), (pressure, "flight.pressure")))
    backspin = spin * math.cos(spin_axis)
    sidespin = spin * math.sin(spin_axis)
    wind = tuple(float(w) for w in wind)
    if len(wind) != 3:
        raise ValueError(f"wind must be (x, y, z) in m/s, not {wind!r}")
    out = _native.fly(
        float(exit_speed), float(launch_angle), backspin, sidespin, float(spray_angle),
        float(height),
        standard_temperature if temperature is None else float(temperature),
        standard_pressure if pressure is None else float(pressure),
        float(elevation), float(humidity), list(wind), True,
    )
    column = {k: np.frombuffer(out[k], dtype="<f8") for k in ["t", *_COLUMNS]}
    data = {
        name: ("time", column[name], {"units": units, "long_name": long_name})
        for name, (units, long_name) in _COLUMNS.items()
    }
    scalars = {
        "carry": (out["carry"], "m", "horizontal distance from the contact point to the landing"),
        "apex": (out["apex"], "m", "greatest height above the ground"),
        "apex_time": (out["apex_time"], "s", "time of the apex"),
        "hang_time": (out["hang_time"], "s", "time from contact to landing"),
        "landing_x": (out["landing"][0], "m", "landing point toward the first-base side"),
        "landing_y": (out["landing"][1], "m", "landing point toward centre field"),
    }
    for name, (value, units, long_name) in scalars.items():
        data[name] = ((), value, {"units": units, "long_name": long_name})
    time = ("time", column["t"], {"units": "s", "long_name": "time since contact"})
    return xr.Dataset(data, coords={"time": time}, attrs={
        "title": "a batted ball's flight (batstudy.fly)",
        "exit_speed": float(exit_speed), "launch_angle": float(launch_angle),
        "backspin": backspin, "sidespin": sidespin,
    })
