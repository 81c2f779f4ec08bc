"""The curves of a results file: what the figures are drawn from (nothing here draws).

- :class:`Results` is a results file (or a tree from :func:`batstudy.open_results`) seen as
  its *curves*.
- A :class:`Curve` is one exit-speed-vs-``impact_z`` curve: one index along every summary dim
  except ``impact_z``, with the parameters that describe it.  Parameters come from grid dims
  (``swing_omega``, ``model``, ...) and from the 1-D coordinates of a ``points`` block dim
  (``case``: ``bat_material_density(case)`` ...).  That one view serves both study forms: a
  ``case`` block varying one factor at a time around case 0, and plain grid axes.
- :func:`select` and :func:`one_factor` pick the curves that differ from a base curve only in
  the named parameters (NaN equals NaN).
- :meth:`Results.history_of` finds the stored time history nearest a wanted impact
  position; :func:`remove_rigid` subtracts the bat's rigid motion from a displacement field.
"""

from __future__ import annotations

import itertools
import math
import os
import re
from dataclasses import dataclass, field
from typing import Union

import numpy as np
import xarray as xr

from .._open import history_grid_index, open_results

IMPACT = "impact_z"
MODEL = "model"
LABEL = "case_label"

# Short display names of the study parameters (dotted path with '.' -> '_').
PRETTY = {
    "bat_preset": "bat",
    "bat_material_density": "ρ",
    "bat_material_youngs_modulus": "Y",
    "bat_handle_radius_scale": "handle radius ×",
    "bat_length": "L",
    "bat_ends_barrel": "barrel end",
    "bat_ends_knob": "knob end",
    "bat_shell_thickness": "shell",
    "bat_fill_density": "fill ρ",
    "ball_law_kind": "ball law",
    "ball_speed": "v_ball",
    "swing_omega": "ω",
    "hoop_frequency": "hoop f",
    "hoop_mass": "hoop m",
    "model": "model",
}


class Skip(Exception):
    """A figure cannot be drawn from this file (its data are absent); the message says why."""


# --------------------------------------------------------------------------- parameters


def same(a, b) -> bool:
    """Parameter equality: strings exactly, numbers to 1e-9 relative, NaN equals NaN,
    a missing parameter (None) only equals another missing one."""
    if a is None or b is None:
        return a is None and b is None
    if isinstance(a, str) or isinstance(b, str):
        return a == b
    a, b = float(a), float(b)
    if math.isnan(a) or math.isnan(b):
        return math.isnan(a) and math.isnan(b)
    return math.isclose(a, b, rel_tol=1e-9, abs_tol=1e-12)


def matches(value, cond) -> bool:
    """``cond`` is a value (compared with :func:`same`) or a predicate on the value."""
    if callable(cond):
        return value is not None and bool(cond(value))
    return same(value, cond)


def _scalar(v):
    """numpy scalar / 0-d array -> python str or float."""
    v = np.asarray(v).item()
    if isinstance(v, bytes):
        return v.decode()
    if isinstance(v, str):
        return v
    return float(v)


@dataclass
class Curve:
    """One curve along ``impact_z``: ``index`` = integer index per other summary dim."""

    index: dict
    params: dict
    label: str = ""
    key: tuple = field(default=())

    def __hash__(self):
        return hash(self.key)

    def __eq__(self, other):
        return isinstance(other, Curve) and self.key == other.key


def curves_of(summary: xr.Dataset, default_model: str = "wave") -> list[Curve]:
    """All curves of a summary dataset, in row-major order of its non-``impact_z`` dims.

    A dim with 1-D auxiliary coordinates is a points block: its parameters are those
    coordinates (``case_label`` becomes the curve's label).  Any other dim is a grid axis and
    is itself the parameter.  Without a ``model`` dim every curve gets ``model`` =
    ``default_model``."""
    dims = [d for d in summary.sizes if d != IMPACT]
    per_dim = []
    for d in dims:
        aux = [n for n, c in summary.coords.items() if c.dims == (d,) and n != d]
        values = {n: summary[n].values for n in aux}
        if not aux:
            values = {d: summary[d].values} if d in summary.coords else {d: np.arange(summary.sizes[d])}
        per_dim.append(values)
    out = []
    for idx in itertools.product(*(range(summary.sizes[d]) for d in dims)):
        params, label = {}, ""
        for d, i, values in zip(dims, idx, per_dim):
            for n, arr in values.items():
                if n == LABEL:
                    label = str(_scalar(arr[i]))
                else:
                    params[n] = _scalar(arr[i])
        params.setdefault(MODEL, default_model)
        out.append(Curve(index=dict(zip(dims, idx)), params=params, label=label, key=idx))
    return out


