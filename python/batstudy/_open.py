"""open_results(): a results file as a lazily loaded xarray.DataTree, histories kept sparse."""

from __future__ import annotations

import math
import os
import posixpath
import threading
from typing import Any, Mapping, Union

import h5py
import numpy as np
import xarray as xr
from xarray.backends import BackendArray
from xarray.core import indexing

from ._files import check_structure, reading, require_results
from ._modal import ModalReader

GROUPS = ("summary", "sweet_spot", "bat", "errors", "uncertainty")
# `/optimize`'s per-variable and per-constraint columns (design_0, …), stacked in tidy form
_STACKED = (("design", "variable"), ("constraint", "constraint"), ("margin", "constraint"))
# the stacked names (a variable may not take its dimension's name)
_TIDY_NAME = {"design": "design", "constraint": "constraint_value", "margin": "margin"}
HISTORY_DIM = "history"


def _chunk_offsets(ds: h5py.Dataset) -> np.ndarray:
    """The element offsets of every allocated chunk of `ds`, (chunks, ndim): one pass over the
    chunk index (H5Dchunk_iter, h5py >= 3.8 with HDF5 >= 1.12.1). Without it, one
    H5Dget_chunk_info call per chunk, each of which walks the index from its start (quadratic:
    27 s for 20 000 histories)."""
    dsid = ds.id
    if hasattr(dsid, "chunk_iter"):
        offsets: list[tuple] = []
        dsid.chunk_iter(lambda info: offsets.append(info.chunk_offset))
    else:
        offsets = [dsid.get_chunk_info(i).chunk_offset for i in range(dsid.get_num_chunks())]
    return np.array(offsets, dtype=np.int64).reshape(len(offsets), ds.ndim)


def _stored_positions(ds: h5py.Dataset, rank: int) -> np.ndarray:
    """Grid positions of the histories stored in `ds`, (histories, rank), in flat (row-major)
    order, the order of the summary. The chunks of points without a history are never
    allocated (docs/layout.md). A chunk that spans several points along the study's last
    dim (a group) is allocated when one of them has a history; a point of it without one
    holds the fill value, NaN, throughout, and is left out."""
    starts = _chunk_offsets(ds)[:, :rank]
    span = ds.chunks[rank - 1] if rank else 1
    pos = _grouped_positions(ds, rank, starts, span) if span > 1 else starts
    return pos[np.lexsort(pos.T[::-1])] if len(pos) else pos


def _grouped_positions(ds: h5py.Dataset, rank: int, starts: np.ndarray, span: int) -> np.ndarray:
    """The points of chunks spanning `span` points along the last study dim (`starts`: each
    chunk's first) whose values are not all the fill value: one read per chunk."""
    last = ds.shape[rank - 1]
    out: list[np.ndarray] = []
    for start in starts:
        first, stop = int(start[-1]), min(int(start[-1]) + span, last)
        slab = np.asarray(ds[tuple(int(i) for i in start[:-1]) + (slice(first, stop),)])
        stored = ~np.isnan(slab.reshape(stop - first, -1)).all(axis=1)
        for j in np.flatnonzero(stored):
            p = start.copy()
            p[-1] = first + j
            out.append(p)
    return np.array(out, dtype=np.int64).reshape(len(out), rank)


class _HistoryRows(BackendArray):
    """A lazy array whose first axis is the stored histories: reads only the rows asked for
    (`_read`, given xarray's outer-indexing key)."""

    def __getitem__(self, key):
        return indexing.explicit_indexing_adapter(
            key, self.shape, indexing.IndexingSupport.OUTER, self._read
        )

    def _rows(self, key: tuple) -> tuple[np.ndarray, bool]:
        """The history rows a key selects (at least one dimension) and whether it asked for
        a single row."""
        rows = np.arange(self.shape[0])[key[0]]
        return np.atleast_1d(rows), np.ndim(rows) == 0


class _SparseHistoryArray(_HistoryRows):
    """(history, time[, z]) view of a dense (…grid…, time[, z]) HDF5 dataset: row k is the
    stored history at grid position `positions[k]`. Reads only the rows asked for."""

    def __init__(self, path: str, name: str, positions: np.ndarray, tail: tuple, dtype):
        self.path, self.name, self.positions = path, name, positions
        self.shape = (len(positions),) + tuple(tail)
        self.dtype = np.dtype(dtype)
        self._lock = threading.Lock()

    def _read(self, key: tuple) -> np.ndarray:
        rows, scalar = self._rows(key)
        tail_key = tuple(key[1:])
        with self._lock, reading(self.path), h5py.File(self.path, "r") as f:
            ds = f["history"][self.name]
            parts = [ds[tuple(int(i) for i in self.positions[r]) + tail_key] for r in rows]
        if not parts:
            tail_shape = np.empty(self.shape[1:])[tail_key].shape
            return np.empty((0,) + tail_shape, dtype=self.dtype)
        out = np.stack(parts)
        return out[0] if scalar else out


