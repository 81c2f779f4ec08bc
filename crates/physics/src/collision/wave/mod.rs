//! Time integration of the wave model: beam + ball (+ optional hoop mode).
//!
//! Two integrators share the set-up and the bookkeeping:
//! - `Modal` (default): the linear beam is advanced exactly in its modal basis (precomputed in
//!   `PreparedBat`) under a contact force that varies linearly over each step; the force at
//!   the end of the step is found implicitly (one scalar equation: compression is affine in
//!   the new force), so the step is set by the contact (µs), not by the highest beam mode.
//!   For the ball (and hoop) this is the linear-acceleration method, stable for
//!   ω_c·dt < 2√3 and second-order accurate.
//! - `Verlet`: plain explicit velocity Verlet in physical coordinates at a step below the
//!   stability limit of the highest beam mode (the paper's approach; the baseline).
//!
//! Sign conventions (docs/physics.md): y along the incoming ball's velocity; the ball's front
//! surface is at w, the contact point of the bat at y_c; compression s = w − y_c (or
//! w − x_h with a hoop mass at x_h); the ball pushes the bat (or hoop) with +F and is pushed
//! back with −F. Time 0 = first contact (s = 0).

use crate::ball::ContactLaw;
use crate::bat::motion::grip_recoil_speed;
use crate::bat::PreparedBat;
use crate::collision::history::Recorder;
use crate::collision::oblique::Oblique;
use crate::error::ModelError;
use crate::outcome::{
    BattedBall, EnergyPartition, HistoryDisplacement, HistoryField, HistoryRequest, Outcome,
};
use crate::protocol::KNOB6;
use crate::spec::{BeamTheory, CollisionSpec, Integrator};

mod contact;
mod exit;
mod hoop;
mod modal;
mod project;
mod shell_contact;
mod step;
mod verlet;
mod wall;

use contact::Contact;
pub use hoop::{resolve_hoop, Hoop};
use modal::run_modal;
pub use shell_contact::{
    footprint_axes, resolve_shell, Footprint, ShellContact, HERTZ_FOOTPRINT_RATIO,
};
use step::contact_omega;
pub use step::{approach_speed, checked_step_budget, stability_limit, step_budget, time_step};
use verlet::run_verlet;
pub use wall::simulate_wall;

/// Time simulated after the last separation to catch a re-contact, s.
pub const COAST_TIME: f64 = 0.5e-3;
/// Upper bound of the simulated time, s.
pub const MAX_TIME: f64 = 20e-3;
/// Default step budget of one collision (`numerics.max_steps`): a few seconds of computing
/// for the explicit baseline, thousands of times what a default collision takes.
pub const DEFAULT_MAX_STEPS: u64 = 10_000_000;
/// Default modal step as a fraction of the contact's time scale 1/ω_c (ω_c from the ball's
/// stiffest tangent, plus the hoop): ≈ 3.4 µs for the base case, exit speed within 4e-5 of
/// the converged value.
pub const MODAL_STEP_FRACTION: f64 = 0.02;
/// Largest modal step accepted, as a fraction of 1/ω_c.
pub const MODAL_MAX_STEP_FRACTION: f64 = 0.2;
/// Modes with ω_n above this multiple of the contact's frequency scale are treated
/// quasi-statically by the modal integrator (their dynamic correction is ~(ω_c/ω_n)²).
pub const MODE_CUTOFF_FACTOR: f64 = 50.0;
/// Fewest modes the modal integrator keeps.
const MIN_MODES: usize = 12;
/// Default Verlet step as a fraction of its stability limit.
pub const VERLET_STEP_FRACTION: f64 = 0.9;

/// Conservation checks of one run (for tests and benchmarks). Without a grip: bat-CM frame,
/// angular momentum about z_cm. With a grip: the frame of the hands, angular momentum about
/// the grip point (conserved: the grip force has no moment about it), and linear momentum
/// is not conserved (the hands push).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Diagnostics {
    pub momentum_initial: f64,
    pub momentum_final: f64,
    pub angular_momentum_initial: f64,
    pub angular_momentum_final: f64,
    /// Sum of the final energy partition (must equal `energy.initial`).
    pub energy_final: f64,
    pub dt: f64,
    pub steps: usize,
    pub segments: usize,
    /// Modes time-stepped (modal integrator; all segments for Verlet).
    pub modes: usize,
}

