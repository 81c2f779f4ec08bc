"""The field's units in SI: multiply by one to get SI (``45 * units.MPH`` is m/s), or call
the function of the same name (``units.mph(100)``); divide to go back
(``carry / units.FT``).

Every value batstudy takes and returns is SI (m, s, rad, kg); these are the factors the
field's numbers need on the way in and out.
"""

import math

MPH = 0.44704
"""One mile per hour in m/s (exact: 1609.344 m / 3600 s)."""
FT = 0.3048
"""One foot in m (exact)."""
INCH = 0.0254
"""One inch in m (exact)."""
RPM = 2 * math.pi / 60
"""One revolution per minute in rad/s."""
DEG = math.pi / 180
"""One degree in rad."""
OUNCE = 0.028349523125
"""One avoirdupois ounce in kg (exact)."""


def mph(x):
    """Miles per hour to m/s."""
    return x * MPH


def ft(x):
    """Feet to m."""
    return x * FT


def rpm(x):
    """Revolutions per minute to rad/s."""
    return x * RPM


def deg(x):
    """Degrees to rad."""
    return x * DEG


def fahrenheit(x):
    """Degrees Fahrenheit to K."""
    return (x - 32.0) * 5.0 / 9.0 + 273.15


def celsius(x):
    """Degrees Celsius to K."""
    return x + 273.15
