"""The ball rig: what a ball certification reports, from a study of balls fired at a wall."""

from __future__ import annotations

import json

import numpy as np
import xarray as xr

# The ball-alone quantities the standards report (ASTM F1887's wall COR; ASTM F2845's dynamic
# stiffness, from the peak force and the speed) and the stored variables they come from.
RIG = ("cor", "peak_force", "contact_time", "max_compression", "dynamic_stiffness")


def ball_rig(results) -> xr.Dataset:
    """A results file (path, or a tree from :func:`open_results`) of balls fired at
    ``bat.preset: wall`` as a Dataset over the study's dimensions with: ``cor`` (rebound over
    approach speed, 1), ``peak_force`` (N), ``contact_time`` (s), ``max_compression`` (m) and
    ``dynamic_stiffness`` (N/m), ``(F_peak / v)² / m``: the stiffness of the linear spring
    that would peak at the same force (ASTM F2845's form; batstudy's contact law does not
    depend on the target's curvature, so a rigid cylinder gives these same numbers).

    Points whose target is not the wall are NaN."""
    from ._open import open_results

    tree = open_results(results) if not isinstance(results, xr.DataTree) else results
    s = tree["summary"].to_dataset()
    speed = s["approach_speed"]
    mass = 2 * s["energy_initial"] / speed**2  # the ball's kinetic energy: a wall never moves
    wall = _on_wall(tree, s)
    out = xr.Dataset({
        "cor": (s["exit_speed"] / speed).where(wall),
        "peak_force": s["peak_force"].where(wall),
        "contact_time": s["contact_time"].where(wall),
        "max_compression": s["max_compression"].where(wall),
        "dynamic_stiffness": ((s["peak_force"] / speed) ** 2 / mass).where(wall),
    })
    units = {"cor": "1", "peak_force": "N", "contact_time": "s", "max_compression": "m", "dynamic_stiffness": "N/m"}
    for name, unit in units.items():
        out[name].attrs["units"] = unit
    return out


def _on_wall(tree, s: xr.Dataset) -> xr.DataArray:
    """Whether each point's target is the wall (its bat's stored spec says so)."""
    specs = tree["bat"].to_dataset()["spec_json"].values
    is_wall = np.array([json.loads(str(j)).get("bat", {}).get("preset") == "wall" for j in np.ravel(specs)])
    return xr.apply_ufunc(lambda i: is_wall[i], s["bat_index"])
