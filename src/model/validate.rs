//! Physical checks of a spec without heavy work: every error names the field by its dotted
//! path and the allowed range.

use super::error::{out_of_range, ModelError};
use super::outcome::HistoryRequest;
use super::section::BatGeometry;
use super::spec::CollisionSpec;

/// Lowest and highest hoop frequency accepted, Hz.
pub const HOOP_FREQUENCY_RANGE: (f64, f64) = (1.0, 1.0e5);
/// Largest hoop mass, in ball masses.
pub const HOOP_MASS_MAX_BALL_MASSES: f64 = 10.0;

fn check(path: &str, v: f64, ok: bool, allowed: &str) -> Result<(), ModelError> {
    if ok && v.is_finite() {
        Ok(())
    } else {
        Err(out_of_range(path, v, allowed))
    }
}

/// Check a collision spec: positive quantities, 0 < cor ≤ 1, shell thinner than the radius
/// wherever it applies, impact inside the bat, hoop in a sane range, numerics sane.
pub fn validate_spec(spec: &CollisionSpec) -> Result<(), ModelError> {
    let geometry = BatGeometry::resolve(&spec.bat)?;
    let ball = &spec.ball;
    check(
        "ball.mass",
        ball.mass,
        ball.mass > 0.0,
        "a finite number > 0 kg",
    )?;
    check(
        "ball.speed",
        ball.speed,
        ball.speed > 0.0,
        "a finite number > 0 m/s",
    )?;
    let law = &ball.law;
    check(
        "ball.law.stiffness",
        law.stiffness,
        law.stiffness > 0.0,
        "a finite number > 0 N/m",
    )?;
    check(
        "ball.law.cor",
        law.cor,
        law.cor > 0.0 && law.cor <= 1.0,
        "(0, 1]",
    )?;
    check(
        "ball.law.k1",
        law.k1,
        law.k1 > 0.0,
        "a finite number > 0 N/m^α",
    )?;
    check(
        "ball.law.alpha",
        law.alpha,
        law.alpha > 0.0,
        "a finite number > 0",
    )?;
    check("swing.omega", spec.swing.omega, true, "finite rad/s")?;
    check("swing.cm_speed", spec.swing.cm_speed, true, "finite m/s")?;
    if let Some(hoop) = &spec.hoop {
        let (lo, hi) = HOOP_FREQUENCY_RANGE;
        check(
            "hoop.frequency",
            hoop.frequency,
            hoop.frequency >= lo && hoop.frequency <= hi,
            &format!("{lo} to {hi} Hz"),
        )?;
        let max_mass = HOOP_MASS_MAX_BALL_MASSES * ball.mass;
        check(
            "hoop.mass",
            hoop.mass,
            hoop.mass > 0.0 && hoop.mass < max_mass,
            &format!("> 0 and < {max_mass} kg (10 ball masses)"),
        )?;
    }
    let length = geometry.length;
    check(
        "impact.z",
        spec.impact.z,
        spec.impact.z >= 0.0 && spec.impact.z <= length,
        &format!("on the bat: 0 <= z <= {length} m"),
    )?;
    if let Some(n) = spec.numerics.segments {
        let (lo, hi) = (super::bat::MIN_SEGMENTS, super::bat::MAX_SEGMENTS);
        check(
            "numerics.segments",
            n as f64,
            (lo..=hi).contains(&n),
            &format!("[{lo}, {hi}]"),
        )?;
    }
    if let Some(dt) = spec.numerics.dt {
        check("numerics.dt", dt, dt > 0.0, "(0, stability limit] s")?;
    }
    Ok(())
}

/// Check a history request: positive interval, a bounded number of samples.
pub fn validate_history(request: &HistoryRequest) -> Result<(), ModelError> {
    check(
        "history.interval",
        request.interval,
        request.interval > 0.0,
        "a finite number > 0 s",
    )?;
    let duration = request.interval * request.n_samples as f64;
    check(
        "history duration",
        duration,
        duration <= super::wave::MAX_TIME,
        &format!("[0, {}] s", super::wave::MAX_TIME),
    )
}
