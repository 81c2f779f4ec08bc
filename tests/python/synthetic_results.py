"""Write a synthetic batstudy results file with the parts of docs/layout.md that the figure
scripts read (not a complete results file: scripts/check_layout.py rejects it, e.g. it has no
/errors group and no run attributes).

It has the structure of the bundled main study (``studies/param_space.yaml``): summary dims
(model, impact_z, case), a ``case`` points block varying one factor at a time around case 0,
histories only for the wave model at impact_z = 0.60 for the base and aluminum cases, and one
``/bat`` entry per distinct bat.  The numbers are plausible analytic stand-ins, not
simulations: the rigid model is Brody's formula (docs/physics.md), the "wave" curves a peaked
collision efficiency around 0.70 m.  Use it to develop and test the figure scripts without the
Rust build:

    python tests/python/synthetic_results.py out.h5
"""

from __future__ import annotations

import sys

import h5py
import numpy as np

BALL_MASS = 0.145
COR = 0.5
NAN = float("nan")

# Parameter coordinates along `case`: name -> (units, base value).
PARAMS = {
    "bat_preset": ("", "r161"),
    "bat_material_density": ("kg/m3", 649.0),
    "bat_material_youngs_modulus": ("N/m2", 1.814e10),
    "bat_handle_radius_scale": ("1", 1.0),
    "bat_length": ("m", 0.84),
    "bat_ends_barrel": ("", "free"),
    "bat_shell_thickness": ("m", NAN),
    "ball_law_kind": ("", "linear_hysteresis"),
    "ball_preset": ("", ""),
    "swing_omega": ("rad/s", 0.0),
    "ball_speed": ("m/s", 40.0),
    "hoop_frequency": ("Hz", 0.0),
    "hoop_mass": ("kg", NAN),
}

ALUMINUM = {"bat_preset": "aluminum", "bat_shell_thickness": 0.003}


def cases() -> list[tuple[str, dict]]:
    """(label, parameters set) per case; case 0 is the base."""
    out = [("base (R161 wood)", {})]
    out += [(f"density {r:g}", {"bat_material_density": r}) for r in (500.0, 640.0, 700.0, 1000.0)]
    out += [(f"Y x{s:g}", {"bat_material_youngs_modulus": 1.814e10 * s}) for s in (0.8, 1.25)]
    out += [(f"handle x{s:g}", {"bat_handle_radius_scale": s}) for s in (1.2, 0.8)]
    out += [(f"omega {w:g}", {"swing_omega": w}) for w in (-20.0, -40.0, -60.0)]
    out += [(f"ball {v:g} m/s", {"ball_speed": v}) for v in (30.0, 50.0)]
    out += [
        (f"elastic, omega {w:g}", {"ball_law_kind": "elastic", "swing_omega": w}) for w in (0.0, -20.0, -40.0, -60.0)
    ]
    out += [
        (f"speed-dependent ball, omega {w:g}", {"ball_law_kind": "speed_dependent", "swing_omega": w})
        for w in (0.0, -20.0, -40.0, -60.0)
    ]
    out += [
        (f"mlb ball, omega {w:g}", {"ball_preset": "mlb", "ball_law_kind": "speed_dependent", "swing_omega": w})
        for w in (0.0, -20.0, -40.0, -60.0)
    ]
    out += [(f"corked {h * 100:g} cm", {"bat_preset": "corked", "bat_shell_thickness": h}) for h in (0.01, 0.015)]
    out += [("aluminum", dict(ALUMINUM))]
    out += [("fixed barrel end", {"bat_ends_barrel": "fixed"})]
    out += [("110 cm bat", {"bat_length": 1.10})]
    out += [
        (f"aluminum, hoop {f:g} Hz", {**ALUMINUM, "hoop_frequency": f, "hoop_mass": 0.05})
        for f in (300.0, 500.0, 800.0, 1250.0, 2000.0)
    ]
    return out


def bat_key(p: dict) -> tuple:
    """Parameters that make a distinct bat."""
    names = ("bat_preset", "bat_material_density", "bat_material_youngs_modulus", "bat_handle_radius_scale")
    return tuple(str(p[n]) for n in names) + (str(p["bat_length"]), str(p["bat_shell_thickness"]))


