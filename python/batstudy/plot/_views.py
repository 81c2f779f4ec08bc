"""Figures of any results file, for a notebook or a script: each takes a results file (or the
tree of :func:`batstudy.open_results`), selects by coordinate value as
:func:`batstudy.histories` does (``case_label="base"``, ``model="wave"``, ``impact_z=0.6``),
draws on `ax` (default: a new pyplot figure) and returns the axes.

A dimension that is neither drawn along nor selected is taken at its first value; the title
says which.
"""

from __future__ import annotations

import os
from typing import Optional, Sequence, Union

import numpy as np
import xarray as xr

from .._open import dim_labels, history_grid_index, open_results, value_text, where_index
from ._curves import IMPACT, Results, Skip
from ._draw import COLORS, Z_LABEL, draw_profiles, loaded_bats

Source = Union[str, os.PathLike, xr.DataTree]
MOST_LINES = 12  # a history figure draws at most this many histories


def _tree(source: Source) -> xr.DataTree:
    return source if isinstance(source, xr.DataTree) else open_results(source)


def _group(tree: xr.DataTree, name: str) -> xr.Dataset:
    if name not in tree.children:
        raise Skip(f"the file has no /{name}")
    return tree[name].to_dataset()


def _axes(ax):
    if ax is not None:
        return ax
    import matplotlib.pyplot as plt

    return plt.subplots(figsize=(7.5, 4.8), layout="constrained")[1]


def axis_label(da: xr.DataArray) -> str:
    """``exit speed (m/s)``: the long name and units of a variable (no units for ``1``)."""
    units = str(da.attrs.get("units", ""))
    name = str(da.attrs.get("long_name", da.name))
    return f"{name} ({units})" if units not in ("", "1") else name


def pick(ds: xr.Dataset, var: str, keep: Sequence[str], where: dict) -> tuple[xr.Dataset, list[str]]:
    """`ds` at the entries `where` selects, with every dimension of `var` not in `keep` at
    one entry (its first selected): ``(selection, ["dim=label", ...] of the dims so fixed)``."""
    if var not in ds:
        raise KeyError(f"no variable {var!r}; there are: {', '.join(sorted(map(str, ds.data_vars)))}")
    ds = ds.isel(where_index(ds, where))
    fixed = [str(d) for d in ds[var].dims if d not in keep]
    if any(ds.sizes[d] == 0 for d in ds[var].dims):
        raise Skip(f"nothing matches {where}")
    texts = [f"{d}={dim_labels(ds, d)[0]}" for d in fixed]
    return ds.isel({d: 0 for d in fixed}), texts


def _title(ax, what: str, fixed: list[str], tree: xr.DataTree) -> None:
    study = tree.attrs.get("study_name", "")
    lines = [what] + ([", ".join(fixed)] if fixed else []) + ([f"(study: {study})"] if study else [])
    ax.set_title("\n".join(lines), fontsize=10)
    ax.grid(alpha=0.3)


def exit_speed(source: Source, by: Optional[str] = None, *, var: str = "exit_speed", ax=None, **where):
    """`var` of /summary (default exit speed) against impact position, one line per value
    of the dimension `by` (``"swing_omega"``, ``"case"``, ``"model"``; None: one line)."""
    tree = _tree(source)
    summary = _group(tree, "summary")
    ds, fixed = pick(summary, var, [IMPACT] + ([by] if by else []), where)
    ax = _axes(ax)
    da = ds[var]
    if by is None:
        ax.plot(ds[IMPACT], da, color="black", lw=1.8)
    else:
        for i, label in enumerate(dim_labels(ds, by)):
            ax.plot(ds[IMPACT], da.isel({by: i}), color=COLORS[i % len(COLORS)], lw=1.6, label=f"{by}={label}")
        ax.legend(fontsize=8)
    ax.set_xlabel(axis_label(ds[IMPACT]))
    ax.set_ylabel(axis_label(da))
    _title(ax, f"{da.attrs.get('long_name', var)} against impact position", fixed, tree)
    return ax


def sweet_spots(source: Source, against: str, *, var: str = "position", ax=None, **where):
    """`var` of /sweet_spot (default the sweet spot's position; ``exit_speed``, ``width``,
    ``min_vibration_position``, ...) against the dimension `against`. The position is drawn
    with its sweet zone (``width``, centred on it for display)."""
    tree = _tree(source)
    sweet = _group(tree, "sweet_spot")
    ds, fixed = pick(sweet, var, [against], where)
    ax = _axes(ax)
    labels = dim_labels(ds, against)
    numeric = against in ds.coords and ds[against].dtype.kind in "fiu" and f"{against}_label" not in ds.coords
    x = ds[against].values if numeric else np.arange(len(labels))
    y = ds[var].transpose(against).values
    if var == "position" and "width" in ds:
        half = ds["width"].transpose(against).values / 2
        ax.errorbar(x, y, yerr=half, fmt="o-", color="black", capsize=3, label="sweet spot, with its zone's width")
        ax.legend(fontsize=8)
    else:
        ax.plot(x, y, "o-", color="black")
    if numeric:
        ax.set_xlabel(axis_label(ds[against]))
    else:
        ax.set_xticks(x, labels, rotation=30, ha="right", fontsize=7)
        ax.set_xlabel(against)
    ax.set_ylabel(axis_label(ds[var]))
    _title(ax, f"{ds[var].attrs.get('long_name', var)} against {against}", fixed, tree)
    return ax


