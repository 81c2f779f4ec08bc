"""The figures of the paper's section 4, drawn from any results file that has their data.

``FIGURES`` names each one (the file it is written to) and its drawing function
``f(res, path)``; a figure whose data the file does not hold (for instance a study without
aluminum cases) raises :class:`Skip` with a one-line reason.

Data each figure needs (curves are exit speed vs ``impact_z``; "varying F" means the curves
that equal the base curve on every parameter but F, from a ``case`` block or a grid axis F):

fig02  rigid model, base curve                  fig10  varying bat_material_density
fig04a /history/force, wave, impact near 0.60   fig11a varying bat_material_youngs_modulus
fig04b /history/displacement at z near 0.10     fig11b varying bat_handle_radius_scale
fig05a bat_ends_barrel == fixed vs base         fig12  varying ball_speed
fig05b bat_length ≈ 1.10 vs base                fig13a bat_preset == corked vs base
fig06  varying swing_omega, wave and rigid      fig13b bat_preset == aluminum vs base
fig07a varying swing_omega, approach_speed      fig14  displacement + rigid motion histories,
fig07b the same with ball_law_kind == elastic          base and aluminum, impact near 0.60
fig07c the same with ball_law_kind == speed_dependent (no preset)
fig07d the same with ball_preset == mlb
fig08  /sweet_spot/position, varying omega      fig15  hoop_frequency > 0 and the no-hoop bat
anim   as fig14                                 bat_profiles  /bat profile and mode nodes
sweet_spot_definitions  /bat profiles with every sweet-spot definition (/bat, /sweet_spot)
ball_tests  the wall test: COR and contact times vs ball_speed per ball law (studies/ball_tests.yaml)
batter      exit speed and carry along the barrel per bat, swing fixed or scaled (studies/batter.yaml)
undercut    launch, spin and carry vs impact.offset, and the contact's parameters (studies/undercut.yaml)
"""

from __future__ import annotations

import numpy as np
from matplotlib.lines import Line2D
from PIL import Image

from ._curves import IMPACT, MODEL, Skip, excess_speed, one_factor, select
from ._draw import (COLORS, STYLES, Z_LABEL, draw_profiles, loaded_bats, new_axes, new_figure, require, save,
                    short_bat_label)  # fmt: skip
from ._batter import BATTER_FIGURES
from ._uncertainty import UNCERTAINTY_FIGURES
from ._sweet_defs import sweet_spot_definitions

EXIT = "exit speed (m/s, bat-CM frame)"
IMPACT_LABEL = "impact position z (m from the knob)"
HANDLE_Z = 0.10  # Fig. 4b: motion 10 cm from the knob
IMPACT_Z = 0.60  # Figs. 4 and 14: impact 60 cm from the knob
SNAPSHOTS = (1.05e-3, 1.10e-3)  # Fig. 14 times (s)
MAX_FRAMES = 40  # the GIF: at most this many frames (the brief: <= 60)
# Parameters that come with a bat preset (free to differ when selecting corked/aluminum).
PRESET_PARAMS = {"bat_preset", "bat_shell_thickness", "bat_fill_density", "bat_material_density",
                 "bat_material_youngs_modulus"}  # fmt: skip


# --------------------------------------------------------------------------- drawing helpers


