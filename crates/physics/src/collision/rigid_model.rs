//! The rigid model as an outcome: Brody's head-on collision (`rigid`), the oblique rigid
//! collision with friction (`oblique::rigid_oblique`), and the immovable wall.
//!
//! It has no time scale of its own: contact time, peak force and compression are NaN, the
//! hoop mode is ignored, and the energy lost counts as lost in the ball.

use crate::ball::cor_on_target;
use crate::bat::motion::grip_recoil_speed;
use crate::bat::PreparedBat;
use crate::collision::oblique::{rigid_oblique, Oblique, RigidOblique};
use crate::collision::rigid::rigid_collision;
use crate::error::ModelError;
use crate::outcome::{BallExit, BattedBall, EnergyPartition, Outcome};
use crate::protocol::{free_effective_mass, KNOB6};
use crate::spec::CollisionSpec;

/// Brody's model against an immovable wall: the ball comes back at e(v)·v.
pub(super) fn rigid_wall(spec: &CollisionSpec) -> Outcome {
    let (m, v) = (spec.ball.mass, spec.ball.speed);
    let e = cor_on_target(
        &spec.ball.law,
        v,
        spec.ball_radius(),
        spec.rigid_target_radius(),
    );
    Outcome {
        exit_speed: e * v,
        exit_speed_lab: e * v,
        collision_efficiency: e,
        approach_speed: v,
        contact_time: f64::NAN,
        impulse_time_99: f64::NAN,
        peak_force: f64::NAN,
        max_compression: f64::NAN,
        impulse: m * (1.0 + e) * v,
        hoop_frequency: f64::NAN,
        hoop_mass: f64::NAN,
        energy: EnergyPartition {
            initial: 0.5 * m * v * v,
            ball_final: 0.5 * m * (e * v).powi(2),
            ball_loss: 0.5 * m * v * v * (1.0 - e * e),
            ..EnergyPartition::default()
        },
        ball_exit: BallExit {
            along: -e * v,
            across: 0.0,
            spin: 0.0,
        },
        tangential_cor: f64::NAN,
        batted: BattedBall::default(),
        ..Outcome::default()
    }
}

/// The rigid model on a bat: Brody's collision head-on, the oblique rigid collision with
/// friction otherwise. e = the ball's COR at the normal approach speed.
pub(super) fn simulate_rigid(
    spec: &CollisionSpec,
    bat: &PreparedBat,
) -> Result<Outcome, ModelError> {
    let lever_arm = spec.impact.z - bat.properties().z_cm;
    let approach = spec.ball.speed - spec.swing.omega * lever_arm;
    Ok(match Oblique::resolve(spec, bat, approach)? {
        None => rigid_head_on(spec, bat),
        Some(o) => rigid_oblique_outcome(spec, bat, &o),
    })
}

/// Brody's rigid-body model with e = `ball.law.cor` (its value at the approach speed for
/// `speed_dependent`), on the prepared bat's mass properties.
fn rigid_head_on(spec: &CollisionSpec, bat: &PreparedBat) -> Outcome {
    let properties = bat.properties();
    let lever_arm = spec.impact.z - properties.z_cm;
    let r = rigid_collision(
        spec.ball.mass,
        spec.ball.speed,
        properties.mass,
        properties.moment_of_inertia,
        lever_arm,
        spec.swing.omega,
        // The COR at the relative normal speed of ball and bat surface at the impact point.
        cor_on_target(
            &spec.ball.law,
            spec.ball.speed - spec.swing.omega * lever_arm,
            spec.ball_radius(),
            Some(bat.geometry().outer_radius(spec.impact.z)),
        ),
    );
    Outcome {
        exit_speed: r.exit_speed,
        exit_speed_lab: r.exit_speed + spec.swing.cm_speed,
        collision_efficiency: r.collision_efficiency,
        approach_speed: r.approach_speed,
        impulse: r.impulse,
        energy: EnergyPartition {
            initial: r.energy_initial,
            ball_final: r.energy_ball_final,
            ball_loss: r.energy_lost,
            bat_rigid: r.energy_bat_final,
            ..EnergyPartition::default()
        },
        grip_recoil_speed: recoil(bat, r.impulse, lever_arm),
        ball_exit: BallExit {
            along: -r.exit_speed,
            across: 0.0,
            spin: 0.0,
        },
        ..no_time_scale()
    }
}