def bat_props(p: dict) -> dict:
    """Mass, CM, moment of inertia, modes and profile of a stand-in bat."""
    length = p["bat_length"]
    scale = p["bat_material_density"] / 649.0
    if p["bat_preset"] == "aluminum":
        scale = 0.95
    elif p["bat_preset"] == "corked":
        scale = 0.93
    mass = 0.88 * scale * length / 0.84
    z_cm = 0.60 * length / 0.84
    inertia = 0.045 * scale * (length / 0.84) ** 3
    stiff = np.sqrt(p["bat_material_youngs_modulus"] / 1.814e10 / scale)
    freqs = np.array([169.0, 612.0, 1334.0]) * stiff * (0.84 / length) ** 2
    nodes = np.array([[0.17, 0.68, NAN, NAN], [0.07, 0.39, 0.72, NAN], [0.05, 0.25, 0.50, 0.74]]) * length / 0.84
    z = np.linspace(0.0, length, 40)
    outer = 0.0125 + 0.021 / (1 + np.exp(-(z - 0.45 * length / 0.84) / 0.04))
    outer[z < 0.02] = 0.03
    handle = z < 0.45 * length / 0.84
    outer[handle] *= p["bat_handle_radius_scale"]
    shell = p["bat_shell_thickness"]
    inner = np.where((z > 0.5 * length) & np.isfinite(shell), outer - np.nan_to_num(shell), 0.0)
    return dict(
        mass=mass, z_cm=z_cm, moment_of_inertia=inertia, length=length, mode_frequency=freqs,
        mode_nodes=nodes, profile_z=z, outer_radius=outer, inner_radius=inner,
    )  # fmt: skip


def rigid_exit(z, p, bat, cor=COR):
    """Brody: e_A = (e − m/M*)/(1 + m/M*), exit = e_A v + (1 + e_A)(−ω l)."""
    l = z - bat["z_cm"]
    m_eff = bat["mass"] / (1 + bat["mass"] * l**2 / bat["moment_of_inertia"])
    r = BALL_MASS / m_eff
    e_a = (cor - r) / (1 + r)
    return e_a * p["ball_speed"] + (1 + e_a) * (-p["swing_omega"] * l)


def wave_exit(z, p, bat):
    """A peaked stand-in for the wave model (peak near 0.70 m of an 84 cm bat)."""
    l = z - bat["z_cm"]
    peak = 0.70 * p["bat_length"] / 0.84 - 0.0005 * p["swing_omega"]
    width = 0.35 if p["bat_preset"] == "aluminum" else 0.22
    if p["bat_ends_barrel"] == "fixed":
        width *= 1.5
    e_a = 0.21 - ((z - peak) / width) ** 2
    if p["hoop_frequency"] > 0:
        e_a += 0.03 * np.exp(-(((p["hoop_frequency"] - 900.0) / 500.0) ** 2))
    if p["ball_law_kind"] != "elastic":
        e_a -= 0.0008 * (-p["swing_omega"] * l)
    e_a -= 0.002 * abs(np.log(p["bat_material_density"] / 649.0)) * 10
    return e_a * p["ball_speed"] + (1 + e_a) * (-p["swing_omega"] * l)


def history_fields(p, bat, z_imp, t, zs):
    """Force, compression, ball velocity, displacement and rigid motion histories."""
    contact = 1.4e-3 if p["bat_preset"] != "aluminum" else 1.2e-3
    s = np.clip(t / contact, 0, 1)
    force = 2.0e4 * np.sin(np.pi * s**0.8) * (t <= contact)
    dt = t[1] - t[0]
    impulse = np.cumsum(force) * dt
    ball_v = p["ball_speed"] - impulse / BALL_MASS
    translation = np.cumsum(impulse) * dt / bat["mass"]
    rotation = np.cumsum(impulse * (z_imp - bat["z_cm"])) * dt / bat["moment_of_inertia"]
    # A bending pulse leaving the impact point at ~1.25 m/ms, reaching z = 0.10 at ~0.4 ms.
    speed = 1250.0 if p["bat_preset"] != "aluminum" else 2500.0
    front = np.abs(zs[None, :] - z_imp) - speed * t[:, None]
    amp = 2.0e-3 * (1.0 if p["bat_preset"] != "aluminum" else 0.6)
    pulse = np.exp(-((front / 0.05) ** 2)) * np.minimum(t[:, None] / contact, 1)
    dent = np.exp(-(((zs[None, :] - z_imp) / 0.08) ** 2)) * np.sin(np.pi * np.minimum(t[:, None] / contact, 1))
    flex = -amp * (pulse + dent)
    displacement = translation[:, None] + rotation[:, None] * (zs[None, :] - bat["z_cm"]) + flex
    return dict(
        force=force, compression=force / 7e5, ball_velocity=ball_v, displacement=displacement,
        rigid_translation=translation, rigid_rotation=rotation,
    )  # fmt: skip


