//! The layout's names, units and long names, in one place (see docs/layout.md).
//! Renaming anything here is a layout change: bump [`LAYOUT_VERSION`].

use crate::results::{PointGroups, ResultShape, StudyInfo};
use batstudy_physics::outcome::{
    History, HistoryCompression, HistoryDisplacement, HistoryField, HistoryPrecision,
    HistoryRequest, Outcome,
};

mod bat;
pub use bat::*;

/// Version of the file layout documented in docs/layout.md.
pub const LAYOUT_VERSION: u32 = 7;

pub const GROUP_SUMMARY: &str = "summary";
pub const GROUP_ERRORS: &str = "errors";
pub const GROUP_SWEET_SPOT: &str = "sweet_spot";
pub const GROUP_HISTORY: &str = "history";
pub const GROUP_BAT: &str = "bat";

/// The dim whose curves define the sweet spot.
pub const IMPACT_Z: &str = "impact_z";

/// A stored variable's public name, units and long name: the layout's own are `'static`;
/// those made at run time (an index coordinate, a reduced quantity) borrow their strings
/// (attributes are written as they are given, so nothing needs to outlive the write).
#[derive(Debug, Clone, Copy)]
pub struct VarDef<'a> {
    pub name: &'a str,
    /// UDUNITS spelling; empty for text (then no `units` attribute is written).
    pub units: &'a str,
    /// Short: a plot's axis label.
    pub long_name: &'a str,
    /// The full sentence (attribute `description`).
    pub description: &'a str,
}

/// A [`VarDef`] whose strings are made at run time, owned.
#[derive(Debug, Clone)]
pub struct OwnedVarDef {
    pub name: String,
    pub units: String,
    pub long_name: String,
    pub description: String,
}

impl From<VarDef<'_>> for OwnedVarDef {
    fn from(d: VarDef<'_>) -> Self {
        OwnedVarDef::new(d.name, d.units, d.long_name, d.description)
    }
}

impl OwnedVarDef {
    pub fn new(name: &str, units: &str, long_name: &str, description: &str) -> Self {
        OwnedVarDef {
            name: name.to_string(),
            units: units.to_string(),
            long_name: long_name.to_string(),
            description: description.to_string(),
        }
    }

    /// The definition, lending this one's strings.
    #[must_use]
    pub fn def(&self) -> VarDef<'_> {
        VarDef {
            name: &self.name,
            units: &self.units,
            long_name: &self.long_name,
            description: &self.description,
        }
    }
}

const fn v(
    name: &'static str,
    units: &'static str,
    long_name: &'static str,
    description: &'static str,
) -> VarDef<'static> {
    VarDef {
        name,
        units,
        long_name,
        description,
    }
}

/// Number of f64 summary variables (the order of [`SUMMARY_FLOATS`] and [`summary_floats`]).
pub const N_SUMMARY_FLOATS: usize = 38;

