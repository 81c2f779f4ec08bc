#!/usr/bin/env python3
"""Check a batstudy results file against the layout that docs/layout.md promises.

    python scripts/check_layout.py RESULTS.h5 [--no-data] [--quiet]

Prints one line per problem and exits 1 if there is any, 0 (after "layout ok") if there is
none, and 2 if the file cannot be checked at all (missing, not HDF5, or h5py / xarray /
h5netcdf not installed).

What is checked (layout_version 7, as docs/layout.md describes it):

- root attributes: every documented one is present with its type; `Conventions` is CF-1.8;
  `title` names the study; `study_sha256` is the SHA-256 of `study_yaml` (for a study that names no profile file); `created` is ISO 8601
  UTC; `git_dirty` and `complete` are 0/1; `shard` is "" or "I/N" (a shard also has
  `shard_start`/`shard_stop` within the study); `allow_implausible`, where present, is 0/1;
  `batstudy_store_header` is JSON that agrees with
  the file (layout version, study, dims and sizes, history variables, number of bats);
- groups: `/summary`, `/errors` and `/bat` always; `/sweet_spot` exactly when the summary has a
  dim `impact_z`; `/history` exactly when the study stores histories (the store header says
  which) — a summary-only file has no `/history` and that is correct;
- in every group: each numeric variable has `units` (a UDUNITS-style spelling, `1` for
  dimensionless) and text has none; each has a non-empty `long_name` of at most 40
  characters (a plot label; the sentence is in `description`); each dimension is a real HDF5
  dimension scale (CLASS, NAME = its variable's name, 1-D, the length of the axis it is
  attached to) kept in the same group (each group is self-contained); one length per dim name;
  each name in a `coordinates` attribute is a 1-D variable of the group along one of the
  variable's dims; integer variables carry no `_FillValue`;
- xarray (h5netcdf engine) opens every group with named dims (no `phony_dim_*`) and a
  coordinate for every dim;
- `/summary`: every public variable with its type and units over the same dims; grid axes
  have coordinates with `parameter_path`, zip/points dims an integer index coordinate 0..n-1
  and a text label coordinate `<dim>_label`;
  the dims multiply to `n_points`; `status` has its `flag_values`/`flag_meanings` and
  (unless --no-data) `n_done`, `n_failed`, `complete` agree with it, floats are NaN where a
  point did not succeed and `exit_speed` finite where it did, `point_id` is 0 exactly where
  a point was not computed, `bat_index` points into `/bat`;
- `/errors`: dim `error` with `flat_index`, `point_id` and `message`, one row per failed
  point, each naming a failed point of `/summary`;
- `/sweet_spot`: the summary dims without `impact_z`, with the same coordinate values, every
  public variable (`position_at_edge` int8); positions inside the sampled `impact_z` range, widths from 0 to its length;
- `/history`: the summary dims plus `time` (s, from 0, increasing) and `z` (m); only known
  variables, f32 or f64, with their units; the displacement on the grid (`displacement`) or
  in modal form (`modal_coordinate`, `bat_load`, `static_shape`, f64, with `/bat/shape_z` and
  `/bat/mode_shape` of matching dims), never both;
- `/bat`: dims `bat` (text labels), `mode` (1, 2, …), `node`, `profile_point`, `bbcor_point`,
  and every public variable with its dims and units.

New variables may be added to the layout without a version bump, so variables this script
does not know are only checked for units, long names and dimension scales.
"""
from __future__ import annotations

import argparse
import hashlib
import json
import re
import sys

LAYOUT_VERSION = 7
# longest `long_name` (short, for plot labels; layout 3)
LONG_NAME_MAX = 40

# ---- the public names of docs/layout.md ------------------------------------------------

ROOT_STR = ["Conventions", "title", "source", "history", "references", "study_name", "study_description", "study_yaml",
            "study_sha256", "study_path", "batstudy_version", "git_commit", "created", "host",
            "command_line", "shard", "batstudy_store_header"]
ROOT_INT = ["layout_version", "git_dirty", "threads", "n_points", "n_done", "n_failed",
            "complete"]

