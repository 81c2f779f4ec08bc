//! The motion of a bat state after (or during) a collision, as felt at the hands: the
//! free-vibration amplitude at a grip point, modal coordinates of nodal values, and the
//! rigid recoil of a grip point. Pure functions of a prepared bat and its state.

use crate::bat::PreparedBat;

/// Largest displacement the free (undamped) vibration reaches at `z_grip` after the ball has
/// left: `Σ_n |φ_n(z_grip)| A_n` over the flexible modes, `A_n = √(q_n² + (q̇_n/ω_n)²)`
/// (the bound is approached arbitrarily closely since the modes' frequencies are
/// incommensurate). `q`, `qd`: modal coordinates (mass-normalised shapes) of the first
/// `q.len()` modes of `bat`; rigid modes (ω = 0) are skipped. Metres.
pub fn grip_vibration_amplitude(bat: &PreparedBat, q: &[f64], qd: &[f64], z_grip: f64) -> f64 {
    let (k, a) = bat.beam.interpolation(z_grip);
    let shapes = &bat.modes.shapes;
    q.iter()
        .zip(qd)
        .zip(&bat.modes.omega)
        .enumerate()
        .filter(|(_, (_, &w))| w > 0.0)
        .map(|(j, ((&x, &xd), &w))| {
            let phi = (1.0 - a) * shapes[(k, j)] + a * shapes[(k + 1, j)];
            phi.abs() * (x * x + (xd / w).powi(2)).sqrt()
        })
        .sum()
}

/// Modal coordinates `q_n = Σ_i m_i φ_n,i y_i` of nodal values `y` (all modes).
pub fn modal_coordinates(bat: &PreparedBat, y: &[f64]) -> Vec<f64> {
    let beam = &bat.beam;
    (0..bat.modes.omega.len())
        .map(|j| {
            let col = bat.modes.shapes.column(j);
            (0..beam.len()).map(|i| beam.mass[i] * col[i] * y[i]).sum()
        })
        .collect()
}

/// Change of the rigid-body velocity of the point `z_grip` caused by the collision, m/s
/// (+ along the incoming ball): `ΔP/M + ΔL (z_grip − z_cm)/I_cm` from the bat's changes of
/// momentum ΔP and of angular momentum about the CM ΔL. Zero when the impact is at the
/// centre of percussion of `z_grip` (rigid bat).
pub fn grip_recoil_speed(
    momentum_change: f64,
    angular_momentum_change: f64,
    mass: f64,
    inertia_cm: f64,
    z_cm: f64,
    z_grip: f64,
) -> f64 {
    momentum_change / mass + angular_momentum_change * (z_grip - z_cm) / inertia_cm
}