/// The f64 summary variables, in journal order.
pub const SUMMARY_FLOATS: [VarDef; N_SUMMARY_FLOATS] = [
    v(
        "exit_speed",
        "m/s",
        "exit speed",
        "ball exit speed, bat-CM frame, positive toward the pitcher",
    ),
    v(
        "exit_speed_lab",
        "m/s",
        "exit speed (lab)",
        "ball exit speed, lab frame, positive toward the pitcher",
    ),
    v(
        "collision_efficiency",
        "1",
        "e_A",
        "collision efficiency e_A",
    ),
    v(
        "approach_speed",
        "m/s",
        "approach speed",
        "relative approach speed at the impact point, bat-CM frame",
    ),
    v(
        "contact_time",
        "s",
        "contact time",
        "contact duration",
    ),
    v(
        "peak_force",
        "N",
        "peak force",
        "peak contact force",
    ),
    v(
        "max_compression",
        "m",
        "max compression",
        "maximum ball compression",
    ),
    v(
        "impulse",
        "N s",
        "impulse",
        "impulse delivered to the ball",
    ),
    v(
        "energy_initial",
        "J",
        "initial energy",
        "kinetic energy of ball and bat before contact, bat-CM frame",
    ),
    v(
        "energy_ball_final",
        "J",
        "ball energy after",
        "ball kinetic energy after separation, bat-CM frame",
    ),
    v(
        "energy_ball_loss",
        "J",
        "ball loss",
        "energy dissipated in the ball",
    ),
    v(
        "energy_bat_rigid",
        "J",
        "bat rigid energy",
        "energy left in the bat's rigid motion, bat-CM frame",
    ),
    v(
        "energy_bat_vibration",
        "J",
        "vibration energy",
        "energy left in bat vibration",
    ),
    v(
        "energy_hoop",
        "J",
        "hoop energy",
        "energy left in the hoop mode",
    ),
    v(
        "grip_vibration_amplitude",
        "m",
        "grip vibration",
        "largest free-vibration displacement at the grip (0.1524 m from the knob) after the ball leaves, rigid motion excluded",
    ),
    v(
        "grip_recoil_speed",
        "m/s",
        "grip recoil",
        "change of the grip point's rigid-body velocity caused by the collision, positive along the incoming ball",
    ),
    v(
        "energy_bat_damping",
        "J",
        "bat damping loss",
        "energy dissipated by the bat's material damping",
    ),
    v(
        "energy_grip_damping",
        "J",
        "grip damping loss",
        "energy dissipated by the grip's damper (the hands)",
    ),
    v(
        "impulse_time_99",
        "s",
        "99 % impulse time",
        "time from first contact to 99 % of the impulse (collision time)",
    ),
    v(
        "bbcor",
        "1",
        "BBCOR",
        "bat-ball COR of a bat at rest (NCAA BBCOR)",
    ),
    v(
        "besr",
        "1",
        "BESR",
        "ball exit speed ratio of a bat at rest (e_A + 1/2)",
    ),
    v(
        "bpf",
        "1",
        "BPF",
        "bat performance factor: BBCOR over the ball's wall COR",
    ),
    // not `hoop_frequency`/`hoop_mass`: those name the swept parameters' coordinates
    v(
        "hoop_mode_frequency",
        "Hz",
        "hoop frequency",
        "hoop-mode frequency the collision used",
    ),
    v(
        "hoop_mode_mass",
        "kg",
        "hoop mass",
        "hoop-mode mass the collision used",
    ),
    v(
        "tangential_cor",
        "1",
        "tangential COR",
        "minus the ball's slip velocity on the bat after the collision over the one before (0: rolls off; NaN head-on without spin)",
    ),
    v(
        "bat_speed",
        "m/s",
        "bat speed",
        "lab-frame speed of the bat's impact point toward the pitcher before contact",
    ),
    v(
        "launch_angle",
        "rad",
        "launch angle",
        "batted ball's launch angle above the horizontal, lab frame",
    ),
    v(
        "spray_angle",
        "rad",
        "spray angle",
        "batted ball's direction from straight-away centre field, positive toward the first-base side",
    ),
    v(
        "spin",
        "rad/s",
        "spin",
        "batted ball's backspin (positive) or topspin (negative) about the horizontal axis across its path",
    ),
    v(
        "sidespin",
        "rad/s",
        "sidespin",
        "batted ball's sidespin, positive curving toward the third-base side",
    ),
    v(
        "carry",
        "m",
        "carry",
        "horizontal distance from the contact point to the landing (flight; NaN without one)",
    ),
    v(
        "apex",
        "m",
        "apex",
        "greatest height of the flight above the ground",
    ),
    v(
        "hang_time",
        "s",
        "hang time",
        "time from contact to landing",
    ),
    v(
        "energy_friction",
        "J",
        "friction loss",
        "energy dissipated by the tangential contact: sliding, and the shear a shrinking patch lets go",
    ),
    v(
        "bat_speed_6in",
        "m/s",
        "bat speed 6 in from the end",
        "lab speed of the bat's point 6 in from its barrel end before contact, where bat tracking measures it",
    ),
    v(
        "pitch_speed_plate",
        "m/s",
        "pitch speed at the plate",
        "the pitch's lab speed at contact (the front of the plate)",
    ),
    v(
        "collision_efficiency_q",
        "1",
        "q",
        "collision efficiency in the field's convention: (exit_speed_lab - bat_speed_6in) / (pitch_speed_plate + bat_speed_6in)",
    ),
    v(
        "squared_up",
        "1",
        "squared up",
        "1 if exit_speed_lab is at least 80 % of best_q pitch_speed_plate + (1 + best_q) bat_speed_6in with the bat's best_q, 0 if not",
    ),
];

