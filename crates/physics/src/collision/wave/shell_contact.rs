//! The barrel's breathing modes as one collision sees them: each mode's frequency and its
//! shape averaged over the ball's footprint at the impact point (`bat::shell`).
//!
//! Each mode is an oscillator q̈ + 2ζωq̇ + ω²q = φ F driven by the contact force F, in
//! parallel with the beam: the ball's side of the contact moves by the beam's displacement
//! plus the shell's under the footprint. Its effective mass at the contact is 1/φ² and its
//! spring ω²/φ², so a mode is the mass–spring hoop of the paper with the mass referred to
//! the impact point, except that the beam is pushed by the ball's force, not through the
//! hoop's spring: the wall's mass moves the beam once, as the beam's own.
//!
//! The footprint follows the contact: it grows from a point as the ball is compressed and
//! shrinks as it unloads, an ellipse whose semi-axes are those of the region where the
//! undeformed ball and barrel overlap, scaled by √`footprint_ratio` (Hertz's 0.5 by
//! default). φ is tabulated over the compression once per collision and read at each step.

use crate::ball::contact_law_on;
use crate::bat::PreparedBat;
use crate::error::ModelError;
use crate::spec::CollisionSpec;

/// The footprint's area over the undeformed bodies' overlap when `hoop.footprint_ratio` is
/// unset: Hertz's elastic contact, a² = R s, where the overlap has 2 R s (Johnson, "Contact
/// Mechanics", §4.2).
pub const HERTZ_FOOTPRINT_RATIO: f64 = 0.5;

/// Compressions the footprint's φ is tabulated at (evenly in √s, so evenly in its size).
const FOOTPRINT_ROWS: usize = 48;

/// The smallest compression the table reaches, m (a ball barely moving toward the bat).
const MIN_TOP_COMPRESSION: f64 = 1e-4;

/// How the ball's load spreads over the wall.
#[derive(Debug, Clone)]
pub enum Footprint {
    /// A patch of one radius throughout the contact (`hoop.patch_radius`).
    Fixed,
    /// The contact's own footprint: φ of every mode at compressions s_k = s_top (k/(K−1))²
    /// (rows of `table`), linear between rows in √s, the last row beyond s_top.
    Growing { s_top: f64, table: Vec<Vec<f64>> },
}

/// The shell's modes at one contact.
#[derive(Debug, Clone)]
pub struct ShellContact {
    /// Angular frequencies, rad/s.
    pub omega: Vec<f64>,
    /// Each mode's shape averaged over the footprint at the reference compression (the
    /// ball's largest on a rigid surface of this radius at this speed; the fixed patch's
    /// throughout), unit modal mass, 1/√kg.
    pub phi: Vec<f64>,
    /// How the footprint changes with the compression.
    pub footprint: Footprint,
    /// Each mode's damping ratio: the bat's material damping (`bat.material.quality_factor`)
    /// plus half the mode's loss factor from its wall's materials.
    pub zeta: Vec<f64>,
    /// The lowest breathing mode's frequency (the hoop frequency bats are ranked by), Hz,
    /// and its effective mass at this contact (at the reference compression), kg.
    pub frequency: f64,
    pub mass: f64,
    /// The static compliance the kept modes leave out at the reference footprint, m/N: the
    /// wave numbers' static response (`ShellModes::static_over_footprint`) less Σ φⱼ²/ωⱼ² of
    /// the kept modes. Their axial overtones lie far above the contact's frequency and
    /// answer quasi-statically, a spring in series with the kept modes (the
    /// mode-acceleration method, as the beam's dropped modes are treated).
    pub residual: f64,
    /// The footprint's size as the compression changes.
    pub size: FootprintSize,
}

/// The footprint's semi-axes as the compression changes: a fixed patch's radius, or the
/// growing contact's rule ([`footprint_axes`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FootprintSize {
    Patch(f64),
    Growing { ball: f64, barrel: f64, ratio: f64 },
}

impl FootprintSize {
    /// The semi-axes (along the bat, around it) at compression `s`, m.
    pub fn axes(&self, s: f64) -> (f64, f64) {
        match *self {
            FootprintSize::Patch(p) => (p, p),
            FootprintSize::Growing {
                ball,
                barrel,
                ratio,
            } => footprint_axes(s, ball, barrel, ratio),
        }
    }
}

