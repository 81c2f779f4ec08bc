"""The batter's figures: one batter swinging different bats (``batter``), and
undercut hits over the offset of the ball below the bat's axis (``undercut``).

``batter`` needs a summary over ``batter_exponent``, ``impact_offset``, ``impact_z`` and a
points dimension ``bat`` (studies/batter.yaml); ``undercut`` one over
``swing_attack_angle``, ``impact_offset`` and a points dimension ``contact``
(studies/undercut.yaml). Every string shown comes from the file's labels through matplotlib's
text (never evaluated).
"""

from __future__ import annotations

import numpy as np

from ._curves import Skip
from ._draw import COLORS, new_figure, save, short_bat_label

MPH = 0.44704
FOOT = 0.3048
RPM = np.pi / 30.0


def _need(s, dims, what):
    if s is None or any(d not in s.dims for d in dims):
        raise Skip(f"not {what} (dimensions {', '.join(dims)})")


def _labels(s, dim):
    name = f"{dim}_label"
    return [short_bat_label(str(v)) for v in s[name].values] if name in s else [str(i) for i in range(s.sizes[dim])]


def _bat_names(s) -> list[str]:
    """Short names of the bats: the preset, drilled if bored, with its hoop mode."""
    names = []
    for k in range(s.sizes["bat"]):
        row = s.isel(bat=k)
        name = str(row["bat_preset"].values) if "bat_preset" in s.coords else "bat"
        name = {"r161": "wood"}.get(name, name)
        if "bat_bore_diameter" in s.coords and np.isfinite(float(row["bat_bore_diameter"].values)):
            name += f", drilled {float(row['bat_bore_diameter'].values) * 100:.2g} cm and filled"
        if "hoop" in s.coords and str(row["hoop"].values) not in ("", "null", "None", "nan"):
            name += " + hoop mode"
        names.append(name)
    return names


def batter(res, path):
    """Exit speed and carry along the barrel for each bat, swung at the same rate (dashed)
    and by the batter whose swing answers to the bat's MOI (solid)."""
    s = res.summary
    _need(s, ("batter_exponent", "impact_offset", "impact_z", "bat"), "a batter study")
    if "carry" not in s:
        raise Skip("no carry in this file")
    n_values = s["batter_exponent"].values
    offsets = s["impact_offset"].values
    z = s["impact_z"].values
    labels = _bat_names(s)
    fig = new_figure(figsize=(12.5, 4.8), layout="constrained")
    left, right = fig.subplots(1, 2)
    fig.suptitle(f"One batter, several bats (study: {res.name})", fontsize=10)
    head_on = int(np.argmin(np.abs(offsets)))
    undercut = int(np.argmax(np.abs(offsets)))
    for k, label in enumerate(labels):
        color = COLORS[k % len(COLORS)]
        for j, n in enumerate(n_values):
            style = "-" if n > 0 else "--"
            row = s.isel(bat=k, batter_exponent=j)
            name = f"{label}, n = {n:g}"
            left.plot(z, row["exit_speed_lab"].isel(impact_offset=head_on).values / MPH, style, color=color,
                      label=name)
            right.plot(z, row["carry"].isel(impact_offset=undercut).values / FOOT, style, color=color, label=name)
    left.set_title(f"head-on (offset {offsets[head_on] * 100:g} cm): batted-ball speed", fontsize=9)
    right.set_title(f"undercut by {abs(offsets[undercut]) * 100:g} cm: carry", fontsize=9)
    for ax, ylabel in ((left, "batted-ball speed, lab (mph)"), (right, "carry (ft)")):
        ax.set_xlabel("impact position z (m from the knob)")
        ax.set_ylabel(ylabel)
        ax.grid(alpha=0.3)
    left.legend(fontsize=7, title="solid: swing answers to the MOI; dashed: same swing", title_fontsize=7)
    save(fig, path)


def undercut(res, path):
    """Launch angle, backspin and carry against the offset, per swing plane; and the carry's
    dependence on the contact's uncertain parameters (friction, tangential stiffness)."""
    s = res.summary
    _need(s, ("swing_attack_angle", "impact_offset", "contact"), "an undercut study")
    if "launch_angle" not in s:
        raise Skip("no launch angle in this file")
    where = ""
    if "impact_z" in s.dims:
        s = s.sel(impact_z=0.70, method="nearest")
        where = f", {float(s['impact_z']):.2f} m from the knob"
    offset = s["impact_offset"].values * 100
    angles = s["swing_attack_angle"].values
    fig = new_figure(figsize=(12.5, 8.5), layout="constrained")
    axes = fig.subplots(2, 2)
    fig.suptitle(f"Undercut hits{where}: the ball below (+) or above (−) the bat's axis (study: {res.name})",
                 fontsize=10)
    base = s.isel(contact=0)
    panels = ((axes[0, 0], "launch_angle", np.degrees(1.0), "launch angle (deg)"),
              (axes[0, 1], "spin", 1 / RPM, "backspin (rpm; negative: topspin)"),
              (axes[1, 0], "carry", 1 / FOOT, "carry (ft)"))
    for ax, var, scale, ylabel in panels:
        for i, a in enumerate(angles):
            ax.plot(offset, base[var].isel(swing_attack_angle=i).values * scale, "-", color=COLORS[i % len(COLORS)],
                    label=f"swing plane {np.degrees(a):.0f}°")
        ax.set_ylabel(ylabel)
    middle = len(angles) // 2
    ax = axes[1, 1]
    for k, label in enumerate(_labels(s, "contact")):
        row = s.isel(contact=k, swing_attack_angle=middle)
        ax.plot(offset, row["carry"].values / FOOT, "-" if k == 0 else "--", color=COLORS[k % len(COLORS)],
                label=label if k else f"{label} (the defaults)")
    ax.set_title(f"the contact's parameters, swing plane {np.degrees(angles[middle]):.0f}°", fontsize=9)
    ax.set_ylabel("carry (ft)")
    for ax in axes.flat:
        ax.set_xlabel("impact offset (cm; negative: undercut)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    save(fig, path)


BATTER_FIGURES = {"batter": batter, "undercut": undercut}
