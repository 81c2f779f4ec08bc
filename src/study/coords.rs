//! The coordinates of `points` and `zip` dims as a reader needs them:
//! - the value each point really ran with, where a set leaves a field to the base or a
//!   preset (`bat.material.density` of the `r161` base case is 649, not NaN);
//! - a record (e.g. `bat.grip: {kind: spring, z: 0.15, stiffness: 2e5}`) as one
//!   coordinate per field (`bat_grip_stiffness`), selectable by number;
//! - a text label per entry (`case_label`: `base`, `bat.preset=aluminum, hoop.frequency=300`).

use super::paths::{coord_name, meta};
use super::plan::{is_unset, value_text, DimOrigin, Plan};
use crate::model::resolved::{resolved_tree, resolved_value};
use crate::results::{Coord, CoordValues};
use serde_json::Value as Json;
use yaml_serde::Value;

pub use crate::results::LABEL_SUFFIX;

/// Fill in, flatten and label the coordinates of every `points` and `zip` dim of the plan.
/// Call once the plan resolves (every axis value was checked against the base).
pub(super) fn complete_coords(plan: &mut Plan) {
    let n_dims = plan.dims.len();
    for d in 0..n_dims {
        if matches!(plan.dims[d].origin, DimOrigin::Grid { .. }) {
            continue;
        }
        let size = plan.dims[d].size;
        // The resolved parameters of each entry, the other dims at their first and last
        // values: a value that differs between the two depends on another dim, and a 1-D
        // coordinate cannot show it (it stays NaN / empty there).
        let trees = |last: bool| -> Vec<Option<Json>> {
            (0..size)
                .map(|i| {
                    let m: Vec<usize> = (0..n_dims)
                        .map(|k| match (k == d, last) {
                            (true, _) => i,
                            (false, false) => 0,
                            (false, true) => plan.dims[k].size.saturating_sub(1),
                        })
                        .collect();
                    plan.resolve(&m).ok().map(|s| resolved_tree(&s))
                })
                .collect()
        };
        // When every other dim has one value, first and last are the same points.
        let others_vary = (0..n_dims).any(|k| k != d && plan.dims[k].size > 1);
        let first = trees(false);
        let last = if others_vary { trees(true) } else { Vec::new() };
        let resolved = |path: &str, i: usize| -> Option<Json> {
            let a = first[i].as_ref().and_then(|t| resolved_value(t, path));
            if !others_vary {
                return a;
            }
            let b = last[i].as_ref().and_then(|t| resolved_value(t, path));
            (a == b).then_some(a).flatten()
        };
        let params = plan.dims[d].params.clone();
        let mut coords: Vec<Coord> = Vec::new();
        for (k, (path, vals)) in params.iter().enumerate() {
            let mut c = plan.shape.dims[d].coords[k].clone();
            let records: Vec<&Value> = vals.iter().filter(|v| v.is_mapping()).collect();
            if records.is_empty() {
                fill_unset(&mut c, vals, |i| resolved(path, i));
                coords.push(c);
                continue;
            }
            // A record: keep its text, and add each of its fields as a coordinate.
            coords.push(c);
            for leaf in leaf_paths(&records) {
                let full = format!("{path}.{leaf}");
                let values: Vec<Option<Json>> = (0..size).map(|i| resolved(&full, i)).collect();
                coords.push(coord_of(&full, &values));
            }
        }
        let label_name = format!("{}{LABEL_SUFFIX}", plan.dims[d].name);
        if !coords.iter().any(|c| c.name == label_name) {
            coords.push(Coord {
                name: label_name,
                path: String::new(),
                units: String::new(),
                long_name: plan.dims[d].name.clone(),
                description: format!(
                    "what each {} sets (`base`: nothing, the base case)",
                    plan.dims[d].name
                ),
                values: CoordValues::Labels((0..size).map(|i| entry_label(&params, i)).collect()),
            });
        }
        plan.shape.dims[d].coords = coords;
    }
}

/// Where an entry left the parameter unset, the value it resolves to.
fn fill_unset(c: &mut Coord, vals: &[Value], resolved: impl Fn(usize) -> Option<Json>) {
    match &mut c.values {
        CoordValues::Numbers(x) => {
            for (i, xi) in x.iter_mut().enumerate() {
                if is_unset(&vals[i]) || xi.is_nan() {
                    if let Some(v) = resolved(i).and_then(|v| v.as_f64()) {
                        *xi = v;
                    }
                }
            }
        }
        CoordValues::Labels(s) => {
            for (i, si) in s.iter_mut().enumerate() {
                if si.is_empty() {
                    if let Some(v) = resolved(i) {
                        *si = json_text(&v);
                    }
                }
            }
        }
    }
}

/// Dotted paths of the scalar fields of these records (`kind`, `z`, `stiffness`), in first
/// appearance order.
fn leaf_paths(records: &[&Value]) -> Vec<String> {
    fn walk(v: &Value, prefix: &str, out: &mut Vec<String>) {
        if let Value::Mapping(m) = v {
            for (k, v) in m {
                let Some(k) = k.as_str() else { continue };
                let p = if prefix.is_empty() {
                    k.to_string()
                } else {
                    format!("{prefix}.{k}")
                };
                if v.is_mapping() {
                    walk(v, &p, out);
                } else if !out.contains(&p) {
                    out.push(p);
                }
            }
        }
    }
    let mut out = Vec::new();
    for r in records {
        walk(r, "", &mut out);
    }
    out
}

/// A coordinate of resolved values: numbers if every present value is a number, else text.
fn coord_of(path: &str, values: &[Option<Json>]) -> Coord {
    let m = meta(path);
    let numeric = values.iter().flatten().all(|v| v.is_number());
    let values = if numeric {
        CoordValues::Numbers(
            values
                .iter()
                .map(|v| v.as_ref().and_then(Json::as_f64).unwrap_or(f64::NAN))
                .collect(),
        )
    } else {
        CoordValues::Labels(
            values
                .iter()
                .map(|v| v.as_ref().map(json_text).unwrap_or_default())
                .collect(),
        )
    };
    Coord {
        name: coord_name(path),
        path: path.to_string(),
        units: if numeric {
            m.units.to_string()
        } else {
            String::new()
        },
        long_name: m.long_name,
        description: m.description,
        values,
    }
}

fn json_text(v: &Json) -> String {
    match v {
        Json::String(s) => s.clone(),
        _ => v.to_string(),
    }
}

/// A value as a label shows it: large and small numbers in exponent form (`1.4512e10`).
pub(crate) fn short_text(v: &Value) -> String {
    match v.as_f64() {
        Some(x) if x != 0.0 && !(1e-3..1e5).contains(&x.abs()) => format!("{x:e}"),
        Some(x) if v.is_f64() => format!("{x}"),
        _ => value_text(v),
    }
}

/// `path=value, …` of what entry `i` sets; `base` when it sets nothing.
fn entry_label(params: &[(String, Vec<Value>)], i: usize) -> String {
    let parts: Vec<String> = params
        .iter()
        .filter(|(_, vals)| !is_unset(&vals[i]))
        .map(|(p, vals)| format!("{p}={}", short_text(&vals[i])))
        .collect();
    if parts.is_empty() {
        "base".into()
    } else {
        parts.join(", ")
    }
}