/// Index of `exit_speed_lab` in [`SUMMARY_FLOATS`].
pub const EXIT_SPEED_LAB_INDEX: usize = 1;
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
        o.tangential_cor,
        o.batted.bat_speed,
        o.batted.launch_angle,
        o.batted.spray_angle,
        o.batted.backspin,
        o.batted.sidespin,
        o.batted.carry,
        o.batted.apex,
        o.batted.hang_time,
        o.energy.friction,
        o.batted.bat_speed_6in,
        o.batted.pitch_speed,
        o.batted.collision_efficiency_q,
        o.batted.squared_up,
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
        tangential_cor: f[24],
        batted: batstudy_physics::outcome::BattedBall {
            bat_speed: f[25],
            launch_angle: f[26],
            spray_angle: f[27],
            backspin: f[28],
            sidespin: f[29],
            carry: f[30],
            apex: f[31],
            hang_time: f[32],
            bat_speed_6in: f[34],
            pitch_speed: f[35],
            collision_efficiency_q: f[36],
            squared_up: f[37],
        },
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
    o.energy.friction = f[33];
    o
}

pub const RECONTACT: VarDef = v(
    "recontact",
    "1",
    "recontact",
    "ball came back into contact after separating (1 yes, 0 no, -1 not available)",
);
pub const STATUS: VarDef = v(
    "status",
    "1",
    "status",
    "point status (0 ok, 1 failed, -1 not computed)",
);
pub const POINT_ID: VarDef = v(
    "point_id",
    "1",
    "point id",
    "stable point id (0 = not computed)",
);
pub const BAT_INDEX: VarDef = v(
    "bat_index",
    "1",
    "bat index",
    "index of the point's bat in group bat (-1 = not computed)",
);

pub const STATUS_OK: i8 = 0;
pub const STATUS_FAILED: i8 = 1;
pub const STATUS_NOT_COMPUTED: i8 = -1;

pub const ERR_DIM: &str = "error";
pub const ERR_FLAT_INDEX: VarDef = v(
    "flat_index",
    "1",
    "flat index",
    "row-major flat index of the failed point in group summary",
);
pub const ERR_POINT_ID: VarDef = v(
    "point_id",
    "1",
    "point id",
    "stable point id of the failed point",
);
pub const ERR_MESSAGE: VarDef = v("message", "", "error", "error message of the failed point");

pub const SWEET_POSITION: VarDef = v(
    "position",
    "m",
    "sweet spot",
    "sweet spot: impact position of maximum exit speed, from the knob (parabola-refined)",
);
pub const SWEET_EXIT_SPEED: VarDef = v(
    "exit_speed",
    "m/s",
    "sweet-spot exit speed",
    "maximum exit speed over impact_z, bat-CM frame (parabola-refined)",
);
pub const SWEET_WIDTH: VarDef = v(
    "width",
    "m",
    "sweet-spot width",
    "length of the impact_z range around the maximum where exit_speed >= max - 1 m/s",
);

