//! After the collision: whether the ball can still come back to the bat, and the samples a
//! history asks for after the collision has ended.
//!
//! The collision ends when the ball has left, has been watched for a re-contact for
//! `COAST_TIME`, and cannot come back ([`may_return`]). Histories play no part in that
//! decision: a point's summary is the same with or without them. A history that reaches past
//! the end is completed by coasting ([`coast`]): the ball flies on and the bat vibrates
//! freely, stepped as the collision would step them without a contact force, so the samples
//! are those the collision's own steps would give, bit for bit.

use super::super::contact::{steps_on_for_history, Contact};
use super::super::Collision;
use super::record::record_now;
use super::setup::Setup;
use super::state::{self, State};
use crate::model::bat::PreparedBat;
use crate::model::collision::history::Recorder;
use crate::model::error::ModelError;

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
    c.hoop.is_none() && c.oblique.is_none() && s.grip.is_none()
}

/// Complete the history in `rec` after the collision has ended at `state`: steps without
/// contact until it has its samples or the time bound is reached. Where [`may_return`]
/// proves that no contact can come back, a step is the collision's step without its contact
/// solve and losses ([`free_step`]); elsewhere the collision's own step, its contact
/// bookkeeping on a copy of `contact`, so that nothing of the summary changes.
pub(super) fn coast(
    c: &Collision,
    s: &Setup,
    bat: &PreparedBat,
    (state, contact): (&mut State, &Contact),
    rec: &mut Recorder,
    modal: bool,
) -> Result<(), ModelError> {
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
