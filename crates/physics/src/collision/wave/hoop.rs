//! The hoop mode: a mass on a spring between the ball and the bat's impact point, given
//! or derived from the shell's geometry (the ring's n = 2 ovalling mode).

use crate::bat::PreparedBat;
use crate::error::ModelError;
use crate::spec::CollisionSpec;

/// The hoop mode: mass and spring constant.
#[derive(Debug, Clone, Copy)]
pub struct Hoop {
    /// Effective mass, kg.
    pub mass: f64,
    /// Spring constant, N/m.
    pub stiffness: f64,
}

impl Hoop {
    /// Frequency, Hz.
    pub fn frequency(&self) -> f64 {
        (self.stiffness / self.mass).sqrt() / (2.0 * std::f64::consts::PI)
    }
}

/// Circumferential wave number of the hoop mode derived from geometry (ovalling).
pub const HOOP_WAVE_NUMBER: f64 = 2.0;

/// The hoop mode of a collision: given, or derived from the shell at the impact point.
///
/// Geometry (Love/Rayleigh inextensional ring, Graff 1975 §4.x; Soedel, "Vibrations of
/// shells and plates", ring modes): a shell of wall h, mid-surface radius a, in the
/// n-th ovalling mode w = W cos nθ, v = −(W/n) sin nθ, has
/// ω² = Y h² / (12 ρ (1 − ν²) a⁴) · n²(n² − 1)²/(n² + 1) — the free ring per unit length
/// with the plate modulus Y/(1 − ν²). This is also the lowest mode of a cylinder with free
/// ends (Rayleigh's inextensional mode); a held or capped end only raises it. Its kinetic
/// energy ½ ρ h a ℓ Ẇ² π (1 + 1/n²) gives the mass referred to the radial displacement at
/// the impact point, m = (1 + 1/n²) π ρ h a ℓ, over an axial length ℓ (`hoop.length`).
pub fn resolve_hoop(spec: &CollisionSpec, bat: &PreparedBat) -> Result<Option<Hoop>, ModelError> {
    let Some(h) = &spec.hoop else {
        return Ok(None);
    };
    let two_pi = 2.0 * std::f64::consts::PI;
    if !h.from_geometry {
        let (Some(f), Some(m)) = (h.frequency, h.mass) else {
            return Err(ModelError::Unsupported(
                "hoop needs frequency and mass, or from_geometry: true",
            ));
        };
        return Ok(Some(Hoop {
            mass: m,
            stiffness: m * (two_pi * f).powi(2),
        }));
    }
    if h.frequency.is_some() || h.mass.is_some() {
        return Err(ModelError::Unsupported(
            "hoop.from_geometry derives frequency and mass: leave them unset",
        ));
    }
    let g = &bat.geometry;
    let z = spec.impact.z;
    let (outer, inner) = (g.outer_radius(z), g.inner_radius(z));
    let wall = outer - inner;
    if inner <= 0.0 {
        // a solid section: its ovalling mode is far above the contact's frequencies
        return Ok(None);
    }
    let a = outer - 0.5 * wall;
    let nu = g.poisson_ratio;
    let n = HOOP_WAVE_NUMBER;
    let n2 = n * n;
    let omega2 = g.youngs_modulus * wall * wall / (12.0 * g.density * (1.0 - nu * nu) * a.powi(4))
        * n2
        * (n2 - 1.0).powi(2)
        / (n2 + 1.0);
    let length = match h.length {
        Some(l) => l,
        None => default_hoop_length(a, wall, nu),
    };
    let mass = (1.0 + 1.0 / n2) * std::f64::consts::PI * g.density * wall * a * length;
    Ok(Some(Hoop {
        mass,
        stiffness: mass * omega2,
    }))
}

/// Default axial length of the hoop mode, m: twice the decay length of an n = 2 load on a
/// long shell in semi-membrane theory, a (12(1 − ν²))^¼ √(a/h) / (n √(n² − 1)) (an
/// order-of-magnitude estimate; the mass it gives is a modelling choice, stored with the
/// results as `hoop.length` may be swept).
pub fn default_hoop_length(a: f64, wall: f64, nu: f64) -> f64 {
    let n = HOOP_WAVE_NUMBER;
    2.0 * a * (12.0 * (1.0 - nu * nu)).powf(0.25) * (a / wall).sqrt() / (n * (n * n - 1.0).sqrt())
}
