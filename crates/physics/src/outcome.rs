//! What one collision produces, and what a prepared bat knows about itself.
//!
//! Frames: unless a name says `lab`, every velocity is in the frame where the bat's
//! centre of mass is initially at rest (docs/physics.md). Positive exit speed = the ball goes
//! back toward the pitcher.

use crate::protocol::{BBCOR_BALL_SPEED, KNOB6};
use serde::{Deserialize, Serialize};

/// Which time histories to record, on one common time axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum HistoryField {
    /// Contact force between ball and bat (N).
    Force,
    /// Ball compression s (m).
    Compression,
    /// Ball velocity (m/s, + toward the bat, CM frame).
    BallVelocity,
    /// Bat displacement y(z, t) at the requested z (m).
    Displacement,
    /// Rigid part of the bat's motion: CM translation (m) and rotation (rad).
    RigidMotion,
    /// Displacement of the hoop mass relative to the impact point (m).
    HoopDisplacement,
    /// The batted ball's flight: its position (m, the flight's frame) on the flight's own
    /// time axis, every `flight::TRAJECTORY_STEP_S` from contact, NaN once it has landed
    /// (and throughout without a `flight`).
    Trajectory,
}

/// A request for sampled time histories: samples at t = k·interval, k = 0..n_samples,
/// with t = 0 at first contact.
#[derive(Debug, Clone, PartialEq)]
pub struct HistoryRequest {
    pub fields: Vec<HistoryField>,
    /// Sampling interval in s.
    pub interval: f64,
    /// Number of samples (duration / interval, rounded).
    pub n_samples: usize,
    /// Positions (m from the knob) at which the bat displacement is sampled; points
    /// beyond the bat's length get NaN.
    pub z: Vec<f64>,
    /// Stored precision of the histories (`history.precision`; the physics always computes f64).
    pub precision: HistoryPrecision,
    /// How the stored histories are compressed (`history.compression`).
    pub compression: HistoryCompression,
    /// How the bat's displacement is recorded (`history.displacement`).
    pub displacement: HistoryDisplacement,
}

/// How the bat's displacement is recorded and stored (`history.displacement`).
#[derive(
    Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize, schemars::JsonSchema,
)]
#[serde(rename_all = "snake_case")]
pub enum HistoryDisplacement {
    /// The modal integrator's own coordinates: per sample the coordinates of the modes it
    /// steps and the force on the bat, per history the static shape of the other modes,
    /// per bat the mode shapes (docs/layout.md). y(z, t) follows exactly, at any z, from
    /// a quarter of the bytes of the grid. The modal integrator only.
    #[default]
    Modal,
    /// y(z, t) on the `z` grid (`history.z_step`), computed while the collision runs.
    Grid,
}

/// How stored histories are compressed.
#[derive(
    Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize, schemars::JsonSchema,
)]
#[serde(rename_all = "snake_case")]
pub enum HistoryCompression {
    /// HDF5's shuffle and deflate (level 1) filters: the smallest file. The bat's
    /// displacement is float noise to deflate (about a quarter of its bytes saved), and
    /// compressing it is most of a history point's time.
    #[default]
    Deflate,
    /// No filters: about a third more bytes for displacement-heavy studies, and a history
    /// point takes about 40 % of the time (faster when the disk keeps up: few cores per disk).
    None,
}

/// Floating-point precision in which histories are stored.
#[derive(
    Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize, schemars::JsonSchema,
)]
#[serde(rename_all = "snake_case")]
pub enum HistoryPrecision {
    /// 4-byte floats (half the size; about 7 significant digits).
    F32,
    /// 8-byte floats.
    #[default]
    F64,
}

