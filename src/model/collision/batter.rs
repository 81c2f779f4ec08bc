//! A swing that answers to the bat (`batter`): the bat turns about the batter's pivot with
//! Ω = Ω_ref (I_ref / I_pivot)^n (docs/physics.md, "The batter").

use crate::model::bat::PreparedBat;
use crate::model::error::ModelError;
use crate::model::protocol::moment_of_inertia_about;
use crate::model::spec::{BatterSpec, CollisionSpec};
use std::borrow::Cow;

/// The angular speed this batter swings `bat` with, rad/s (> 0).
pub fn swing_rate(batter: &BatterSpec, bat: &PreparedBat) -> f64 {
    let p = bat.properties();
    let inertia = moment_of_inertia_about(p.mass, p.z_cm, p.moment_of_inertia, batter.pivot);
    let reference_rate = batter.bat_speed / (batter.bat_speed_at - batter.pivot);
    reference_rate * (batter.reference_moi / inertia).powf(batter.exponent)
}

/// `spec` with the swing its batter gives this bat: the bat turns about the pivot, which is
/// at rest at contact, so in the frame of the bat's CM it turns at ω = −Ω (toward the
/// ball) while the CM moves at Ω (z_cm − pivot) toward the pitcher; the ball meets the CM
/// at the pitch speed plus that. Unchanged without a batter.
pub fn swung<'a>(
    spec: &'a CollisionSpec,
    bat: &PreparedBat,
) -> Result<Cow<'a, CollisionSpec>, ModelError> {
    let Some(batter) = &spec.batter else {
        return Ok(Cow::Borrowed(spec));
    };
    if spec.swing.omega != 0.0 || spec.swing.cm_speed != 0.0 {
        return Err(ModelError::Unsupported(
            "swing.omega or swing.cm_speed with a batter (the batter sets the swing)",
        ));
    }
    let rate = swing_rate(batter, bat);
    let cm_speed = rate * (bat.properties().z_cm - batter.pivot);
    let mut swung = spec.clone();
    swung.swing.omega = -rate;
    swung.swing.cm_speed = cm_speed;
    swung.ball.speed = batter.pitch_speed + cm_speed;
    Ok(Cow::Owned(swung))
}
