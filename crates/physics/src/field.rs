//! The field's conventions: how public bat tracking states a swing and a batted ball, so
//! that a collision's answers can be set beside measured ones (docs/physics.md, "The
//! field's conventions").
//!
//! - **Bat speed** is the speed of the point 6 in from the barrel's end (Baseball Savant's
//!   bat tracking), not of the impact point.
//! - **The pitch's speed** is its speed at the front of the plate, where contact happens
//!   (about 0.92 of its release speed).
//! - **Collision efficiency** q (Nathan's convention): exit speed = q v_pitch +
//!   (1 + q) v_bat, with both speeds in those conventions. It is then
//!   q = (v_exit − v_bat)/(v_pitch + v_bat).
//! - **Squared up** (Savant): the exit speed is at least 80 % of the most this swing could
//!   give this pitch, q_max v_pitch + (1 + q_max) v_bat. Savant takes one q_max for every
//!   bat; here it is the bat's own best q (`measures::metrics::best_q`).

use crate::bat::PreparedBat;
use crate::outcome::{BattedBall, Outcome};
use crate::spec::CollisionSpec;

/// Where bat tracking measures bat speed: 6 in from the barrel's end, m.
pub const BAT_SPEED_FROM_END: f64 = 0.1524;

/// The share of the most a swing could give that makes a hit squared up.
pub const SQUARED_UP_SHARE: f64 = 0.8;

/// The field's reference swing for a bat's best q: a 70-mph swing (at 6 in from the end)
/// meeting an 82-mph pitch at the plate (a 90-mph pitch at release), level, head-on,
/// turning about the knob. These are about the means of the major-league swings and
/// pitches in `data/bat_tracking_2025.csv` (70.6 mph; 89.7 mph released).
pub const REFERENCE_BAT_SPEED: f64 = 70.0 * crate::units::MPH;
pub const REFERENCE_PITCH_SPEED: f64 = 82.0 * crate::units::MPH;

/// The lab speed of the point 6 in from the barrel's end, m/s, in a swing that turns the
/// bat at `omega` (rad/s, bat-CM frame) with its CM moving at `cm_speed`.
pub fn bat_speed_6in(bat: &PreparedBat, cm_speed: f64, omega: f64) -> f64 {
    let p = bat.properties();
    cm_speed - omega * (p.length - BAT_SPEED_FROM_END - p.z_cm)
}

/// The pitch's lab speed at contact, m/s: the `pitch` block's or the batter's, or without
/// a batter the ball's speed toward the bat less the bat's CM speed.
pub fn pitch_speed(spec: &CollisionSpec) -> f64 {
    match (
        &spec.pitch,
        spec.batter.as_ref().and_then(|b| b.pitch_speed),
    ) {
        (Some(p), _) => p.speed,
        (None, Some(speed)) => speed,
        (None, None) => spec.ball.speed - spec.swing.cm_speed,
    }
}

/// q = (v_exit − v_bat)/(v_pitch + v_bat); NaN when nothing moves.
pub fn collision_efficiency_q(exit_speed: f64, pitch: f64, bat: f64) -> f64 {
    let scale = pitch + bat;
    if scale > 0.0 {
        (exit_speed - bat) / scale
    } else {
        f64::NAN
    }
}

/// Fill the field's numbers of a swung collision's batted ball. `spec` is the collision as
/// swung (a batter's ω and CM speed set).
pub fn fill(spec: &CollisionSpec, bat: &PreparedBat, outcome: &mut Outcome) {
    let b = &mut outcome.batted;
    b.bat_speed_6in = bat_speed_6in(bat, spec.swing.cm_speed, spec.swing.omega);
    b.pitch_speed = pitch_speed(spec);
    b.collision_efficiency_q =
        collision_efficiency_q(outcome.exit_speed_lab, b.pitch_speed, b.bat_speed_6in);
}

/// 1 when the batted ball is squared up against a bat whose best q is `best_q`, 0 when it
/// is not; NaN without a swing or a best q.
pub fn squared_up(batted: &BattedBall, exit_speed: f64, best_q: f64) -> f64 {
    let (pitch, bat) = (batted.pitch_speed, batted.bat_speed_6in);
    let most = best_q * pitch + (1.0 + best_q) * bat;
    if !(most > 0.0 && bat > 0.0 && exit_speed.is_finite()) {
        return f64::NAN;
    }
    if exit_speed >= SQUARED_UP_SHARE * most {
        1.0
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn q_is_the_field_formula_inverted() {
        // exit = q v_p + (1 + q) v_b with q = 0.2, 90 and 70 mph: 102 mph
        let (vp, vb) = (90.0, 70.0);
        let exit = 0.2 * vp + 1.2 * vb;
        assert!((collision_efficiency_q(exit, vp, vb) - 0.2).abs() < 1e-12);
        assert!(collision_efficiency_q(1.0, 0.0, 0.0).is_nan());
    }

    #[test]
    fn squared_up_is_eighty_percent_of_the_most_possible() {
        let batted = BattedBall {
            pitch_speed: 40.0,
            bat_speed_6in: 30.0,
            ..BattedBall::default()
        };
        // the most with q 0.2: 0.2·40 + 1.2·30 = 44 m/s; 80 % is 35.2
        assert_eq!(squared_up(&batted, 35.3, 0.2), 1.0);
        assert_eq!(squared_up(&batted, 35.1, 0.2), 0.0);
        assert!(squared_up(&batted, 35.1, f64::NAN).is_nan());
    }
}
