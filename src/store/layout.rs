//! The layout's names, units and long names, in one place (see docs/layout.md).
//! Renaming anything here is a layout change: bump [`LAYOUT_VERSION`].

use crate::model::outcome::{History, HistoryField, Outcome};

/// Version of the file layout documented in docs/layout.md.
pub const LAYOUT_VERSION: u32 = 2;

pub const GROUP_SUMMARY: &str = "summary";
pub const GROUP_ERRORS: &str = "errors";
pub const GROUP_SWEET_SPOT: &str = "sweet_spot";
pub const GROUP_HISTORY: &str = "history";
pub const GROUP_BAT: &str = "bat";

/// The dim whose curves define the sweet spot.
pub const IMPACT_Z: &str = "impact_z";

/// A stored variable's public name, units and long name.
#[derive(Debug, Clone, Copy)]
pub struct VarDef {
    pub name: &'static str,
    pub units: &'static str,
    pub long_name: &'static str,
}

const fn v(name: &'static str, units: &'static str, long_name: &'static str) -> VarDef {
    VarDef {
        name,
        units,
        long_name,
    }
}

/// Number of f64 summary variables (the order of [`SUMMARY_FLOATS`] and [`summary_floats`]).
pub const N_SUMMARY_FLOATS: usize = 24;

/// The f64 summary variables, in journal order.
pub const SUMMARY_FLOATS: [VarDef; N_SUMMARY_FLOATS] = [
    v(
        "exit_speed",
        "m/s",
        "ball exit speed, bat-CM frame, positive toward the pitcher",
    ),
    v(
        "exit_speed_lab",
        "m/s",
        "ball exit speed, lab frame, positive toward the pitcher",
    ),
    v("collision_efficiency", "1", "collision efficiency e_A"),
    v(
        "approach_speed",
        "m/s",
        "relative approach speed at the impact point, bat-CM frame",
    ),
    v("contact_time", "s", "contact duration"),
    v("peak_force", "N", "peak contact force"),
    v("max_compression", "m", "maximum ball compression"),
    v("impulse", "N s", "impulse delivered to the ball"),
    v(
        "energy_initial",
        "J",
        "kinetic energy of ball and bat before contact, bat-CM frame",
    ),
    v(
        "energy_ball_final",
        "J",
        "ball kinetic energy after separation, bat-CM frame",
    ),
    v("energy_ball_loss", "J", "energy dissipated in the ball"),
    v(
        "energy_bat_rigid",
        "J",
        "energy left in the bat's rigid motion, bat-CM frame",
    ),
    v("energy_bat_vibration", "J", "energy left in bat vibration"),
    v("energy_hoop", "J", "energy left in the hoop mode"),
    v(
        "grip_vibration_amplitude",
        "m",
        "largest free-vibration displacement at the grip (0.1524 m from the knob) after the ball leaves, rigid motion excluded",
    ),
    v(
        "grip_recoil_speed",
        "m/s",
        "change of the grip point's rigid-body velocity caused by the collision, positive along the incoming ball",
    ),
    v(
        "energy_bat_damping",
        "J",
        "energy dissipated by the bat's material damping",
    ),
    v(
        "energy_grip_damping",
        "J",
        "energy dissipated by the grip's damper (the hands)",
    ),
    v(
        "impulse_time_99",
        "s",
        "time from first contact to 99 % of the impulse (collision time)",
    ),
    v("bbcor", "1", "bat-ball COR of a bat at rest (NCAA BBCOR)"),
    v("besr", "1", "ball exit speed ratio of a bat at rest (e_A + 1/2)"),
    v("bpf", "1", "bat performance factor: BBCOR over the ball's wall COR"),
    // not `hoop_frequency`/`hoop_mass`: those name the swept parameters' coordinates
    v("hoop_mode_frequency", "Hz", "hoop-mode frequency the collision used"),
    v("hoop_mode_mass", "kg", "hoop-mode mass the collision used"),
];

/// Index of `grip_vibration_amplitude` in [`SUMMARY_FLOATS`].
pub const GRIP_VIBRATION_INDEX: usize = 14;
/// Index of `energy_bat_vibration` in [`SUMMARY_FLOATS`].
pub const VIBRATION_ENERGY_INDEX: usize = 12;

/// The f64 summary values of an outcome, in [`SUMMARY_FLOATS`] order.
pub fn summary_floats(o: &Outcome) -> [f64; N_SUMMARY_FLOATS] {
    [
        o.exit_speed,
        o.exit_speed_lab,
        o.collision_efficiency,
        o.approach_speed,
        o.contact_time,
        o.peak_force,
        o.max_compression,
        o.impulse,
        o.energy.initial,
        o.energy.ball_final,
        o.energy.ball_loss,
        o.energy.bat_rigid,
        o.energy.bat_vibration,
        o.energy.hoop,
        o.grip_vibration_amplitude,
        o.grip_recoil_speed,
        o.energy.bat_damping,
        o.energy.grip_damping,
        o.impulse_time_99,
        o.bbcor,
        o.besr,
        o.bpf,
        o.hoop_frequency,
        o.hoop_mass,
    ]
}

