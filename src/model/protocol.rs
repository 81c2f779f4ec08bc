//! Constants of the certification protocols that the results refer to.

/// The NCAA/ASTM pivot and grip point: 6 in (0.1524 m) from the knob.
pub const KNOB6: f64 = 0.1524;
/// Protocol ball speed toward the stationary bat, m/s: 136 mph (NCAA BBCOR protocol;
/// 136 × 0.44704 = 60.80 m/s).
pub const BBCOR_BALL_SPEED: f64 = 136.0 * 0.44704;