class _ModalDisplacementArray(_HistoryRows):
    """(history, time, z) displacement computed from the file's modal form, row by row as
    asked for (``_modal``)."""

    def __init__(self, path: str, positions: np.ndarray, n_time: int, z: np.ndarray):
        self.path, self.positions, self.z = path, positions, np.asarray(z, dtype=float)
        self.shape = (len(positions), n_time, len(self.z))
        self.dtype = np.dtype("float64")
        self._lock = threading.Lock()

    def _read(self, key: tuple) -> np.ndarray:
        rows, scalar = self._rows(key)
        with self._lock, reading(self.path), h5py.File(self.path, "r") as f:
            reader = ModalReader(f)
            parts = [reader.displacement(tuple(int(i) for i in self.positions[r]), self.z)[key[1:]]
                     for r in rows]  # fmt: skip
        if not parts:
            tail_shape = np.empty(self.shape[1:])[tuple(key[1:])].shape
            return np.empty((0,) + tail_shape, dtype=self.dtype)
        out = np.stack(parts)
        return out[0] if scalar else out


def _tail_dims(ds: h5py.Dataset, rank: int) -> tuple:
    """The names of a history variable's dims after the study's (its dimension scales)."""
    names = []
    for i in range(rank, ds.ndim):
        scales = ds.dims[i]
        names.append(posixpath.basename(scales[0].name) if len(scales) else f"dim_{i}")
    return tuple(names)


def _history_parts(path: str, summary: xr.Dataset) -> tuple | None:
    """What the sparse view of ``/history`` needs from the file: the stored positions, time,
    z, each variable's (dims, shape, dtype, attributes) and the extra coordinates."""
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
        # one chunk per history (the modal coordinates may take several)
        one_chunk = [k for k in names if k != "modal_coordinate"] or names
        positions = _stored_positions(g[one_chunk[0]], rank)
        time = g["time"][...]
        zs = g["z"][...]
        meta = {k: (_tail_dims(g[k], rank), g[k].shape[rank:], g[k].dtype, dict(g[k].attrs))
                for k in names}  # fmt: skip
        extra = {k: g[k][...] for k in ("bat_mode", "shape_point", "flight_time") if k in g}
    return dims, positions, time, zs, meta, extra


def _sparse_history(path: str, summary: xr.Dataset, parts: tuple, z: Any = None) -> xr.Dataset:
    dims, positions, time, zs, meta, extra = parts
    modal = "modal_coordinate" in meta
    if z is not None and not modal:
        raise ValueError("z= needs the displacement's modal form (history.displacement: modal); "
                         "this file stores it on its grid")  # fmt: skip
    data_vars = {}
    for k, (vdims, tail, dtype, attrs) in meta.items():
        arr = indexing.LazilyIndexedArray(_SparseHistoryArray(path, k, positions, tail, dtype))
        keep = {a: v for a, v in attrs.items() if a in ("units", "long_name", "description", "precision")}
        data_vars[k] = xr.Variable((HISTORY_DIM,) + vdims, arr, attrs={a: _plain(v) for a, v in keep.items()})
    if modal:
        zs = zs if z is None else np.atleast_1d(np.asarray(z, dtype=float))
        arr = indexing.LazilyIndexedArray(_ModalDisplacementArray(path, positions, len(time), zs))
        data_vars["displacement"] = xr.Variable((HISTORY_DIM, "time", "z"), arr, attrs={
            "units": "m", "long_name": "bat displacement",
            "description": "bat transverse displacement, computed from the stored modal form "
                           "(linear in z between the bat's shape points; NaN beyond the bat)",
        })  # fmt: skip
    coords: dict[str, Any] = {
        "time": ("time", time, {"units": "s", "long_name": "time since first contact"}),
        "z": ("z", zs, {"units": "m", "long_name": "position from the knob"}),
    }
    for k, v in extra.items():
        units = "s" if k == "flight_time" else "1"
        coords[k] = (k, v, {"units": units, "long_name": k.replace("_", " ")})
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