impl ShellContact {
    /// φ of every mode at compression `s` (m) into `out`.
    pub fn phi_at(&self, s: f64, out: &mut [f64]) {
        match &self.footprint {
            Footprint::Fixed => out.copy_from_slice(&self.phi),
            Footprint::Growing { s_top, table } => {
                let x = (s.max(0.0) / s_top).sqrt() * (table.len() - 1) as f64;
                let k = (x.floor() as usize).min(table.len() - 2);
                let t = (x - k as f64).min(1.0);
                for (j, o) in out.iter_mut().enumerate() {
                    *o = table[k][j] + t * (table[k + 1][j] - table[k][j]);
                }
            }
        }
    }
}

/// The footprint's semi-axes (along the bat, around it), m, at compression `s` of a ball of
/// radius `ball` on a barrel of radius `barrel`: the overlap of the undeformed bodies has
/// a² = 2 R s along the bat (R the ball's radius; the barrel is straight there) and
/// 2 R′ s around it (1/R′ = 1/R_ball + 1/R_barrel), each area scaled by `ratio`.
pub fn footprint_axes(s: f64, ball: f64, barrel: f64, ratio: f64) -> (f64, f64) {
    let across = ball * barrel / (ball + barrel);
    let s = s.max(0.0);
    (
        (2.0 * ratio * ball * s).sqrt(),
        (2.0 * ratio * across * s).sqrt(),
    )
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
    let radius = bat.geometry.outer_radius(z);
    let n = modes.modes.len();
    // φ at the reference footprint, how the footprint changes, and the reference's axes
    let (phi, footprint, axes, size) = match hoop.patch_radius {
        Some(patch) => (
            (0..n)
                .map(|j| modes.over_patch(j, z, patch, radius))
                .collect(),
            Footprint::Fixed,
            (patch, patch),
            FootprintSize::Patch(patch),
        ),
        None => {
            let size = FootprintSize::Growing {
                ball: spec.ball_radius(),
                barrel: radius,
                ratio: hoop.footprint_ratio.unwrap_or(HERTZ_FOOTPRINT_RATIO),
            };
            let at = |s: f64| -> Vec<f64> {
                (0..n)
                    .map(|j| modes.over_footprint(j, z, size.axes(s), radius))
                    .collect()
            };
            let reference = reference_compression(spec, bat, radius);
            // beyond the rigid surface's compression, with room for a softer contact
            let s_top = (1.5 * reference).max(MIN_TOP_COMPRESSION);
            let rows = FOOTPRINT_ROWS;
            let table: Vec<Vec<f64>> = (0..rows)
                .map(|k| at(s_top * (k as f64 / (rows - 1) as f64).powi(2)))
                .collect();
            let axes = size.axes(reference);
            (
                at(reference),
                Footprint::Growing { s_top, table },
                axes,
                size,
            )
        }
    };
    let lowest = &modes.modes[0];
    let kept: f64 = modes
        .modes
        .iter()
        .zip(&phi)
        .map(|(m, p)| p * p / (m.omega * m.omega))
        .sum();
    let residual = (modes.static_over_footprint(z, axes, radius) - kept).max(0.0);
    Ok(Some(ShellContact {
        residual,
        omega: modes.modes.iter().map(|m| m.omega).collect(),
        zeta: modes
            .modes
            .iter()
            .map(|m| bat.damping_ratio + 0.5 * m.loss_factor)
            .collect(),
        frequency: lowest.omega / std::f64::consts::TAU,
        mass: 1.0 / (phi[0] * phi[0]),
        phi,
        footprint,
        size,
    }))
}

/// The ball's largest compression on a rigid surface of the barrel's radius at the
/// collision's normal approach speed, m: the footprint's reference size.
fn reference_compression(spec: &CollisionSpec, bat: &PreparedBat, radius: f64) -> f64 {
    let approach = super::step::approach_speed(spec, bat).abs();
    let law = contact_law_on(&spec.ball.law, approach, spec.ball_radius(), Some(radius));
    law.wall_compression(spec.ball.mass, approach)
}