/// Inverse of [`summary_floats`] (history and recontact left default).
pub fn outcome_from_floats(f: &[f64; N_SUMMARY_FLOATS]) -> Outcome {
    let mut o = Outcome {
        exit_speed: f[0],
        exit_speed_lab: f[1],
        collision_efficiency: f[2],
        approach_speed: f[3],
        contact_time: f[4],
        peak_force: f[5],
        max_compression: f[6],
        impulse: f[7],
        impulse_time_99: f[18],
        bbcor: f[19],
        besr: f[20],
        bpf: f[21],
        hoop_frequency: f[22],
        hoop_mass: f[23],
        grip_vibration_amplitude: f[14],
        grip_recoil_speed: f[15],
        ..Default::default()
    };
    o.energy.initial = f[8];
    o.energy.ball_final = f[9];
    o.energy.ball_loss = f[10];
    o.energy.bat_rigid = f[11];
    o.energy.bat_vibration = f[12];
    o.energy.hoop = f[13];
    o.energy.bat_damping = f[16];
    o.energy.grip_damping = f[17];
    o
}

pub const RECONTACT: VarDef = v(
    "recontact",
    "1",
    "ball came back into contact after separating (1 yes, 0 no, -1 not available)",
);
pub const STATUS: VarDef = v(
    "status",
    "1",
    "point status (0 ok, 1 failed, -1 not computed)",
);
pub const POINT_ID: VarDef = v("point_id", "1", "stable point id (0 = not computed)");
pub const BAT_INDEX: VarDef = v(
    "bat_index",
    "1",
    "index of the point's bat in group bat (-1 = not computed)",
);

pub const STATUS_OK: i8 = 0;
pub const STATUS_FAILED: i8 = 1;
pub const STATUS_NOT_COMPUTED: i8 = -1;

pub const ERR_DIM: &str = "error";
pub const ERR_FLAT_INDEX: VarDef = v(
    "flat_index",
    "1",
    "row-major flat index of the failed point in group summary",
);
pub const ERR_POINT_ID: VarDef = v("point_id", "1", "stable point id of the failed point");
pub const ERR_MESSAGE: VarDef = v("message", "", "error message of the failed point");

pub const SWEET_POSITION: VarDef = v(
    "position",
    "m",
    "sweet spot: impact position of maximum exit speed, from the knob (parabola-refined)",
);
pub const SWEET_EXIT_SPEED: VarDef = v(
    "exit_speed",
    "m/s",
    "maximum exit speed over impact_z, bat-CM frame (parabola-refined)",
);
pub const SWEET_WIDTH: VarDef = v(
    "width",
    "m",
    "length of the impact_z range around the maximum where exit_speed >= max - 1 m/s",
);

pub const SWEET_MIN_VIBRATION_POSITION: VarDef = v(
    "min_vibration_position",
    "m",
    "impact position minimising grip_vibration_amplitude, from the knob (parabola-refined)",
);
pub const SWEET_MIN_VIBRATION_AMPLITUDE: VarDef = v(
    "min_vibration_amplitude",
    "m",
    "minimum of grip_vibration_amplitude over impact_z (parabola-refined)",
);
pub const SWEET_MIN_VIBRATION_ENERGY_POSITION: VarDef = v(
    "min_vibration_energy_position",
    "m",
    "impact position minimising energy_bat_vibration, from the knob (parabola-refined)",
);

pub const TIME: VarDef = v("time", "s", "time since first contact");
pub const HIST_Z: VarDef = v("z", "m", "position along the bat from the knob");

/// The history variables: public name, units, long name, the field that requests it,
/// whether it has a `z` dim.
pub const HISTORY_VARS: [(VarDef, HistoryField, bool); 7] = [
    (
        v("force", "N", "contact force between ball and bat"),
        HistoryField::Force,
        false,
    ),
    (
        v("compression", "m", "ball compression"),
        HistoryField::Compression,
        false,
    ),
    (
        v(
            "ball_velocity",
            "m/s",
            "ball velocity, positive toward the bat, bat-CM frame",
        ),
        HistoryField::BallVelocity,
        false,
    ),
    (
        v("displacement", "m", "bat transverse displacement"),
        HistoryField::Displacement,
        true,
    ),
    (
        v(
            "rigid_translation",
            "m",
            "rigid translation of the bat's centre of mass",
        ),
        HistoryField::RigidMotion,
        false,
    ),
    (
        v(
            "rigid_rotation",
            "rad",
            "rigid rotation of the bat about its centre of mass",
        ),
        HistoryField::RigidMotion,
        false,
    ),
    (
        v(
            "hoop_displacement",
            "m",
            "hoop mass displacement relative to the impact point",
        ),
        HistoryField::HoopDisplacement,
        false,
    ),
];