SUMMARY_FLOATS = {
    "exit_speed": "m/s", "exit_speed_lab": "m/s", "collision_efficiency": "1",
    "approach_speed": "m/s", "contact_time": "s", "peak_force": "N", "max_compression": "m",
    "impulse": "N s", "energy_initial": "J", "energy_ball_final": "J", "energy_ball_loss": "J",
    "energy_bat_rigid": "J", "energy_bat_vibration": "J", "energy_hoop": "J",
    "grip_vibration_amplitude": "m", "grip_recoil_speed": "m/s", "energy_bat_damping": "J",
    "energy_grip_damping": "J", "impulse_time_99": "s", "bbcor": "1", "besr": "1", "bpf": "1",
    "hoop_mode_frequency": "Hz", "hoop_mode_mass": "kg", "tangential_cor": "1",
    "bat_speed": "m/s", "launch_angle": "rad", "spray_angle": "rad", "spin": "rad/s",
    "sidespin": "rad/s", "carry": "m", "apex": "m", "hang_time": "s", "energy_friction": "J",
    "bat_speed_6in": "m/s", "pitch_speed_plate": "m/s", "collision_efficiency_q": "1", "squared_up": "1",
}
# name: (numpy dtype string, units)
SUMMARY_INTS = {"recontact": ("int8", "1"), "status": ("int8", "1"),
                "point_id": ("uint64", "1"), "bat_index": ("int32", "1")}

ERRORS = {"flat_index": ("uint64", "1"), "point_id": ("uint64", "1"), "message": ("str", "")}

SWEET = {"position": "m", "exit_speed": "m/s", "width": "m", "min_vibration_position": "m",
         "min_vibration_amplitude": "m", "min_vibration_energy_position": "m",
         "carry_position": "m", "carry": "m", "exit_speed_lab": "m/s"}

# name: (units, dims after the study's)
HISTORY = {"force": ("N", ("time",)), "compression": ("m", ("time",)),
           "ball_velocity": ("m/s", ("time",)), "displacement": ("m", ("time", "z")),
           "rigid_translation": ("m", ("time",)), "rigid_rotation": ("rad", ("time",)),
           "hoop_displacement": ("m", ("time",)),
           "trajectory_x": ("m", ("flight_time",)), "trajectory_y": ("m", ("flight_time",)),
           "trajectory_z": ("m", ("flight_time",)),
           # the displacement's modal form (layout 4): f64, and /bat's MODAL_BAT
           "modal_coordinate": ("m", ("bat_mode", "time")), "bat_load": ("N", ("time",)),
           "static_shape": ("m/N", ("shape_point",))}
MODAL = ("modal_coordinate", "bat_load", "static_shape")
# /bat with the modal form: name: (dims, units)
MODAL_BAT = {"shape_z": (("bat", "shape_point"), "m"),
             "mode_shape": (("bat", "bat_mode", "shape_point"), "1")}

# name: (dims, units); "str" units mark text variables
BAT = {
    "mass": (("bat",), "kg"), "z_cm": (("bat",), "m"), "moment_of_inertia": (("bat",), "kg m^2"),
    "moment_of_inertia_knob6": (("bat",), "kg m^2"), "moment_of_inertia_knob": (("bat",), "kg m^2"),
    "length": (("bat",), "m"),
    "mode_frequency": (("bat", "mode"), "Hz"), "mode_nodes": (("bat", "mode", "node"), "m"),
    "profile_z": (("bat", "profile_point"), "m"), "outer_radius": (("bat", "profile_point"), "m"),
    "inner_radius": (("bat", "profile_point"), "m"), "spec_json": (("bat",), ""),
    "pivot_position": (("bat",), "m"), "centre_of_percussion": (("bat",), "m"),
    "node1_barrel": (("bat",), "m"), "node2_barrel": (("bat",), "m"),
    "bbcor_ball_speed": (("bat",), "m/s"), "bbcor_z": (("bat", "bbcor_point"), "m"),
    "bbcor": (("bat", "bbcor_point"), "1"), "bbcor_max": (("bat",), "1"),
    "bbcor_max_position": (("bat",), "m"), "bbcor_shot": (("bat",), ""),
    "drop": (("bat",), "1"), "barrel_diameter": (("bat",), "m"),
    "sweet_zone_start": (("bat",), "m"), "sweet_zone_end": (("bat",), "m"),
    "sweet_zone_length": (("bat",), "m"), "hoop_mode_frequency": (("bat",), "Hz"),
    "barrel_compression": (("bat",), "N"),
    "wall_stress_ratio": (("bat",), "1"), "wall_stress_ratio_position": (("bat",), "m"),
    "best_q": (("bat",), "1"), "best_q_position": (("bat",), "m"),
    "rule_units": (("rule_check",), ""),
    # each limit in its own units (attribute units_from: rule_units)
    "rule_value": (("bat", "rule_check"), None), "rule_margin": (("bat", "rule_check"), None),
}
BAT_DIMS = ["bat", "mode", "node", "profile_point", "bbcor_point", "rule_check"]

