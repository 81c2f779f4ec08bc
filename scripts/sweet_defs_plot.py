"""The figure ``sweet_spot_definitions.png``: each bat's profile with every sweet-spot
definition marked (issue 10).

Per bat (from ``/bat``): centre of percussion for the pivot at the hands
(``centre_of_percussion``, ``pivot_position``), barrel nodes of modes 1 and 2
(``node1_barrel``, ``node2_barrel``), maximum BBCOR (``bbcor_max_position``).  Per curve (from
``/sweet_spot``, the first curve of the main model using that bat): maximum exit speed
(``position`` with its ``width`` as a band), least grip vibration (``min_vibration_position``)
and least energy in bat vibration (``min_vibration_energy_position``).  Variables a file does
not hold are left out; bats are drawn in the order wood (r161), corked, aluminum, then the rest.
"""

from __future__ import annotations

import math

import matplotlib.pyplot as plt
import numpy as np

from batplot import MODEL, Results, Skip

# (source, variable, label, colour, line style, marker)
DEFINITIONS = [
    ("sweet", "position", "max exit speed (band: within 1 m/s)", "tab:red", "-", "o"),
    ("bat", "centre_of_percussion", "centre of percussion (pivot 6 in)", "tab:blue", "--", "s"),
    ("bat", "node1_barrel", "mode-1 node", "tab:green", ":", "v"),
    ("bat", "node2_barrel", "mode-2 node", "tab:olive", ":", "^"),
    ("sweet", "min_vibration_position", "least grip vibration", "tab:purple", "-.", "D"),
    ("sweet", "min_vibration_energy_position", "least vibration energy", "tab:pink", "-.", "P"),
    ("bat", "bbcor_max_position", "max BBCOR", "tab:orange", (0, (5, 1, 1, 1)), "*"),
]
ORDER = ["r161", "corked", "aluminum"]


def _value(ds, name) -> float:
    if ds is None or name not in ds:
        return math.nan
    v = np.asarray(ds[name].values, dtype=float).ravel()
    return float(v[0]) if v.size else math.nan


def _bat_rank(label: str) -> tuple:
    head = label.split(",")[0].strip()
    return (ORDER.index(head) if head in ORDER else len(ORDER), label)


def _curve_per_bat(res: Results) -> dict[int, object]:
    """Bat index -> the first curve of the main model that uses it."""
    out = {}
    if res.summary is None or "bat_index" not in res.summary:
        return out
    try:
        model = res.main_model()
    except Skip:
        return out
    for c in res.curves:
        if c.params.get(MODEL) != model:
            continue
        idx = np.asarray(res.summary["bat_index"].isel(c.index).values).ravel()
        idx = idx[idx >= 0]
        if idx.size:
            out.setdefault(int(idx[0]), c)
    return out


def sweet_spot_definitions(res: Results, path) -> None:
    bat = res.bat
    if bat is None or "outer_radius" not in bat:
        raise Skip("no /bat profiles")
    bat = bat.load()
    labels = [str(v) for v in bat["bat"].values]
    order = sorted(range(len(labels)), key=lambda i: _bat_rank(labels[i]))[:6]
    curves = _curve_per_bat(res)
    ss = res.sweet_spot
    fig, axes = plt.subplots(len(order), 1, sharex=True, squeeze=False,
                             figsize=(8.0, 1.2 + 1.7 * len(order)), layout="constrained")  # fmt: skip
    fig.suptitle(f"Sweet-spot definitions on each bat\n(study: {res.name})", fontsize=10)
    handles = {}
    for ax, i in zip(axes[:, 0], order):
        b = bat.isel(bat=i)
        z, outer = b["profile_z"].values, b["outer_radius"].values
        inner = b["inner_radius"].values if "inner_radius" in b else np.zeros_like(outer)
        ok = np.isfinite(z) & np.isfinite(outer)
        z, outer, inner = z[ok], outer[ok] * 1e3, np.nan_to_num(inner[ok]) * 1e3
        ax.fill_between(z, -outer, outer, color="0.85", lw=0)
        ax.plot(z, outer, color="0.3", lw=1)
        ax.plot(z, -outer, color="0.3", lw=1)
        if inner.max() > 0:
            ax.fill_between(z, -inner, inner, where=inner > 0, color="white", lw=0)
            ax.plot(z, np.where(inner > 0, inner, np.nan), color="0.3", lw=0.7, ls="--")
            ax.plot(z, np.where(inner > 0, -inner, np.nan), color="0.3", lw=0.7, ls="--")
        top = float(np.nanmax(outer)) * 1.25
        sub = None
        if ss is not None and i in curves:
            sub = ss.isel({d: k for d, k in curves[i].index.items() if d in ss.dims})
        text = []
        for k, (src, name, label, color, style, marker) in enumerate(DEFINITIONS):
            v = _value(sub if src == "sweet" else b, name)
            if not math.isfinite(v):
                continue
            if name == "position":
                w = _value(sub, "width")
                if math.isfinite(w):
                    # the band is centred for display; the stored width is the zone's length
                    ax.axvspan(v - w / 2, v + w / 2, color=color, alpha=0.08, lw=0)
            ax.axvline(v, color=color, ls=style, lw=1.3)
            y = top * (0.95 - 0.27 * (k % 4))
            h = ax.plot([v], [y], marker=marker, color=color, ms=7, ls="none")[0]
            handles.setdefault(label, (h, style, color))
            text.append(f"{label.split(' (')[0]} {v * 100:.1f}")
        zcm = _value(b, "z_cm")
        if math.isfinite(zcm):
            ax.plot([zcm], [0], "+", color="black", ms=9)
        pivot = _value(b, "pivot_position")
        if math.isfinite(pivot):
            ax.plot([pivot], [0], marker=6, color="black", ms=8)
        bb = _value(b, "bbcor_max")
        extra = f", BBCOR max {bb:.3f}" if math.isfinite(bb) else ""
        ax.set_title(f"{labels[i].split(',')[0]}: {float(b['mass']):.3f} kg{extra}", fontsize=9, loc="left")
        ax.set_ylim(-top, top * 1.1)
        ax.set_ylabel("radius (mm)", fontsize=8)
        ax.grid(alpha=0.3)
        ax.text(0.01, 0.04, "cm from knob: " + "; ".join(text), transform=ax.transAxes, fontsize=6.5)
    axes[-1, 0].set_xlabel("z (m from the knob)")
    from matplotlib.lines import Line2D

    legend = [Line2D([], [], color=c, ls=s, marker=h.get_marker(), label=lab) for lab, (h, s, c) in handles.items()]
    legend += [Line2D([], [], color="black", marker="+", ls="none", label="centre of mass"),
               Line2D([], [], color="black", marker=6, ls="none", label="pivot / grip (6 in)")]  # fmt: skip
    fig.legend(handles=legend, fontsize=7, ncol=3, loc="outside lower center")
    fig.savefig(path, dpi=110)
    plt.close(fig)
