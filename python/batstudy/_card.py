"""What each bat of a results file *is*, as the trade states it (``batstudy card``)."""

from __future__ import annotations

# The trade's units in SI (the same as the Rust crate's `units`).
INCH = 0.0254
OUNCE = 0.028349523125
OUNCE_SQUARE_INCH = OUNCE * INCH * INCH
# the standard pound-force, N (0.45359237 kg × 9.80665 m/s²)
POUND_FORCE = 0.45359237 * 9.80665

# (card variable, /bat variable) in the order the card shows them
_FROM_BAT = [
    ("length", "length"),
    ("mass", "mass"),
    ("drop", "drop"),
    ("balance_point", "z_cm"),
    ("moment_of_inertia_knob", "moment_of_inertia_knob"),
    ("moment_of_inertia_knob6", "moment_of_inertia_knob6"),
    ("barrel_diameter", "barrel_diameter"),
    ("bbcor_max", "bbcor_max"),
    ("bbcor_max_position", "bbcor_max_position"),
    ("bbcor_shot", "bbcor_shot"),
    ("sweet_zone_start", "sweet_zone_start"),
    ("sweet_zone_end", "sweet_zone_end"),
    ("sweet_zone_length", "sweet_zone_length"),
    ("hoop_mode_frequency", "hoop_mode_frequency"),
    ("barrel_compression", "barrel_compression"),
    ("wall_stress_ratio", "wall_stress_ratio"),
    ("wall_stress_ratio_position", "wall_stress_ratio_position"),
    ("best_q", "best_q"),
    ("best_q_position", "best_q_position"),
    ("rule_value", "rule_value"),
    ("rule_margin", "rule_margin"),
    ("rule_units", "rule_units"),
]

# the card's quantities that older files lack (layout 7 added the best q; the barrel
# compression came within layout 7)
_OPTIONAL = {"best_q": "1", "best_q_position": "m", "barrel_compression": "N",
             "wall_stress_ratio": "1", "wall_stress_ratio_position": "m"}

# the trade's units beside SI: (new variable, SI variable, scale, units)
_TRADE = [
    ("length_in", "length", 1 / INCH, "in"),
    ("mass_oz", "mass", 1 / OUNCE, "oz"),
    ("balance_point_in", "balance_point", 1 / INCH, "in"),
    ("moment_of_inertia_knob_oz_in2", "moment_of_inertia_knob", 1 / OUNCE_SQUARE_INCH, "oz in^2"),
    ("moment_of_inertia_knob6_oz_in2", "moment_of_inertia_knob6", 1 / OUNCE_SQUARE_INCH, "oz in^2"),
    ("barrel_diameter_in", "barrel_diameter", 1 / INCH, "in"),
    ("sweet_zone_length_in", "sweet_zone_length", 1 / INCH, "in"),
    ("barrel_compression_lbf", "barrel_compression", 1 / POUND_FORCE, "lbf"),
]