/// Everything of one collision that both integrators need.
struct Collision {
    law: ContactLaw,
    ball_mass: f64,
    /// Ball velocity toward the bat in the collision's frame (the hands' with a grip).
    ball_speed: f64,
    omega: f64,
    /// Velocity of the frame (the hands) in the bat-CM frame: ω (z_grip − z_cm), or 0.
    frame_velocity: f64,
    hoop: Option<Hoop>,
    /// The barrel's breathing modes at the impact point (a hoop from the geometry).
    shell: Option<ShellContact>,
    /// Impact point: node pair k, k+1 and weight a of node k+1; lever arm z − z_cm.
    k: usize,
    a: f64,
    lever: f64,
    dt: f64,
    /// Most steps this collision may take.
    budget: u64,
    /// Modes above this angular frequency are treated quasi-statically (modal integrator).
    mode_cutoff: f64,
    /// The oblique contact (`None`: head-on without spin, the paper's collision).
    oblique: Option<Oblique>,
}

/// What an integrator hands back at the end.
struct FinalState {
    ball_velocity: f64,
    bat_energy: f64,
    /// Energy of the rigid modes (rotation about the grip) with a grip; unused without.
    bat_rigid_energy: f64,
    /// Dissipated by material damping.
    bat_damping: f64,
    /// Dissipated by the grip damper.
    grip_loss: f64,
    bat_momentum: f64,
    bat_angular_momentum: f64,
    hoop_energy: f64,
    hoop_velocity: f64,
    /// Free-vibration amplitude at the grip at the end (`bat::motion::grip_vibration_amplitude`).
    grip_amplitude: f64,
    steps: usize,
    modes: usize,
    /// The oblique contact's final state (modal integrator; `None` head-on).
    tangential: Option<modal::tangential::Tangential>,
    /// The barrel wall at the instants its stress can peak (empty without a shell).
    wall: Vec<crate::bat::wall_stress::WallInstant>,
}

/// Run one wave-model collision.
pub fn simulate_wave(
    spec: &CollisionSpec,
    bat: &PreparedBat,
    history: Option<&HistoryRequest>,
) -> Result<(Outcome, Diagnostics), ModelError> {
    let approach = approach_speed(spec, bat);
    if approach <= 0.0 {
        return Err(ModelError::NoApproach {
            approach_speed: approach,
        });
    }
    check_integrator(spec, bat)?;
    check_history_form(spec, history)?;
    let collision = collision_of(spec, bat, approach)?;
    let mut recorder = history.map(Recorder::new).transpose()?;
    let mut contact = Contact::started();
    let fin = match spec.numerics.integrator {
        Integrator::Modal => run_modal(&collision, bat, &mut contact, &mut recorder)?,
        Integrator::Verlet => run_verlet(&collision, bat, &mut contact, &mut recorder)?,
    };
    let energy = energy_partition(&collision, bat, &contact, &fin);
    let diagnostics = diagnostics_of(spec, bat, &collision, &fin, &energy);
    let mut outcome = outcome_of(spec, bat, &collision, &contact, &fin, energy, approach);
    outcome.history = recorder.map(|r| r.finish());
    Ok((outcome, diagnostics))
}

/// The explicit baseline steps the plain Euler–Bernoulli beam only, head-on.
fn check_integrator(spec: &CollisionSpec, bat: &PreparedBat) -> Result<(), ModelError> {
    if spec.numerics.integrator != Integrator::Verlet {
        return Ok(());
    }
    if spec.impact.offset != 0.0 || spec.ball.spin != 0.0 {
        return Err(ModelError::Unsupported(
            "an oblique impact or a spinning ball needs the modal integrator",
        ));
    }
    if bat.beam.pin.is_some() {
        return Err(ModelError::Unsupported(
            "a pinned grip needs the modal integrator",
        ));
    }
    if spec.hoop.as_ref().is_some_and(|h| h.from_geometry) {
        return Err(ModelError::Unsupported(
            "hoop.from_geometry (the barrel's shell modes) needs the modal integrator",
        ));
    }
    if bat.damping_ratio > 0.0 || bat.grip_damping > 0.0 {
        return Err(ModelError::Unsupported(
            "material damping needs the modal integrator",
        ));
    }
    if spec.bat.beam == BeamTheory::Timoshenko {
        return Err(ModelError::Unsupported(
            "the Timoshenko beam needs the modal integrator",
        ));
    }
    Ok(())
}