/// Sampled time histories. Arrays for fields not requested are empty.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct History {
    /// Contact force, N, length n_samples.
    pub force: Vec<f64>,
    /// Ball compression, m.
    pub compression: Vec<f64>,
    /// Ball velocity, m/s.
    pub ball_velocity: Vec<f64>,
    /// Bat displacement, m, row-major [n_samples][z.len()].
    pub displacement: Vec<f64>,
    /// Rigid CM translation of the bat, m.
    pub rigid_translation: Vec<f64>,
    /// Rigid rotation of the bat about its CM, rad.
    pub rigid_rotation: Vec<f64>,
    /// Hoop mass displacement relative to the impact point, m.
    pub hoop_displacement: Vec<f64>,
    /// The batted ball's position in the flight's frame (x toward first base, y toward
    /// centre field, z up), m, every `flight::TRAJECTORY_STEP_S`, length
    /// `flight::TRAJECTORY_SAMPLES` (NaN after the landing).
    pub trajectory_x: Vec<f64>,
    pub trajectory_y: Vec<f64>,
    pub trajectory_z: Vec<f64>,
    /// The displacement's modal form (`HistoryDisplacement::Modal`; empty otherwise).
    pub modal: ModalHistory,
}

/// The bat's displacement in modal form: y(z, t) = Σ_j φ_j(z) q_j(t) + s(z) p(t), with φ_j
/// the bat's scaled mode shapes (`bat::shapes`), q_j the coordinates below, s the static
/// shape and p the bat load.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ModalHistory {
    /// Modes the collision stepped (the coordinates' columns).
    pub modes: usize,
    /// Scaled modal coordinates q_j, m, row-major [n_samples][modes].
    pub coordinate: Vec<f64>,
    /// The force on the bat p(t), N: the contact force, or the hoop spring's with a hoop.
    pub bat_load: Vec<f64>,
    /// Static displacement per unit bat load of the modes not stepped, m/N, at the bat's
    /// shape points (`bat::shapes::shape_points`).
    pub static_shape: Vec<f64>,
}

/// Where the collision's energy went, J (bat-CM frame; with a grip, the frame of the
/// hands, where the grip does no work). `initial` = sum of the rest (up to the
/// integrator's accuracy).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct EnergyPartition {
    /// Kinetic energy of ball + bat before contact.
    pub initial: f64,
    /// Kinetic energy of the ball after separation.
    pub ball_final: f64,
    /// Dissipated in the ball's hysteresis loop.
    pub ball_loss: f64,
    /// Left in the bat's rigid motion (translation + rotation).
    pub bat_rigid: f64,
    /// Left in bat vibration (kinetic + strain, rigid motion removed).
    pub bat_vibration: f64,
    /// Left in the hoop mode.
    pub hoop: f64,
    /// Dissipated by the bat's material damping (`bat.material.quality_factor`; 0 without).
    pub bat_damping: f64,
    /// Dissipated by the grip's damper (`bat.grip.damping`; 0 without).
    pub grip_damping: f64,
    /// Dissipated by the ball sliding on the bat (oblique impacts and spin; 0 head-on).
    pub friction: f64,
}

/// The ball as it leaves the bat, in the bat-CM frame and the collision's plane (ŷ along
/// the incoming ball, x̂ across the swing plane, b̂ the bat's axis: docs/physics.md,
/// "Oblique impacts").
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct BallExit {
    /// Velocity along ŷ, m/s (negative: back toward the pitcher).
    pub along: f64,
    /// Velocity along x̂, m/s.
    pub across: f64,
    /// Spin about b̂, rad/s, in the sense of a pitch's backspin (so a batted ball's
    /// backspin is negative here).
    pub spin: f64,
}

