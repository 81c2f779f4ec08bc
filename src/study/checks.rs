//! Physical checks of one resolved `CollisionSpec`, for error reports that point at the
//! study file. The checks themselves are the model's (`model::validate_spec`): one
//! definition of what is physically allowed.

use crate::model::bat::section::BatGeometry;
use crate::model::plausible::check_plausible;
use crate::model::spec::{BatSpec, CollisionSpec};
use crate::model::validate_spec;

/// One failed check: the dotted path, the value and what is allowed.
#[derive(Debug, Clone, PartialEq)]
pub struct Violation {
    pub path: String,
    pub value: String,
    pub allowed: String,
    /// The model's own sentence, where "out of range" would not say enough.
    pub message: Option<String>,
}

/// Length of the bat in m as the model will build it (profile, or `bat.length` when set);
/// NaN when the bat spec is invalid.
pub fn bat_length(bat: &BatSpec) -> f64 {
    BatGeometry::resolve(bat).map_or(f64::NAN, |g| g.length)
}

/// For a bare number outside its plausible range that a trade's unit puts inside it (34 as
/// a bat's length): the suffix that says so (`; if 34 in is meant, write `34in``).
fn meant_in_trade_units(path: &str, value: &str) -> String {
    let (Some(r), Ok(x)) = (
        crate::model::plausible::range_of(path),
        value.parse::<f64>(),
    ) else {
        return String::new();
    };
    crate::model::units::meant_unit(x, r.unit, r.min, r.max)
        .map(|u| format!("; if {x} {} is meant, write `{x}{}`", u.suffix, u.suffix))
        .unwrap_or_default()
}

/// Check one resolved collision: the first violation, if any. The plausible ranges are
/// checked too unless the study allows implausible values.
pub fn check_spec(spec: &CollisionSpec, allow_implausible: bool) -> Vec<Violation> {
    let violation = |e: crate::model::ModelError, message: Option<String>| {
        let (path, value, allowed) = e.field_value_allowed();
        use crate::model::ModelError as E;
        // errors that name no single field say what is wrong in the model's own sentence
        let message = message.or_else(|| {
            matches!(
                e,
                E::StepBudget { .. } | E::Unsupported(_) | E::NoSeparation { .. }
            )
            .then(|| e.to_string())
        });
        vec![Violation {
            path,
            value,
            allowed,
            message,
        }]
    };
    if let Err(e) = validate_spec(spec) {
        return violation(e, None);
    }
    if !allow_implausible {
        if let Err(e) = check_plausible(spec) {
            let (path, value, _) = e.field_value_allowed();
            let message = format!(
                "`{path}` = {value} is outside its plausible range{}",
                meant_in_trade_units(&path, &value)
            );
            return violation(e, Some(message));
        }
    }
    Vec::new()
}