/// What the rigid model leaves undefined or zero.
fn no_time_scale() -> Outcome {
    Outcome {
        contact_time: f64::NAN,
        impulse_time_99: f64::NAN,
        peak_force: f64::NAN,
        max_compression: f64::NAN,
        hoop_frequency: f64::NAN,
        hoop_mass: f64::NAN,
        bbcor: f64::NAN,
        besr: f64::NAN,
        bpf: f64::NAN,
        recontact: false,
        grip_vibration_amplitude: 0.0,
        tangential_cor: f64::NAN,
        batted: BattedBall::default(),
        history: None,
        ..Outcome::default()
    }
}

/// The grip point's recoil from an impulse along ŷ on the rigid bat at `lever_arm`.
fn recoil(bat: &PreparedBat, impulse: f64, lever_arm: f64) -> f64 {
    let p = bat.properties();
    grip_recoil_speed(
        impulse,
        impulse * lever_arm,
        p.mass,
        p.moment_of_inertia,
        p.z_cm,
        KNOB6,
    )
}

/// The oblique rigid collision as an outcome.
fn rigid_oblique_outcome(spec: &CollisionSpec, bat: &PreparedBat, o: &Oblique) -> Outcome {
    let p = bat.properties();
    let lever_arm = spec.impact.z - p.z_cm;
    let (m, v, omega) = (spec.ball.mass, spec.ball.speed, spec.swing.omega);
    let bat_speed = omega * lever_arm;
    let approach = v - bat_speed;
    let effective = free_effective_mass(p.mass, p.z_cm, p.moment_of_inertia, lever_arm + p.z_cm);
    let cor = cor_on_target(
        &spec.ball.law,
        o.normal_speed(approach),
        spec.ball_radius(),
        Some(bat.geometry().outer_radius(spec.impact.z)),
    );
    let r = rigid_oblique(o, m, effective, (v, bat_speed), cor);
    let ball_exit = BallExit {
        along: r.velocity.0,
        across: r.velocity.1,
        spin: r.spin,
    };
    let exit_speed = ball_exit.speed();
    Outcome {
        exit_speed,
        exit_speed_lab: exit_speed + spec.swing.cm_speed,
        collision_efficiency: (exit_speed + omega * lever_arm) / approach,
        approach_speed: approach,
        impulse: -r.impulse.0,
        energy: oblique_energies(spec, bat, o, &r),
        grip_recoil_speed: recoil(bat, -r.impulse.0, lever_arm),
        ball_exit,
        tangential_cor: -r.slip_after / r.slip_before,
        ..no_time_scale()
    }
}

/// Energies of the oblique rigid collision, J: the bat takes the opposite of the ball's
/// impulse at the impact point (translation, rotation in and across the swing plane, roll).
fn oblique_energies(
    spec: &CollisionSpec,
    bat: &PreparedBat,
    o: &Oblique,
    r: &RigidOblique,
) -> EnergyPartition {
    let p = bat.properties();
    let (m, v, omega) = (spec.ball.mass, spec.ball.speed, spec.swing.omega);
    let lever_arm = spec.impact.z - p.z_cm;
    let (jy, jx) = (-r.impulse.0, -r.impulse.1);
    let (inertia, ball_inertia) = (p.moment_of_inertia, o.ball.inertia);
    let initial = 0.5 * m * (v * v + o.across_speed.powi(2))
        + 0.5 * inertia * omega * omega
        + 0.5 * ball_inertia * o.spin.powi(2);
    let ball_final = 0.5 * m * (r.velocity.0.powi(2) + r.velocity.1.powi(2))
        + 0.5 * ball_inertia * r.spin.powi(2);
    let turn_in = omega + jy * lever_arm / inertia;
    let turn_across = jx * lever_arm / inertia;
    let bat_rigid = 0.5 * (jy * jy + jx * jx) / p.mass
        + 0.5 * inertia * (turn_in * turn_in + turn_across * turn_across)
        + 0.5 * o.roll_inertia * r.roll_rate.powi(2);
    EnergyPartition {
        initial,
        ball_final,
        // the normal loss and any sliding: the rigid model does not tell them apart
        ball_loss: initial - ball_final - bat_rigid,
        bat_rigid,
        ..EnergyPartition::default()
    }
}
