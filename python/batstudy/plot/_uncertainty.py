"""Figures of uncertainty and design: what a `sample` study's scatter does to the answers
(:func:`uncertainty`), and the record of a design search (:func:`search`)."""

from __future__ import annotations

import numpy as np


def uncertainty(path, ax=None):
    """Two panels from a `sample` study: the bat's BBCOR over the sample (a histogram, the
    NCAA limit 0.50, the probability above it) and the sweet spot's position against the
    sampled modulus (its wander). Returns the two axes."""
    import matplotlib.pyplot as plt
    import xarray as xr

    with xr.open_dataset(path, engine="h5netcdf", group="summary") as s:
        bb = s.bbcor.max("impact_z").squeeze(drop=True).values
        modulus = s.bat_material_youngs_modulus.values
    with xr.open_dataset(path, engine="h5netcdf", group="sweet_spot") as w:
        pos = w.position.squeeze(drop=True).values
    with xr.open_dataset(path, engine="h5netcdf", group="uncertainty") as u:
        p_above = float(u.bbcor_max_above_limit.squeeze())
        lo, hi = (float(u.sweet_spot_position.sel(quantile=q).squeeze()) for q in (0.025, 0.975))
    if ax is None:
        _, ax = plt.subplots(1, 2, figsize=(10, 4), constrained_layout=True)
    a, b = ax
    a.hist(bb, bins=24, color="0.6", edgecolor="0.3")
    a.axvline(0.50, color="C3", label=f"NCAA limit 0.50: P(above) = {p_above:.2f}")
    a.set_xlabel("BBCOR (maximum along the barrel)")
    a.set_ylabel("samples")
    a.legend(loc="upper left", fontsize=8)
    b.scatter(modulus / 1e9, pos * 100, s=8, color="C0")
    b.axhspan(lo * 100, hi * 100, color="C0", alpha=0.15, label=f"95 % interval: {lo*100:.1f}-{hi*100:.1f} cm")
    b.set_xlabel("Young's modulus (GPa)")
    b.set_ylabel("sweet spot, cm from the knob")
    b.legend(loc="upper left", fontsize=8)
    return ax


def search(path, ax=None):
    """A design search from its `/optimize` group: each candidate's objective in the order
    evaluated (feasible filled, infeasible hollow), and the best feasible so far."""
    import matplotlib.pyplot as plt
    import xarray as xr

    with xr.open_dataset(path, engine="h5netcdf", group="optimize") as o:
        y, st, units, name = o.objective.values, o.status.values, o.attrs["objective_units"], o.attrs["objective"]
    if ax is None:
        _, ax = plt.subplots(figsize=(6, 4), constrained_layout=True)
    k = np.arange(len(y))
    ok = st == 0
    ax.scatter(k[ok], y[ok], s=10, color="C0", label="feasible")
    ax.scatter(k[~ok], y[~ok], s=10, facecolors="none", edgecolors="0.5", label="outside a limit")
    best = np.fmax.accumulate(np.where(ok, y, np.nan))
    ax.plot(k, best, color="C3", label="best feasible so far")
    ax.set_xlabel("candidate")
    ax.set_ylabel(f"{name} ({units})")
    ax.legend(fontsize=8)
    return ax



def _file_with(res, group: str, what: str):
    """The results file of `res` if it holds `group`, else Skip naming what makes one."""
    from ._curves import Skip

    if res.path is None or group not in res.tree.children:
        raise Skip(f"no /{group} group in this file ({what})")
    return res.path


def uncertainty_figure(res, path):
    """`batstudy figures`' `uncertainty`: :func:`uncertainty` of a `sample` study's file."""
    from ._draw import new_figure, save

    source = _file_with(res, "uncertainty", "a `sample` study writes one: studies/uncertainty.yaml")
    fig = new_figure(figsize=(10, 4), layout="constrained")
    fig.suptitle(f"The answers over the sample (study: {res.name})", fontsize=10)
    uncertainty(source, ax=fig.subplots(1, 2))
    save(fig, path)


def search_figure(res, path):
    """`batstudy figures`' `search`: :func:`search` of a design search's file."""
    from ._draw import new_figure, save

    source = _file_with(res, "optimize", "`batstudy optimize` writes one: studies/design_bbcor.yaml")
    fig = new_figure(figsize=(6, 4), layout="constrained")
    fig.suptitle(f"The design search (study: {res.name})", fontsize=10)
    search(source, ax=fig.subplots())
    save(fig, path)


UNCERTAINTY_FIGURES = {"uncertainty": uncertainty_figure, "search": search_figure}
