//! A swing that answers to the bat (`batter`): the bat turns about the batter's pivot with
//! Ω = Ω_ref (I_ref / I_pivot)^n (docs/physics.md, "The batter").

use crate::bat::PreparedBat;
use crate::collision::frame::pitch_components;
use crate::error::ModelError;
use crate::protocol::moment_of_inertia_about;
use crate::spec::{BatterSpec, CollisionSpec};
use std::borrow::Cow;

/// The angular speed this batter swings `bat` with, rad/s (> 0).
pub fn swing_rate(batter: &BatterSpec, bat: &PreparedBat) -> f64 {
    let p = bat.properties();
    let inertia = moment_of_inertia_about(p.mass, p.z_cm, p.moment_of_inertia, batter.pivot);
    let reference_rate = batter.bat_speed / (batter.bat_speed_at - batter.pivot);
    reference_rate * (batter.reference_moi / inertia).powf(batter.exponent)
}

/// A batter sets the swing: a spec that also sets `swing.omega` or `swing.cm_speed` says
/// two things at once.
pub fn swing_conflict(spec: &CollisionSpec) -> Option<ModelError> {
    spec.batter.as_ref()?;
    let allowed = "unset with a batter block (the batter's bat_speed and the bat's moment of inertia set the swing)";
    [
        ("swing.omega", spec.swing.omega),
        ("swing.cm_speed", spec.swing.cm_speed),
    ]
    .into_iter()
    .find(|&(_, v)| v != 0.0)
    .map(|(path, v)| crate::error::out_of_range(path, v, allowed))
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
    if let Some(e) = swing_conflict(spec) {
        return Err(e);
    }
    let rate = swing_rate(batter, bat);
    let cm_speed = rate * (bat.properties().z_cm - batter.pivot);
    let mut swung = spec.clone();
    swung.swing.omega = -rate;
    swung.swing.cm_speed = cm_speed;
    swung.ball.speed = pitch_along(spec)? + cm_speed;
    Ok(Cow::Owned(swung))
}

/// The pitch's speed along the bat's path toward the bat, m/s: the whole of
/// `batter.pitch_speed` on plane, the component of the `pitch` block's velocity otherwise
/// (exactly one of the two gives the pitch).
pub fn pitch_along(spec: &CollisionSpec) -> Result<f64, ModelError> {
    let given = spec.batter.as_ref().and_then(|b| b.pitch_speed);
    match (given, pitch_components(spec)) {
        (Some(speed), None) => Ok(speed),
        (None, Some(p)) => Ok(p.along),
        (Some(speed), Some(_)) => Err(crate::error::out_of_range(
            "batter.pitch_speed",
            speed,
            "unset with a pitch block (pitch.speed gives the pitch)",
        )),
        (None, None) => Err(crate::error::out_of_range(
            "batter.pitch_speed",
            f64::NAN,
            "a speed in m/s, required without a pitch block",
        )),
    }
}