/// The batted ball in the lab frame (docs/physics.md, "Launch" and "Flight"). NaN where it
/// does not apply (the wall; the flight without a `flight` block or for a ball that goes
/// back past the batter).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BattedBall {
    /// Lab-frame speed of the bat's impact point toward the pitcher before contact, m/s
    /// (`swing.cm_speed` − ω l).
    pub bat_speed: f64,
    /// Launch angle above the horizontal, rad.
    pub launch_angle: f64,
    /// Spray angle from straight-away centre field toward the first-base side, rad.
    pub spray_angle: f64,
    /// Backspin (positive) or topspin (negative), rad/s, about the horizontal axis across
    /// the ball's path.
    pub backspin: f64,
    /// Sidespin, rad/s, about the axis across the path in its vertical plane, positive
    /// curving toward the third-base (left-field) side.
    pub sidespin: f64,
    /// Horizontal distance from the contact point to the landing, m.
    pub carry: f64,
    /// Greatest height above the ground, m.
    pub apex: f64,
    /// Time from contact to landing, s.
    pub hang_time: f64,
    /// Lab speed of the bat's point 6 in from its barrel end before contact, m/s (where bat
    /// tracking measures bat speed; `field`).
    pub bat_speed_6in: f64,
    /// The pitch's lab speed at contact (the front of the plate), m/s.
    pub pitch_speed: f64,
    /// Collision efficiency in the field's convention, q = (exit − bat)/(pitch + bat) with
    /// `bat_speed_6in` and `pitch_speed`.
    pub collision_efficiency_q: f64,
    /// 1 if the exit speed is at least 80 % of the most the swing could give the pitch with
    /// the bat's best q, 0 if not, NaN unknown.
    pub squared_up: f64,
}

impl Default for BattedBall {
    fn default() -> Self {
        Self {
            bat_speed: f64::NAN,
            launch_angle: f64::NAN,
            spray_angle: f64::NAN,
            backspin: f64::NAN,
            sidespin: f64::NAN,
            carry: f64::NAN,
            apex: f64::NAN,
            hang_time: f64::NAN,
            bat_speed_6in: f64::NAN,
            pitch_speed: f64::NAN,
            collision_efficiency_q: f64::NAN,
            squared_up: f64::NAN,
        }
    }
}

impl BallExit {
    /// The exit speed, m/s, positive when the ball goes back toward the pitcher: −`along`
    /// head-on (exactly), the speed in the plane signed so otherwise.
    pub fn speed(&self) -> f64 {
        if self.across == 0.0 {
            -self.along
        } else {
            -self.along.signum() * self.along.hypot(self.across)
        }
    }
}

/// The result of one collision.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Outcome {
    /// Ball speed after separation, m/s, CM frame, positive back toward the pitcher.
    pub exit_speed: f64,
    /// Exit speed in the lab frame (bat CM moving toward the pitcher at `swing.cm_speed`):
    /// `exit_speed + swing.cm_speed`, m/s.
    pub exit_speed_lab: f64,
    /// Collision efficiency e_A (Nathan; ASTM F2219), dimensionless. From
    /// v_exit = e_A v_pitch + (1 + e_A) v_bat with v_pitch = `ball.speed` and the impact
    /// point's speed toward the pitcher v_bat = −ω (z_imp − z_cm):
    /// e_A = (exit_speed + ω l) / approach_speed (frame-independent).
    pub collision_efficiency: f64,
    /// Relative approach speed at the impact point, m/s.
    pub approach_speed: f64,
    /// Duration of the first contact (first touch to the force returning to zero), s.
    pub contact_time: f64,
    /// Peak contact force, N.
    pub peak_force: f64,
    /// Maximum ball compression, m.
    pub max_compression: f64,
    /// Impulse delivered to the ball, N·s.
    pub impulse: f64,
    /// Time from first contact until the ball has received 99 % of its impulse, s (Nathan
    /// 2000's "collision time"; NaN for the rigid model). Shorter than `contact_time`: the
    /// unloading branch ends in a long tail of almost no force.
    pub impulse_time_99: f64,
    /// BBCOR of this collision (NCAA protocol, `protocol`): `e_A (1 + m/M_e) + m/M_e` with
    /// the bat's effective mass at the impact point — about the pivot for a pinned grip, of the
    /// free bat otherwise (infinite for the wall). NaN unless the bat is at rest (ω = 0).
    pub bbcor: f64,
    /// BESR (NCAA until 2010): `e_A + 1/2`. NaN unless the bat is at rest.
    pub besr: f64,
    /// Bat performance factor: `bbcor` over the ball's wall COR at the same approach speed.
    /// NaN unless the bat is at rest.
    pub bpf: f64,
    /// Hoop-mode frequency the collision used, Hz (given, or derived from the shell); NaN
    /// without a hoop mode.
    pub hoop_frequency: f64,
    /// Hoop-mode mass the collision used, kg; NaN without a hoop mode.
    pub hoop_mass: f64,
    /// Energy partition, J.
    pub energy: EnergyPartition,
    /// The ball came back into contact after first separating (within the simulated time:
    /// 0.5 ms after each separation, or longer if histories ask for it).
    pub recontact: bool,
    /// Largest displacement of the bat's free vibration at the grip (6 in from the knob,
    /// `protocol::KNOB6`) after the ball has left, rigid motion excluded, m (0 for the rigid
    /// model). See `bat::motion::grip_vibration_amplitude`.
    pub grip_vibration_amplitude: f64,
    /// The barrel wall at the instants its stress can peak (the largest contact force and
    /// the largest displacement under the ball; `bat::wall_stress`). Empty without the
    /// shell's breathing modes.
    pub wall_instants: Vec<crate::bat::wall_stress::WallInstant>,
    /// Change of the grip point's rigid-body velocity caused by the collision, m/s, + along
    /// the incoming ball (zero for an impact at the grip's centre of percussion).
    pub grip_recoil_speed: f64,
    /// The ball as it leaves, in the collision's plane (what the launch is computed from).
    pub ball_exit: BallExit,
    /// The tangential COR: minus the slip velocity of the ball's contact point on the bat
    /// after the collision over the one before (rigid-body motion of the bat); 0 when the
    /// ball rolls off, > 0 when it leaves spinning faster than rolling. NaN without slip
    /// before (head-on without spin).
    pub tangential_cor: f64,
    /// The batted ball in the lab: its launch and flight (filled by `collision::launch`).
    pub batted: BattedBall,
    /// Requested histories.
    pub history: Option<History>,
}