pub const SWEET_MIN_VIBRATION_POSITION: VarDef = v(
    "min_vibration_position",
    "m",
    "least-vibration z",
    "impact position minimising grip_vibration_amplitude, from the knob (parabola-refined)",
);
pub const SWEET_MIN_VIBRATION_AMPLITUDE: VarDef = v(
    "min_vibration_amplitude",
    "m",
    "least grip vibration",
    "minimum of grip_vibration_amplitude over impact_z (parabola-refined)",
);
pub const SWEET_MIN_VIBRATION_ENERGY_POSITION: VarDef = v(
    "min_vibration_energy_position",
    "m",
    "least-vibration-energy z",
    "impact position minimising energy_bat_vibration, from the knob (parabola-refined)",
);
pub const SWEET_CARRY_POSITION: VarDef = v(
    "carry_position",
    "m",
    "longest-carry z",
    "impact position of the longest carry, from the knob (parabola-refined; NaN without a flight)",
);
pub const SWEET_CARRY: VarDef = v(
    "carry",
    "m",
    "longest carry",
    "longest carry over impact_z (parabola-refined; NaN without a flight)",
);
pub const SWEET_EXIT_SPEED_LAB: VarDef = v(
    "exit_speed_lab",
    "m/s",
    "best lab exit speed",
    "maximum lab-frame exit speed over impact_z (parabola-refined): the batted ball's speed off the bat's best point for the swing and pitch",
);
/// Number of f64 `/sweet_spot` variables (before [`SWEET_AT_EDGE`]).
pub const N_SWEET_FLOATS: usize = 9;
/// The f64 `/sweet_spot` variables, in the order the build computes them.
pub const SWEET_FLOATS: [&VarDef; N_SWEET_FLOATS] = [
    &SWEET_POSITION,
    &SWEET_EXIT_SPEED,
    &SWEET_WIDTH,
    &SWEET_MIN_VIBRATION_POSITION,
    &SWEET_MIN_VIBRATION_AMPLITUDE,
    &SWEET_MIN_VIBRATION_ENERGY_POSITION,
    &SWEET_CARRY_POSITION,
    &SWEET_CARRY,
    &SWEET_EXIT_SPEED_LAB,
];
/// Index of `carry` in [`SUMMARY_FLOATS`].
pub const CARRY_INDEX: usize = 30;
pub const SWEET_AT_EDGE: VarDef = v(
    "position_at_edge",
    "1",
    "sweet spot at edge",
    "1 if the maximum exit speed is at the first or last sampled impact_z (the true sweet spot may lie outside the sampled range; position is then only the range's end), 0 if inside, -1 no curve",
);

pub const TIME: VarDef = v("time", "s", "time", "time since first contact");

/// CF's attributes where CF has them, by a variable's or coordinate's name: its `axis` (empty:
/// none) and `standard_name` (CF standard name table, v84): the two time axes, and the air
/// of a swept `flight` block (`flight.temperature` is the coordinate `flight_temperature`).
pub const CF_NAMES: &[(&str, &str, &str)] = &[
    ("time", "T", "time"),
    ("flight_time", "T", "time"),
    ("flight_temperature", "", "air_temperature"),
    ("flight_pressure", "", "air_pressure_at_mean_sea_level"),
    ("flight_humidity", "", "relative_humidity"),
    ("flight_wind_speed", "", "wind_speed"),
];
pub const HIST_Z: VarDef = v("z", "m", "z", "position along the bat from the knob");
pub const FLIGHT_TIME: VarDef = v(
    "flight_time",
    "s",
    "flight time",
    "time since contact, on the batted ball's flight",
);

/// The dims a history variable has after the study's.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum HistoryDims {
    /// (time)
    Time,
    /// (time, z): the grid form of the displacement
    TimeZ,
    /// (bat_mode, time): the modal coordinates, mode-major so that the zero rows that pad a
    /// point's last block of modes are one run per byte plane (`store::chunks`)
    ModeTime,
    /// (shape_point): one value per shape point of the bat
    ShapePoint,
    /// (flight_time): the batted ball's flight, on a time axis of its own
    FlightTime,
}