def curve_figure(res, path, title, curves, base=None, value=None, ylabel=EXIT, twins=False, always=(), label=None):
    """One line per curve of ``value(res, curve)`` (default exit speed) vs impact position.

    ``base`` (if given and among the curves) is drawn black and solid, the others in colour
    with distinct line styles.  With ``twins`` every (wave) curve is solid in its own colour,
    its rigid-model twin dashed in the same colour and the rigid maximum a dot (Fig. 6).
    ``label(curve)``, if given, names each line instead of its parameters or case label."""
    value = value or (lambda r, c: r.values(c, "exit_speed"))
    fig, ax = new_axes(title, IMPACT_LABEL, ylabel, res.name)
    others = 0
    recontacts = 0
    for i, c in enumerate(curves):
        y = value(res, c)
        name = label(c) if label else res.label(c, base, always)
        # Where the ball came back into contact (the handle whipped back): the curve jumps
        # there, and the mark says why.
        try:
            again = np.asarray(res.values(c, "recontact").values) == 1
        except Skip:
            again = np.zeros(y.shape, dtype=bool)
        if again.any():
            recontacts += 1
            ax.plot(np.asarray(y[IMPACT])[again], np.asarray(y)[again], "x", color="black", ms=6, mew=1.2)
        if c == base and not twins:
            ax.plot(y[IMPACT], y, color="black", lw=2, label=name)
            continue
        color, style = COLORS[i % len(COLORS)], "-" if twins else STYLES[others % len(STYLES)]
        others += 1
        ax.plot(y[IMPACT], y, color=color, ls=style, lw=1.6, label=name)
        rigid = res.partner(c, "rigid") if twins else None
        if rigid is not None:
            yr = value(res, rigid)
            ax.plot(yr[IMPACT], yr, color=color, ls="--", lw=1.2)
            z_max, v_max = res.sweet(rigid)
            ax.plot([z_max], [v_max], "o", color=color, ms=6)
    handles, _ = ax.get_legend_handles_labels()
    if recontacts:
        handles.append(Line2D([], [], color="black", ls="", marker="x", label="ball hit again (re-contact)"))
    if twins:
        handles += [Line2D([], [], color="gray", ls="-", label="wave model"),
                    Line2D([], [], color="gray", ls="--", label="rigid model"),
                    Line2D([], [], color="gray", ls="", marker="o", label="rigid-model maximum")]  # fmt: skip
    ax.legend(handles=handles, fontsize=8)
    save(fig, path)


def factor_figure(res, path, title, factor=None, where=None, free=(), extra=()):
    """Base curve and the curves that differ from it only in ``factor`` (or that satisfy
    ``where``, differing also in ``free``), main model; ``extra`` curves are added."""
    model = res.main_model()
    base = res.base(model)
    if factor is not None:
        chosen = one_factor(res.curves, base, factor)
    else:
        chosen = [base] + select(res.curves, base, free=free, where=where)
    chosen = list(dict.fromkeys(list(chosen) + list(extra)))
    require([c for c in chosen if c != base], f"curves for {title.split(':')[0]}")
    curve_figure(res, path, f"{title} — {model} model", chosen, base)


# --------------------------------------------------------------------------- figures


def fig02(res, path):
    base = res.base("rigid") if "rigid" in res.models() else None
    if base is None:
        raise Skip("no rigid-model curves")
    y = res.values(base)
    z_cm = res.z_cm(base)
    fig, ax = new_axes("Fig. 2: rigid-body (Brody) model, exit speed vs distance from the CM — base case",
                       "l = z − z_cm (m)", EXIT, res.name)  # fmt: skip
    ax.plot(y[IMPACT] - z_cm, y, color="black", lw=2, label=f"rigid model, {res.label(base)}")
    ax.axvline(0, color="gray", ls=":", label=f"centre of mass (z_cm = {z_cm:.3f} m)")
    ax.legend(fontsize=8)
    save(fig, path)


def _wave_candidates(res):
    """The base wave curve first, then every other wave curve (for recorded histories)."""
    model = res.main_model()
    base = res.base(model)
    return [base] + [c for c in res.curves if c.params[MODEL] == model and c != base]


def fig04a(res, path):
    curve, z_imp, force = res.first_history(_wave_candidates(res), "force", IMPACT_Z)
    fig, ax = new_axes(f"Fig. 4a: contact force vs time — {res.label(curve)}, impact at z = {z_imp:.2f} m",
                       "time since first contact (ms)", "force (N)", res.name)  # fmt: skip
    ax.plot(force["time"] * 1e3, force, color="black", lw=1.8, label=f"{curve.params[MODEL]} model")
    ax.legend(fontsize=8)
    save(fig, path)


def fig04b(res, path):
    curve, z_imp, disp = res.first_history(_wave_candidates(res), "displacement", IMPACT_Z)
    k = int(np.argmin(np.abs(disp["z"].values - HANDLE_Z)))
    z_at = float(disp["z"].values[k])
    fig, ax = new_axes(f"Fig. 4b: bat motion at z = {z_at:.2f} m from the knob — {res.label(curve)}, "
                       f"impact at z = {z_imp:.2f} m", "time since first contact (ms)", "displacement y (mm)",
                       res.name)  # fmt: skip
    t_ms = disp["time"] * 1e3
    lines = ax.plot(t_ms, disp.isel(z=k) * 1e3, color="black", lw=1.8, label="displacement y(z, t) (left axis)")
    try:
        _, flex = res.flex_displacement(curve, z_imp)
        right = ax.twinx()  # the flexible part is much smaller than the rigid recoil
        right.set_ylabel("y − rigid motion (mm)", color=COLORS[0])
        lines += right.plot(t_ms, flex.isel(z=k) * 1e3, color=COLORS[0], ls="--",
                            label="rigid motion removed (right axis)")  # fmt: skip
    except Skip:
        pass
    ax.legend(handles=lines, fontsize=8, loc="lower right")
    save(fig, path)