def _stored(tree: xr.DataTree, var: str, where: dict) -> tuple[xr.Dataset, np.ndarray]:
    """The stored histories `where` selects, and their rows in ``tree["history"]``."""
    if "history" not in tree.children or var not in tree["history"]:
        raise Skip(f"the file stores no {var} history")
    stored = tree["history"].to_dataset()
    rows = where_index(stored, where).get("history", np.arange(stored.sizes["history"]))
    if not len(rows):
        raise Skip(f"no stored {var} history matches {where}")
    return stored.isel(history=rows), rows


def _row_labels(tree: xr.DataTree, h: xr.Dataset, every: bool = False) -> list[str]:
    """A label per history row: the coordinates of the summary's dims (a dim's label
    coordinate where it has one), those that differ among the rows unless `every`."""
    dims = tree["summary"]["status"].dims
    names = [f"{d}_label" if f"{d}_label" in h.coords else str(d) for d in dims]
    texts = {n: [value_text(v) for v in h[n].values.tolist()] for n in names}
    shown = names if every else [n for n in names if len(set(texts[n])) > 1] or names[:1]
    return [", ".join(f"{n}={texts[n][r]}" for n in shown) for r in range(h.sizes["history"])]


def history(source: Source, var: str = "force", *, ax=None, **where):
    """A stored history of one value per time (``force``, ``compression``,
    ``ball_velocity``, ...) against time, one line per stored history `where` selects (at
    most 12)."""
    tree = _tree(source)
    h, _ = _stored(tree, var, where)
    if h[var].dims != ("history", "time"):
        raise ValueError(f"{var} has dims {h[var].dims}: draw it with batstudy.plot.displacement")
    ax = _axes(ax)
    labels = _row_labels(tree, h)
    t_ms = h["time"].values * 1e3
    drawn = min(MOST_LINES, h.sizes["history"])
    for row in range(drawn):
        ax.plot(t_ms, h[var].isel(history=row).values, color=COLORS[row % len(COLORS)], label=labels[row])
    ax.legend(fontsize=7)
    ax.set_xlabel("time since first contact (ms)")
    ax.set_ylabel(axis_label(h[var]))
    shown = [f"the first {drawn} of {h.sizes['history']} histories"] if drawn < h.sizes["history"] else []
    _title(ax, f"{h[var].attrs.get('long_name', var)} against time", shown, tree)
    return ax


def _flex(tree: xr.DataTree, row: int, z_impact: float) -> xr.DataArray:
    """The displacement of stored history `row` less the bat's rigid motion."""
    res = Results(tree)
    index = {d: int(i[row]) for d, i in history_grid_index(tree).items() if d != IMPACT}
    curve = next(c for c in res.curves if c.index == index)
    return res.flex_displacement(curve, z_impact)[1]


def displacement(source: Source, times: Optional[Sequence[float]] = None, *, rigid: bool = True, ax=None, **where):
    """The bat's displacement along its length at several `times` (s; default six across the
    stored duration) for the first stored history `where` selects. ``rigid=False`` removes
    the bat's rigid motion (the recorded one, else projected out)."""
    tree = _tree(source)
    h, rows = _stored(tree, "displacement", where)
    z_impact = float(h[IMPACT].values[0])
    disp = h["displacement"].isel(history=0).load() if rigid else _flex(tree, int(rows[0]), z_impact)
    t = disp["time"].values
    times = np.linspace(t[0], t[-1], 6) if times is None else np.asarray(times, dtype=float)
    ax = _axes(ax)
    for k, wanted in enumerate(times):
        i = int(np.argmin(np.abs(t - wanted)))
        ax.plot(disp["z"], disp.isel(time=i) * 1e3, color=COLORS[k % len(COLORS)], label=f"t = {t[i] * 1e3:.2f} ms")
    ax.axvline(z_impact, color="firebrick", ls=":", lw=1, label=f"impact at {z_impact:.2f} m")
    ax.legend(fontsize=7)
    ax.set_xlabel(Z_LABEL)
    ax.set_ylabel("displacement (mm)")
    how = "with the rigid motion" if rigid else disp.attrs["rigid_removal"]
    _title(ax, f"the bat's displacement ({how})", _row_labels(tree, h, every=True)[:1], tree)
    return ax


def bat_profiles(source: Source, *, ax=None):
    """Every distinct bat profile of /bat: outer radius solid, inner (hollow part) dashed."""
    tree = _tree(source)
    bat = loaded_bats(_group(tree, "bat"))
    ax = _axes(ax)
    draw_profiles(ax, bat)
    ax.legend(fontsize=7)
    ax.set_xlabel(Z_LABEL)
    _title(ax, "bat profiles (outer radius solid, inner dashed)", [], tree)
    return ax
