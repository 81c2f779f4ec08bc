//! The time step of a collision: the contact's time scale, each integrator's limit, the
//! default step and the step budget.

use super::hoop::resolve_hoop;
use super::hoop::Hoop;
use super::{
    COAST_TIME, DEFAULT_MAX_STEPS, MODAL_MAX_STEP_FRACTION, MODAL_STEP_FRACTION,
    VERLET_STEP_FRACTION,
};
use crate::ball::ContactLaw;
use crate::bat::PreparedBat;
use crate::error::out_of_range;
use crate::error::ModelError;
use crate::spec::CollisionSpec;
use crate::spec::Integrator;

/// The contact's angular frequency scale: the stiffest ball tangent on the ball (and hoop).
pub(super) fn contact_omega(
    spec: &CollisionSpec,
    hoop: Option<Hoop>,
    law: &ContactLaw,
    approach: f64,
) -> f64 {
    let kt = law.max_tangent(spec.ball.mass, approach);
    let mut w2 = kt / spec.ball.mass;
    if let Some(h) = hoop {
        w2 += kt / h.mass + h.stiffness / h.mass;
    }
    w2.sqrt()
}

/// Largest step accepted for this collision, s: Verlet's stability limit (beam + contact
/// springs, bounded by λ_max(A + B) ≤ λ_max(A) + λ_max(B)); for the modal integrator a
/// resolution limit well inside its stability limit (see `MODAL_MAX_STEP_FRACTION`).
pub fn stability_limit(spec: &CollisionSpec, bat: &PreparedBat) -> f64 {
    let approach = approach_speed(spec, bat);
    let law = crate::ball::contact_law_on(
        &spec.ball.law,
        approach.abs(),
        spec.ball_radius(),
        Some(bat.geometry().outer_radius(spec.impact.z)),
    );
    let hoop = resolve_hoop(spec).ok().flatten();
    let wc = contact_omega(spec, hoop, &law, approach.abs());
    match spec.numerics.integrator {
        // The scheme is stable up to ω_c·dt = 2√3 (linear-acceleration method), but steps
        // that coarse silently give wrong exit speeds (10 % off at 1/3 of it): refuse
        // anything coarser than MODAL_MAX_STEP_FRACTION/ω_c (≈ 1 % error in exit speed).
        Integrator::Modal => MODAL_MAX_STEP_FRACTION / wc,
        Integrator::Verlet => {
            // λ_max(A + B) ≤ λ_max(A) + λ_max(B): beam + each spring's mass-weighted bound
            let beam = &bat.beam;
            let (k, a) = beam.interpolation(spec.impact.z);
            let node = (1.0 - a).powi(2) / beam.mass[k] + a * a / beam.mass[k + 1];
            let kt = law.max_tangent(spec.ball.mass, approach.abs());
            let w_beam = bat.modes.omega.last().copied().unwrap_or(0.0);
            let mut w2 = w_beam * w_beam;
            if bat.beam.pin.is_some() {
                return 0.0; // not supported by Verlet (refused in simulate_wave)
            }
            match hoop {
                None => w2 += kt * (1.0 / spec.ball.mass + node),
                Some(h) => {
                    let kh = h.stiffness;
                    w2 += kt * (1.0 / spec.ball.mass + 1.0 / h.mass) + kh * (1.0 / h.mass + node);
                }
            }
            2.0 / w2.sqrt()
        }
    }
}

/// The step used for this collision: the user's (checked) or the default.
pub fn time_step(spec: &CollisionSpec, bat: &PreparedBat) -> Result<f64, ModelError> {
    let limit = stability_limit(spec, bat);
    let (name, default) = match spec.numerics.integrator {
        Integrator::Modal => (
            "modal",
            MODAL_STEP_FRACTION / MODAL_MAX_STEP_FRACTION * limit,
        ),
        Integrator::Verlet => ("verlet", VERLET_STEP_FRACTION * limit),
    };
    checked_dt(spec.numerics.dt, (limit, "stability"), default, name)
}

/// The study's step `dt` if it is positive, finite and within `limit` (named, e.g.
/// "stability"), else `default` when the study sets none.
pub(super) fn checked_dt(
    dt: Option<f64>,
    (limit, limit_name): (f64, &str),
    default: f64,
    integrator: &'static str,
) -> Result<f64, ModelError> {
    match dt {
        Some(dt) if !(dt > 0.0 && dt.is_finite()) => Err(out_of_range(
            "numerics.dt",
            dt,
            &format!("(0, {limit_name} limit] s"),
        )),
        Some(dt) if dt > limit => Err(ModelError::TimeStepTooLarge {
            dt,
            limit,
            integrator,
        }),
        Some(dt) => Ok(dt),
        None => Ok(default),
    }
}

/// The step budget of this collision, refused when even the shortest run at step `dt`
/// (the re-contact watch after separation, `COAST_TIME`) needs more steps. `cause` names the
/// field that set the step, for the message.
pub fn checked_step_budget(
    spec: &CollisionSpec,
    dt: f64,
    cause: &'static str,
) -> Result<u64, ModelError> {
    let budget = step_budget(spec);
    let least = (COAST_TIME / dt).ceil();
    if least > budget as f64 {
        return Err(ModelError::StepBudget {
            steps: least,
            dt,
            budget,
            cause,
            provable: true,
        });
    }
    Ok(budget)
}

/// The step budget of this collision (`numerics.max_steps`, default `DEFAULT_MAX_STEPS`).
pub fn step_budget(spec: &CollisionSpec) -> u64 {
    spec.numerics.max_steps.unwrap_or(DEFAULT_MAX_STEPS)
}

/// Relative approach speed at the impact point, m/s.
pub fn approach_speed(spec: &CollisionSpec, bat: &PreparedBat) -> f64 {
    spec.ball.speed - spec.swing.omega * (spec.impact.z - bat.z_cm)
}