/// The displacement's modal form is the modal integrator's own state: Verlet records the
/// grid form only.
fn check_history_form(
    spec: &CollisionSpec,
    history: Option<&HistoryRequest>,
) -> Result<(), ModelError> {
    let modal = history.is_some_and(|h| {
        h.displacement == HistoryDisplacement::Modal
            && h.fields.contains(&HistoryField::Displacement)
    });
    match modal && spec.numerics.integrator == Integrator::Verlet {
        true => Err(ModelError::Unsupported(
            "history.displacement: modal needs the modal integrator (set history.displacement: grid)",
        )),
        false => Ok(()),
    }
}

/// The collision as the integrators see it: ball, frame, hoop, impact point, step, budget.
fn collision_of(
    spec: &CollisionSpec,
    bat: &PreparedBat,
    approach: f64,
) -> Result<Collision, ModelError> {
    let hoop = resolve_hoop(spec)?;
    let shell = resolve_shell(spec, bat)?;
    let oblique = Oblique::resolve(spec, bat, approach)?;
    let dt = time_step(spec, bat)?;
    // The run lasts at least the re-contact watch after the ball has left.
    let budget = checked_step_budget(spec, dt, "numerics.max_steps")?;
    let (k, a) = bat.beam.interpolation(spec.impact.z);
    let frame_velocity = bat
        .beam
        .grip_z
        .map_or(0.0, |zg| spec.swing.omega * (zg - bat.z_cm));
    // a speed-dependent ball takes its COR at the normal speed it meets the bat with
    let law = crate::ball::contact_law_on(
        &spec.ball.law,
        oblique.map_or(approach, |o| o.normal_speed(approach)),
        spec.ball_radius(),
        Some(bat.geometry().outer_radius(spec.impact.z)),
    );
    Ok(Collision {
        law,
        ball_mass: spec.ball.mass,
        ball_speed: spec.ball.speed - frame_velocity,
        omega: spec.swing.omega,
        frame_velocity,
        hoop,
        shell,
        k,
        a,
        lever: spec.impact.z - bat.z_cm,
        dt,
        budget,
        mode_cutoff: MODE_CUTOFF_FACTOR * contact_omega(spec, hoop, &law, approach),
        oblique,
    })
}

/// The hoop mass and its velocity at first contact (that of the contact point).
fn hoop_start(c: &Collision) -> (f64, f64) {
    let along = c.omega * c.lever - c.frame_velocity;
    (
        c.hoop.map_or(0.0, |h| h.mass),
        // an oblique contact's hoop mass moves along n̂ with the surface's normal velocity
        c.oblique.map_or(along, |o| along * o.cos),
    )
}

/// Where the energy went: ball, ball's hysteresis, bat's rigid motion and vibration, hoop,
/// damping.
fn energy_partition(
    c: &Collision,
    bat: &PreparedBat,
    contact: &Contact,
    fin: &FinalState,
) -> EnergyPartition {
    let (m, u) = (c.ball_mass, c.frame_velocity);
    let total_mass = bat.beam.total_mass();
    let bat_rigid = if bat.beam.grip_z.is_some() {
        fin.bat_rigid_energy
    } else {
        0.5 * fin.bat_momentum.powi(2) / total_mass
            + 0.5 * fin.bat_angular_momentum.powi(2) / bat.inertia_cm
    };
    let (hoop_mass, hoop_initial_velocity) = hoop_start(c);
    let mut energy = EnergyPartition {
        initial: 0.5 * m * c.ball_speed.powi(2)
            + 0.5 * c.omega.powi(2) * bat.inertia_cm
            + 0.5 * total_mass * u * u
            + 0.5 * hoop_mass * hoop_initial_velocity.powi(2),
        ball_final: 0.5 * m * fin.ball_velocity.powi(2),
        ball_loss: contact.ball_loss,
        bat_rigid,
        bat_vibration: fin.bat_energy - bat_rigid,
        hoop: fin.hoop_energy,
        bat_damping: fin.bat_damping,
        grip_damping: fin.grip_loss,
        friction: 0.0,
    };
    if let Some(extra) = exit::oblique_energies(c, fin) {
        energy.initial += extra.before;
        energy.ball_final += extra.ball_after;
        energy.bat_rigid += extra.bat_after;
        energy.friction = extra.friction;
    }
    energy
}

