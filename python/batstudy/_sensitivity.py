"""`batstudy.sobol_indices`: global sensitivity of a `sample` study's answers.

A study's ``sample`` block stores every drawn value as a coordinate of the ``sample``
dimension, so the inputs X and the outputs Y of a sensitivity analysis are both in the
results file. The first-order Sobol indices S1 (the share of Y's variance that each input
explains alone) are estimated from that one sample by SALib's RBD-FAST (Tarantola et al.
2006; Plischke 2010), which needs no special design. With correlated inputs (a
density-modulus pair) S1 of each partner includes what it explains through the other: read
them together. The total-order indices ST (what each input explains with all its
interactions) need Saltelli's design (``sample.method: saltelli``), whose rows the function
recognises in the file, and are estimated by Saltelli's and Jansen's estimators (SALib's
``sobol.analyze``; Saltelli et al. 2010).
"""

from __future__ import annotations

import os
from typing import Union

import numpy as np


def _groups(source):
    """`/summary` and `/sweet_spot` of a path, a DataTree, or a `/summary` Dataset (no
    `/sweet_spot` then)."""
    import xarray as xr

    if isinstance(source, xr.Dataset):
        return source, None
    if isinstance(source, xr.DataTree):
        sweet = source["sweet_spot"].to_dataset() if "sweet_spot" in source.children else None
        return source["summary"].to_dataset(), sweet
    import h5py

    with xr.open_dataset(source, engine="h5netcdf", group="summary") as s:
        summary = s.load()
    # a file without /sweet_spot (a run of one impact point) has only /summary, as its tree
    with h5py.File(source, "r") as f:
        has_sweet = "sweet_spot" in f
    if not has_sweet:
        return summary, None
    with xr.open_dataset(source, engine="h5netcdf", group="sweet_spot") as w:
        return summary, w.load()


def sobol_indices(
    source,
    output: str = "bbcor_max",
    *,
    dim: str = "sample",
    order: str = "first",
    seed: int = 0,
    **select,
):
    """Sobol indices of ``output`` over the sampled parameters of ``source`` (a results
    file's path, its :class:`xarray.DataTree` from :func:`open_results`, or its ``/summary``
    Dataset): a :class:`dict` parameter path → (index, its bootstrap confidence half-width).
    ``order="first"``: S1 from any sample (RBD-FAST); ``order="total"``: ST, from a sample
    drawn with ``sample.method: saltelli`` (a :class:`ValueError` otherwise).

    ``output`` is a ``/summary`` variable, ``sweet_spot.NAME`` a ``/sweet_spot`` one, or
    ``bbcor_max`` (the bat's BBCOR: the largest ``bbcor`` along ``impact_z``). Every other
    dimension must have one value: select it with keyword arguments, an integer as an index
    along a dimension, any other value as a coordinate's value (``case=2``,
    ``swing_omega=-40.0``). Needs SALib (``pip install 'batstudy[sensitivity]'``)."""
    from SALib.analyze import rbd_fast, sobol

    s, sweet = _groups(source)
    inputs = [c for c in s.coords if s[c].dims == (dim,) and "parameter_path" in s[c].attrs]
    if output == "bbcor_max":
        y = s.bbcor.max("impact_z")
    elif output.startswith("sweet_spot."):
        if sweet is None:
            raise ValueError(f"{output} is in /sweet_spot: pass the path or the tree, not /summary")
        y = sweet[output.split(".", 1)[1]]
    else:
        y = s[output]
    y = _selected(y, select).squeeze(drop=True)
    if y.dims != (dim,):
        others = [d for d in y.dims if d != dim]
        raise ValueError(f"{output} has dims {y.dims}: select one value of {others} (e.g. {others[0]}=0)")
    x = np.column_stack([s[c].values for c in inputs])
    keep = np.isfinite(y.values)
    problem = {
        "num_vars": len(inputs),
        "names": [s[c].attrs["parameter_path"] for c in inputs],
        "bounds": [[float(x[:, k].min()), float(x[:, k].max())] for k in range(len(inputs))],
    }
    if order == "first":
        r = rbd_fast.analyze(problem, x[keep], y.values[keep], seed=seed)
        return {n: (float(a), float(b)) for n, a, b in zip(problem["names"], r["S1"], r["S1_conf"])}
    if order != "total":
        raise ValueError(f"order={order!r}: allowed 'first' or 'total'")
    if not _is_saltelli(x):
        raise ValueError("total-order indices need Saltelli's design: draw the sample with `sample.method: saltelli`")
    # a failed point spoils its whole block of d + 2 rows: drop those blocks
    blocks = keep.reshape(-1, len(inputs) + 2).all(axis=1)
    yb = y.values.reshape(-1, len(inputs) + 2)[blocks].ravel()
    r = sobol.analyze(problem, yb, calc_second_order=False, seed=seed)
    return {n: (float(a), float(b)) for n, a, b in zip(problem["names"], r["ST"], r["ST_conf"])}


def _is_saltelli(x: np.ndarray) -> bool:
    """Whether the sample's rows are Saltelli's blocks: A, A with its k-th column from B for
    each k, then B (``sample.method: saltelli``)."""
    rows, d = x.shape
    if d == 0 or rows % (d + 2):
        return False
    blocks = x.reshape(rows // (d + 2), d + 2, d)
    a, b = blocks[:, 0], blocks[:, -1]
    for k in range(d):
        want = a.copy()
        want[:, k] = b[:, k]
        if not np.array_equal(blocks[:, k + 1], want):
            return False
    return True


def _selected(y, select):
    """`y` at one value of each selected dimension: an integer is an index along a dimension,
    anything else a value of a coordinate along one (`swing_omega=0` is the first swing speed,
    `swing_omega=0.0` the speed 0)."""
    for name, want in select.items():
        if name in y.dims and isinstance(want, (int, np.integer)) and not isinstance(want, bool):
            y = y.isel({name: want})
        elif name in y.dims:
            y = y.sel({name: want})
        elif name in y.coords and y[name].ndim == 1:
            y = y.swap_dims({y[name].dims[0]: name}).sel({name: want})
        else:
            raise KeyError(f"no dimension or coordinate {name!r} to select; there are: {', '.join(map(str, y.dims))}")
    return y
