//! After the collision: whether the ball can still come back to the bat, and the samples a
//! history asks for after the collision has ended.
//!
//! The collision ends when the ball has left, has been watched for a re-contact for
//! `COAST_TIME`, and cannot come back ([`may_return`]). Histories play no part in that
//! decision: a point's summary is the same with or without them. A history that reaches past
//! the end is completed by coasting ([`coast`]): the ball flies on and the bat vibrates
//! freely. Head-on without a hoop or a grip damper that motion is known in closed form, and
//! each sample is taken from it at its own time ([`coast_free`]); otherwise the collision's
//! steps go on without a contact force.

use super::super::contact::{steps_on_for_history, Contact};
use super::super::Collision;
use super::propagator::ModalStep;
use super::record::record_now;
use super::setup::{dot_n, Setup};
use super::state::{self, State};
use crate::bat::PreparedBat;
use crate::collision::history::Recorder;
use crate::error::ModelError;

/// Whether the ball, out of contact, may still meet the bat again. Head-on, without a hoop
/// or a grip damper, the compression is s(t) = s_r(t) − y_v(t): its rigid part s_r, the
/// ball's position less the rigid surface's, changes at the constant rate u = v − v_r (both
/// fly freely), and the vibration y_v = Σ φ_j q_j over the flexible modes never exceeds
/// Σ |φ_j| √(q_j² + (q̇_j/ω_j)²) (each mode's energy can only fall under its damping, and the
/// modes not stepped carry none without a force). So the ball cannot come back once u < 0
/// and s_r + that reach < 0; with u ≥ 0 it will. The hoop, an oblique contact and the grip
/// damper move the surface or the rigid motion in other ways: there the `COAST_TIME` watch
/// alone decides, as before (docs/model.md).
pub(super) fn may_return(c: &Collision, s: &Setup, state: &State) -> bool {
    if !free_after_contact(c, s) {
        return false;
    }
    let (mut rigid_velocity, mut vibration, mut reach) = (0.0, 0.0, 0.0);
    for (((&phi, &w), &q), &qd) in s.phi().iter().zip(s.omega).zip(&state.q).zip(&state.qd) {
        if w > 0.0 {
            // √(q² + (q̇/ω)²) without `hypot`: the values are far from overflow, and libm's
            // scaled hypot, called for every mode on every step of the watch, was a sixth of
            // a summary point's time
            let qd_over_w = qd / w;
            vibration += phi * q;
            reach += phi.abs() * (q * q + qd_over_w * qd_over_w).sqrt();
        } else {
            rigid_velocity += phi * qd;
        }
    }
    let closing = state.v - rigid_velocity;
    closing >= 0.0 || state.s + vibration + reach >= 0.0
}

/// Whether the motion after the ball has left is the free flight [`may_return`] bounds and
/// [`free_step`] steps: head-on, without a hoop or a grip damper.
fn free_after_contact(c: &Collision, s: &Setup) -> bool {
    c.hoop.is_none() && c.shell.is_none() && c.oblique.is_none() && s.grip.is_none()
}

/// Complete the history in `rec` after the collision has ended at `state`, until it has its
/// samples or the time bound is reached. Where [`may_return`] proves that no contact can
/// come back and no force is left on the bat, the samples come from the free motion
/// ([`coast_free`]); elsewhere from the collision's own steps, its contact bookkeeping on a
/// copy of `contact`, so that nothing of the summary changes (or, with a force left, from
/// the collision's step without its contact solve and losses, [`free_step`]).
pub(super) fn coast(
    c: &Collision,
    s: &Setup,
    bat: &PreparedBat,
    (state, contact): (&mut State, &Contact),
    rec: &mut Recorder,
    modal: bool,
) -> Result<(), ModelError> {
    if free_after_contact(c, s) && state.force == 0.0 {
        return coast_free(c, s, bat, state, rec, modal);
    }
    let mut watch = (!free_after_contact(c, s)).then(|| contact.clone());
    while steps_on_for_history(rec.done(), (state.steps, state.t), s.h, c.budget)? {
        match watch.as_mut() {
            None => free_step(c, s, state),
            Some(contact) => super::step(c, s, state, contact),
        }
        if rec.wants(state.t, s.h) {
            record_now(rec, c, bat, state, modal);
        }
    }
    Ok(())
}

/// The samples of a history after the collision, head-on without a hoop or a grip damper and
/// with no force left: each one at its own time from the free motion, the modes advanced
/// exactly (`ModalStep` without forces: damped or not, any time span) and the ball flying on
/// at its speed. Stepping by h only to draw a line between the two steps around each sample
/// makes coasting most of a long history's time (a 10 ms history of the base case steps
/// 2 300 times by 3.4 µs after the collision, recording two states for most of its 790
/// samples there); the samples are the free motion's own, where a line between two steps
/// misses a mode of frequency ω by up to (ωh)²/8 of its amplitude.
fn coast_free(
    c: &Collision,
    s: &Setup,
    bat: &PreparedBat,
    state: &mut State,
    rec: &mut Recorder,
    modal: bool,
) -> Result<(), ModelError> {
    let interval = rec.request().interval;
    // the span from one sample to the next, computed once; the first from the collision's end
    let between_samples = ModalStep::new(s.omega, s.zeta, s.phi(), interval);
    let mut first = true;
    while steps_on_for_history(rec.done(), (state.steps, state.t), s.h, c.budget)? {
        let t = rec.next_time();
        let dt = t - state.t;
        match std::mem::take(&mut first) {
            true => free_motion(&ModalStep::new(s.omega, s.zeta, s.phi(), dt), state),
            false => free_motion(&between_samples, state),
        }
        state.w += dt * state.v;
        state.y_c = dot_n(s.phi(), &state.q);
        state.s_before = state.s;
        state.s = state.w - state.y_c;
        state.steps += 1;
        state.t = t;
        record_now(rec, c, bat, state, modal);
    }
    Ok(())
}