def _scale(group, name, values, units, long_name, dtype=None):
    ds = group.create_dataset(name, data=values, dtype=dtype)
    ds.attrs["units"] = units
    ds.attrs["long_name"] = long_name
    ds.make_scale(name)
    return ds


def _var(group, name, data, dims, units, long_name, coordinates="", **kw):
    ds = group.create_dataset(name, data=data, **kw)
    for i, d in enumerate(dims):
        ds.dims[i].attach_scale(group[d])
    ds.attrs["units"] = units
    ds.attrs["long_name"] = long_name
    if coordinates:
        ds.attrs["coordinates"] = coordinates
    return ds


def write(path, impact_z=None) -> str:
    """Write the synthetic file to ``path`` and return the path."""
    impact_z = np.round(np.arange(0.40, 0.8401, 0.02), 4) if impact_z is None else np.asarray(impact_z)
    models = ["wave", "rigid"]
    spec = cases()
    params = [{n: v[1] for n, v in PARAMS.items()} | over for _, over in spec]
    bats, bat_index = {}, []
    for p in params:
        bat_index.append(bats.setdefault(bat_key(p), len(bats)))
    bat_list = [None] * len(bats)
    for p, b in zip(params, bat_index):
        bat_list[b] = bat_list[b] or (p, bat_props(p))

    shape = (len(models), len(impact_z), len(spec))
    exit_speed = np.full(shape, NAN)
    approach = np.full(shape, NAN)
    for c, (p, b) in enumerate(zip(params, bat_index)):
        bat = bat_list[b][1]
        inside = impact_z <= bat["length"]
        approach[:, :, c] = p["ball_speed"] - p["swing_omega"] * (impact_z - bat["z_cm"])
        exit_speed[0, :, c] = np.where(inside, wave_exit(impact_z, p, bat), NAN)
        cor = 1.0 if p["ball_law_kind"] == "elastic" else COR
        exit_speed[1, :, c] = np.where(inside, rigid_exit(impact_z, p, bat, cor), NAN)

    str_t = h5py.string_dtype()
    with h5py.File(path, "w") as f:
        f.attrs.update(
            Conventions="CF-1.8", title="batstudy results: synthetic", study_name="synthetic",
            study_description="synthetic stand-in for tests", study_yaml="name: synthetic\nmodel: wave\n",
            layout_version=5, n_points=int(np.prod(shape)), n_done=int(np.prod(shape)), n_failed=0,
            complete=1, shard="",
        )  # fmt: skip
        for gname in ("summary", "sweet_spot", "history"):
            g = f.create_group(gname)
            _scale(g, "model", np.array(models, dtype=object), "", "model", dtype=str_t)
            _scale(g, "case", np.arange(len(spec)), "1", "case index")
            if gname != "sweet_spot":
                _scale(g, "impact_z", impact_z, "m", "impact position from the knob")
            for n, (units, _) in PARAMS.items():
                vals = [p[n] for p in params]
                is_str = isinstance(vals[0], str)
                data = np.array(vals, dtype=object if is_str else float)
                _var(g, n, data, ["case"], units, n, dtype=str_t if is_str else None)
                g[n].attrs["parameter_path"] = n.replace("_", ".", 1)
            _var(g, "case_label", np.array([s[0] for s in spec], dtype=object), ["case"], "", "case", dtype=str_t)
        aux = " ".join(list(PARAMS) + ["case_label"])

        s = f["summary"]
        dims = ["model", "impact_z", "case"]
        _var(s, "exit_speed", exit_speed, dims, "m/s", "exit speed", aux)
        _var(s, "approach_speed", approach, dims, "m/s", "approach speed", aux)
        _var(s, "bat_index", np.broadcast_to(np.array(bat_index, np.int32), shape), dims, "1", "bat", aux)
        _var(s, "status", np.zeros(shape, np.int8), dims, "1", "status", aux)
        # Least-vibration stand-ins: |z − node| shapes (wave only; the rigid model has none).
        node2 = np.array([bat_list[b][1]["mode_nodes"][1, 2] for b in bat_index])
        node1 = np.array([bat_list[b][1]["mode_nodes"][0, 1] for b in bat_index])
        grip = np.zeros(shape)
        grip[0] = 1e-3 * (np.abs(impact_z[:, None] - node2[None, :]) + 0.1 * np.abs(impact_z[:, None] - node1[None, :]))
        energy = np.zeros(shape)
        energy[0] = 40.0 * ((impact_z[:, None] - 0.5 * (node1 + node2)[None, :]) / 0.1) ** 2
        _var(s, "grip_vibration_amplitude", np.where(np.isfinite(exit_speed), grip, NAN), dims, "m",
             "grip vibration amplitude", aux)  # fmt: skip
        _var(s, "energy_bat_vibration", np.where(np.isfinite(exit_speed), energy, NAN), dims, "J",
             "energy left in bat vibration", aux)  # fmt: skip
        recoil = 0.3 * (0.69 - impact_z)[None, :, None] * np.ones(shape)
        _var(s, "grip_recoil_speed", np.where(np.isfinite(exit_speed), recoil, NAN), dims, "m/s", "grip recoil", aux)

        ss = f["sweet_spot"]
        k = np.nanargmax(np.nan_to_num(exit_speed, nan=-1e9), axis=1)
        pos = impact_z[k]
        best = np.take_along_axis(exit_speed, k[:, None, :], axis=1)[:, 0, :]
        for name, data, units in (("position", pos, "m"), ("exit_speed", best, "m/s"), ("width", pos * 0 + 0.1, "m")):
            _var(ss, name, data, ["model", "case"], units, name, aux)
        node1 = np.array([bat_list[b][1]["mode_nodes"][0, 1] for b in bat_index])
        node2 = np.array([bat_list[b][1]["mode_nodes"][1, 2] for b in bat_index])
        wave_only = np.array([[1.0], [NAN]])  # model dim: wave, rigid
        for name, data, units in (("min_vibration_position", node2[None, :] * wave_only, "m"),
                                  ("min_vibration_amplitude", 1e-4 * (node2 - node1)[None, :] * wave_only, "m"),
                                  ("min_vibration_energy_position", 0.5 * (node1 + node2)[None, :] * wave_only, "m")):
            _var(ss, name, data, ["model", "case"], units, name, aux)

        write_history(f["history"], params, bat_list, bat_index, spec, impact_z, aux)
        write_bats(f.create_group("bat"), bat_list)
    return str(path)