def select(curves, base: Curve, free=(), where=None) -> list[Curve]:
    """Curves equal to ``base`` on every parameter except those in ``free`` and ``where``,
    and satisfying every condition of ``where`` ({name: value or predicate})."""
    where = where or {}
    fixed = (set(base.params) | {k for c in curves for k in c.params}) - set(free) - set(where)
    return [
        c
        for c in curves
        if all(same(c.params.get(k), base.params.get(k)) for k in fixed)
        and all(matches(c.params.get(k), cond) for k, cond in where.items())
    ]


def one_factor(curves, base: Curve, factor: str) -> list[Curve]:
    """``base`` and the curves that differ from it only in ``factor``, sorted by its value."""
    chosen = select(curves, base, free={factor})
    if all(isinstance(c.params.get(factor), float) for c in chosen):
        chosen.sort(key=lambda c: c.params[factor])
    return chosen


def differing(curve: Curve, base: Curve) -> list[str]:
    """Names of the parameters in which ``curve`` differs from ``base`` (model excluded)."""
    keys = sorted(set(curve.params) | set(base.params))
    return [k for k in keys if k != MODEL and not same(curve.params.get(k), base.params.get(k))]


# --------------------------------------------------------------------------- the file


def study_model(study_yaml: str) -> str:
    """The study's top-level ``model:`` (for files without a ``model`` dim); default wave."""
    m = re.search(r"^model:\s*['\"]?(\w+)", study_yaml or "", re.MULTILINE)
    return m.group(1) if m else "wave"


def _node(tree: xr.DataTree, name: str) -> xr.Dataset | None:
    return tree[name].to_dataset() if name in tree.children else None