/// The samples of history variable `k` (index into [`HISTORY_VARS`]).
pub fn history_array(h: &History, k: usize) -> &Vec<f64> {
    match k {
        0 => &h.force,
        1 => &h.compression,
        2 => &h.ball_velocity,
        3 => &h.displacement,
        4 => &h.rigid_translation,
        5 => &h.rigid_rotation,
        _ => &h.hoop_displacement,
    }
}

/// Mutable access to history variable `k`.
pub fn history_array_mut(h: &mut History, k: usize) -> &mut Vec<f64> {
    match k {
        0 => &mut h.force,
        1 => &mut h.compression,
        2 => &mut h.ball_velocity,
        3 => &mut h.displacement,
        4 => &mut h.rigid_translation,
        5 => &mut h.rigid_rotation,
        _ => &mut h.hoop_displacement,
    }
}

pub const BAT_DIM: VarDef = v("bat", "", "bat variant label");
pub const MODE_DIM: VarDef = v("mode", "1", "flexible free-free mode number, lowest first");
pub const NODE_DIM: VarDef = v("node", "1", "node number within a mode");
pub const PROFILE_DIM: VarDef = v("profile_point", "1", "profile sample number");
pub const BAT_MASS: VarDef = v("mass", "kg", "bat mass");
pub const BAT_Z_CM: VarDef = v("z_cm", "m", "centre of mass, from the knob");
pub const BAT_MOI: VarDef = v(
    "moment_of_inertia",
    "kg m2",
    "moment of inertia about the centre of mass",
);
pub const BAT_MOI6: VarDef = v(
    "moment_of_inertia_knob6",
    "kg m2",
    "moment of inertia about the point 0.1524 m (6 in) from the knob",
);
pub const BAT_LENGTH: VarDef = v("length", "m", "bat length");
pub const BAT_MODE_FREQ: VarDef = v("mode_frequency", "Hz", "free-free flexible mode frequency");
pub const BAT_MODE_NODES: VarDef = v(
    "mode_nodes",
    "m",
    "node positions of the mode, from the knob",
);
pub const BAT_PIVOT: VarDef = v(
    "pivot_position",
    "m",
    "pivot (hands) position for centre of percussion and BBCOR, from the knob",
);
pub const BAT_COP: VarDef = v(
    "centre_of_percussion",
    "m",
    "centre of percussion for the pivot at pivot_position, from the knob (rigid bat)",
);
pub const BAT_NODE1: VarDef = v(
    "node1_barrel",
    "m",
    "barrel-side node of free-free mode 1, from the knob",
);
pub const BAT_NODE2: VarDef = v(
    "node2_barrel",
    "m",
    "barrel-side node of free-free mode 2, from the knob",
);
pub const BAT_BBCOR_SPEED: VarDef = v(
    "bbcor_ball_speed",
    "m/s",
    "ball speed of the BBCOR scan (136 mph, bat at rest)",
);
pub const BAT_BBCOR_MAX: VarDef = v(
    "bbcor_max",
    "1",
    "maximum bat-ball coefficient of restitution along the barrel (wave model, parabola-refined)",
);
pub const BAT_BBCOR_MAX_POS: VarDef = v(
    "bbcor_max_position",
    "m",
    "impact position of maximum BBCOR, from the knob",
);
pub const BBCOR_DIM: VarDef = v("bbcor_point", "1", "BBCOR scan point number");
pub const BAT_BBCOR_Z: VarDef = v(
    "bbcor_z",
    "m",
    "impact position of the BBCOR scan, from the knob",
);
pub const BAT_BBCOR: VarDef = v(
    "bbcor",
    "1",
    "bat-ball coefficient of restitution (NCAA/ASTM F2219 definition, wave model, free bat)",
);
pub const BAT_PROFILE_Z: VarDef = v("profile_z", "m", "profile sample position, from the knob");
pub const BAT_OUTER: VarDef = v("outer_radius", "m", "outer radius of the bat");
pub const BAT_INNER: VarDef = v(
    "inner_radius",
    "m",
    "inner radius of the bat (0 where solid)",
);
pub const BAT_SPEC: VarDef = v(
    "spec_json",
    "",
    "the bat's resolved parameters as canonical JSON",
);

/// Target number of elements in one summary chunk.
pub const SUMMARY_CHUNK_ELEMS: usize = 65536;
/// Deflate level of the summary variables. Compressing them is most of finishing a small
/// study's file (issue 7); on the shuffled f64 summaries of the benchmark's study libdeflate's
/// level 1 takes two thirds of the time of level 4 for a file 0.3 % larger.
pub const DEFLATE_LEVEL: u8 = 1;
/// Deflate level of the history variables. Histories dominate the cost of finishing a file
/// (issue 7's benchmark); on shuffled f32 histories level 1 compresses 1.5× faster than 4
/// for a file 0.6 % larger.
pub const HISTORY_DEFLATE_LEVEL: u8 = 1;