def _stack(ds: xr.Dataset, stem: str, dim: str) -> xr.DataArray:
    """`stem_0`, `stem_1`, … of `ds` (one per entry of `dim`, each with its own units) as one
    variable along (candidate, `dim`); the units per entry in the coordinate `{dim}_units`."""
    parts = [ds[f"{stem}_{k}"] for k in range(ds.sizes.get(dim, 0))]
    if not parts:  # a search without constraints: an empty column block
        empty = np.empty((ds.sizes["candidate"], 0))
        out = xr.DataArray(empty, dims=("candidate", dim), coords={dim: np.array([], dtype=str)})
        out.attrs = {"long_name": stem, "description": f"{stem} of each candidate along {dim} (none)"}
        return out
    out = xr.concat(parts, dim=dim).transpose("candidate", dim)
    out = out.assign_coords({dim: ds[dim].values})
    units = [str(p.attrs.get("units", "")) for p in parts]
    out = out.assign_coords({f"{dim}_units": (dim, units, {"long_name": f"units of each {dim}"})})
    out.attrs = {"long_name": stem, "units": units[0] if len(set(units)) == 1 else "mixed",
                 "description": f"{stem} of each candidate along {dim} (units per {dim}: {dim}_units)"}
    return out


def _tidy_optimize(path: str) -> tuple[xr.Dataset, xr.Dataset]:
    """`/optimize` with its columns stacked (`design(candidate, variable)`,
    `constraint_value(candidate, constraint)`, `margin(candidate, constraint)`), and the best
    feasible design as a Dataset of its own."""
    with xr.open_dataset(path, group="optimize", engine="h5netcdf") as raw:
        raw = raw.load()
    stacked = {_TIDY_NAME[stem]: _stack(raw, stem, dim) for stem, dim in _STACKED}
    drop = [v for v in raw.data_vars if any(v.startswith(f"{stem}_") and v[len(stem) + 1:].isdigit()
                                            for stem, _ in _STACKED)]  # fmt: skip
    tidy = raw.drop_vars(drop).assign(stacked)
    attrs = {k: _plain(v) for k, v in raw.attrs.items()}
    best_index = int(attrs.get("best_candidate", -1))
    best = xr.Dataset(attrs={"description": "the best feasible design of the search (none: no candidate met "
                                            "every constraint)"})  # fmt: skip
    tidy.attrs = {k: v for k, v in attrs.items() if not k.startswith("best")}
    if best_index >= 0:
        best = tidy[["design", "constraint_value", "margin", "objective"]].sel(candidate=best_index)
        best.attrs = {"description": "the best feasible design of the search, its constraints' values and "
                                     "margins, and its objective"}  # fmt: skip
    return tidy, best


def open_results(path: Union[str, os.PathLike], z: Any = None) -> xr.DataTree:
    """Open a results file as an :class:`xarray.DataTree` (also ``batstudy.open``).

    Lazily: at open only metadata is read (attributes, dimension coordinates, and the
    chunk index of ``/history``, in one pass), never a variable's values until used.

    - ``/summary``: one value per point; the study's grid as named dimensions, with the
      resolved parameter values as coordinates (never NaN for a value a preset supplies)
      and, for a ``points`` or ``zip`` block, a text label coordinate (e.g. ``case_label``).
    - ``/sweet_spot``, ``/bat``, ``/errors``, ``/uncertainty`` (a sampled study's): as in
      the file (``docs/layout.md``).
    - ``/optimize`` (a design search's) in tidy form: ``design(candidate, variable)``,
      ``constraint_value(candidate, constraint)`` and ``margin(candidate, constraint)``,
      their units per entry in ``variable_units`` and ``constraint_units``, beside
      ``objective``, ``status``, ``message`` and the scaled forms; ``/optimize/best`` the
      best feasible design as a Dataset (``design``, ``constraint_value``, ``margin``,
      ``objective``, its ``candidate`` a coordinate), empty when no candidate met the
      constraints.
    - ``/history``: only the stored histories, along a dimension ``history``, each row
      with its point's coordinates (``impact_z``, ``case_label``, …); see
      :func:`histories`. A file that stores the bat's displacement in modal form
      (``history.displacement: modal``) gets ``displacement(history, time, z)`` computed
      from it, row by row as read, at the study's grid ``z`` or at the positions given as
      `z` (m from the knob, any number of them; NaN beyond the bat).

    The root carries the file's attributes (study name and text, counts, version). Every
    numeric variable has a CF ``units`` attribute, every variable a ``long_name``.

    Raises :class:`~batstudy.ResultsFileError` naming the file for one that is not a
    complete batstudy results file: not HDF5, damaged (checked before HDF5 reads it, which
    could hang on it), or another program's HDF5.
    """
    path = os.fspath(path)
    check_structure(path)
    nodes: dict[str, xr.Dataset] = {}
    with reading(path):
        with h5py.File(path, "r") as f:
            require_results(path, f)
            root_attrs = {k: _plain(v) for k, v in f.attrs.items()}
            present = [g for g in GROUPS if g in f]
            searched = "optimize" in f
        nodes["/"] = xr.Dataset(attrs=root_attrs)
        for g in present:
            nodes[f"/{g}"] = xr.open_dataset(path, group=g, engine="h5netcdf")
        if searched:
            nodes["/optimize"], nodes["/optimize/best"] = _tidy_optimize(path)
        parts = _history_parts(path, nodes["/summary"])
    if parts is not None:
        nodes["/history"] = _sparse_history(path, nodes["/summary"], parts, z)
    return xr.DataTree.from_dict(nodes)