class Results:
    """A results file as its curves, over the tree of :func:`batstudy.open_results`:
    ``summary``, ``sweet_spot``, ``history`` (the stored histories only) and ``bat`` are its
    groups as (lazy) datasets, None where the file has none."""

    def __init__(self, source: Union[str, os.PathLike, xr.DataTree]):
        self.tree = source if isinstance(source, xr.DataTree) else open_results(source)
        # the file itself, for the figures that read a group of their own (None for a tree)
        self.path = None if isinstance(source, xr.DataTree) else os.fspath(source)
        self.attrs = dict(self.tree.attrs)
        self.summary = _node(self.tree, "summary")
        self.sweet_spot = _node(self.tree, "sweet_spot")
        self.history = _node(self.tree, "history")
        self.bat = _node(self.tree, "bat")
        default = study_model(str(self.attrs.get("study_yaml", "")))
        self.curves = curves_of(self.summary, default) if self.summary is not None else []
        self._history_index = history_grid_index(self.tree) if self.history is not None else {}

    def close(self):
        self.tree.close()
        for ds in (self.summary, self.sweet_spot, self.history, self.bat):
            if ds is not None:
                ds.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
    # --- names and units
    @property
    def name(self) -> str:
        return str(self.attrs.get("study_name", "study"))

    def models(self) -> list[str]:
        return list(dict.fromkeys(c.params[MODEL] for c in self.curves))

    def main_model(self) -> str:
        """``wave`` if the file has it, else its first model."""
        models = self.models()
        if not models:
            raise Skip("no summary data")
        return "wave" if "wave" in models else models[0]

    def units(self, name: str) -> str:
        if self.summary is not None and name in self.summary.variables:
            return str(self.summary[name].attrs.get("units", ""))
        return ""

    def format_param(self, name: str, value) -> str:
        """``ρ = 700 kg/m3``-style text for one parameter value."""
        pretty = PRETTY.get(name, name)
        if isinstance(value, str):
            return f"{pretty} {value}"
        if value is None or math.isnan(value):
            return f"{pretty} unset"
        unit = self.units(name)
        unit = "" if unit in ("", "1") else " " + unit
        return f"{pretty} = {value:.4g}{unit}"

    def label(self, curve: Curve, base: Curve | None = None, always: tuple[str, ...] = ()) -> str:
        """The curve's ``case_label`` if it has one, else its parameters differing from
        ``base`` (default: the base curve of its model). Parameters in ``always`` are shown
        even where they equal the base (e.g. ω = 0 among curves at several ω)."""
        if curve.label:
            return curve.label
        if base is None:
            try:
                base = self.base(curve.params[MODEL])
            except Skip:
                base = None
        shown = [k for k in always if k in curve.params]
        is_base = base is None or curve == base or not differing(curve, base)
        names = shown + ([] if is_base else [k for k in differing(curve, base) if k not in shown])
        text = ", ".join(self.format_param(k, curve.params.get(k)) for k in names)
        if is_base:
            return f"{text} (base case)" if text else "base case"
        return text

    # --- curves
    def base(self, model: str | None = None) -> Curve:
        """The base curve of ``model``: index 0 along every dim except ``model``."""
        model = model or self.main_model()
        for c in self.curves:
            if c.params[MODEL] == model and all(i == 0 for d, i in c.index.items() if d != MODEL):
                return c
        raise Skip(f"no curves of the {model} model")

    def partner(self, curve: Curve, model: str) -> Curve | None:
        """The same curve in another model (e.g. the rigid twin of a wave curve)."""
        found = select(self.curves, curve, where={MODEL: model})
        return found[0] if found else None

    def values(self, curve: Curve, var: str = "exit_speed") -> xr.DataArray:
        """``summary[var]`` along ``impact_z`` for one curve (loaded)."""
        if self.summary is None or var not in self.summary:
            raise Skip(f"no /summary/{var}")
        if IMPACT not in self.summary[var].dims:
            raise Skip("the summary has no impact_z dim")
        return self.summary[var].isel(curve.index).load()

    def bat_of(self, curve: Curve) -> xr.Dataset:
        """The curve's entry of /bat (via /summary/bat_index)."""
        if self.bat is None or self.summary is None or "bat_index" not in self.summary:
            raise Skip("no /bat group or bat_index")
        idx = np.asarray(self.summary["bat_index"].isel(curve.index).values).ravel()
        idx = idx[idx >= 0]
        if idx.size == 0:
            raise Skip("bat of the curve not known (no computed point)")
        return self.bat.isel(bat=int(idx[0]))

    def z_cm(self, curve: Curve) -> float:
        """Centre of mass (m from the knob) of the curve's bat, from /bat."""
        return float(self.bat_of(curve)["z_cm"].values)

    def area(self, curve: Curve, z) -> np.ndarray:
        """Cross-section area of the curve's bat at ``z`` (from the /bat profile; 0 outside)."""
        b = self.bat_of(curve)
        pz, outer = b["profile_z"].values, b["outer_radius"].values
        inner = b["inner_radius"].values if "inner_radius" in b else np.zeros_like(outer)
        ok = np.isfinite(pz) & np.isfinite(outer)
        a = np.pi * (outer[ok] ** 2 - np.nan_to_num(inner[ok]) ** 2)
        return np.interp(z, pz[ok], a, left=0.0, right=0.0)

    def sweet(self, curve: Curve) -> tuple[float, float]:
        """(position, exit speed) of the curve's maximum: /sweet_spot if present, else the
        best sample of the summary curve."""
        ss = self.sweet_spot
        if ss is not None and "position" in ss and "exit_speed" in ss:
            sub = ss.isel({d: i for d, i in curve.index.items() if d in ss.dims})
            return float(sub["position"].values), float(sub["exit_speed"].values)
        y = self.values(curve)
        if not np.isfinite(y.values).any():
            return math.nan, math.nan
        k = int(np.nanargmax(y.values))
        return float(y[IMPACT].values[k]), float(y.values[k])

    # --- histories
    def history_of(self, curve: Curve, var: str, z_target: float):
        """``(impact_z, DataArray over time[, z])`` of the stored history of ``var`` for
        ``curve`` nearest ``z_target``, or None if nothing finite is stored for it."""
        h = self.history
        if h is None or var not in h:
            return None
        rows = np.ones(h.sizes["history"], dtype=bool)
        for dim, i in curve.index.items():
            rows &= self._history_index[dim] == i
        rows = np.flatnonzero(rows)
        if not len(rows):
            return None
        data = h[var].isel(history=rows).load()
        finite = np.isfinite(data.values).reshape(len(rows), -1).any(axis=1)
        if not finite.any():
            return None
        if IMPACT not in h.coords:  # no impact_z dim: the curve is one point
            return math.nan, data.isel(history=int(np.flatnonzero(finite)[0]))
        candidates = np.flatnonzero(finite)
        zs = h[IMPACT].values[rows]
        k = candidates[np.argmin(np.abs(zs[candidates] - z_target))]
        return float(zs[k]), data.isel(history=k)

    def first_history(self, candidates, var: str, z_target: float):
        """``(curve, impact_z, data)`` of the first candidate curve with a recorded history."""
        for c in candidates:
            found = self.history_of(c, var, z_target)
            if found is not None:
                return (c, *found)
        raise Skip(f"no recorded /history/{var} for these curves")

    def flex_displacement(self, curve: Curve, z_target: float):
        """``(impact_z, DataArray (time, z))``: displacement minus rigid motion for a curve."""
        found = self.history_of(curve, "displacement", z_target)
        if found is None:
            return None
        z_imp, disp = found
        z = disp["z"].values
        trans = self.history_of(curve, "rigid_translation", z_imp)
        rot = self.history_of(curve, "rigid_rotation", z_imp)
        if trans is not None and rot is not None:
            flex = remove_rigid(disp.values, z, trans[1].values, rot[1].values, self.z_cm(curve))
            how = "recorded rigid motion removed"
        else:  # not recorded: project the sampled field on rigid motion instead
            flex = remove_rigid(disp.values, z, *rigid_projection(disp.values, z, self.area(curve, z)))
            how = "rigid motion projected out (not recorded)"
        out = disp.copy(data=flex)
        out.attrs["rigid_removal"] = how
        return z_imp, out


