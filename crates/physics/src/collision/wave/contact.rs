//! Contact bookkeeping shared by the integrators: first contact, separations, re-contact,
//! peak force and compression, the energy the ball's loop dissipates, and the impulse as it
//! builds up (for the time to 99 % of it, Nathan's "collision time").

use super::{COAST_TIME, MAX_TIME};
use crate::ball::ContactLaw;
use crate::error::ModelError;

/// Contact bookkeeping shared by the integrators.
#[derive(Default, Clone)]
pub(super) struct Contact {
    pub(super) in_contact: bool,
    pub(super) separations: usize,
    pub(super) start: f64,
    pub(super) first_duration: f64,
    pub(super) last_separation: f64,
    pub(super) peak_force: f64,
    pub(super) max_compression: f64,
    pub(super) ball_loss: f64,
    pub(super) recontact: bool,
    pub(super) s_max: f64,
    /// ∫F dt on the ball so far, N·s (trapezoid over the steps).
    impulse: f64,
    /// Force at the end of the last step, N.
    last_force: f64,
    /// (t, ∫F dt) at the end of every step that added impulse.
    impulse_path: Vec<(f64, f64)>,
}

impl Contact {
    pub(super) fn started() -> Self {
        Self {
            in_contact: true,
            ..Self::default()
        }
    }

    /// Time from first contact until the impulse on the ball reached `fraction` of its
    /// total, s (linear within a step); NaN without impulse.
    pub(super) fn impulse_time(&self, fraction: f64) -> f64 {
        let target = fraction * self.impulse;
        let mut previous = (0.0, 0.0);
        for &(t, j) in &self.impulse_path {
            if j >= target {
                let (t0, j0) = previous;
                return t0 + (t - t0) * (target - j0) / (j - j0);
            }
            previous = (t, j);
        }
        f64::NAN
    }

    /// After a step from (t0, s0) to (t1, s1) with end force f1.
    pub(super) fn update(&mut self, law: &ContactLaw, t0: f64, s0: f64, t1: f64, s1: f64, f1: f64) {
        let step_impulse = 0.5 * (self.last_force + f1) * (t1 - t0);
        if step_impulse > 0.0 {
            self.impulse += step_impulse;
            self.impulse_path.push((t1, self.impulse));
        }
        self.last_force = f1;
        let crossing = || {
            if s0 != s1 {
                t0 + (t1 - t0) * s0 / (s0 - s1)
            } else {
                t1
            }
        };
        if s1 > 0.0 {
            if !self.in_contact {
                self.in_contact = true;
                self.recontact = true;
                self.start = crossing();
            }
            self.s_max = self.s_max.max(s1);
            self.peak_force = self.peak_force.max(f1);
            self.max_compression = self.max_compression.max(s1);
        } else if self.in_contact {
            let t_sep = crossing();
            if self.separations == 0 {
                self.first_duration = t_sep - self.start;
            }
            self.separations += 1;
            self.last_separation = t_sep;
            self.ball_loss += law.loop_loss(self.s_max);
            self.s_max = 0.0;
            self.in_contact = false;
        }
    }

    /// The end-of-step test every integrator makes: `Ok(true)` when the collision is over
    /// (the ball has left, been watched for a re-contact for `COAST_TIME`, and cannot come
    /// back: `may_return`, asked only then, says whether it still can; or the time bound is
    /// reached out of contact); an error when the ball is still in contact at the time bound
    /// or the step budget is spent. Whether histories are recorded plays no part: a point's
    /// summary is the same with or without them (the histories' samples after the end come
    /// from the integrators' coasting, which cannot change it).
    pub(super) fn stop_after(
        &self,
        t: f64,
        steps: usize,
        h: f64,
        budget: u64,
        may_return: impl FnOnce() -> bool,
    ) -> Result<bool, ModelError> {
        if self.watched(t) && !may_return() {
            return Ok(true);
        }
        if t > MAX_TIME {
            if self.in_contact {
                return Err(ModelError::NoSeparation { t });
            }
            return Ok(true);
        }
        within_budget(steps, h, budget).map(|()| false)
    }

    /// Whether the ball has left and been watched for a re-contact for `COAST_TIME`.
    fn watched(&self, t: f64) -> bool {
        !self.in_contact && self.separations > 0 && t >= self.last_separation + COAST_TIME
    }
}

/// The step budget's test: an error once `steps` of length `h` have spent it.
pub(super) fn within_budget(steps: usize, h: f64, budget: u64) -> Result<(), ModelError> {
    match steps as u64 >= budget {
        true => Err(ModelError::StepBudget {
            steps: steps as f64,
            dt: h,
            budget,
            cause: "numerics.max_steps",
            provable: false,
        }),
        false => Ok(()),
    }
}

/// Whether to take one more step after the collision has ended, for a history that asks for
/// more time: not once the history is complete (`history_done`) or the time bound is
/// passed; an error once the step budget is spent. The one test of the three integrators'
/// loops past the end (the modal `coast`, Verlet's and the wall's).
pub(super) fn steps_on_for_history(
    history_done: bool,
    (steps, t): (usize, f64),
    h: f64,
    budget: u64,
) -> Result<bool, ModelError> {
    if history_done || t > MAX_TIME {
        return Ok(false);
    }
    within_budget(steps, h, budget).map(|()| true)
}