def write_history(h, params, bat_list, bat_index, spec, impact_z, aux):
    """Histories for the wave model at impact_z nearest 0.60, base and aluminum cases only."""
    t = np.arange(0.0, 3.0e-3 + 1e-9, 2.0e-5)
    zs = np.round(np.arange(0.0, 0.8401, 0.02), 4)
    _scale(h, "time", t, "s", "time since first contact")
    _scale(h, "z", zs, "m", "position from the knob")
    dims = ["model", "impact_z", "case", "time"]
    n = (2, len(impact_z), len(spec), len(t))
    units = dict(force="N", compression="m", ball_velocity="m/s", displacement="m", rigid_translation="m",
                 rigid_rotation="rad")  # fmt: skip
    for name, u in units.items():
        with_z = name == "displacement"
        shape = n + (len(zs),) if with_z else n
        chunks = (1, 1, 1) + shape[3:]
        _var(h, name, None, dims + ["z"] if with_z else dims, u, name, aux, shape=shape, dtype="f8",
             chunks=chunks, fillvalue=NAN)  # fmt: skip
    iz = int(np.argmin(np.abs(impact_z - 0.60)))
    for c, p in enumerate(params):
        if c == 0 or spec[c][0] == "aluminum":
            fields = history_fields(p, bat_list[bat_index[c]][1], impact_z[iz], t, zs)
            for name, data in fields.items():
                h[name][0, iz, c] = data