/// Derived properties of one bat, for the store's `/bat` group.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct BatProperties {
    /// Profile sample positions, m from the knob.
    pub z: Vec<f64>,
    /// Outer radius at `z`, m.
    pub outer_radius: Vec<f64>,
    /// Inner radius at `z` (0 where solid), m.
    pub inner_radius: Vec<f64>,
    /// Length, m.
    pub length: f64,
    /// Mass, kg.
    pub mass: f64,
    /// Centre of mass, m from the knob.
    pub z_cm: f64,
    /// Moment of inertia about the CM, kg·m².
    pub moment_of_inertia: f64,
    /// Moment of inertia about the point 6 in (0.1524 m) from the knob, kg·m².
    pub moment_of_inertia_knob6: f64,
    /// Free–free flexible mode frequencies, Hz, lowest first (rigid modes excluded).
    pub mode_frequency: Vec<f64>,
    /// Node positions of each flexible mode, m from the knob.
    pub mode_nodes: Vec<Vec<f64>>,
    /// Sweet-spot definitions and standard metrics of the bat (centre of percussion, barrel
    /// nodes, BBCOR): filled by `metrics::bat_metrics`, NaN until then.
    pub metrics: crate::outcome::BatMetrics,
    /// The bat against each rule book's limits: filled by the study layer, which knows the
    /// rule books (empty until then).
    pub rule_checks: Vec<RuleCheck>,
}

impl BatProperties {
    /// Weight in ounces minus length in inches: the rule books' "drop" (negative for a bat
    /// lighter in ounces than it is long in inches).
    pub fn drop(&self) -> f64 {
        self.mass / crate::units::OUNCE - self.length / crate::units::INCH
    }

    /// Twice the largest outer radius, m (NaN without a profile).
    pub fn barrel_diameter(&self) -> f64 {
        2.0 * self.outer_radius.iter().copied().fold(f64::NAN, f64::max)
    }

    /// Moment of inertia about the knob, kg·m² (parallel axes).
    pub fn moment_of_inertia_knob(&self) -> f64 {
        self.moment_of_inertia + self.mass * self.z_cm * self.z_cm
    }
}

/// One limit of a rule book applied to a bat.
/// The check of a rule set for wood bats alone (`mlb_wood`): its label after the rule set's
/// name; valued 1 for a bat of one piece of solid wood and 0 otherwise. A bat it fails is one
/// the rule set is not for, not one that breaks it.
pub const SOLID_WOOD_CHECK: &str = "one piece of solid wood";

