"""`batstudy.sobol_indices`: global sensitivity of a `sample` study's answers.

A study's ``sample`` block stores every drawn value as a coordinate of the ``sample``
dimension, so the inputs X and the outputs Y of a sensitivity analysis are both in the
results file. The first-order Sobol indices S1 (the share of Y's variance that each input
explains alone) are estimated from that one sample by SALib's RBD-FAST (Tarantola et al.
2006; Plischke 2010), which, unlike Saltelli's estimator, needs no special design. With
correlated inputs (a density-modulus pair) S1 of each partner includes what it explains
through the other: read them together.
"""

from __future__ import annotations

import os
from typing import Union

import numpy as np


def sobol_indices(
    path: Union[str, os.PathLike],
    output: str = "bbcor_max",
    *,
    dim: str = "sample",
    seed: int = 0,
):
    """First-order Sobol indices of ``output`` over the sampled parameters of the results
    file ``path``: a :class:`dict` parameter path → (S1, its bootstrap confidence half-width).

    ``output`` is a ``/summary`` variable, ``sweet_spot.NAME`` a ``/sweet_spot`` one, or
    ``bbcor_max`` (the bat's BBCOR: the largest ``bbcor`` along ``impact_z``). Every other
    dimension must have one value (select it first in a study of your own). Needs SALib
    (``pip install 'batstudy[sensitivity]'``)."""
    import xarray as xr
    from SALib.analyze import rbd_fast

    with xr.open_dataset(path, engine="h5netcdf", group="summary") as s:
        s = s.load()
    inputs = [c for c in s.coords if s[c].dims == (dim,) and "parameter_path" in s[c].attrs]
    if output == "bbcor_max":
        y = s.bbcor.max("impact_z")
    elif output.startswith("sweet_spot."):
        with xr.open_dataset(path, engine="h5netcdf", group="sweet_spot") as w:
            y = w[output.split(".", 1)[1]].load()
    else:
        y = s[output]
    y = y.squeeze(drop=True)
    if y.dims != (dim,):
        raise ValueError(f"{output} has dims {y.dims}: select one value of every dim but {dim!r}")
    x = np.column_stack([s[c].values for c in inputs])
    keep = np.isfinite(y.values)
    problem = {
        "num_vars": len(inputs),
        "names": [s[c].attrs["parameter_path"] for c in inputs],
        "bounds": [[float(x[:, k].min()), float(x[:, k].max())] for k in range(len(inputs))],
    }
    r = rbd_fast.analyze(problem, x[keep], y.values[keep], seed=seed)
    return {n: (float(a), float(b)) for n, a, b in zip(problem["names"], r["S1"], r["S1_conf"])}