def bat_card(tree, bat=None):
    """Each bat's card as an :class:`xarray.Dataset` along ``bat`` (one bat: ``bat``, its
    label or index from 0).

    SI variables with their units, as ``/bat`` stores them: ``length``, ``mass``, ``drop``
    (weight in oz minus length in in), ``balance_point`` (the centre of mass, from the
    knob), ``moment_of_inertia_knob`` and ``moment_of_inertia_knob6`` (about the knob and
    about the point 6 in from it), ``barrel_diameter``, ``bbcor_max`` and where
    (``bbcor_max_position``), ``bbcor_shot`` (the ball and hoop of the BBCOR scan, JSON),
    the sweet zone (``sweet_zone_start``, ``sweet_zone_end``, ``sweet_zone_length``: the
    barrel whose BBCOR is within 0.01 of its peak), ``bending_frequency`` (the lowest
    free-free bending mode) and ``hoop_mode_frequency`` (the wall's lowest breathing mode;
    NaN for a solid bat), ``barrel_compression`` (N: the static force that closes the
    barrel's diameter by 0.040 in 6 in from its end, the trade's barrel compression; NaN
    without a shell barrel), ``wall_stress_ratio`` and where (``wall_stress_ratio_position``:
    the barrel wall's largest stress under the BBCOR shots over its strength; above 1 it
    would dent or crack; NaN without a shell barrel), ``best_q`` and where (``best_q_position``: the best collision
    efficiency in the field's convention, exit = q pitch + (1 + q) bat speed 6 in from the
    end, at a 70-mph swing meeting an 82-mph pitch); along ``rule_check`` each rule's ``rule_value``, ``rule_margin``
    (negative: the bat breaks it), ``rule_units``, ``rule_passes`` and ``rule_applies``
    (False where the rule set is not for the bat: MLB's wood-bat rules on a hollow bat, as
    ``batstudy card`` shows them). The trade's units
    beside: ``length_in``, ``mass_oz``, ``balance_point_in``, the swing weights in
    ``oz in^2``, ``barrel_diameter_in``, ``sweet_zone_length_in``, ``barrel_compression_lbf``.

    One bat's card has no ``bat`` dimension (its label is a scalar coordinate).
    ``tree`` is what :func:`batstudy.open_results` returns. A file written before bats had
    cards raises ``ValueError`` (run the study again).
    """
    import numpy as np
    import xarray as xr

    if "bat" not in tree.children:
        raise ValueError("the results file has no /bat group")
    stored = tree["bat"].to_dataset()
    for name, units in _OPTIONAL.items():  # an older file's card shows them unknown
        if name not in stored and "mass" in stored:
            stored[name] = xr.full_like(stored["mass"], np.nan)
            stored[name].attrs = {"units": units}
    missing = [b for _, b in _FROM_BAT if b not in stored]
    if missing:
        raise ValueError(
            "the results file has no bat card (/bat lacks " + ", ".join(missing)
            + "): it was written by an older batstudy; run the study again"
        )
    card = xr.Dataset({name: stored[src] for name, src in _FROM_BAT})
    if stored.sizes.get("mode", 0):
        card["bending_frequency"] = stored["mode_frequency"].isel(mode=0, drop=True)
    else:  # only rigid targets (a wall): no bending mode
        card["bending_frequency"] = xr.full_like(card["mass"], np.nan)
    card["bending_frequency"].attrs = {"units": "Hz", "long_name": "lowest free-free bending mode"}
    for name, si, scale, units in _TRADE:
        card[name] = card[si] * scale
        card[name].attrs = {"units": units, "long_name": f"{si.replace('_', ' ')} ({units})"}
    margin = card["rule_margin"]
    card["rule_applies"] = _rule_applies(card)
    card["rule_applies"].attrs = {
        "units": "1",
        "long_name": "the rule set is for this bat (a wood-bat rule set is not for a bat that is not one piece of solid wood)",
    }
    card["rule_passes"] = xr.where(np.isfinite(margin), margin >= 0, False)
    card["rule_passes"].attrs = {"units": "1", "long_name": "the bat keeps the rule"}
    if bat is not None:
        labels = [str(b) for b in card["bat"].values]
        if bat in labels:
            card = card.isel(bat=labels.index(bat))
        elif isinstance(bat, int) or (isinstance(bat, str) and bat.isdigit()):
            k = int(bat)
            if not 0 <= k < len(labels):
                raise ValueError(f"bat {bat!r} is not a bat of the file; it has {len(labels)}")
            card = card.isel(bat=k)
        else:
            raise ValueError(f"bat {bat!r} is not a bat of the file; allowed: {labels}")
    return card


# The check of a wood-bat rule set (`mlb_wood`), valued 1 for a bat of one piece of solid
# wood: a bat that fails it is one the rule set is not for (`outcome::SOLID_WOOD_CHECK`).
SOLID_WOOD_CHECK = "one piece of solid wood"


def _rule_applies(card):
    """(bat, rule_check): whether each rule's set is for each bat, as the terminal card says."""
    import numpy as np
    import xarray as xr

    labels = [str(x) for x in card["rule_check"].values]
    sets = [label.split(":")[0] for label in labels]
    value = np.atleast_2d(card["rule_value"].values)
    applies = np.ones(value.shape, dtype=bool)
    for k, label in enumerate(labels):
        if label.endswith(SOLID_WOOD_CHECK):
            not_wood = value[:, k] != 1.0
            for j, s in enumerate(sets):
                if s == sets[k]:
                    applies[:, j] &= ~not_wood
    return xr.DataArray(applies.reshape(card["rule_value"].shape), dims=card["rule_value"].dims,
                        coords=card["rule_value"].coords)
