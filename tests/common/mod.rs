//! Shared helpers for the physics tests.
#![allow(dead_code)]

use batstudy::model::spec::*;

/// The base case: R161, default ball (linear hysteresis, e = 0.5, 40 m/s), free ends.
pub fn base_spec(z: f64) -> CollisionSpec {
    CollisionSpec::base_case(z)
}

pub fn elastic() -> BallLaw {
    BallLaw {
        kind: BallLawKind::Elastic,
        ..BallLaw::default()
    }
}