def fig05a(res, path):
    factor_figure(res, path, "Fig. 5a: free vs fixed barrel end (knob free)", where={"bat_ends_barrel": "fixed"})


def fig05b(res, path):
    top = float(np.nanmax(res.summary[IMPACT].values)) if res.summary is not None and IMPACT in res.summary else 0.0
    note = f" (impacts sampled to {top:.2f} m; studies/boundaries.yaml reaches 1.10 m)" if top < 1.0 else ""
    factor_figure(res, path, "Fig. 5b: a 110 cm bat vs the base bat" + note,
                  where={"bat_length": lambda v: abs(v - 1.10) < 0.005}, free={"bat_ends_barrel"})  # fmt: skip


# The ball's own parameters, which a ball of its own (a `case`) may set.
BALL_LAW_PARAMS = {"ball_law_kind", "ball_law_stiffness", "ball_law_cor", "ball_law_k1", "ball_law_alpha",
                   "ball_law_reference_speed", "ball_law_cor_slope", "ball_law_loading", "ball_law_cor_exponent"}


def _omega_curves(res, law=None):
    """Wave curves varying swing_omega, with the base ball law or with ``law`` (a
    ``ball_law_kind`` such as ``elastic``, or ``preset:NAME`` for a built-in ball)."""
    base = res.base(res.main_model())
    if law:
        free = {"swing_omega"} | BALL_LAW_PARAMS | {"ball_preset"}
        preset = law.split(":", 1)[1] if law.startswith("preset:") else None
        where = {"ball_preset": preset} if preset else {"ball_law_kind": law}
        curves = [c for c in select(res.curves, base, free=free, where=where)
                  if preset or c.params.get("ball_preset") in (None, "")]
        curves.sort(key=lambda c: c.params.get("swing_omega", 0.0))
    else:
        curves = one_factor(res.curves, base, "swing_omega")
    if len(curves) < 2:
        raise Skip("no swing_omega variation" + (f" with a {law} ball" if law else ""))
    return curves


def fig06(res, path):
    curves = _omega_curves(res)
    curve_figure(res, path, "Fig. 6: exit speed vs impact position at several swing speeds ω",
                 curves, twins=True, always=("swing_omega",))  # fmt: skip


def _excess_figure(res, path, title, law):
    curves = _omega_curves(res, law)
    # every line has the same ball: name the swing speed, which is what varies
    by_omega = (lambda c: res.format_param("swing_omega", c.params.get("swing_omega", 0.0))) if law else None
    curve_figure(res, path, title, curves, res.base(), value=excess_speed, always=("swing_omega",),
                 ylabel="exit speed − approach speed (m/s)\napproach = v_ball − ω (z − z_cm)",
                 label=by_omega)  # fmt: skip


def fig07a(res, path):
    _excess_figure(res, path, "Fig. 7a: excess exit speed vs impact position at several ω (with hysteresis)", None)


def fig07b(res, path):
    _excess_figure(res, path, "Fig. 7b: excess exit speed vs impact position at several ω (elastic ball)", "elastic")


def fig07c(res, path):
    _excess_figure(res, path, "Fig. 7a with a ball whose COR falls with speed (e = 0.5 at 40 m/s, −0.001 per m/s)",
                   "speed_dependent")  # fmt: skip


def fig07d(res, path):
    _excess_figure(res, path, "Fig. 7a with the calibrated MLB ball (ball.preset: mlb)", "preset:mlb")


def fig08(res, path):
    curves = _omega_curves(res)
    omega = [c.params["swing_omega"] for c in curves]
    fig, ax = new_axes("Fig. 8: optimal impact position vs swing speed ω",
                       "ω (rad/s; negative = barrel toward the ball)", "sweet-spot position (m from the knob)",
                       res.name)  # fmt: skip
    ax.plot(omega, [res.sweet(c)[0] for c in curves], "o", color="black", label="wave model")
    rigid = [res.partner(c, "rigid") for c in curves]
    if all(r is not None for r in rigid):
        ax.plot(omega, [res.sweet(r)[0] for r in rigid], "-", color=COLORS[0], label="rigid model")
    ax.legend(fontsize=8)
    save(fig, path)


