//! `/bat`'s variables and dims: each bat's profile, mass properties, modes, metrics and card.

use super::{v, VarDef};

pub const BAT_DIM: VarDef = v("bat", "", "bat", "bat variant label");
pub const MODE_DIM: VarDef = v(
    "mode",
    "1",
    "mode",
    "flexible free-free mode number, lowest first",
);
pub const NODE_DIM: VarDef = v("node", "1", "node", "node number within a mode");
pub const PROFILE_DIM: VarDef = v(
    "profile_point",
    "1",
    "profile point",
    "profile sample number",
);
pub const BAT_MASS: VarDef = v("mass", "kg", "bat mass", "bat mass");
pub const BAT_Z_CM: VarDef = v("z_cm", "m", "CM z", "centre of mass, from the knob");
pub const BAT_MOI: VarDef = v(
    "moment_of_inertia",
    "kg m^2",
    "MOI (CM)",
    "moment of inertia about the centre of mass",
);
pub const BAT_MOI6: VarDef = v(
    "moment_of_inertia_knob6",
    "kg m^2",
    "MOI (6 in)",
    "moment of inertia about the point 0.1524 m (6 in) from the knob",
);
pub const BAT_MOI_KNOB: VarDef = v(
    "moment_of_inertia_knob",
    "kg m^2",
    "MOI (knob)",
    "moment of inertia about the knob (the batter model's default pivot)",
);
pub const BAT_LENGTH: VarDef = v("length", "m", "bat length", "bat length");
pub const BAT_MODE_FREQ: VarDef = v(
    "mode_frequency",
    "Hz",
    "mode frequency",
    "free-free flexible mode frequency",
);
pub const BAT_MODE_NODES: VarDef = v(
    "mode_nodes",
    "m",
    "node z",
    "node positions of the mode, from the knob",
);
pub const BAT_PIVOT: VarDef = v(
    "pivot_position",
    "m",
    "pivot z",
    "pivot (hands) position for centre of percussion and BBCOR, from the knob",
);
pub const BAT_COP: VarDef = v(
    "centre_of_percussion",
    "m",
    "COP z",
    "centre of percussion for the pivot at pivot_position, from the knob (rigid bat)",
);
pub const BAT_NODE1: VarDef = v(
    "node1_barrel",
    "m",
    "mode-1 node z",
    "barrel-side node of free-free mode 1, from the knob",
);
pub const BAT_NODE2: VarDef = v(
    "node2_barrel",
    "m",
    "mode-2 node z",
    "barrel-side node of free-free mode 2, from the knob",
);
pub const BAT_BBCOR_SPEED: VarDef = v(
    "bbcor_ball_speed",
    "m/s",
    "BBCOR ball speed",
    "ball speed of the BBCOR scan (136 mph, bat at rest)",
);
pub const BAT_BBCOR_MAX: VarDef = v(
    "bbcor_max",
    "1",
    "max BBCOR",
    "maximum bat-ball coefficient of restitution along the barrel (wave model, parabola-refined)",
);
pub const BAT_BBCOR_MAX_POS: VarDef = v(
    "bbcor_max_position",
    "m",
    "max-BBCOR z",
    "impact position of maximum BBCOR, from the knob",
);
pub const BAT_BEST_Q: VarDef = v(
    "best_q",
    "1",
    "best q",
    "the bat's best collision efficiency in the field's convention, (exit - bat speed 6 in from the end) / (pitch + bat speed), at a 70-mph swing meeting an 82-mph pitch, free bat turning about the knob, head-on",
);
pub const BAT_BEST_Q_POS: VarDef = v(
    "best_q_position",
    "m",
    "best q position",
    "where the bat's best q is reached, from the knob",
);
pub const BBCOR_DIM: VarDef = v("bbcor_point", "1", "BBCOR point", "BBCOR scan point number");
/// The bat card's quantities (`batstudy card`).
pub const BAT_DROP: VarDef = v(
    "drop",
    "1",
    "drop",
    "weight in ounces minus length in inches (the rule books' length-to-weight difference)",
);
pub const BAT_BARREL_DIAMETER: VarDef = v(
    "barrel_diameter",
    "m",
    "barrel diameter",
    "twice the largest outer radius",
);
pub const BAT_SWEET_ZONE_START: VarDef = v(
    "sweet_zone_start",
    "m",
    "sweet zone start",
    "knob-side end of the barrel range whose BBCOR is within 0.01 of bbcor_max, from the knob",
);
pub const BAT_SWEET_ZONE_END: VarDef = v(
    "sweet_zone_end",
    "m",
    "sweet zone end",
    "tip-side end of the barrel range whose BBCOR is within 0.01 of bbcor_max, from the knob",
);
pub const BAT_SWEET_ZONE_LENGTH: VarDef = v(
    "sweet_zone_length",
    "m",
    "sweet zone length",
    "length of the barrel range whose BBCOR is within 0.01 of bbcor_max",
);
pub const BAT_HOOP_MODE_FREQ: VarDef = v(
    "hoop_mode_frequency",
    "Hz",
    "hoop frequency",
    "lowest breathing mode of the barrel wall as a shell (NaN for a solid bat), whatever hoop the collisions use",
);
pub const BAT_BARREL_COMPRESSION: VarDef = v(
    "barrel_compression",
    "N",
    "barrel compression",
    "force that closes the barrel's diameter by 0.040 in between a load head and an anvil 6 in from its end, from the shell (NaN without a shell barrel)",
);
pub const BAT_WALL_STRESS_RATIO: VarDef = v(
    "wall_stress_ratio",
    "1",
    "wall stress ratio",
    "largest ratio of the barrel wall's stress under the BBCOR scan's shots to its strength (von Mises over yield for a metal, Tsai-Hill for a laminate's worst ply): above 1 the certification's impact dents or cracks it (NaN without the shell's breathing modes, or for a wood wall)",
);
pub const BAT_WALL_STRESS_POS: VarDef = v(
    "wall_stress_ratio_position",
    "m",
    "wall stress position",
    "where the wall stress ratio is largest, from the knob",
);
pub const RULE_CHECK_DIM: VarDef = v(
    "rule_check",
    "",
    "rule",
    "a rule set and one of its limits, e.g. `ncaa_bbcor: bat.bbcor <= 0.5`",
);
pub const BAT_RULE_UNITS: VarDef = v(
    "rule_units",
    "",
    "rule units",
    "units of rule_value and rule_margin for each limit",
);
pub const BAT_RULE_VALUE: VarDef = v(
    "rule_value",
    "",
    "rule value",
    "the bat's value of the limited quantity (units: rule_units)",
);
pub const BAT_RULE_MARGIN: VarDef = v(
    "rule_margin",
    "",
    "rule margin",
    "how far inside the limit the bat is, in rule_units; negative: the bat breaks the rule",
);

pub const BAT_BBCOR_SHOT: VarDef = v(
    "bbcor_shot",
    "",
    "BBCOR ball and hoop",
    "the ball and hoop the BBCOR scan fired (the first point's of the study that uses the bat), canonical JSON",
);
pub const BAT_BBCOR_Z: VarDef = v(
    "bbcor_z",
    "m",
    "BBCOR z",
    "impact position of the BBCOR scan, from the knob",
);
pub const BAT_BBCOR: VarDef = v(
    "bbcor",
    "1",
    "BBCOR",
    "bat-ball coefficient of restitution (NCAA/ASTM F2219 definition, wave model, free bat)",
);
pub const BAT_PROFILE_Z: VarDef = v(
    "profile_z",
    "m",
    "profile z",
    "profile sample position, from the knob",
);
pub const BAT_OUTER: VarDef = v(
    "outer_radius",
    "m",
    "outer radius",
    "outer radius of the bat",
);
pub const BAT_INNER: VarDef = v(
    "inner_radius",
    "m",
    "inner radius",
    "inner radius of the bat (0 where solid)",
);
pub const BAT_SPEC: VarDef = v(
    "spec_json",
    "",
    "bat spec",
    "the bat's resolved parameters as canonical JSON",
);
