"""The figure ``sweet_spot_definitions``: each bat's profile with every sweet-spot
definition marked.

Per bat (from ``/bat``): centre of percussion for the pivot at the hands
(``centre_of_percussion``, ``pivot_position``), barrel nodes of modes 1 and 2
(``node1_barrel``, ``node2_barrel``), maximum BBCOR (``bbcor_max_position``).  Per curve (from
``/sweet_spot``, the first curve of the main model using that bat): maximum exit speed
(``position`` with its ``width`` as a band), least grip vibration (``min_vibration_position``)
and least energy in bat vibration (``min_vibration_energy_position``), and the longest carry
(``carry_position``, a study with a ``flight``).  Variables a file does
not hold are left out; bats are drawn in the order wood (r161), corked, aluminum, then the rest.
"""

from __future__ import annotations

import math

import numpy as np
from matplotlib.lines import Line2D

from ._curves import MODEL, Results, Skip
from ._draw import Z_LABEL, loaded_bats, new_figure, save

# (source, variable, label, colour, line style, marker)
DEFINITIONS = [
    ("sweet", "position", "max exit speed (band: within 1 m/s)", "tab:red", "-", "o"),
    ("bat", "centre_of_percussion", "centre of percussion (pivot 6 in)", "tab:blue", "--", "s"),
    ("bat", "node1_barrel", "mode-1 node", "tab:green", ":", "v"),
    ("bat", "node2_barrel", "mode-2 node", "tab:olive", ":", "^"),
    ("sweet", "min_vibration_position", "least grip vibration", "tab:purple", "-.", "D"),
    ("sweet", "min_vibration_energy_position", "least vibration energy", "tab:pink", "-.", "P"),
    ("bat", "bbcor_max_position", "max BBCOR", "tab:orange", (0, (5, 1, 1, 1)), "*"),
    ("sweet", "carry_position", "longest carry (a study with a flight)", "tab:brown", "--", "X"),
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


def _shown_bats(labels: list[str], most: int = 6) -> list[int]:
    """Up to `most` bats: first the plainest bat of each kind (wood, corked, aluminum — the
    comparison the figure is for), then the variants, in ORDER and label order."""
    ranked = sorted(range(len(labels)), key=lambda i: (_bat_rank(labels[i])[0], labels[i].count(","), labels[i]))
    firsts, seen = [], set()
    for i in ranked:
        head = labels[i].split(",")[0].strip()
        if head not in seen:
            seen.add(head)
            firsts.append(i)
    rest = [i for i in ranked if i not in firsts]
    return sorted((firsts + rest)[:most], key=lambda i: ranked.index(i))


def _at_edge(summary, v: float) -> bool:
    """An extremum found at the first or last sampled impact position is the edge of the
    grid, not a sweet spot (the true one may lie beyond)."""
    if summary is None or "impact_z" not in getattr(summary, "coords", {}):
        return False
    z = np.asarray(summary["impact_z"].values, dtype=float)
    return z.size > 0 and (abs(v - np.nanmin(z)) < 1e-9 or abs(v - np.nanmax(z)) < 1e-9)


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


def _profile(ax, b):
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
    return float(np.nanmax(outer)) * 1.25


def sweet_spot_definitions(res: Results, path) -> None:
    bat = loaded_bats(res.bat)
    labels = [str(v) for v in bat["bat"].values]
    order = _shown_bats(labels)
    curves = _curve_per_bat(res)
    ss = res.sweet_spot
    fig = new_figure(figsize=(10.0, 1.4 + 2.0 * len(order)), layout="constrained")
    axes = fig.subplots(len(order), 2, squeeze=False, width_ratios=[1.3, 1])
    fig.suptitle(f"Sweet-spot definitions on each bat (right: the barrel, zoomed)\n(study: {res.name})", fontsize=10)
    handles = {}
    for (ax, zoom), i in zip(axes, order):
        b = bat.isel(bat=i)
        sub = None
        if ss is not None and i in curves:
            sub = ss.isel({d: k for d, k in curves[i].index.items() if d in ss.dims})
        found = []
        for k, (src, name, label, color, style, marker) in enumerate(DEFINITIONS):
            v = _value(sub if src == "sweet" else b, name)
            if math.isfinite(v) and not (src == "sweet" and _at_edge(res.summary, v)):
                found.append((k, name, label, color, style, marker, v))
        for a in (ax, zoom):
            top = _profile(a, b)
            for k, name, label, color, style, marker, v in found:
                if name == "position":
                    w = _value(sub, "width")
                    if math.isfinite(w):  # the band is centred for display; width = zone length
                        a.axvspan(v - w / 2, v + w / 2, color=color, alpha=0.08, lw=0)
                a.axvline(v, color=color, ls=style, lw=1.3)
                y = top * (0.95 - 0.3 * (k % 4))
                a.plot([v], [y], marker=marker, color=color, ms=7, ls="none")
                handles.setdefault(label, (marker, style, color))
            zcm, pivot = _value(b, "z_cm"), _value(b, "pivot_position")
            if math.isfinite(zcm):
                a.plot([zcm], [0], "+", color="black", ms=9)
            if math.isfinite(pivot):
                a.plot([pivot], [0], marker=6, color="black", ms=8)
            a.set_ylim(-top, top * 1.1)
            a.grid(alpha=0.3)
        if found:
            vals = [f[-1] for f in found]
            zoom.set_xlim(min(vals) - 0.03, max(vals) + 0.03)
            lines = [f"{f[2].split(' (')[0]}: {f[-1] * 100:.1f} cm" for f in found]
            zoom.text(1.02, 0.5, "\n".join(lines), transform=zoom.transAxes, fontsize=7, va="center")
        bb = _value(b, "bbcor_max")
        extra = f", BBCOR max {bb:.3f}" if math.isfinite(bb) else ""
        ax.set_title(f"{labels[i]}: {float(b['mass']):.3f} kg{extra}", fontsize=9, loc="left")
        ax.set_ylabel("radius (mm)", fontsize=8)
    axes[-1, 0].set_xlabel(Z_LABEL)
    axes[-1, 1].set_xlabel(Z_LABEL)
    legend = [Line2D([], [], color=c, ls=s, marker=m, label=lab) for lab, (m, s, c) in handles.items()]
    legend += [Line2D([], [], color="black", marker="+", ls="none", label="centre of mass"),
               Line2D([], [], color="black", marker=6, ls="none", label="pivot / grip (6 in)")]  # fmt: skip
    fig.legend(handles=legend, fontsize=7, ncol=3, loc="outside lower center")
    save(fig, path)
