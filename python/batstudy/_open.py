"""open(): a results file as a lazily loaded xarray.DataTree, histories kept sparse."""

from __future__ import annotations

import os
import threading
from typing import Any, Union

import h5py
import numpy as np
import xarray as xr
from xarray.backends import BackendArray
from xarray.core import indexing

GROUPS = ("summary", "sweet_spot", "bat", "errors")
HISTORY_DIM = "history"


def _stored_positions(ds: h5py.Dataset, rank: int) -> np.ndarray:
    """Grid positions of the histories stored in `ds`: one chunk is one history, and the
    chunks of points without a history are never allocated (docs/layout.md)."""
    dsid = ds.id
    n = dsid.get_num_chunks()
    chunk = ds.chunks
    pos = np.empty((n, rank), dtype=np.int64)
    for i in range(n):
        offset = dsid.get_chunk_info(i).chunk_offset
        pos[i] = [o // c for o, c in zip(offset[:rank], chunk[:rank])]
    # flat (row-major) order, the order of the summary
    if n:
        order = np.lexsort(pos.T[::-1])
        pos = pos[order]
    return pos


class _SparseHistoryArray(BackendArray):
    """(history, time[, z]) view of a dense (…grid…, time[, z]) HDF5 dataset: row k is the
    stored history at grid position `positions[k]`. Reads only the rows asked for."""

    def __init__(self, path: str, name: str, positions: np.ndarray, tail: tuple, dtype):
        self.path, self.name, self.positions = path, name, positions
        self.shape = (len(positions),) + tuple(tail)
        self.dtype = np.dtype(dtype)
        self._lock = threading.Lock()

    def __getitem__(self, key):
        return indexing.explicit_indexing_adapter(
            key, self.shape, indexing.IndexingSupport.OUTER, self._read
        )

    def _read(self, key: tuple) -> np.ndarray:
        rows = np.arange(self.shape[0])[key[0]]
        tail_key = tuple(key[1:])
        scalar = np.ndim(rows) == 0
        rows = np.atleast_1d(rows)
        with self._lock, h5py.File(self.path, "r") as f:
            ds = f["history"][self.name]
            parts = [ds[tuple(int(i) for i in self.positions[r]) + tail_key] for r in rows]
        if not parts:
            tail_shape = np.empty(self.shape[1:])[tail_key].shape
            return np.empty((0,) + tail_shape, dtype=self.dtype)
        out = np.stack(parts)
        return out[0] if scalar else out


def _sparse_history(path: str, summary: xr.Dataset) -> xr.Dataset | None:
    with h5py.File(path, "r") as f:
        if "history" not in f:
            return None
        g = f["history"]
        dims = [d for d in summary["status"].dims]
        rank = len(dims)
        names = [
            k
            for k, v in g.items()
            if isinstance(v, h5py.Dataset) and v.ndim > rank and v.chunks is not None
        ]
        if not names:
            return None
        positions = _stored_positions(g[names[0]], rank)
        time = g["time"][...]
        zs = g["z"][...]
        meta = {k: (g[k].shape[rank:], g[k].dtype, dict(g[k].attrs)) for k in names}
    data_vars = {}
    for k, (tail, dtype, attrs) in meta.items():
        vdims = (HISTORY_DIM, "time") + (("z",) if len(tail) == 2 else ())
        arr = indexing.LazilyIndexedArray(_SparseHistoryArray(path, k, positions, tail, dtype))
        keep = {a: v for a, v in attrs.items() if a in ("units", "long_name", "description", "precision")}
        data_vars[k] = xr.Variable(vdims, arr, attrs={a: _plain(v) for a, v in keep.items()})
    coords: dict[str, Any] = {
        "time": ("time", time, {"units": "s", "long_name": "time since first contact"}),
        "z": ("z", zs, {"units": "m", "long_name": "position from the knob"}),
    }
    # every coordinate of the summary, taken at each stored history's grid position
    for name, c in summary.coords.items():
        if not set(c.dims) <= set(dims):
            continue
        idx = tuple(positions[:, dims.index(d)] for d in c.dims)
        values = c.values[idx] if c.dims else np.repeat(c.values, len(positions))
        coords[name] = (HISTORY_DIM, values, dict(c.attrs))
    for k, d in enumerate(dims):
        if d not in coords:
            coords[d] = (HISTORY_DIM, positions[:, k], {"long_name": f"index along {d}"})
    ds = xr.Dataset(data_vars, coords=coords)
    ds.attrs["description"] = (
        "the stored time histories only: one row per point that has one, with that point's "
        "coordinates (a sparse view of the file's dense /history group)"
    )
    return ds


def _plain(v):
    if isinstance(v, bytes):
        return v.decode()
    if isinstance(v, np.ndarray) and v.shape == ():
        return v.item()
    return v


def open(path: Union[str, os.PathLike]) -> xr.DataTree:
    """Open a results file as an :class:`xarray.DataTree` (lazily: nothing is read until
    used).

    - ``/summary``: one value per point; the study's grid as named dimensions, with the
      resolved parameter values as coordinates (never NaN for a value a preset supplies)
      and, for a ``points`` or ``zip`` block, a text label coordinate (e.g. ``case_label``).
    - ``/sweet_spot``, ``/bat``, ``/errors``: as in the file (``docs/layout.md``).
    - ``/history``: only the stored histories, along a dimension ``history``, each row
      with its point's coordinates (``impact_z``, ``case_label``, …); see
      :func:`histories`.

    The root carries the file's attributes (study name and text, counts, version).
    """
    path = os.fspath(path)
    nodes: dict[str, xr.Dataset] = {}
    with h5py.File(path, "r") as f:
        root_attrs = {k: _plain(v) for k, v in f.attrs.items()}
        present = [g for g in GROUPS if g in f]
    nodes["/"] = xr.Dataset(attrs=root_attrs)
    for g in present:
        nodes[f"/{g}"] = xr.open_dataset(path, group=g, engine="h5netcdf")
    if "summary" in present:
        hist = _sparse_history(path, nodes["/summary"])
        if hist is not None:
            nodes["/history"] = hist
    return xr.DataTree.from_dict(nodes)


def histories(source: Union[xr.DataTree, str, os.PathLike], **where: Any) -> xr.Dataset:
    """The stored histories of a results tree (or file), as a Dataset along ``history``.

    Keyword arguments select by coordinate value, e.g.
    ``histories(tree, case_label="base", impact_z=0.6, swing_omega=0)``; a value may be a
    list of values. Floats match to within 1e-9 of their magnitude.
    """
    tree = source if isinstance(source, xr.DataTree) else open(source)
    if "history" not in tree.children:
        raise KeyError("this results file has no stored histories (the study's `history` block)")
    ds = tree["history"].to_dataset()
    mask = np.ones(ds.sizes[HISTORY_DIM], dtype=bool)
    for name, want in where.items():
        if name not in ds.coords:
            raise KeyError(
                f"no coordinate {name!r}; the histories have: {', '.join(sorted(ds.coords))}"
            )
        have = ds.coords[name].values
        wants = want if isinstance(want, (list, tuple, np.ndarray)) else [want]
        m = np.zeros_like(mask)
        for w in wants:
            if isinstance(w, (float, int, np.floating, np.integer)) and have.dtype.kind == "f":
                m |= np.isclose(have, float(w), rtol=1e-9, atol=1e-12)
            else:
                m |= have == w
        mask &= m
    return ds.isel({HISTORY_DIM: np.flatnonzero(mask)})