def remove_rigid(displacement, z, translation, rotation, z_cm):
    """Displacement (time, z) minus the rigid motion ``translation + rotation·(z − z_cm)``."""
    displacement = np.asarray(displacement, dtype=float)
    rigid = np.asarray(translation, float)[:, None] + np.asarray(rotation, float)[:, None] * (
        np.asarray(z, float)[None, :] - z_cm
    )
    return displacement - rigid


def rigid_projection(displacement, z, weight):
    """``(translation, rotation, z_c)`` of the rigid motion carrying the same linear and angular
    momentum as ``displacement`` (time, z) sampled at ``z`` with mass weights ``weight`` (e.g.
    the cross-section area, for a uniform density), about the weighted centroid ``z_c``.

    A fallback for files without rigid_translation/rigid_rotation histories: it is exact for
    pure rigid motion and approximate otherwise (coarse z sampling, non-uniform density)."""
    y = np.asarray(displacement, dtype=float)
    w = np.asarray(weight, dtype=float)
    z = np.asarray(z, dtype=float)
    if not w.sum() > 0:
        raise Skip("no bat cross-section at the sampled z to project out rigid motion")
    z_c = float((w * z).sum() / w.sum())
    arm = z - z_c
    translation = (y * w).sum(axis=1) / w.sum()
    rotation = (y * w * arm).sum(axis=1) / (w * arm**2).sum()
    return translation, rotation, z_c


def excess_speed(res: Results, curve: Curve) -> xr.DataArray:
    """Exit speed minus the impact (approach) speed at the impact point, both bat-CM frame.

    The approach speed is ``v_ball − ω (z − z_cm)`` (docs/physics.md): the stored
    ``/summary/approach_speed`` when present, else computed from the curve's parameters."""
    exit_ = res.values(curve, "exit_speed")
    if res.summary is not None and "approach_speed" in res.summary:
        return exit_ - res.values(curve, "approach_speed")
    v = curve.params.get("ball_speed")
    if v is None:
        raise Skip("no approach_speed and no ball_speed parameter")
    omega = curve.params.get("swing_omega", 0.0)
    omega = 0.0 if omega is None or math.isnan(omega) else omega
    return exit_ - (v - omega * (exit_[IMPACT] - res.z_cm(curve)))
