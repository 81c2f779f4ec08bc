"""`batstudy.fly` from the installed wheel: one batted ball's flight on its own.

Reference: A. M. Nathan's trajectory calculator's own output (mosaicCalc ``Fly_ball``):
103 mph, 27.5°, 2500 rpm of backspin from 3 ft; 70 °F, 50 % RH, 29.92 inHg, 15 ft of
elevation. Its table crosses the ground 419.49 ft from contact after 5.520 s and peaks at
92.04 ft. Band, set beforehand: ±1 % each (the workbook's first-order 0.01-s step and its drag
factor 0.3 % larger are about a foot each)."""

import math

import numpy as np
import pytest

import batstudy
from batstudy import units


def test_the_calculators_fly_ball():
    f = batstudy.fly(units.mph(103), units.deg(27.5), units.rpm(2500),
                     elevation=units.ft(15), temperature=units.fahrenheit(70),
                     pressure=29.92 * 3386.389)
    carry, apex, hang = float(f.carry) / units.FT, float(f.apex) / units.FT, float(f.hang_time)
    assert abs(carry / 419.49 - 1) < 0.01, carry
    assert abs(apex / 92.04 - 1) < 0.01, apex
    assert abs(hang / 5.520 - 1) < 0.01, hang
    assert f.carry.attrs["units"] == "m" and f.hang_time.attrs["units"] == "s"


def test_the_trajectory_has_a_time_axis_of_its_own():
    f = batstudy.fly(45.0, 0.45, 250.0)
    t = f.time.values
    assert f.time.attrs["units"] == "s" and t[0] == 0 and np.all(np.diff(t) > 0)
    assert math.isclose(t[-1], float(f.hang_time), rel_tol=1e-12)
    assert f.z.dims == ("time",) and f.z.attrs["units"] == "m" and f.vz.attrs["units"] == "m/s"
    assert math.isclose(float(f.z[0]), 0.9144) and abs(float(f.z[-1])) < 1e-9
    assert math.isclose(math.hypot(float(f.x[-1]), float(f.y[-1])), float(f.carry), rel_tol=1e-9)
    # the apex is the trajectory's highest point (to the step's resolution)
    assert float(f.z.max()) <= float(f.apex) + 1e-9
    # energy: the ball only loses it to drag on the way (lift does no work)
    e = 0.5 * (f.vx**2 + f.vy**2 + f.vz**2) + 9.80665 * f.z
    assert float(e[-1]) < float(e[0])


def test_the_spin_axis_splits_backspin_and_sidespin():
    back = batstudy.fly(45.0, 0.45, 250.0, 0.0)
    same = batstudy.fly(45.0, 0.45, 250.0 * math.cos(0.3), 0.0)
    tilted = batstudy.fly(45.0, 0.45, 250.0, 0.3)
    assert abs(float(back.landing_x)) < 1e-9
    # sidespin toward the left-field side: the ball lands there (x < 0), and carries as far
    # as its backspin share alone would within the sidespin's own drag and lift change
    assert float(tilted.landing_x) < -1.0
    assert tilted.attrs["backspin"] == pytest.approx(250.0 * math.cos(0.3))
    assert tilted.attrs["sidespin"] == pytest.approx(250.0 * math.sin(0.3))
    assert float(tilted.hang_time) == pytest.approx(float(same.hang_time), rel=0.05)


def test_a_value_out_of_range_is_named():
    with pytest.raises(ValueError, match="launch.exit_speed"):
        batstudy.fly(300.0, 0.4, 200.0)
    with pytest.raises(ValueError, match="flight.humidity"):
        batstudy.fly(40.0, 0.4, 200.0, humidity=1.5)


def test_a_number_in_the_trades_unit_is_refused_not_flown():
    # the ranges of a study's flight block and of `batstudy fly`: 100 meant as mph would fly
    # at 100 m/s (832 ft), 29.92 meant as inHg in near vacuum
    with pytest.raises(ValueError, match="launch.exit_speed.*batstudy.units"):
        batstudy.fly(100.0, 0.4, 200.0)
    with pytest.raises(ValueError, match="flight.pressure"):
        batstudy.fly(45.0, 0.4, 200.0, pressure=29.92)
    with pytest.raises(ValueError, match="launch.launch_angle"):
        batstudy.fly(45.0, 28.0, 200.0)
    assert float(batstudy.fly(units.mph(100), units.deg(28), units.rpm(2000)).carry) > 100


def test_a_flight_without_spin_is_asked_for_not_flown_as_a_knuckleball():
    # a batted ball leaves with 1,000-3,000 rpm; one without spin carries tens of feet less
    # (100 mph at 28 deg: 358 ft against 408.6 ft with 2,000 rpm), so the spin has no default
    with pytest.raises(TypeError, match="spin"):
        batstudy.fly(units.mph(100), units.deg(28))
    knuckle = float(batstudy.fly(units.mph(100), units.deg(28), 0.0).carry)
    spun = float(batstudy.fly(units.mph(100), units.deg(28), units.rpm(2000)).carry)
    assert spun - knuckle > 10 * 0.3048, (knuckle, spun)


def test_values_with_units_are_the_same_flight():
    # "103mph" is 103 x 0.44704 m/s by definition (NIST SP 811), as units.mph(103) is
    a = batstudy.fly("103mph", "27.5deg", "2500rpm", elevation="15ft")
    b = batstudy.fly(units.mph(103), units.deg(27.5), units.rpm(2500), elevation=units.ft(15))
    assert float(a.carry) == float(b.carry)
    with pytest.raises(ValueError, match="launch.exit_speed.*allowed: m/s, mph"):
        batstudy.fly("103oz", 0.45, 200.0)