# UDUNITS-style: "1", or unit symbols with optional integer powers, joined by space, '.', '*'
# or '/': "m/s", "kg m^2", "kg/m^3", "N s", "rad/s".
_UNIT = r"[A-Za-z]+(?:\^?-?\d+)?"
UNITS_RE = re.compile(rf"^(?:1|{_UNIT}(?:[ .*/]{_UNIT})*)$")
# The power-law loading coefficient k₁ (`ball.law.k1`) is in N/m^α, its power the law's own α:
# written with the study's α where every point has the same one ("N m^-1.5"), else symbolic.
K1_UNITS_RE = re.compile(r"^N m\^-(?:alpha|\d+(?:\.\d+)?)$")
CREATED_RE = re.compile(r"^\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d(?:\.\d+)?Z$")
SHARD_RE = re.compile(r"^(\d+)/(\d+)$")


class Checker:
    def __init__(self, path, check_data=True):
        self.path = path
        self.check_data = check_data
        self.problems = []

    def bad(self, where, what):
        self.problems.append(f"{where}: {what}")

    # ---- helpers -----------------------------------------------------------------------

    @staticmethod
    def text(v):
        """An attribute value as str, or None if it is not text."""
        if isinstance(v, bytes):
            return v.decode("utf-8", "replace")
        if isinstance(v, str):
            return v
        return None

    @staticmethod
    def integer(v):
        """An attribute value as int, or None if it is not one integer."""
        import numpy as np
        a = np.asarray(v)
        if a.size != 1 or a.dtype.kind not in "iu":
            return None
        return int(a.reshape(()))

    @staticmethod
    def is_text(ds):
        import h5py
        return h5py.check_string_dtype(ds.dtype) is not None

    # ---- root --------------------------------------------------------------------------

    def root(self, f):
        a = f.attrs
        s, n = {}, {}
        for k in ROOT_STR:
            if k not in a:
                self.bad("/", f"root attribute `{k}` missing")
            elif (v := self.text(a[k])) is None:
                self.bad("/", f"root attribute `{k}` is not text")
            else:
                s[k] = v
        for k in ROOT_INT:
            if k not in a:
                self.bad("/", f"root attribute `{k}` missing")
            elif (v := self.integer(a[k])) is None:
                self.bad("/", f"root attribute `{k}` is not an integer")
            else:
                n[k] = v
        if s.get("Conventions", "CF-1.8") != "CF-1.8":
            self.bad("/", f"Conventions is {s['Conventions']!r}, not 'CF-1.8'")
        if "title" in s and "study_name" in s \
                and s["title"] != f"batstudy results: {s['study_name']}":
            self.bad("/", f"title {s['title']!r} does not name the study {s['study_name']!r}")
        # a study that names profile files has them in its digest too (docs/layout.md),
        # which this checker cannot read back: only a study that names none is recomputed
        names_files = "csv" in s.get("study_yaml", "")
        if "study_yaml" in s and "study_sha256" in s and not names_files:
            h = hashlib.sha256(s["study_yaml"].encode("utf-8")).hexdigest()
            if h != s["study_sha256"]:
                self.bad("/", "study_sha256 is not the SHA-256 of study_yaml")
        if "created" in s and not CREATED_RE.match(s["created"]):
            self.bad("/", f"created {s['created']!r} is not ISO 8601 UTC (YYYY-MM-DDThh:mm:ssZ)")
        if n.get("layout_version", LAYOUT_VERSION) != LAYOUT_VERSION:
            self.bad("/", f"layout_version {n['layout_version']}: this checker knows "
                          f"version {LAYOUT_VERSION} (docs/layout.md)")
        for k in ("git_dirty", "complete"):
            if k in n and n[k] not in (0, 1):
                self.bad("/", f"{k} is {n[k]}, not 0 or 1")
        # Added to layout 1 later: files written before it lack it.
        if "allow_implausible" in a and self.integer(a["allow_implausible"]) not in (0, 1):
            self.bad("/", "allow_implausible is not the integer 0 or 1")
        if n.get("threads", 1) < 1:
            self.bad("/", f"threads is {n['threads']}")
        if "n_done" in n and "n_failed" in n and "n_points" in n:
            if not 0 <= n["n_failed"] <= n["n_done"] <= n["n_points"]:
                self.bad("/", f"counts out of order: n_failed {n['n_failed']}, n_done "
                              f"{n['n_done']}, n_points {n['n_points']}")
            if "complete" in n and n["complete"] != int(n["n_done"] == n["n_points"]):
                self.bad("/", f"complete is {n['complete']} but n_done {n['n_done']} of "
                              f"n_points {n['n_points']}")
        shard = s.get("shard")
        if shard:
            m = SHARD_RE.match(shard)
            if not m or not 1 <= int(m[1]) <= int(m[2]):
                self.bad("/", f"shard {shard!r} is not I/N with 1 <= I <= N")
            for k in ("shard_start", "shard_stop"):
                if k not in a or self.integer(a[k]) is None:
                    self.bad("/", f"shard file without integer root attribute `{k}`")
            if "shard_start" in a and "shard_stop" in a and "n_points" in n:
                lo, hi = self.integer(a["shard_start"]), self.integer(a["shard_stop"])
                if lo is not None and hi is not None and not 0 <= lo <= hi <= n["n_points"]:
                    self.bad("/", f"shard block [{lo}, {hi}) outside the study's "
                                  f"{n['n_points']} points")
        header = None
        if "batstudy_store_header" in s:
            try:
                header = json.loads(s["batstudy_store_header"])
                if not isinstance(header, dict):
                    raise ValueError("not an object")
            except ValueError as e:
                self.bad("/", f"batstudy_store_header is not a JSON object: {e}")
                header = None
        if header is not None:
            for k, want in (("layout_version", n.get("layout_version")),
                            ("study_name", s.get("study_name")),
                            ("study_sha256", s.get("study_sha256"))):
                if want is not None and header.get(k) != want:
                    self.bad("/", f"batstudy_store_header {k} {header.get(k)!r} differs "
                                  f"from the root attribute ({want!r})")
        return s, n, header

    # ---- every group -------------------------------------------------------------------

    def group_generic(self, g):
        """Units, long names, dimension scales, coordinates attributes. Returns
        {variable: tuple of dim names} (None for an axis without a usable scale)."""
        import h5py
        gname = g.name
        dims_of = {}
        sizes = {}
        for name, ds in g.items():
            where = f"{gname}/{name}"
            if not isinstance(ds, h5py.Dataset):
                continue
            units = self.text(ds.attrs.get("units")) if "units" in ds.attrs else None
            if self.is_text(ds):
                if "units" in ds.attrs:
                    self.bad(where, "text variable with a `units` attribute (text has none)")
            elif "units" not in ds.attrs and "units_from" in ds.attrs:
                # each row in its own units, named by a text variable of the group
                src = self.text(ds.attrs["units_from"])
                if src not in g or not self.is_text(g[src]):
                    self.bad(where, f"units_from {src!r} is not a text variable of the group")
            elif "units" not in ds.attrs:
                self.bad(where, "no `units` attribute")
            elif units is None:
                self.bad(where, "`units` is not text")
            elif not UNITS_RE.match(units) and not K1_UNITS_RE.match(units):
                self.bad(where, f"units {units!r} is not a UDUNITS spelling"
                         + (" (numbers need a unit; '1' if dimensionless)" if units == "" else ""))
            ln = self.text(ds.attrs.get("long_name")) if "long_name" in ds.attrs else None
            if not ln:
                self.bad(where, "no (or an empty) `long_name` attribute")
            elif len(ln) > LONG_NAME_MAX:
                self.bad(where, f"long_name of {len(ln)} characters (at most {LONG_NAME_MAX}: "
                                "a plot label; the sentence goes in `description`)")
            if ds.dtype.kind in "iu" and "_FillValue" in ds.attrs:
                self.bad(where, "integer variable with a `_FillValue` attribute")
            if ds.is_scale:
                label = self.text(ds.attrs.get("NAME"))
                if label != name:
                    self.bad(where, f"dimension scale NAME {label!r} is not its name")
                if ds.ndim != 1:
                    self.bad(where, f"dimension scale with {ds.ndim} dimensions")
                dims_of[name] = (name,)
                self.note_size(gname, name, ds.shape[0] if ds.ndim == 1 else -1, sizes)
                continue
            names = []
            for i in range(ds.ndim):
                try:
                    scales = list(ds.dims[i].values())
                except Exception as e:  # noqa: BLE001 - a broken DIMENSION_LIST
                    self.bad(where, f"axis {i}: cannot read its dimension scale ({e})")
                    names.append(None)
                    continue
                if not scales:
                    self.bad(where, f"axis {i} has no dimension scale attached")
                    names.append(None)
                    continue
                sc = scales[0]
                sname = sc.name.rsplit("/", 1)[-1]
                if sc.parent.name != gname:
                    self.bad(where, f"axis {i} uses dimension scale {sc.name} of another group")
                if sc.ndim != 1 or sc.shape[0] != ds.shape[i]:
                    self.bad(where, f"axis {i} has length {ds.shape[i]} but its dimension "
                                    f"scale `{sname}` has shape {sc.shape}")
                names.append(sname)
                self.note_size(gname, sname, ds.shape[i], sizes)
            if len(set(n for n in names if n)) != len([n for n in names if n]):
                self.bad(where, f"a dim is used twice: {names}")
            dims_of[name] = tuple(names)
        for name, ds in g.items():
            if not isinstance(ds, h5py.Dataset) or "coordinates" not in ds.attrs:
                continue
            coords = self.text(ds.attrs["coordinates"])
            for c in (coords or "").split():
                if c not in g or not isinstance(g[c], h5py.Dataset):
                    self.bad(f"{gname}/{name}", f"`coordinates` names `{c}`, which is not a "
                                                f"variable of {gname}")
                elif len(dims_of.get(c, ())) != 1 or dims_of[c][0] not in dims_of[name]:
                    self.bad(f"{gname}/{name}", f"coordinate `{c}` (dims {dims_of.get(c)}) "
                                                f"is not 1-D along one of {dims_of[name]}")
        return dims_of

    def note_size(self, gname, dim, n, sizes):
        if dim in sizes and sizes[dim] != n:
            self.bad(gname, f"dim `{dim}` has lengths {sizes[dim]} and {n}")
        sizes.setdefault(dim, n)

    def xarray_view(self, group):
        """Open one group the way users do; return the Dataset or None."""
        import xarray as xr
        try:
            ds = xr.open_dataset(self.path, engine="h5netcdf", group=group)
        except Exception as e:  # noqa: BLE001 - report whatever xarray says
            self.bad(f"/{group}", f"xarray (h5netcdf) cannot open it: {str(e)[:200]}")
            return None
        for name, v in ds.variables.items():
            unnamed = [d for d in v.dims if str(d).startswith("phony_dim")]
            if unnamed:
                self.bad(f"/{group}/{name}", f"xarray sees unnamed dims {unnamed}")
        for d in ds.dims:
            if d not in ds.coords:
                self.bad(f"/{group}", f"xarray shows no coordinate for dim `{d}`")
        return ds

    def want(self, g, dims_of, name, dtype=None, units=None, dims=None):
        """A documented variable: present, of this type, units and dims."""
        where = f"{g.name}/{name}"
        if name not in g:
            self.bad(where, "missing")
            return None
        ds = g[name]
        if dtype == "str":
            if not self.is_text(ds):
                self.bad(where, f"type {ds.dtype}, expected text")
        elif dtype == "float":
            if ds.dtype.kind != "f":
                self.bad(where, f"type {ds.dtype}, expected floating point")
        elif dtype is not None and ds.dtype.name != dtype:
            self.bad(where, f"type {ds.dtype}, expected {dtype}")
        if units is not None and "units" in ds.attrs and self.text(ds.attrs["units"]) != units:
            self.bad(where, f"units {self.text(ds.attrs['units'])!r}, expected {units!r}")
        if dims is not None and dims_of.get(name) != tuple(dims):
            self.bad(where, f"dims {dims_of.get(name)}, expected {tuple(dims)}")
        return ds

    # ---- groups ------------------------------------------------------------------------

    def summary(self, f, n, header):
        import numpy as np
        g = f["summary"]
        dims_of = self.group_generic(g)
        if "exit_speed" not in g:
            self.bad("/summary/exit_speed", "missing")
            return None
        dims = dims_of["exit_speed"]
        if None in dims:
            return None
        shape = g["exit_speed"].shape
        for name, units in SUMMARY_FLOATS.items():
            self.want(g, dims_of, name, "float64", units, dims)
        for name, (dt, units) in SUMMARY_INTS.items():
            self.want(g, dims_of, name, dt, units, dims)
        for d in dims:
            c = g.get(d)
            if c is None:
                continue
            if "parameter_path" not in c.attrs:
                # a zip/points dim: an integer index 0..n-1
                if c.dtype.kind not in "iu" or not np.array_equal(c[()], np.arange(c.shape[0])):
                    self.bad(f"/summary/{d}", "coordinate without `parameter_path` that is "
                                              "not an index 0..n-1")
                # … with a text label per entry (layout 3)
                lab = g.get(f"{d}_label")
                if lab is None or not self.is_text(lab) or lab.shape != c.shape:
                    self.bad(f"/summary/{d}_label", "missing: a zip/points dim has a text "
                                                    "label coordinate")
        aux = set()
        for name in g:
            a = g[name].attrs.get("coordinates")
            aux.update((self.text(a) or "").split() if a is not None else [])
        for c in sorted(aux):
            if c in g and "parameter_path" not in g[c].attrs and not c.endswith("_label"):
                self.bad(f"/summary/{c}", "coordinate without `parameter_path`")
        n_points = int(np.prod(shape)) if shape else 1
        if "n_points" in n and n["n_points"] != n_points:
            self.bad("/", f"n_points {n['n_points']} but the summary has {n_points} points")
        if header is not None and "dims" in header:
            hd = [tuple(x) for x in header["dims"]]
            if hd != list(zip(dims, shape)):
                self.bad("/", f"batstudy_store_header dims {hd} differ from /summary "
                              f"{list(zip(dims, shape))}")
        st = g.get("status")
        if st is not None:
            fv = st.attrs.get("flag_values")
            if fv is None or list(np.asarray(fv).ravel()) != [-1, 0, 1]:
                self.bad("/summary/status", f"flag_values {fv!r}, expected [-1, 0, 1]")
            fm = self.text(st.attrs.get("flag_meanings")) if "flag_meanings" in st.attrs else None
            if fm != "not_computed ok failed":
                self.bad("/summary/status", f"flag_meanings {fm!r}, expected "
                                            "'not_computed ok failed'")
        if not self.check_data or st is None:
            return dims, shape
        status = st[()]
        if not np.isin(status, (-1, 0, 1)).all():
            self.bad("/summary/status", "values other than -1, 0, 1")
        done, failed = int((status >= 0).sum()), int((status == 1).sum())
        if "n_done" in n and n["n_done"] != done:
            self.bad("/", f"n_done {n['n_done']} but {done} points have status >= 0")
        if "n_failed" in n and n["n_failed"] != failed:
            self.bad("/", f"n_failed {n['n_failed']} but {failed} points have status 1")
        not_ok = status != 0
        for name in SUMMARY_FLOATS:
            if name in g and g[name].shape == shape:
                v = g[name][()]
                if not np.isnan(v[not_ok]).all():
                    self.bad(f"/summary/{name}", "a value where the point failed or was not "
                                                 "computed (should be NaN)")
                if name == "exit_speed" and not np.isfinite(v[~not_ok]).all():
                    self.bad("/summary/exit_speed", "NaN or infinite where status is ok")
        if "point_id" in g and g["point_id"].shape == shape:
            pid = g["point_id"][()]
            if (pid[status == -1] != 0).any() or (pid[status >= 0] == 0).any():
                self.bad("/summary/point_id", "not 0 exactly where a point was not computed")
        return dims, shape

    def bat_index_range(self, f, n_bat):
        import numpy as np
        g = f["summary"]
        if not self.check_data or "bat_index" not in g or "status" not in g \
                or g["bat_index"].shape != g["status"].shape:
            return
        bi, st = g["bat_index"][()], g["status"][()]
        if (bi[st == -1] != -1).any():
            self.bad("/summary/bat_index", "not -1 where a point was not computed")
        if ((bi[st == 0] < 0) | (bi[st == 0] >= n_bat)).any():
            self.bad("/summary/bat_index", f"outside 0..{n_bat - 1} (the /bat entries) "
                                           "where a point succeeded")

    def errors(self, f, n):
        import numpy as np
        g = f["errors"]
        dims_of = self.group_generic(g)
        for name, (dt, units) in ERRORS.items():
            self.want(g, dims_of, name, dt, units, ("error",))
        if "error" not in g:
            self.bad("/errors/error", "missing (the dim's coordinate)")
        if not self.check_data or any(k not in g for k in ("flat_index", "point_id")):
            return
        rows = g["flat_index"].shape[0]
        if "n_failed" in n and rows != n["n_failed"]:
            self.bad("/errors", f"{rows} rows but n_failed is {n['n_failed']}")
        s = f["summary"]
        if rows and "status" in s and "point_id" in s:
            flat = g["flat_index"][()]
            size = s["status"].size
            if (flat >= size).any():
                self.bad("/errors/flat_index", f"beyond the {size} points of /summary")
                return
            st = s["status"][()].ravel()[flat]
            if (st != 1).any():
                self.bad("/errors/flat_index", "names a point whose status is not 1 (failed)")
            if not np.array_equal(s["point_id"][()].ravel()[flat], g["point_id"][()]):
                self.bad("/errors/point_id", "differs from /summary/point_id at flat_index")

    def sweet_spot(self, f, dims):
        import numpy as np
        g = f["sweet_spot"]
        dims_of = self.group_generic(g)
        rest = tuple(d for d in dims if d != "impact_z")
        for name, units in SWEET.items():
            self.want(g, dims_of, name, "float64", units, rest)
        self.want(g, dims_of, "position_at_edge", "int8", "1", rest)
        s = f["summary"]
        for d in rest:
            if d in g and d in s and not np.array_equal(g[d][()], s[d][()]):
                self.bad(f"/sweet_spot/{d}", "coordinate values differ from /summary's")
        if not self.check_data or "impact_z" not in s:
            return
        z = s["impact_z"][()]
        lo, hi = float(np.min(z)), float(np.max(z))
        for name in ("position", "min_vibration_position", "min_vibration_energy_position",
                     "carry_position"):
            if name in g:
                v = g[name][()]
                v = v[np.isfinite(v)]
                out = v[(v < lo - 1e-12) | (v > hi + 1e-12)]
                if out.size:
                    self.bad(f"/sweet_spot/{name}", f"{out.size} value(s) outside the sampled "
                                                    f"impact_z range [{lo:g}, {hi:g}] m "
                                                    f"(e.g. {out[0]:g})")
        if "width" in g:
            w = g["width"][()]
            w = w[np.isfinite(w)]
            out = w[(w < 0) | (w > hi - lo + 1e-12)]
            if out.size:
                self.bad("/sweet_spot/width", f"{out.size} value(s) outside [0, {hi - lo:g}] m, "
                                              f"the sampled impact_z range (e.g. {out[0]:g})")

    def history(self, f, dims, header):
        import numpy as np
        g = f["history"]
        dims_of = self.group_generic(g)
        self.want(g, dims_of, "time", None, "s", ("time",))
        present = [k for k in HISTORY if k in g]
        if not present:
            self.bad("/history", "no history variable")
        for name in present:
            units, tail = HISTORY[name]
            want_dims = tuple(dims) + tail
            ds = self.want(g, dims_of, name, "float64" if name in MODAL else None, units,
                           want_dims)
            if ds is not None and ds.dtype.name not in ("float32", "float64"):
                self.bad(f"/history/{name}", f"type {ds.dtype}, expected float32 or float64")
        if "displacement" in g or any(k in g for k in MODAL):
            self.want(g, dims_of, "z", None, "m", ("z",))
        if "trajectory_x" in g:
            self.want(g, dims_of, "flight_time", None, "s", ("flight_time",))
        modal = [k for k in MODAL if k in g]
        if modal and len(modal) != len(MODAL):
            self.bad("/history", f"the modal form needs {', '.join(MODAL)}; it has {', '.join(modal)}")
        if modal and "displacement" in g:
            self.bad("/history", "both forms of the displacement (grid and modal)")
        if modal:
            self.modal(f, g)
        if "time" in g and self.check_data:
            t = g["time"][()]
            if t.size and (t[0] != 0 or (np.diff(t) <= 0).any()):
                self.bad("/history/time", "does not start at 0 and increase")
        if header is not None and header.get("history"):
            names = header["history"][0]
            if sorted(names) != sorted(present):
                self.bad("/history", f"variables {sorted(present)}, but the store header "
                                     f"lists {sorted(names)}")

    def modal(self, f, g):
        """The modal form: its dims agree with /bat's shapes, which must be there; the
        coordinates' chunks are blocks of modes, the static shape's one per history."""
        import numpy as np
        b = f["bat"] if "bat" in f else None
        if b is None or any(k not in b for k in MODAL_BAT):
            self.bad("/bat", f"the modal form needs {', '.join(MODAL_BAT)} in /bat")
            return
        bdims = self.group_generic(b)
        for name, (dims, units) in MODAL_BAT.items():
            self.want(b, bdims, name, "float64", units, dims)
        for dim, var, axis in (("bat_mode", "mode_shape", 1), ("shape_point", "shape_z", 1)):
            if dim in g and g[dim].shape[0] != b[var].shape[axis]:
                self.bad(f"/history/{dim}", f"{g[dim].shape[0]} entries, /bat/{var} has "
                                            f"{b[var].shape[axis]}")
        q = g["modal_coordinate"]
        if q.chunks is not None and q.chunks[-1] != q.shape[-1]:
            self.bad("/history/modal_coordinate", "a chunk does not hold every time sample")
        if self.check_data and "shape_z" in b:
            z = b["shape_z"][()]
            for k, row in enumerate(z):
                row = row[np.isfinite(row)]
                if row.size and (row[0] != 0 or (np.diff(row) <= 0).any()):
                    self.bad("/bat/shape_z", f"bat {k}: shape points do not start at 0 and increase")

    def bat(self, f, header):
        import numpy as np
        g = f["bat"]
        dims_of = self.group_generic(g)
        for d in BAT_DIMS:
            if d not in g:
                self.bad(f"/bat/{d}", "missing (the dim's coordinate)")
        if "bat" in g and not self.is_text(g["bat"]):
            self.bad("/bat/bat", "labels are not text")
        if "mode" in g and self.check_data:
            m = g["mode"][()]
            if not np.array_equal(m, np.arange(1, m.size + 1)):
                self.bad("/bat/mode", "coordinate is not 1, 2, …")
        for name, (dims, units) in BAT.items():
            self.want(g, dims_of, name, "str" if units == "" else "float", units, dims)
        n_bat = g["bat"].shape[0] if "bat" in g else 0
        if header is not None and "n_bats" in header and header["n_bats"] != n_bat:
            self.bad("/bat", f"{n_bat} bats, but the store header says {header['n_bats']}")
        return n_bat

    # ---- the file ----------------------------------------------------------------------

    def run(self):
        import h5py
        with h5py.File(self.path, "r") as f:
            _, n, header = self.root(f)
            for grp in ("summary", "errors", "bat"):
                if grp not in f:
                    self.bad(f"/{grp}", "group missing")
            got = self.summary(f, n, header) if "summary" in f else None
            dims = got[0] if got else None
            if "errors" in f:
                self.errors(f, n)
            if "bat" in f:
                n_bat = self.bat(f, header)
                if "summary" in f:
                    self.bat_index_range(f, n_bat)
            if dims is not None:
                if "impact_z" in dims:
                    if "sweet_spot" not in f:
                        self.bad("/sweet_spot", "group missing (the summary has dim impact_z)")
                    else:
                        self.sweet_spot(f, dims)
                elif "sweet_spot" in f:
                    self.bad("/sweet_spot", "present although the summary has no dim impact_z")
            stores_history = header.get("history") is not None if header is not None else None
            if "history" in f:
                if stores_history is False:
                    self.bad("/history", "present although the store header says the study "
                                         "stores no histories")
                if dims is not None:
                    self.history(f, dims, header)
            elif stores_history:
                self.bad("/history", "group missing although the store header lists "
                                     f"{header['history'][0]}")
            # a `sample` study's statistics, a design search's record
            for extra in ("uncertainty", "optimize"):
                if extra in f:
                    self.group_generic(f[extra])
            if "optimize" in f:
                for key in ("method", "objective", "sense", "stopped", "best_candidate"):
                    if key not in f["optimize"].attrs:
                        self.bad("/optimize", f"attribute {key} missing")
            groups = [x for x in ("summary", "sweet_spot", "history", "bat", "errors",
                                  "uncertainty", "optimize") if x in f]
        for grp in groups:
            ds = self.xarray_view(grp)
            if ds is not None:
                ds.close()
        return self.problems


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("results", help="a batstudy results file (.h5)")
    p.add_argument("--no-data", action="store_true",
                   help="check names, types, units and dims only, not the stored values")
    p.add_argument("--quiet", action="store_true", help="print nothing when the file is ok")
    a = p.parse_args(argv)
    try:
        import h5py  # noqa: F401
        import numpy  # noqa: F401
        import xarray  # noqa: F401
        import h5netcdf  # noqa: F401
    except ImportError as e:
        print(f"check_layout: cannot check, {e} (bash scripts/setup.sh installs h5py, xarray "
              "and h5netcdf in .venv: run .venv/bin/python scripts/check_layout.py)",
              file=sys.stderr)
        return 2
    import h5py
    try:
        with h5py.File(a.results, "r"):
            pass
    except OSError as e:
        print(f"check_layout: cannot open {a.results}: {e}", file=sys.stderr)
        return 2
    problems = Checker(a.results, check_data=not a.no_data).run()
    for line in problems:
        print(line)
    if problems:
        print(f"{a.results}: {len(problems)} layout problem(s) (docs/layout.md)")
        return 1
    if not a.quiet:
        print(f"layout ok: {a.results}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
