//! What the ball hits: a prepared bat, or a rigid target (the ball-certification wall,
//! `bat.preset: wall`, or the cylinder of the ball's dynamic-stiffness test). Prepared once per distinct bat, shared read-only by every point.

use crate::bat::{prepare_bat, PreparedBat};
use crate::error::ModelError;
use crate::outcome::BatProperties;
use crate::spec::{BatSpec, NumericsSpec};

/// A prepared target.
#[derive(Debug, Clone)]
pub enum Target {
    /// A bat: geometry, beam, modes, properties.
    Bat(Box<PreparedBat>),
    /// A rigid, immovable target: the wall, or the cylinder (whose curvature the ball's
    /// law reads from the spec's `bat.radius`).
    Wall,
}

impl Target {
    /// Prepare the target a bat spec names (a wall needs no preparation).
    pub fn prepare(bat: &BatSpec, numerics: &NumericsSpec) -> Result<Target, ModelError> {
        if bat.preset.is_rigid_target() {
            return Ok(Target::Wall);
        }
        prepare_bat(bat, numerics).map(|b| Target::Bat(Box::new(b)))
    }

    /// The bat's properties; a wall has none (every number NaN, no profile, no modes).
    pub fn properties(&self) -> BatProperties {
        match self {
            Target::Bat(b) => b.properties().clone(),
            Target::Wall => BatProperties {
                length: f64::NAN,
                mass: f64::NAN,
                z_cm: f64::NAN,
                moment_of_inertia: f64::NAN,
                moment_of_inertia_knob6: f64::NAN,
                ..BatProperties::default()
            },
        }
    }

    /// The prepared bat, if the target is one.
    pub fn bat(&self) -> Option<&PreparedBat> {
        match self {
            Target::Bat(b) => Some(b),
            Target::Wall => None,
        }
    }
}