/// The point's summary (histories are added by the caller).
fn outcome_of(
    spec: &CollisionSpec,
    bat: &PreparedBat,
    c: &Collision,
    contact: &Contact,
    fin: &FinalState,
    energy: EnergyPartition,
    approach: f64,
) -> Outcome {
    // back to the bat-CM frame
    let ball_exit = exit::ball_exit(c, fin);
    let exit_speed = ball_exit.speed();
    Outcome {
        ball_exit,
        tangential_cor: exit::tangential_cor(c, bat, fin),
        // the lab-frame launch and flight are the caller's (`collision::launch`)
        batted: BattedBall::default(),
        exit_speed,
        exit_speed_lab: exit_speed + spec.swing.cm_speed,
        // v_exit = e_A v_pitch + (1 + e_A) v_bat with v_pitch = ball.speed and the bat's
        // impact-point speed toward the pitcher v_bat = −ω l: e_A = (exit + ω l)/approach.
        collision_efficiency: (exit_speed + c.omega * c.lever) / approach,
        approach_speed: approach,
        contact_time: contact.first_duration,
        impulse_time_99: contact.impulse_time(0.99),
        hoop_frequency: match (&c.hoop, &c.shell) {
            (Some(h), _) => h.frequency(),
            (None, Some(s)) => s.frequency,
            (None, None) => f64::NAN,
        },
        hoop_mass: match (&c.hoop, &c.shell) {
            (Some(h), _) => h.mass,
            (None, Some(s)) => s.mass,
            (None, None) => f64::NAN,
        },
        // filled for a bat at rest by `collision::simulate`
        bbcor: f64::NAN,
        besr: f64::NAN,
        bpf: f64::NAN,
        peak_force: contact.peak_force,
        max_compression: contact.max_compression,
        impulse: c.ball_mass * (c.ball_speed - fin.ball_velocity),
        energy,
        recontact: contact.recontact,
        grip_vibration_amplitude: fin.grip_amplitude,
        wall_instants: fin.wall.clone(),
        grip_recoil_speed: grip_recoil_speed(
            fin.bat_momentum,
            fin.bat_angular_momentum - c.omega * bat.inertia_cm,
            bat.beam.total_mass(),
            bat.inertia_cm,
            bat.z_cm,
            KNOB6,
        ),
        history: None,
    }
}

/// The conservation checks: momentum and angular momentum before and after (about the grip
/// with one, else the CM), and the energy's final sum.
fn diagnostics_of(
    spec: &CollisionSpec,
    bat: &PreparedBat,
    c: &Collision,
    fin: &FinalState,
    energy: &EnergyPartition,
) -> Diagnostics {
    let m = c.ball_mass;
    let (hoop_mass, hoop_initial_velocity) = hoop_start(c);
    // its momentum along ŷ: an oblique contact's hoop mass moves along n̂
    let hoop_initial_along = hoop_initial_velocity * c.oblique.map_or(1.0, |o| o.cos);
    // about the grip (with one) or the CM; bat angular momentum about the CM → about centre
    let centre = bat.beam.grip_z.unwrap_or(bat.z_cm);
    let lever = spec.impact.z - centre;
    let shift = bat.z_cm - centre;
    let bat_momentum_initial = -bat.beam.total_mass() * c.frame_velocity;
    Diagnostics {
        momentum_initial: m * c.ball_speed + hoop_mass * hoop_initial_along + bat_momentum_initial,
        momentum_final: m * fin.ball_velocity + fin.bat_momentum + hoop_mass * fin.hoop_velocity,
        angular_momentum_initial: (m * c.ball_speed + hoop_mass * hoop_initial_along) * lever
            + c.omega * bat.inertia_cm
            + shift * bat_momentum_initial,
        angular_momentum_final: (m * fin.ball_velocity + hoop_mass * fin.hoop_velocity) * lever
            + fin.bat_angular_momentum
            + shift * fin.bat_momentum,
        energy_final: energy.ball_final
            + energy.ball_loss
            + energy.bat_rigid
            + energy.bat_vibration
            + energy.hoop
            + energy.bat_damping
            + energy.grip_damping
            + energy.friction,
        dt: c.dt,
        steps: fin.steps,
        segments: bat.beam.len(),
        modes: fin.modes,
    }
}

/// Interpolation weights of the requested z (NaN marks points beyond the bat).
fn displacement_points(
    bat: &PreparedBat,
    request: Option<&HistoryRequest>,
) -> Vec<(usize, f64, bool)> {
    request.map_or(Vec::new(), |r| {
        r.z.iter()
            .map(|&z| {
                let (k, a) = bat.beam.interpolation(z);
                (k, a, (0.0..=bat.length()).contains(&z))
            })
            .collect()
    })
}

fn spec_history<'a>(recorder: &'a Option<Recorder>) -> Option<&'a HistoryRequest> {
    recorder.as_ref().map(|r| r.request())
}
