//! Physical checks of one resolved `CollisionSpec`, for error reports that point at the
//! study file. The checks themselves are the model's (`model::validate_spec`): one
//! definition of what is physically allowed.

use crate::model::section::BatGeometry;
use crate::model::spec::{BatSpec, CollisionSpec};
use crate::model::validate_spec;

/// One failed check: the dotted path, the value and what is allowed.
#[derive(Debug, Clone, PartialEq)]
pub struct Violation {
    pub path: String,
    pub value: String,
    pub allowed: String,
}

/// Length of the bat in m as the model will build it (profile, or `bat.length` when set);
/// NaN when the bat spec is invalid.
pub fn bat_length(bat: &BatSpec) -> f64 {
    BatGeometry::resolve(bat).map_or(f64::NAN, |g| g.length)
}

/// Check one resolved collision: the first violation, if any.
pub fn check_spec(spec: &CollisionSpec) -> Vec<Violation> {
    match validate_spec(spec) {
        Ok(()) => Vec::new(),
        Err(e) => {
            let (path, value, allowed) = e.field_value_allowed();
            vec![Violation {
                path,
                value,
                allowed,
            }]
        }
    }
}