# `batstudy.open`: the same function (not in `__all__`, so `from batstudy import *` leaves the
# builtin `open` alone)
open = open_results


def _matches(have: np.ndarray, want: Any) -> np.ndarray:
    """Which of `have` equal `want` (a value or a list of values); floats to within 1e-9 of
    their magnitude."""
    wants = want if isinstance(want, (list, tuple, np.ndarray)) else [want]
    mask = np.zeros(have.shape, dtype=bool)
    for w in wants:
        if isinstance(w, (float, int, np.floating, np.integer)) and have.dtype.kind == "f":
            mask |= np.isclose(have, float(w), rtol=1e-9, atol=1e-12)
        else:
            mask |= have == w
    return mask


def where_index(ds: xr.Dataset, where: Mapping[str, Any]) -> dict[str, np.ndarray]:
    """``{dim: indices}`` of the entries of `ds` whose coordinates match `where`
    (``{coordinate: value or list of values}``, each coordinate along one dimension, e.g.
    ``case_label="base"`` selects along ``case``); for ``ds.isel``."""
    masks: dict[str, np.ndarray] = {}
    for name, want in where.items():
        if name not in ds.coords:
            raise KeyError(f"no coordinate {name!r}; there are: {', '.join(sorted(map(str, ds.coords)))}")
        c = ds.coords[name]
        if c.ndim != 1:
            raise KeyError(f"{name!r} is a coordinate along {c.dims}, not along one dimension")
        (dim,) = c.dims
        masks[dim] = masks.get(dim, np.ones(ds.sizes[dim], dtype=bool)) & _matches(c.values, want)
    return {dim: np.flatnonzero(mask) for dim, mask in masks.items()}


def histories(source: Union[xr.DataTree, str, os.PathLike], **where: Any) -> xr.Dataset:
    """The stored histories of a results tree (or file), as a Dataset along ``history``.

    Keyword arguments select by coordinate value, e.g.
    ``histories(tree, case_label="base", impact_z=0.6, swing_omega=0)``; a value may be a
    list of values. Floats match to within 1e-9 of their magnitude.
    """
    tree = source if isinstance(source, xr.DataTree) else open_results(source)
    if "history" not in tree.children:
        raise KeyError("this results file has no stored histories (the study's `history` block)")
    ds = tree["history"].to_dataset()
    return ds.isel(where_index(ds, where))


def history_grid_index(tree: xr.DataTree) -> dict[str, np.ndarray]:
    """``{summary dim: index}`` of every row of ``tree["history"]``: where along each
    dimension of the summary the stored history lies."""
    summary, history = tree["summary"].to_dataset(), tree["history"].to_dataset()
    out = {}
    for dim in summary["status"].dims:
        if dim in summary.indexes:  # the row holds the coordinate's value
            out[dim] = summary.indexes[dim].get_indexer(history[dim].values)
        else:  # the row holds the index itself
            out[dim] = np.asarray(history[dim].values, dtype=np.int64)
    return out


def text_of(v) -> str:
    """A text value of a file as str (h5py may give bytes)."""
    return v.decode() if isinstance(v, bytes) else str(v)


def value_text(v) -> str:
    """A coordinate value as short text: numbers as ``%g``."""
    return f"{v:g}" if isinstance(v, (float, np.floating)) else text_of(v)


def dim_labels(summary: xr.Dataset, dim: str) -> list[str]:
    """A label per index of `dim`: its label coordinate (``case_label``), else what differs
    from the first entry among the coordinates along it, else its own values."""
    if f"{dim}_label" in summary.coords:
        return [text_of(v) for v in summary[f"{dim}_label"].values]
    along = [n for n, c in summary.coords.items() if c.dims == (dim,) and n != dim]
    if not along:
        values = summary[dim].values if dim in summary.coords else range(summary.sizes[dim])
        return [value_text(v) for v in values]
    parts: list[list[str]] = [[] for _ in range(summary.sizes[dim])]
    for name in along:
        texts = ["" if isinstance(v, float) and not math.isfinite(v) else value_text(v)
                 for v in summary[name].values.tolist()]  # fmt: skip
        for i, t in enumerate(texts):
            if t and t != texts[0]:  # what differs from the first (the base) entry
                parts[i].append(f"{name}={t}")
    return [f"{i}: " + (", ".join(p) if p else ("base" if i == 0 else "as the base")) for i, p in enumerate(parts)]