def fig10(res, path):
    factor_figure(res, path, "Fig. 10: varying the wood density", "bat_material_density")


def fig11a(res, path):
    factor_figure(res, path, "Fig. 11a: varying Young's modulus", "bat_material_youngs_modulus")


def fig11b(res, path):
    factor_figure(res, path, "Fig. 11b: varying the handle profile", "bat_handle_radius_scale")


def fig12(res, path):
    factor_figure(res, path, "Fig. 12: varying the ball speed", "ball_speed")


def fig13a(res, path):
    factor_figure(res, path, "Fig. 13a: corked vs wood bat", where={"bat_preset": "corked"}, free=PRESET_PARAMS)


def fig13b(res, path):
    factor_figure(res, path, "Fig. 13b: aluminum vs wood bat", where={"bat_preset": "aluminum"}, free=PRESET_PARAMS)


def fig15(res, path):
    model = res.main_model()
    hooped = [c for c in res.curves if c.params[MODEL] == model and c.params.get("hoop_frequency", 0) > 0]
    first = require(hooped, "curves with a hoop mode (hoop_frequency > 0)")[0]
    chosen = select(res.curves, first, free={"hoop_frequency", "hoop_mass"})  # same bat, with and without hoop
    chosen.sort(key=lambda c: c.params.get("hoop_frequency") if c.params.get("hoop_frequency", 0) > 0 else -1.0)
    wood = res.base(model)
    curves = ([wood] if wood not in chosen else []) + chosen
    # Labelled against the wood base case, as in every other figure ("base case" = the wood bat);
    # the hoop curves share their bat, so their labels name the hoop.
    curve_figure(res, path, f"Fig. 15: hoop modes on the {first.params.get('bat_preset', 'hollow')} bat, "
                 f"and the wood base case ({model} model)", curves, wood)  # fmt: skip


def _wood_and_aluminum(res):
    """[(name, curve)] for the base (wood) bat and the first aluminum curve, main model."""
    base = res.base(res.main_model())
    alu = select(res.curves, base, free=PRESET_PARAMS, where={"bat_preset": "aluminum"})
    return [("wood (base)", base)] + [("aluminum", c) for c in alu[:1]]


def _flex_histories(res):
    """[(name, impact_z, flex DataArray (time, z))] for wood and aluminum, where recorded."""
    found = []
    for name, curve in _wood_and_aluminum(res):
        got = res.flex_displacement(curve, IMPACT_Z)
        if got is not None:
            found.append((name, *got))
    return require(found, "displacement histories of the base or aluminum bat")


def fig14(res, path):
    found = _flex_histories(res)
    how = found[0][2].attrs["rigid_removal"]
    fig, ax = new_axes(f"Fig. 14: displacement along the bat ({how})\nwood (solid) vs aluminum (dashed)",
                       Z_LABEL, "displacement − rigid motion (mm)", res.name)  # fmt: skip
    for (name, z_imp, flex), style in zip(found, ("-", "--")):
        for t, color in zip(SNAPSHOTS, COLORS):
            k = int(np.argmin(np.abs(flex["time"].values - t)))
            t_at = float(flex["time"].values[k]) * 1e3
            ax.plot(flex["z"], flex.isel(time=k) * 1e3, ls=style, color=color,
                    label=f"{name}, t = {t_at:.2f} ms (impact at {z_imp:.2f} m)")  # fmt: skip
    ax.legend(fontsize=8)
    save(fig, path)