/// The modes' free motion over the span of `st` (no force on the bat).
fn free_motion(st: &ModalStep, state: &mut State) {
    for (j, (qj, qdj)) in state.q.iter_mut().zip(state.qd.iter_mut()).enumerate() {
        let (x, xd) = (*qj, *qdj);
        *qj = st.cos[j] * x + st.sin_over_omega[j] * xd;
        *qdj = st.minus_omega_sin[j] * x + st.a22[j] * xd;
    }
}

/// The collision's step ([`super::step`]) with no force on the ball or the bat, head-on
/// without a hoop or a grip damper: the same arithmetic on the states a history records,
/// without the contact solve, the contact's bookkeeping and the damping losses (the summary,
/// taken when the collision ended, does not use them).
fn free_step(c: &Collision, s: &Setup, state: &mut State) {
    let (y_free, g_end, _) = state::free_contact_point(c, s, state);
    let (p0, p1) = (state.force, 0.0);
    let h2 = s.h * s.h;
    let w_free = state.w + s.h * state.v - h2 * p0 / (3.0 * c.ball_mass);
    state::advance_modes(s, state, (p0, p1), (0.0, 0.0));
    state.y_c = y_free + s.g_start * p0 + g_end * p1;
    state.w = w_free - h2 * p1 / (6.0 * c.ball_mass);
    state.v -= s.h * (p0 + p1) / (2.0 * c.ball_mass);
    state.s_before = state.s;
    state.force = p1;
    state.steps += 1;
    state.t = state.steps as f64 * s.h;
    state.s = state.w - state.y_c;
}

#[cfg(test)]
mod tests {
    use crate::outcome::{HistoryDisplacement, HistoryField, HistoryPrecision, HistoryRequest};
    use crate::spec::CollisionSpec;
    use crate::{prepare_bat, simulate};

    /// Largest |q(t+Δ) + e^{−2ζωΔ} q(t−Δ) − 2 e^{−ζωΔ} cos(ω_d Δ) q(t)| over the samples from
    /// `from` on, relative to the largest |q| there, over every stepped mode: zero for the
    /// free motion of a mode q̈ + 2ζωq̇ + ω²q = 0, whose solution e^{−ζωt}(A cos ω_d t + B sin
    /// ω_d t), ω_d = ω√(1 − ζ²), gives the identity at any Δ (a rigid mode, ω = 0: a line).
    fn free_motion_residual(quality_factor: Option<f64>) -> f64 {
        let mut spec = CollisionSpec::base_case(0.7);
        spec.bat.material.quality_factor = quality_factor;
        let bat = prepare_bat(&spec.bat, &spec.numerics).expect("the bat");
        let (interval, n) = (1e-5, 1000); // 10 ms; this collision ends at 2.1 ms
        let request = HistoryRequest {
            fields: vec![HistoryField::Displacement],
            interval,
            n_samples: n,
            z: vec![0.7],
            precision: HistoryPrecision::F64,
            compression: Default::default(),
            displacement: HistoryDisplacement::Modal,
        };
        let o = simulate(&spec, &bat, Some(&request)).expect("the collision");
        let m = o.history.expect("a history").modal;
        let zeta = bat.damping_ratio;
        let from = 300; // 3 ms
        let mut worst = 0.0_f64;
        for (j, &w) in bat.modes.omega[..m.modes].iter().enumerate() {
            let q = |k: usize| m.coordinate[k * m.modes + j];
            let z = if w > 0.0 { zeta } else { 0.0 };
            let (decay, wd) = ((-z * w * interval).exp(), w * (1.0 - z * z).sqrt());
            let scale = (from..n).map(|k| q(k).abs()).fold(0.0, f64::max);
            for k in from + 1..n - 1 {
                let r = q(k + 1) + decay * decay * q(k - 1)
                    - 2.0 * decay * (wd * interval).cos() * q(k);
                worst = worst.max(r.abs() / scale);
            }
        }
        worst
    }

    // After the collision the history samples the free motion exactly (each mode's
    // closed-form solution, undamped and damped): a residual of 7e-16 here, rounding. The
    // samples drawn on a line between the collision's steps, as coasting made them before,
    // left 5e-2 (measured with that path put back).
    #[test]
    fn after_the_collision_the_samples_are_the_free_motion() {
        for quality_factor in [None, Some(30.0)] {
            let r = free_motion_residual(quality_factor);
            assert!(r < 1e-9, "Q = {quality_factor:?}: residual {r:e}");
        }
    }
}
