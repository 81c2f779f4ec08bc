//! The barrel's breathing modes as one collision sees them: each mode's frequency and its
//! shape averaged over the ball's contact patch at the impact point (`bat::shell`).
//!
//! Each mode is an oscillator q̈ + 2ζωq̇ + ω²q = φ F driven by the contact force F, in
//! parallel with the beam: the ball's side of the contact moves by the beam's displacement
//! plus Σ φ q. Its effective mass at the contact is 1/φ² and its spring ω²/φ², so a mode
//! is the mass–spring hoop of the paper with the mass referred to the impact point, except
//! that the beam is pushed by the ball's force, not through the hoop's spring: the wall's
//! mass moves the beam once, as the beam's own.

use crate::bat::PreparedBat;
use crate::error::ModelError;
use crate::spec::CollisionSpec;

/// Radius of the ball's contact patch on the barrel when `hoop.patch_radius` is unset, m:
/// a baseball (radius 3.7 cm) compressed by 1–1.5 cm, its compression at certification
/// speeds, touches a flat over a radius √(2Rs − s²) ≈ 2.6–3.1 cm and a 3.3 cm barrel over
/// less across the barrel; averaged over the contact's time, about 2 cm.
pub const DEFAULT_PATCH_RADIUS: f64 = 0.02;

/// The shell's modes at one contact.
#[derive(Debug, Clone)]
pub struct ShellContact {
    /// Angular frequencies, rad/s.
    pub omega: Vec<f64>,
    /// Each mode's shape averaged over the patch (unit modal mass), 1/√kg.
    pub phi: Vec<f64>,
    /// Modal damping ratio (the bat's material damping).
    pub zeta: f64,
    /// The lowest breathing mode's frequency (the hoop frequency bats are ranked by), Hz,
    /// and its effective mass at this contact, kg.
    pub frequency: f64,
    pub mass: f64,
}

/// The shell's modes at the impact point when the hoop comes from the geometry (`None`
/// otherwise, for a solid bat, or an impact on a solid part of the bat).
pub fn resolve_shell(
    spec: &CollisionSpec,
    bat: &PreparedBat,
) -> Result<Option<ShellContact>, ModelError> {
    let Some(hoop) = spec.hoop.as_ref().filter(|h| h.from_geometry) else {
        return Ok(None);
    };
    let Some(modes) = bat.shell_modes()? else {
        return Ok(None);
    };
    let z = spec.impact.z;
    if z < modes.nodes[0] || modes.modes.is_empty() {
        return Ok(None);
    }
    let patch = hoop.patch_radius.unwrap_or(DEFAULT_PATCH_RADIUS);
    let radius = bat.geometry.outer_radius(z);
    let phi: Vec<f64> = (0..modes.modes.len())
        .map(|j| modes.over_patch(j, z, patch, radius))
        .collect();
    let lowest = &modes.modes[0];
    Ok(Some(ShellContact {
        omega: modes.modes.iter().map(|m| m.omega).collect(),
        zeta: bat.damping_ratio,
        frequency: lowest.omega / std::f64::consts::TAU,
        mass: 1.0 / (phi[0] * phi[0]),
        phi,
    }))
}
