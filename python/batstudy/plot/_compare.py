"""Bats side by side: the BBCOR along the barrel with each bat's sweet zone, and, for a study
with an ``impact_z`` dimension, the lab exit speed and the vibration left in the bat against
impact position, one line per bat."""

from __future__ import annotations

import numpy as np
import xarray as xr

from .._card import bat_card
from .._open import where_index
from ._curves import IMPACT, Skip
from ._draw import COLORS, Z_LABEL
from ._views import Source, _tree, axis_label

# the summary variables of the lower panels: what the batter gets, and what stings the hands
PER_POINT = ("exit_speed_lab", "energy_bat_vibration")


def compare(source: Source, *, axes=None, **where):
    """Every bat of a results file side by side: BBCOR along the barrel (its sweet zone,
    where BBCOR is within 0.01 of its peak, shaded), and with an ``impact_z`` dimension the
    lab exit speed and the vibration energy left in the bat against impact position. `where`
    selects the summary's other dimensions as :func:`batstudy.histories` does; each bat's
    curve is its first one left. `axes`: three axes to draw on (default: a new figure).
    Returns the axes drawn on."""
    tree = _tree(source)
    card = bat_card(tree)
    curves = _curves_per_bat(tree, where)
    n_panels = 3 if curves else 1
    axes = _new_axes(n_panels) if axes is None else list(np.atleast_1d(axes))
    labels = [str(b) for b in card["bat"].values]
    bat = tree["bat"].to_dataset()
    for k, label in enumerate(labels):
        color = COLORS[k % len(COLORS)]
        z, bbcor = bat["bbcor_z"].values[k], bat["bbcor"].values[k]
        ok = np.isfinite(z) & np.isfinite(bbcor)
        axes[0].plot(z[ok], bbcor[ok], color=color, label=label)
        start, end = float(card["sweet_zone_start"][k]), float(card["sweet_zone_end"][k])
        if np.isfinite(start) and np.isfinite(end):
            axes[0].axvspan(start, end, color=color, alpha=0.12, lw=0)
        for ax, var in zip(axes[1:], PER_POINT):
            if k in curves:
                z_points, values = curves[k][var]
                ax.plot(z_points, values, color=color, marker=".", label=label)
                if np.isfinite(start) and np.isfinite(end):
                    ax.axvspan(start, end, color=color, alpha=0.12, lw=0)
    axes[0].set_ylabel("BBCOR")
    axes[0].set_title("bats side by side (shaded: BBCOR within 0.01 of its peak)", fontsize=10)
    summary = tree["summary"].to_dataset() if curves else None
    for ax, var in zip(axes[1:], PER_POINT):
        ax.set_ylabel(axis_label(summary[var]))
    for ax in axes:
        ax.grid(alpha=0.3)
    axes[-1].set_xlabel(Z_LABEL)
    axes[0].legend(fontsize=7)
    return axes


def _new_axes(n: int):
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(n, 1, figsize=(7.5, 2.6 + 2.4 * n), sharex=True, layout="constrained")
    return list(np.atleast_1d(axes))


def _curves_per_bat(tree: xr.DataTree, where: dict) -> dict:
    """{bat index: {variable: (impact_z, values)}}: for each bat, the first curve along
    ``impact_z`` (after `where`) whose points use it; empty without an ``impact_z`` dim."""
    if "summary" not in tree.children:
        return {}
    s = tree["summary"].to_dataset()
    if IMPACT not in s.dims or "bat_index" not in s or any(v not in s for v in PER_POINT):
        return {}
    s = s.isel(where_index(s, where))
    if any(s.sizes[d] == 0 for d in s.dims):
        raise Skip(f"nothing matches {where}")
    others = [d for d in s["bat_index"].dims if d != IMPACT]
    order = np.argsort(s[IMPACT].values)
    z = s[IMPACT].values[order]
    stacked = {v: s[v].transpose(*others, IMPACT).values.reshape(-1, z.size)[:, order]
               for v in ("bat_index",) + PER_POINT}  # fmt: skip
    out = {}
    for row, bats in enumerate(stacked["bat_index"]):
        b = int(bats[0])
        if b < 0 or b in out or not (bats == b).all():
            continue
        out[b] = {v: (z, stacked[v][row]) for v in PER_POINT}
    return out