#[derive(Debug, Clone, PartialEq)]
pub struct RuleCheck {
    /// The rule set and its limit, e.g. `ncaa_bbcor: bat.bbcor <= 0.5`.
    pub label: String,
    /// Units of `value` and `margin` (UDUNITS spelling).
    pub units: String,
    /// The bat's value of the limited quantity.
    pub value: f64,
    /// How far inside the limit the value is (negative: the bat breaks the rule).
    pub margin: f64,
}

/// The bat-only sweet-spot definitions and standard metrics of one bat.
#[derive(Debug, Clone, PartialEq)]
pub struct BatMetrics {
    /// Pivot (hands) position used for the centre of percussion and BBCOR, m from the knob.
    pub pivot: f64,
    /// Centre of percussion for the pivot, m from the knob.
    pub centre_of_percussion: f64,
    /// Barrel-side node of free–free mode 1, m.
    pub node1_barrel: f64,
    /// Barrel-side node of free–free mode 2, m.
    pub node2_barrel: f64,
    /// Ball speed of the BBCOR scan, m/s.
    pub bbcor_ball_speed: f64,
    /// Impact positions of the BBCOR scan, m.
    pub bbcor_z: Vec<f64>,
    /// BBCOR at `bbcor_z` (NaN where a collision failed).
    pub bbcor: Vec<f64>,
    /// Maximum BBCOR (parabola-refined), and where, m.
    pub bbcor_max: f64,
    pub bbcor_max_position: f64,
    /// The sweet zone of the BBCOR scan: the barrel from `sweet_zone_start` to
    /// `sweet_zone_end` (m from the knob) has BBCOR within `sweet::BBCOR_ZONE_DROP` of its
    /// maximum.
    pub sweet_zone_start: f64,
    pub sweet_zone_end: f64,
    /// The barrel wall's lowest breathing (hoop) mode as a shell, Hz: a property of the
    /// hollow bat whatever hoop its collisions are given; NaN for a solid bat.
    pub hoop_mode_frequency: f64,
    /// The force that closes the barrel's diameter by 0.040 in between a load head and an
    /// anvil 6 in from its end (`bat::compression::BASEBALL`), N: the trade's barrel
    /// compression, from the shell; NaN for a bat without a shell barrel.
    pub barrel_compression: f64,
    /// The largest stress ratio of the barrel's wall under the BBCOR scan's shots (its von
    /// Mises stress over its yield for a metal, the Tsai–Hill index of its worst ply for a
    /// laminate; `bat::wall_stress`), 1: above 1 the certification's impact would dent or
    /// crack it there. NaN without the shell's breathing modes in the shot, or for a wood
    /// wall.
    pub wall_stress_ratio: f64,
    /// Where that largest ratio is, m from the knob.
    pub wall_stress_ratio_position: f64,
    /// The ball and hoop the scan fired and gave (`metrics::BbcorShot`), canonical JSON.
    pub bbcor_shot: String,
    /// The bat's best collision efficiency in the field's convention at the field's
    /// reference swing (`measures::metrics::best_q`), and where, m from the knob.
    pub best_q: f64,
    pub best_q_position: f64,
}

impl Default for BatMetrics {
    fn default() -> Self {
        Self {
            pivot: KNOB6,
            centre_of_percussion: f64::NAN,
            node1_barrel: f64::NAN,
            node2_barrel: f64::NAN,
            bbcor_ball_speed: BBCOR_BALL_SPEED,
            bbcor_z: Vec::new(),
            bbcor: Vec::new(),
            bbcor_max: f64::NAN,
            bbcor_max_position: f64::NAN,
            sweet_zone_start: f64::NAN,
            sweet_zone_end: f64::NAN,
            hoop_mode_frequency: f64::NAN,
            barrel_compression: f64::NAN,
            wall_stress_ratio: f64::NAN,
            wall_stress_ratio_position: f64::NAN,
            bbcor_shot: String::new(),
            best_q: f64::NAN,
            best_q_position: f64::NAN,
        }
    }
}
