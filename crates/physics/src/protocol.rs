//! The certification protocols the results refer to: their constants, and the formulas that
//! turn a collision of a bat at rest into the protocols' numbers.
//!
//! - **BBCOR** (NCAA, built on ASTM F2219): the bat at rest, pivoted 6 in from the knob, the
//!   ball fired at it; `BBCOR = e_A (1 + m/M_e) + m/M_e` with `M_e` the bat's effective mass at
//!   the impact point (derivation in `measures::metrics`). NCAA limit 0.50.
//! - **BESR** (NCAA until 2010): `BESR = e_A + 1/2` (Washington State University Sports
//!   Science Laboratory, "Bat performance measures"; Nathan, SABR Baseball Research Journal
//!   2003, "Ball exit speed ratio").
//! - **BPF** (bat performance factor, ASTM F1890 for softball bats): `BBCOR / ball COR`, the
//!   ball's COR on a rigid wall at the same speed; above 1 the bat gives back more than a
//!   rigid wall would (a trampoline effect).

/// The NCAA/ASTM pivot and grip point: 6 in (0.1524 m) from the knob.
pub const KNOB6: f64 = 0.1524;
/// Protocol ball speed toward the stationary bat, m/s: 136 mph (NCAA BBCOR protocol;
/// 136 × 0.44704 = 60.80 m/s).
pub const BBCOR_BALL_SPEED: f64 = 136.0 * 0.44704;

/// Moment of inertia about a point `pivot` on the axis, from the CM one (parallel axes).
pub fn moment_of_inertia_about(mass: f64, z_cm: f64, inertia_cm: f64, pivot: f64) -> f64 {
    inertia_cm + mass * (z_cm - pivot).powi(2)
}

/// Effective mass at `z` of a bat pivoted at `pivot`: `I_p/(z − z_p)²`.
pub fn pivoted_effective_mass(inertia_pivot: f64, pivot: f64, z: f64) -> f64 {
    inertia_pivot / (z - pivot).powi(2)
}

/// Effective mass at `z` of a free rigid bat: `1/(1/M + (z − z_cm)²/I_cm)`.
pub fn free_effective_mass(mass: f64, z_cm: f64, inertia_cm: f64, z: f64) -> f64 {
    1.0 / (1.0 / mass + (z - z_cm).powi(2) / inertia_cm)
}

/// The protocol's BBCOR from the collision efficiency e_A = v_r/v_i of a bat at rest:
/// `e_A (1 + m/M_e) + m/M_e`.
pub fn bbcor_from_efficiency(efficiency: f64, ball_mass: f64, effective_mass: f64) -> f64 {
    let r = ball_mass / effective_mass;
    efficiency * (1.0 + r) + r
}

/// Inverse of [`bbcor_from_efficiency`]: `e_A = (BBCOR − r)/(1 + r)`.
pub fn efficiency_from_bbcor(bbcor: f64, ball_mass: f64, effective_mass: f64) -> f64 {
    let r = ball_mass / effective_mass;
    (bbcor - r) / (1.0 + r)
}

/// BESR from the collision efficiency of a bat at rest: `e_A + 1/2`.
pub fn besr_from_efficiency(efficiency: f64) -> f64 {
    efficiency + 0.5
}