def anim(res, path):
    found = _flex_histories(res)
    time = found[0][2]["time"].values
    frames = np.unique(np.linspace(0, len(time) - 1, min(MAX_FRAMES, len(time))).round().astype(int))
    ymax = max(float(np.nanmax(np.abs(f.values))) for _, _, f in found) * 1e3 or 1.0
    fig, ax = new_axes(f"Bat displacement during the collision ({found[0][2].attrs['rigid_removal']})",
                       Z_LABEL, "displacement − rigid motion (mm)", res.name)  # fmt: skip
    ax.set_ylim(-1.1 * ymax, 1.1 * ymax)
    lines = [ax.plot([], [], ls=s, color="black" if s == "-" else COLORS[0], lw=1.8,
                     label=f"{name} (impact at {z:.2f} m)")[0] for (name, z, _), s in zip(found, ("-", "--"))]  # fmt: skip
    # The z grid reaches the study's longest bat; show the bats drawn, not the empty rest.
    ends = [float(flex["z"].values[np.isfinite(flex.values).any(axis=0)].max()) for _, _, flex in found]
    ax.set_xlim(float(found[0][2]["z"].min()), max(ends))
    for (name, z, _), s in zip(found, ("-", "--")):  # where the ball hits
        ax.axvline(z, color="0.5", ls=":", lw=1)
        ax.plot([z], [1.0 * ymax], marker="v", color="firebrick", ms=9, ls="none")
    ax.text(found[0][1], 1.05 * ymax, " impact", color="firebrick", fontsize=8, va="center")
    stamp = ax.text(0.02, 0.95, "", transform=ax.transAxes, va="top", animated=True)
    for line in lines:
        line.set_animated(True)  # drawn per frame, not into the background
    ax.legend(fontsize=8, loc="lower right")
    # Blitting: the axes, labels and legend are drawn once; each frame draws only the two
    # curves and the time stamp onto that background (a full redraw per frame took 0.2 s).
    fig.set_dpi(70)
    fig.canvas.draw()
    fig.set_layout_engine("none")
    background = fig.canvas.copy_from_bbox(fig.bbox)
    images = []
    for k in frames:
        fig.canvas.restore_region(background)
        for line, (_, _, flex) in zip(lines, found):
            kk = min(k, flex.sizes["time"] - 1)
            line.set_data(flex["z"].values, flex.isel(time=kk).values * 1e3)
            ax.draw_artist(line)
        stamp.set_text(f"t = {time[k] * 1e3:.2f} ms")
        ax.draw_artist(stamp)
        rgba = np.asarray(fig.canvas.buffer_rgba())
        images.append(Image.fromarray(rgba[..., :3].copy()).quantize(colors=64, method=Image.Quantize.MEDIANCUT))
    images[0].save(path, save_all=True, append_images=images[1:], duration=round(1000 / 12), loop=0)


def bat_profiles(res, path):
    bat = loaded_bats(res.bat)
    fig = new_figure(figsize=(11.0, 4.2 + 0.25 * bat.sizes["bat"]), layout="constrained")
    top, low = fig.subplots(2, 1, sharex=True, height_ratios=[2, 1.2])
    top.set_title(f"Bat profiles (outer radius solid, inner dashed) and mode nodes\n(study: {res.name})", fontsize=10)
    draw_profiles(top, bat)
    top.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0)
    markers = ["v", "^", "s", "D", "P"]
    n_modes = min(3, bat.sizes.get("mode", 0)) if "mode_nodes" in bat else 0
    ticks = []
    for i in range(bat.sizes["bat"]):
        b = bat.isel(bat=i)
        freqs = b["mode_frequency"].values[:n_modes] if "mode_frequency" in b else []
        ticks.append(f"{short_bat_label(str(b['bat'].item()))}: {float(b['mass']):.3f} kg, "
                     f"f = {', '.join(f'{f:.0f}' for f in freqs)} Hz")  # fmt: skip
        for m in range(n_modes):
            nodes = b["mode_nodes"].isel(mode=m).values
            nodes = nodes[np.isfinite(nodes)]
            low.plot(nodes, np.full(nodes.shape, i), markers[m], color=COLORS[m], ms=5,
                     label=f"nodes of mode {m + 1}" if i == 0 else None)  # fmt: skip
        low.plot([float(b["z_cm"])], [i], "|", color="black", ms=10, label="centre of mass" if i == 0 else None)
    low.set_yticks(range(len(ticks)), ticks, fontsize=7)
    low.invert_yaxis()
    low.set_xlabel(Z_LABEL)
    low.grid(alpha=0.3)
    fig.legend(*low.get_legend_handles_labels(), fontsize=7, ncol=4, loc="outside lower center")
    save(fig, path)


# Published points for the ball-test figure (docs/physics.md, "The ball"; docs/results.md).
MLB_SPEC = (25.9, 0.546, 0.032)  # 85 ft/s, COR 0.546 ± 0.032 on northern white ash
CROSS_LOW_SPEED = (1.0, 0.64)  # measured on a hard floor (Nathan 2000, §III.B)
NATHAN_MODEL_COR = [(58.0, 0.53), (71.0, 0.50)]  # Nathan's (2000) choices, not measurements
NATHAN_FIG3 = [(1.0, 2.2), (11.0, 1.0), (45.0, 0.7), (67.0, 0.6)]  # ms to 99 % of the impulse