def write_bats(g, bat_list):
    """/bat: one entry per distinct bat, padded with NaN."""
    labels = []
    for p, _ in bat_list:
        n = sum(label.split("-")[0] == p["bat_preset"] for label in labels)
        labels.append(p["bat_preset"] + (f"-{n + 1}" if n else ""))
    props = [b for _, b in bat_list]
    str_t = h5py.string_dtype()
    _scale(g, "bat", np.array(labels, dtype=object), "", "bat label", dtype=str_t)
    _scale(g, "mode", np.arange(1, 4), "1", "mode number")
    _scale(g, "node", np.arange(4), "1", "node index")
    _scale(g, "profile_point", np.arange(40), "1", "profile point index")
    for name, u in (("mass", "kg"), ("z_cm", "m"), ("moment_of_inertia", "kg m^2"), ("length", "m")):
        _var(g, name, np.array([b[name] for b in props]), ["bat"], u, name)
    _var(g, "mode_frequency", np.array([b["mode_frequency"] for b in props]), ["bat", "mode"], "Hz", "modes")
    _var(g, "mode_nodes", np.array([b["mode_nodes"] for b in props]), ["bat", "mode", "node"], "m", "nodes")
    for name in ("profile_z", "outer_radius", "inner_radius"):
        _var(g, name, np.array([b[name] for b in props]), ["bat", "profile_point"], "m", name)
    # Sweet-spot definitions and BBCOR (stand-ins: a parabola peaking between the nodes).
    pivot = 0.1524
    _var(g, "pivot_position", np.full(len(props), pivot), ["bat"], "m", "pivot")
    cop = [pivot + (b["moment_of_inertia"] + b["mass"] * (b["z_cm"] - pivot) ** 2) / (b["mass"] * (b["z_cm"] - pivot))
           for b in props]  # fmt: skip
    _var(g, "centre_of_percussion", np.array(cop), ["bat"], "m", "centre of percussion")
    _var(g, "node1_barrel", np.array([b["mode_nodes"][0, 1] for b in props]), ["bat"], "m", "mode-1 barrel node")
    _var(g, "node2_barrel", np.array([b["mode_nodes"][1, 2] for b in props]), ["bat"], "m", "mode-2 barrel node")
    _var(g, "bbcor_ball_speed", np.full(len(props), 136 * 0.44704), ["bat"], "m/s", "BBCOR ball speed")
    n_bb = 50
    _scale(g, "bbcor_point", np.arange(n_bb), "1", "BBCOR scan point")
    bz = np.array([b["z_cm"] + 0.005 * np.arange(n_bb) for b in props])
    peak = np.array([0.5 * (b["mode_nodes"][0, 1] + b["mode_nodes"][1, 2]) for b in props])
    bb = 0.5 - 8.0 * (bz - peak[:, None]) ** 2
    lengths = np.array([b["length"] for b in props])
    outside = bz > lengths[:, None] - 0.0366
    bz[outside], bb[outside] = NAN, NAN
    _var(g, "bbcor_z", bz, ["bat", "bbcor_point"], "m", "BBCOR scan position")
    _var(g, "bbcor", bb, ["bat", "bbcor_point"], "1", "BBCOR")
    _var(g, "bbcor_max", np.full(len(props), 0.5), ["bat"], "1", "max BBCOR")
    _var(g, "bbcor_max_position", peak, ["bat"], "m", "max BBCOR position")


def write_many_histories(path, n_cases: int = 200, n_impacts: int = 200) -> tuple[str, int]:
    """A results file of ``n_impacts`` x ``n_cases`` points (summary dims impact_z, case) in
    which every other case stored a force history: ``(path, number of stored histories)``.
    The history of point (i, c) is ``i + 1000 c`` at every time, so a row says which point
    it is."""
    impact_z = np.round(np.linspace(0.4, 0.84, n_impacts), 6)
    t = np.arange(0.0, 2.0e-3, 1.0e-4)
    stored = np.arange(0, n_cases, 2)
    with h5py.File(path, "w") as f:
        f.attrs.update(study_name="many_histories", layout_version=5)
        s, h = f.create_group("summary"), f.create_group("history")
        for g in (s, h):
            _scale(g, "impact_z", impact_z, "m", "impact position")
            _scale(g, "case", np.arange(n_cases), "1", "case index")
        _var(s, "status", np.zeros((n_impacts, n_cases), np.int8), ["impact_z", "case"], "1", "status")
        _scale(h, "time", t, "s", "time since first contact")
        _scale(h, "z", np.array([0.0]), "m", "position from the knob")
        force = _var(h, "force", None, ["impact_z", "case", "time"], "N", "force",
                     shape=(n_impacts, n_cases, len(t)), dtype="f8", chunks=(1, 1, len(t)), fillvalue=NAN)  # fmt: skip
        rows = np.arange(n_impacts)[:, None, None] + 1000.0 * stored[None, :, None]
        force[:, ::2, :] = np.broadcast_to(rows, (n_impacts, len(stored), len(t)))
    return str(path), n_impacts * len(stored)


def write_hostile(path, payload: str) -> str:
    """The synthetic file with `payload` appended to every string a page of it can show: the
    study's name and description, every text value of /summary, /sweet_spot and /history
    (the models, the bat presets, the case labels, ...), and their variables' units and long
    names. Returns the path."""
    write(path)
    with h5py.File(path, "r+") as f:
        for attr in ("study_name", "study_description", "title"):
            f.attrs[attr] = str(f.attrs[attr]) + payload
        for group in ("summary", "sweet_spot", "history"):
            for ds in f[group].values():
                if ds.dtype.kind == "O":
                    ds[...] = np.array([v.decode() + payload for v in ds[...]], dtype=object)
                for attr in ("units", "long_name"):
                    if attr in ds.attrs:
                        ds.attrs[attr] = str(ds.attrs[attr]) + payload
    return str(path)


if __name__ == "__main__":
    print(write(sys.argv[1] if len(sys.argv) > 1 else "synthetic.h5"))