/// The history variables: public name, units, long name, the field that requests it, its
/// dims after the study's. `displacement` is the grid form; the last three are the modal
/// form of the same field (`history.displacement`, [`history_stored`]).
pub const HISTORY_VARS: [(VarDef, HistoryField, HistoryDims); 13] = [
    (
        v("force", "N", "force", "contact force between ball and bat"),
        HistoryField::Force,
        HistoryDims::Time,
    ),
    (
        v("compression", "m", "compression", "ball compression"),
        HistoryField::Compression,
        HistoryDims::Time,
    ),
    (
        v(
            "ball_velocity",
            "m/s",
            "ball velocity",
            "ball velocity, positive toward the bat, bat-CM frame",
        ),
        HistoryField::BallVelocity,
        HistoryDims::Time,
    ),
    (
        v(
            "displacement",
            "m",
            "bat displacement",
            "bat transverse displacement",
        ),
        HistoryField::Displacement,
        HistoryDims::TimeZ,
    ),
    (
        v(
            "rigid_translation",
            "m",
            "rigid translation",
            "rigid translation of the bat's centre of mass",
        ),
        HistoryField::RigidMotion,
        HistoryDims::Time,
    ),
    (
        v(
            "rigid_rotation",
            "rad",
            "rigid rotation",
            "rigid rotation of the bat about its centre of mass",
        ),
        HistoryField::RigidMotion,
        HistoryDims::Time,
    ),
    (
        v(
            "hoop_displacement",
            "m",
            "hoop displacement",
            "hoop mass displacement relative to the impact point",
        ),
        HistoryField::HoopDisplacement,
        HistoryDims::Time,
    ),
    (
        v(
            "trajectory_x",
            "m",
            "trajectory x",
            "batted ball's position toward the first-base side, flight frame (origin on the ground below contact); NaN after landing",
        ),
        HistoryField::Trajectory,
        HistoryDims::FlightTime,
    ),
    (
        v(
            "trajectory_y",
            "m",
            "trajectory y",
            "batted ball's position toward centre field, flight frame; NaN after landing",
        ),
        HistoryField::Trajectory,
        HistoryDims::FlightTime,
    ),
    (
        v(
            "trajectory_z",
            "m",
            "trajectory z",
            "batted ball's height above the ground, flight frame; NaN after landing",
        ),
        HistoryField::Trajectory,
        HistoryDims::FlightTime,
    ),
    (
        v(
            "modal_coordinate",
            "m",
            "modal coordinate",
            "coordinate of the bat's mode, scaled so that its shape (bat/mode_shape) is dimensionless; 0 for the modes the collision does not step",
        ),
        HistoryField::Displacement,
        HistoryDims::ModeTime,
    ),
    (
        v(
            "bat_load",
            "N",
            "bat load",
            "force on the bat: the contact force, or the hoop spring's force with a hoop mode",
        ),
        HistoryField::Displacement,
        HistoryDims::Time,
    ),
    (
        v(
            "static_shape",
            "m/N",
            "static shape",
            "static displacement per unit bat load of the modes the collision does not step, at the bat's shape points",
        ),
        HistoryField::Displacement,
        HistoryDims::ShapePoint,
    ),
];

/// Index of `modal_coordinate` in [`HISTORY_VARS`].
pub const MODAL_COORDINATE: usize = 10;

/// Whether history variable `k` belongs to the displacement's modal form.
pub fn is_modal(k: usize) -> bool {
    k >= MODAL_COORDINATE
}

/// Whether a request stores history variable `k`: its field is requested, and a
/// displacement variable is of the requested form.
pub fn history_stored(h: &HistoryRequest, k: usize) -> bool {
    let field = HISTORY_VARS[k].1;
    let form_ok = match field {
        HistoryField::Displacement => is_modal(k) == (h.displacement == HistoryDisplacement::Modal),
        _ => true,
    };
    h.fields.contains(&field) && form_ok
}

/// Whether a request stores the displacement in modal form.
pub fn stores_modal(h: &HistoryRequest) -> bool {
    (0..HISTORY_VARS.len()).any(|k| is_modal(k) && history_stored(h, k))
}

/// The precision variable `k` is stored in: the request's, but f64 for the modal form, whose
/// variables the model has already rounded to what the request's precision calls for
/// (`model::collision::modal_precision`): the low modes' terms cancel, so they need more
/// than an f32's 24 bits, the high modes' far fewer (docs/layout.md).
pub fn history_precision(h: &HistoryRequest, k: usize) -> HistoryPrecision {
    match is_modal(k) {
        true => HistoryPrecision::F64,
        false => h.precision,
    }
}

/// Modes per chunk of `modal_coordinate` (and of `bat/mode_shape`): most collisions step
/// 12 to 34 modes, so one chunk holds a history's coordinates; the zero rows that pad it
/// cost a few bytes (`store::chunks`), or nothing at all beyond the modes a collision steps.
pub const MODE_BLOCK: usize = 32;

