//! The ball's exit from a wave-model collision in the collision's plane, and what an oblique
//! contact adds to the energy balance and the outcome (the tangential COR).

use super::modal::tangential::Tangential;
use super::{Collision, FinalState};
use crate::bat::PreparedBat;
use crate::collision::oblique::Oblique;
use crate::outcome::BallExit;

/// The ball as it leaves, bat-CM frame: along ŷ, across the swing plane, and its spin.
pub(super) fn ball_exit(c: &Collision, fin: &FinalState) -> BallExit {
    let along = fin.ball_velocity + c.frame_velocity;
    match fin.tangential {
        Some(t) => BallExit {
            along,
            across: t.ball_vx,
            spin: t.ball_spin,
        },
        None => BallExit {
            along,
            across: 0.0,
            spin: 0.0,
        },
    }
}

/// Kinetic energies an oblique contact adds, J: the pitch's spin and motion across the
/// plane before; the ball's motion
/// across the plane and its spin after; the bat's rigid motion across the plane and its
/// roll after; and what sliding dissipated.
pub(super) struct ObliqueEnergies {
    pub(super) before: f64,
    pub(super) ball_after: f64,
    pub(super) bat_after: f64,
    pub(super) friction: f64,
}

pub(super) fn oblique_energies(c: &Collision, fin: &FinalState) -> Option<ObliqueEnergies> {
    let (o, t) = (c.oblique.as_ref()?, fin.tangential.as_ref()?);
    let inertia = o.ball.inertia;
    Some(ObliqueEnergies {
        before: 0.5 * inertia * o.spin * o.spin
            + 0.5 * c.ball_mass * o.across_speed * o.across_speed,
        ball_after: 0.5 * c.ball_mass * t.ball_vx * t.ball_vx
            + 0.5 * inertia * t.ball_spin * t.ball_spin,
        bat_after: 0.5 * o.cross_mass * t.bat_vx * t.bat_vx
            + 0.5 * o.roll_inertia * t.roll_rate * t.roll_rate,
        friction: t.slip_loss,
    })
}

/// The tangential COR, −(slip after)/(slip before), with the bat's rigid-body velocity at
/// the impact point after the collision (its vibration left out, as e_A leaves it out);
/// NaN head-on without spin, or without slip before.
pub(super) fn tangential_cor(c: &Collision, bat: &PreparedBat, fin: &FinalState) -> f64 {
    let (Some(o), Some(t)) = (c.oblique.as_ref(), fin.tangential.as_ref()) else {
        return f64::NAN;
    };
    let bat_before = c.omega * c.lever - c.frame_velocity;
    let before = o.slip_velocity((c.ball_speed - bat_before, o.across_speed), o.spin, 0.0);
    if before.abs() < 1e-12 {
        return f64::NAN;
    }
    -slip_after(c, bat, fin, o, t) / before
}

fn slip_after(
    c: &Collision,
    bat: &PreparedBat,
    fin: &FinalState,
    o: &Oblique,
    t: &Tangential,
) -> f64 {
    let mass = bat.beam.total_mass();
    let (momentum_before, angular_before) = (-mass * c.frame_velocity, c.omega * bat.inertia_cm);
    let bat_after = c.omega * c.lever - c.frame_velocity
        + (fin.bat_momentum - momentum_before) / mass
        + (fin.bat_angular_momentum - angular_before) * c.lever / bat.inertia_cm;
    let relative = (fin.ball_velocity - bat_after, t.ball_vx - t.bat_vx);
    o.slip_velocity(relative, t.ball_spin, t.roll_rate)
}
