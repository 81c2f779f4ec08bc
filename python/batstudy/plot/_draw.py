"""Drawing helpers shared by the paper's figures and the figures of any file.

Figures written to files are made without pyplot (:func:`new_figure`: a Figure on an Agg
canvas), so that drawing them neither needs nor disturbs an interactive backend.
"""

from __future__ import annotations

from pathlib import Path

import matplotlib
import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from ._curves import Skip

COLORS = matplotlib.rcParams["axes.prop_cycle"].by_key()["color"]
STYLES = ["--", ":", "-.", (0, (5, 1, 1, 1)), (0, (1, 3)), (0, (8, 2))]
Z_LABEL = "z (m from the knob)"


def new_figure(**kwargs) -> Figure:
    """A Figure on its own Agg canvas (``Figure`` keyword arguments, e.g. figsize, layout)."""
    fig = Figure(**kwargs)
    FigureCanvasAgg(fig)
    return fig


def new_axes(title: str, xlabel: str, ylabel: str, study: str):
    """``(figure, axes)`` of a one-panel figure of the study named `study`."""
    fig = new_figure(figsize=(7.5, 4.8), layout="constrained")
    ax = fig.subplots()
    ax.set_title(f"{title}\n(study: {study})", fontsize=10)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.grid(alpha=0.3)
    return fig, ax


def save(fig: Figure, path: Path):
    fig.savefig(path, dpi=110)  # the format follows the file name (png, svg, pdf)


def require(found, what: str):
    if not found:
        raise Skip(f"no {what} in this file")
    return found


def distinct_profiles(bat) -> list:
    """[(labels, z, outer, inner)] per distinct profile of /bat (bats sharing one are merged)."""
    out = []
    for i in range(bat.sizes["bat"]):
        b = bat.isel(bat=i)
        z, outer = b["profile_z"].values, b["outer_radius"].values
        inner = b["inner_radius"].values if "inner_radius" in b else np.zeros_like(outer)
        for labels, z0, o0, i0 in out:
            same_shape = z0.shape == z.shape
            if same_shape and np.allclose(o0, outer, equal_nan=True) and np.allclose(i0, inner, equal_nan=True):
                labels.append(str(b["bat"].item()))
                break
        else:
            out.append(([str(b["bat"].item())], z, outer, inner))
    return out


def short_bat_label(label: str) -> str:
    """`r161, bat.material.youngs_modulus=14512000000.0` -> `r161, youngs_modulus 1.45e+10`:
    no repeated preset, no `bat.`/`material.` prefixes, numbers to 3 figures."""
    parts = [p.strip() for p in label.split(",")]
    out = [parts[0]]
    for p in parts[1:]:
        key, _, value = p.partition("=")
        if key == "bat.preset":
            continue
        key = key.removeprefix("bat.").removeprefix("material.")
        try:
            value = f"{float(value):.4g}"
        except ValueError:
            pass
        out.append(f"{key} {value}".strip())
    return ", ".join(out)


def draw_profiles(ax, bat) -> None:
    """Every distinct profile of /bat (`bat`, loaded): outer radius solid, inner dashed."""
    for k, (labels, z, outer, inner) in enumerate(distinct_profiles(bat)):
        color = COLORS[k % len(COLORS)]
        short = [short_bat_label(lab) for lab in labels]
        names = "; ".join(short) if len(short) <= 2 else "; ".join(short[:2]) + f" (+{len(short) - 2} more)"
        ax.plot(z, outer * 1e3, color=color, lw=1.5, label=names)
        if np.nanmax(inner) > 0:  # the hollow part only
            ax.plot(z, np.where(inner > 0, inner, np.nan) * 1e3, color=color, ls="--", lw=1)
    ax.set_ylabel("radius (mm)")
    ax.grid(alpha=0.3)


def loaded_bats(bat):
    """/bat loaded, or Skip if the file has no bat profiles."""
    if bat is None or "outer_radius" not in bat:
        raise Skip("no /bat profiles")
    return bat.load()