/// The samples of history variable `k` (index into [`HISTORY_VARS`]).
pub fn history_array(h: &History, k: usize) -> &Vec<f64> {
    match k {
        0 => &h.force,
        1 => &h.compression,
        2 => &h.ball_velocity,
        3 => &h.displacement,
        4 => &h.rigid_translation,
        5 => &h.rigid_rotation,
        6 => &h.hoop_displacement,
        7 => &h.trajectory_x,
        8 => &h.trajectory_y,
        9 => &h.trajectory_z,
        10 => &h.modal.coordinate,
        11 => &h.modal.bat_load,
        _ => &h.modal.static_shape,
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
        6 => &mut h.hoop_displacement,
        7 => &mut h.trajectory_x,
        8 => &mut h.trajectory_y,
        9 => &mut h.trajectory_z,
        10 => &mut h.modal.coordinate,
        11 => &mut h.modal.bat_load,
        _ => &mut h.modal.static_shape,
    }
}

/// The modal form's dims: the bat's modes, and its shape points.
pub const BAT_MODE_DIM: VarDef = v(
    "bat_mode",
    "1",
    "bat mode",
    "mode of the bat as the collision sees it (its grip and ends, rigid modes included), lowest first, from 0",
);
pub const SHAPE_POINT_DIM: VarDef = v(
    "shape_point",
    "1",
    "shape point",
    "shape point of the bat: its knob end, every node of its beam, its barrel end",
);
pub const BAT_SHAPE_Z: VarDef = v(
    "shape_z",
    "m",
    "shape point z",
    "position of the shape point, from the knob",
);
pub const BAT_MODE_SHAPE: VarDef = v(
    "mode_shape",
    "1",
    "mode shape",
    "shape of the bat's mode at the shape points, scaled to be dimensionless (mass-normalised shape times the square root of the bat's mass); 0 for modes no stored history of the bat steps",
);

/// What the numbers of a results file rest on (its CF `references` attribute).
pub const REFERENCES: &str =
    "the wave model: A. M. Nathan, Am. J. Phys. 68, 979 (2000); the rigid \
    model: H. Brody, Am. J. Phys. 54, 640 (1986); the calibrated ball, the protocols and every \
    other source: batstudy's docs/physics.md and docs/validation.md";

/// Points whose modal histories share a chunk, along the study's last dim (one Huffman code, one block header and one `H5Dwrite_chunk` serve the group's points;
/// `benches/chunk_groups.rs`).
pub const MODAL_HISTORY_GROUP: usize = 8;

/// How a study's points are grouped in its history chunks ([`PointGroups`]): in groups of
/// [`MODAL_HISTORY_GROUP`] along the last dim when it stores the displacement's modal form,
/// each point on its own otherwise.
pub fn history_groups(info: &StudyInfo) -> PointGroups {
    history_groups_of(info.history.as_ref(), &info.shape)
}

/// [`history_groups`] of a study of this shape storing these histories.
pub fn history_groups_of(history: Option<&HistoryRequest>, shape: &ResultShape) -> PointGroups {
    let modal = history.is_some_and(stores_modal);
    match (modal, shape.dims.last()) {
        (true, Some(last)) => PointGroups::new(MODAL_HISTORY_GROUP, last.size),
        _ => PointGroups::single(),
    }
}

/// Target number of elements in one summary chunk.
pub const SUMMARY_CHUNK_ELEMS: usize = 65536;
/// Deflate level of the summary variables. Compressing them is most of finishing a small
/// study's file; on the shuffled f64 summaries of the benchmark's study libdeflate's
/// level 1 takes two thirds of the time of level 4 for a file 0.3 % larger.
pub const DEFLATE_LEVEL: u8 = 1;
/// Deflate level of the history variables. Histories dominate the cost of finishing a file
/// (`batstudy bench`'s history study); on shuffled f32 histories level 1 compresses 1.5×
/// faster than 4
/// for a file 0.6 % larger.
pub const HISTORY_DEFLATE_LEVEL: u8 = 1;

/// Deflate level of the histories a request stores; 0 means stored as they are, without
/// the shuffle and deflate filters (`history.compression: none`). On the bat's displacement,
/// y(z, t) in f32, level 1 saves about a quarter of the bytes (68 000 → 52 800 for 200
/// samples × 85 z, shuffled, libdeflate) at 170 MB/s: 60 % of a history point's time on the
/// worker.
pub fn history_deflate_level(h: &HistoryRequest) -> u8 {
    match h.compression {
        HistoryCompression::Deflate => HISTORY_DEFLATE_LEVEL,
        HistoryCompression::None => 0,
    }
}
