//! Quantities written with a unit in a study file (`bat.length: 34in`, `ball.speed: 90mph`,
//! `swing.omega: -1200rpm`): each becomes its SI number before anything else reads the file.
//! The unit must be one of the field's (`model::units::units_of` its SI unit, which the
//! parameter table gives: docs/study-files.md, "Units"); a unit the field does not take is
//! refused with its position and the units it does.
//!
//! Which field a value belongs to is read from the keys above it: the longest run of them
//! (dotted keys split) that names a parameter with a unit, wherever it sits (`base`, a `grid`
//! axis and its `range`, a `points` set, a `sample` distribution), or the `path` beside it (an
//! `optimize` variable's bounds). Text that is no number with a known unit (a label such as
//! `2mm wall`) is left as it is.

#![allow(clippy::result_large_err)] // StudyError: see study/mod.rs

use super::error::StudyError;
use super::locate::Ctx;
use super::source::Seg;
use crate::model::units::{is_unit_suffix, split_quantity, suffixes, to_si, units_of};
use yaml_serde::Value;

/// Parameters whose values are lists of lengths (knots), with their SI unit; the others are
/// in the parameter table (`paths::meta`).
const LIST_UNITS: &[(&str, &str)] = &[
    ("bat.profile.knots", "m"),
    ("bat.shell.thickness_knots", "m"),
    ("bat.shell.layers.thickness", "m"),
    ("bat.shell.layers.angle", "rad"),
    ("optimize.profile.z", "m"),
    ("optimize.profile.radius", "m"),
    ("optimize.profile.thickness", "m"),
    ("optimize.profile.shape.rising", "m"),
];

/// Every value written with a unit, in SI; the first one refused, with its position.
pub(super) fn convert(cx: &Ctx, root: &mut Value) -> Result<(), StudyError> {
    walk(cx, root, &mut Vec::new(), None)
}

fn walk(
    cx: &Ctx,
    v: &mut Value,
    at: &mut Vec<Seg>,
    beside: Option<&str>,
) -> Result<(), StudyError> {
    match v {
        Value::Mapping(m) => {
            // an optimize variable or constraint names its parameter beside its bounds
            let path = m.get("path").and_then(Value::as_str).map(str::to_owned);
            for (k, child) in m.iter_mut() {
                let Some(key) = k.as_str() else { continue };
                at.push(Seg::Key(key.to_string()));
                walk(cx, child, at, path.as_deref().or(beside))?;
                at.pop();
            }
        }
        Value::Sequence(items) => {
            for (i, child) in items.iter_mut().enumerate() {
                at.push(Seg::Index(i));
                walk(cx, child, at, beside)?;
                at.pop();
            }
        }
        Value::Tagged(t) => walk(cx, &mut t.value, at, beside)?,
        Value::String(s) => {
            if let Some(x) = quantity(cx, s, at, beside)? {
                *v = Value::from(x);
            }
        }
        _ => {}
    }
    Ok(())
}

/// The SI value of text written with a unit at `at`, None when it is no such quantity.
fn quantity(
    cx: &Ctx,
    text: &str,
    at: &[Seg],
    beside: Option<&str>,
) -> Result<Option<f64>, StudyError> {
    let Some((_, suffix)) = split_quantity(text) else {
        return Ok(None);
    };
    let Some((path, si)) = parameter_at(at).or_else(|| beside.and_then(parameter_named)) else {
        return Ok(None);
    };
    if !is_unit_suffix(suffix) {
        return Ok(None); // not a unit at all: text (a label's words)
    }
    to_si(text, si).map(Some).map_err(|_| {
        let units = units_of(si);
        let allowed = match units.is_empty() {
            true => format!("a number in {si} (this field takes no unit suffix)"),
            false => format!(
                "a number in {si}, or with one of the units {}",
                suffixes(units)
            ),
        };
        cx.err(
            at,
            format!("`{suffix}` is not a unit of `{path}`, a quantity in {si}"),
        )
        .field(path)
        .value(text.to_string())
        .allowed(allowed)
    })
}

/// The parameter the keys of `at` name, and its SI unit: the longest run of keys (dotted
/// keys split, list positions skipped) that is a parameter with a unit.
fn parameter_at(at: &[Seg]) -> Option<(String, &'static str)> {
    let words: Vec<&str> = at
        .iter()
        .filter_map(|s| match s {
            Seg::Key(k) => Some(k.as_str()),
            Seg::Index(_) => None,
        })
        .flat_map(|k| k.split('.'))
        .collect();
    (1..=words.len()).rev().find_map(|len| {
        words
            .windows(len)
            .find_map(|w| parameter_named(&w.join(".")))
    })
}

/// A parameter's path and SI unit, if it is one with a unit.
fn parameter_named(path: &str) -> Option<(String, &'static str)> {
    let listed = LIST_UNITS.iter().find(|(p, _)| *p == path).map(|(_, u)| *u);
    let units = listed.unwrap_or_else(|| super::paths::meta(path).units);
    (!units.is_empty() && units != "1").then(|| (path.to_string(), units))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn keys(p: &[&str]) -> Vec<Seg> {
        p.iter().map(|k| Seg::Key(k.to_string())).collect()
    }

    #[test]
    fn the_field_is_found_wherever_the_value_sits() {
        let find = |p: &[&str]| parameter_at(&keys(p)).map(|(p, u)| (p, u.to_string()));
        let m = |p: &str| Some((p.to_string(), "m".to_string()));
        assert_eq!(find(&["base", "bat", "length"]), m("bat.length"));
        assert_eq!(find(&["grid", "impact.z", "range"]), m("impact.z"));
        assert_eq!(find(&["points", "sets", "bat.length"]), m("bat.length"));
        assert_eq!(
            find(&["base", "bat", "profile", "knots"]),
            m("bat.profile.knots")
        );
        assert_eq!(
            find(&["base", "ball", "speed"]),
            Some(("ball.speed".into(), "m/s".into()))
        );
        assert_eq!(find(&["name"]), None);
        assert_eq!(find(&["points", "sets", "label"]), None);
    }
}
