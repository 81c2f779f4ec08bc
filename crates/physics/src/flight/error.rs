//! What can go wrong with a flight: an input outside its physical range, or a ball that
//! does not come down within the time bound.

use thiserror::Error;

/// A flight that cannot be computed. Each variant names the offending input and the range
/// it must lie in, so that a study can report exactly what to change.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum FlightError {
    /// An input that is NaN, infinite or outside its physical range. `name` is the field,
    /// e.g. `launch.speed_m_s` or `atmosphere.relative_humidity`.
    #[error("{name} = {value} is outside the allowed range {allowed}")]
    OutOfRange {
        name: &'static str,
        value: f64,
        allowed: &'static str,
    },
    /// The atmosphere's inputs give a negative air density (the vapour term exceeds the
    /// pressure: a near-vacuum pressure with humid air).
    #[error("the atmosphere gives a negative air density ({density} kg/m³): the water-vapour term exceeds the pressure")]
    NegativeDensity { density: f64 },
    /// The ball was still above the ground when the time bound ran out (e.g. an updraft
    /// wind stronger than the ball's terminal speed).
    #[error("the ball had not come down after {max_time_s} s (FlightOptions::max_time_s)")]
    NoLanding { max_time_s: f64 },
}

/// `value` if it is finite and inside `[lo, hi]`, else the error naming it.
pub(crate) fn check_range(
    name: &'static str,
    value: f64,
    lo: f64,
    hi: f64,
    allowed: &'static str,
) -> Result<f64, FlightError> {
    if value.is_finite() && value >= lo && value <= hi {
        Ok(value)
    } else {
        Err(FlightError::OutOfRange {
            name,
            value,
            allowed,
        })
    }
}
