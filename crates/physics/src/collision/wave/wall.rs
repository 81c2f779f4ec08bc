//! The ball against a rigid, immovable wall: the target of ball certification (a ball fired
//! at a massive wall or block; its rebound over approach speed is the ball's COR). The same
//! contact law, step rule, contact bookkeeping and history sampling as the bat collisions,
//! with the bat replaced by a wall that never moves: compression s = ball travel since first
//! contact, m s̈ = −F(s; s_max).
//!
//! Integration: the linear-acceleration method, as for the ball in the modal integrator,
//! with the end-of-step force found implicitly (`ContactLaw::solve_implicit`).

use super::contact::{steps_on_for_history, Contact};
use super::{Diagnostics, MODAL_MAX_STEP_FRACTION, MODAL_STEP_FRACTION};
use crate::ball::ContactLaw;
use crate::collision::history::{Recorder, Sample};
use crate::error::ModelError;
use crate::outcome::{BallExit, BattedBall, EnergyPartition, HistoryRequest, Outcome};
use crate::spec::CollisionSpec;

/// One ball fired at the wall at `ball.speed`.
pub fn simulate_wall(
    spec: &CollisionSpec,
    history: Option<&HistoryRequest>,
) -> Result<(Outcome, Diagnostics), ModelError> {
    let (m, v0) = (spec.ball.mass, spec.ball.speed);
    let law = crate::ball::contact_law_on(
        &spec.ball.law,
        v0,
        spec.ball_radius(),
        spec.rigid_target_radius(),
    );
    let h = wall_step(spec, &law)?;
    let budget = super::checked_step_budget(spec, h, "numerics.max_steps")?;
    let h2_over_6m = h * h / (6.0 * m);
    let mut recorder = history.map(Recorder::new).transpose()?;
    if let Some(rec) = recorder.as_mut() {
        let first = sample(rec, 0.0, 0.0, v0);
        rec.push(0.0, first);
    }
    let mut contact = Contact::started();
    let (mut s, mut v, mut a) = (0.0, v0, 0.0);
    let mut steps = 0usize;
    let mut ended = None;
    loop {
        let (t_prev, s_prev) = (steps as f64 * h, s);
        // s₁ = s + h v + h² (a/3 + a₁/6) with a₁ = −F(s₁)/m.
        let free = s + h * v + h * h * a / 3.0;
        let (force, s1) = law.solve_implicit(free, h2_over_6m, contact.s_max, s);
        let a1 = -force / m;
        v += 0.5 * h * (a + a1);
        a = a1;
        s = s1;
        steps += 1;
        let t = steps as f64 * h;
        contact.update(&law, t_prev, s_prev, t, s, force);
        if let Some(rec) = recorder.as_mut().filter(|r| r.wants(t, h)) {
            let smp = sample(rec, force, s, v);
            rec.push(t, smp);
        }
        // the ball, once it has left the wall, comes back only if it still moves toward it
        if ended.is_some() || contact.stop_after(t, steps, h, budget, || v >= 0.0)? {
            // the summary as the collision ended; a history may ask for more time
            ended.get_or_insert_with(|| (v, steps, contact.clone()));
            let history_done = recorder.as_ref().is_none_or(|r| r.done());
            if !steps_on_for_history(history_done, (steps, t), h, budget)? {
                break;
            }
        }
    }
    let (v, steps, contact) = ended.expect("the loop ends after the collision");
    let mut outcome = wall_outcome(m, v0, v, &contact);
    outcome.history = recorder.map(|r| r.finish());
    let diagnostics = Diagnostics {
        energy_final: outcome.energy.ball_final + outcome.energy.ball_loss,
        dt: h,
        steps,
        ..Diagnostics::default()
    };
    Ok((outcome, diagnostics))
}

/// The time step: the study's (checked against the contact's resolution limit), else the
/// default fraction of the contact's time scale.
fn wall_step(spec: &CollisionSpec, law: &ContactLaw) -> Result<f64, ModelError> {
    let (m, v0) = (spec.ball.mass, spec.ball.speed);
    let omega_c = (law.max_tangent(m, v0) / m).sqrt();
    let limit = MODAL_MAX_STEP_FRACTION / omega_c;
    let default = MODAL_STEP_FRACTION / omega_c;
    super::step::checked_dt(spec.numerics.dt, (limit, "resolution"), default, "wall")
}

/// A sample of the ball against the wall (the wall does not move).
fn sample(rec: &Recorder, force: f64, s: f64, v: f64) -> Sample {
    let positions = if rec.wants_displacement {
        rec.request().z.len()
    } else {
        0
    };
    Sample {
        force,
        compression: s.max(0.0),
        ball_velocity: v,
        displacement: vec![0.0; positions],
        ..Sample::default()
    }
}

/// The outcome of a ball of mass `m` that hit the wall at `v0` and left at velocity `v`
/// (negative: away from the wall).
fn wall_outcome(m: f64, v0: f64, v: f64, contact: &Contact) -> Outcome {
    let exit_speed = -v;
    let energy = EnergyPartition {
        initial: 0.5 * m * v0 * v0,
        ball_final: 0.5 * m * v * v,
        ball_loss: contact.ball_loss,
        ..EnergyPartition::default()
    };
    Outcome {
        exit_speed,
        exit_speed_lab: exit_speed,
        // An immovable target has an infinite effective mass: e_A is the COR itself.
        collision_efficiency: exit_speed / v0,
        approach_speed: v0,
        contact_time: contact.first_duration,
        impulse_time_99: contact.impulse_time(0.99),
        hoop_frequency: f64::NAN,
        hoop_mass: f64::NAN,
        bbcor: f64::NAN,
        besr: f64::NAN,
        bpf: f64::NAN,
        peak_force: contact.peak_force,
        max_compression: contact.max_compression,
        impulse: m * (v0 - v),
        energy,
        recontact: contact.recontact,
        grip_vibration_amplitude: 0.0,
        grip_recoil_speed: 0.0,
        wall_instants: Vec::new(),
        ball_exit: BallExit {
            along: v,
            across: 0.0,
            spin: 0.0,
        },
        tangential_cor: f64::NAN,
        batted: BattedBall::default(),
        history: None,
    }
}
