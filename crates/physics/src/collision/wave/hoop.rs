//! The hoop mode of the paper: a mass on a spring between the ball and the bat's impact
//! point, with its frequency and mass given.

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

/// The mass–spring hoop of a collision when it is given (`hoop: {frequency, mass}`, the
/// paper's model); a hoop from the geometry is the shell's modes (`shell_contact`).
pub fn resolve_hoop(spec: &CollisionSpec) -> Result<Option<Hoop>, ModelError> {
    let Some(h) = spec.hoop.as_ref().filter(|h| !h.from_geometry) else {
        return Ok(None);
    };
    let (Some(f), Some(m)) = (h.frequency, h.mass) else {
        return Err(ModelError::Unsupported(
            "hoop needs frequency and mass, or from_geometry: true",
        ));
    };
    Ok(Some(Hoop {
        mass: m,
        stiffness: m * (2.0 * std::f64::consts::PI * f).powi(2),
    }))
}
