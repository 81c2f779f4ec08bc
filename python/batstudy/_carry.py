"""The longest carry of a study: where on the bat, and how far below (or above) the ball's
centre, the ball should be met to fly farthest."""

from __future__ import annotations

import numpy as np
import xarray as xr

OFFSET = "impact_offset"


def longest_carry(results) -> xr.Dataset:
    """A results file (path, or a tree from :func:`open_results`) of a study with a ``flight``
    as a Dataset over the study's dimensions other than ``impact_z`` and ``impact_offset``:
    ``carry`` (m), the longest carry; ``position`` (m from the knob), where along the bat
    (``/sweet_spot/carry_position``: parabola-refined along ``impact_z``); and ``offset`` (m,
    the study's ``impact.offset``, negative an undercut), the grid value of the longest carry
    over the offsets when the study sweeps them (NaN where every carry is NaN).

    Carries are in metres; multiply by 3.2808 for feet."""
    from ._open import open_results

    tree = open_results(results) if not isinstance(results, xr.DataTree) else results
    if "sweet_spot" not in tree.children or "carry" not in tree["sweet_spot"].to_dataset():
        raise ValueError("this results file has no /sweet_spot/carry (a study with a flight and an impact_z axis)")
    sweet = tree["sweet_spot"].to_dataset()
    carry, position = sweet["carry"], sweet["carry_position"]
    if OFFSET in carry.dims:
        filled = carry.fillna(-np.inf)
        best = filled.argmax(OFFSET)
        offset = carry[OFFSET].isel({OFFSET: best}).where(np.isfinite(filled.max(OFFSET)))
        carry, position = carry.isel({OFFSET: best}), position.isel({OFFSET: best})
        carry = carry.where(np.isfinite(offset))
    else:
        offset = xr.full_like(carry, np.nan)
    out = xr.Dataset({"carry": carry.drop_vars(OFFSET, errors="ignore"),
                      "position": position.drop_vars(OFFSET, errors="ignore"),
                      "offset": offset.drop_vars(OFFSET, errors="ignore")})
    for name, (unit, long) in {"carry": ("m", "longest carry"), "position": ("m", "where along the bat"),
                               "offset": ("m", "the ball's centre below (+) or above (−) the bat's axis")}.items():
        out[name].attrs.update(units=unit, long_name=long)
    return out