def _law_label(summary, i: int) -> str:
    def coord(name):
        if name not in summary.coords:
            return None
        v = summary[name].isel(law=i).values.item()
        return v.decode() if isinstance(v, bytes) else v

    kind = coord("ball_law_kind") or "?"
    text = kind.replace("_", " ")
    cor = coord("ball_law_cor")
    if cor is not None and np.isfinite(cor) and kind != "elastic":
        text += f", e = {cor:g}" + (" at 25.9 m/s" if kind == "speed_dependent" else "")
    loading = coord("ball_law_loading")
    if kind == "speed_dependent" and loading:
        text += f", {loading} loading"
    return text


def ball_tests(res, path):
    """The wall test: COR and contact times against impact speed, one line per ball law."""
    s = res.summary
    if s is None or "ball_speed" not in s.dims or "law" not in s.dims or "approach_speed" not in s:
        raise Skip("not a wall test over ball_speed and law (studies/ball_tests.yaml)")
    if "preset: wall" not in str(res.attrs.get("study_yaml", "")):
        raise Skip("the target is not the wall")
    v = s["ball_speed"].values
    fig = new_figure(figsize=(11.5, 4.6), layout="constrained")
    left, right = fig.subplots(1, 2)
    fig.suptitle(f"Balls fired at a rigid wall (study: {res.name})", fontsize=10)
    for i in range(s.sizes["law"]):
        label = _law_label(s, i)
        row = s.isel(law=i)
        cor = (row["exit_speed"] / row["approach_speed"]).values
        left.plot(v, cor, "-", color=COLORS[i % len(COLORS)], label=label)
        if "impulse_time_99" in row and np.isfinite(row["impulse_time_99"].values).any():
            right.plot(v, row["contact_time"].values * 1e3, "-", color=COLORS[i % len(COLORS)], label=label)
            right.plot(v, row["impulse_time_99"].values * 1e3, "--", color=COLORS[i % len(COLORS)])
    sv, sc, su = MLB_SPEC
    left.errorbar([sv], [sc], yerr=[su], fmt="s", color="black", capsize=4, label="MLB specification (25.9 m/s)")
    left.plot(*CROSS_LOW_SPEED, "o", color="black", label="measured, 1 m/s (Cross, in Nathan 2000)")
    left.plot(*zip(*NATHAN_MODEL_COR), "o", mfc="none", color="black", label="Nathan 2000's assumed e (model)")
    left.set_xlabel("impact speed (m/s)")
    left.set_ylabel("wall COR = rebound / impact speed")
    left.set_ylim(0.4, 1.02)
    left.grid(alpha=0.3)
    left.legend(fontsize=7, loc="center right")
    right.plot(*zip(*NATHAN_FIG3), "D", color="black", label="Nathan 2000 Fig. 3 (99 % of impulse)")
    right.plot([], [], "-", color="gray", label="contact time (compression back to 0)")
    right.plot([], [], "--", color="gray", label="time to 99 % of the impulse")
    right.set_xlabel("impact speed (m/s)")
    right.set_ylabel("time (ms)")
    right.set_ylim(bottom=0)
    right.grid(alpha=0.3)
    right.legend(fontsize=7)
    save(fig, path)


# Output name -> drawing function.
FIGURES = {
    "fig02_rigid_model": fig02,
    "fig04a_force": fig04a,
    "fig04b_handle_motion": fig04b,
    "fig05a_fixed_vs_free": fig05a,
    "fig05b_110cm_bat": fig05b,
    "fig06_exit_speed_vs_omega": fig06,
    "fig07a_excess_exit_speed": fig07a,
    "fig07b_excess_no_hysteresis": fig07b,
    "fig07c_excess_speed_dependent_ball": fig07c,
    "fig07d_excess_calibrated_ball": fig07d,
    "fig08_optimal_position_vs_omega": fig08,
    "fig10_density": fig10,
    "fig11a_modulus": fig11a,
    "fig11b_handle": fig11b,
    "fig12_ball_speed": fig12,
    "fig13a_corked": fig13a,
    "fig13b_aluminum": fig13b,
    "fig14_displacement_along_bat": fig14,
    "fig15_hoop_frequencies": fig15,
    "bat_profiles": bat_profiles,
    "sweet_spot_definitions": sweet_spot_definitions,
    "anim_displacement": anim,
}
# Figures of other kinds of study, drawn when the file holds one (the paper's set above is
# what a bat study gives).
OTHER_FIGURES = {
    "ball_tests": ball_tests,
    **BATTER_FIGURES,
    **UNCERTAINTY_FIGURES,
}
