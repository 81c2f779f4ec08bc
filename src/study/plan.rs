//! The expanded study: a lazy N-dimensional index space of points. `Plan::point(flat)`
//! builds one point on demand (memory does not grow with the number of points).

use super::checks::{check_spec, Violation};
use super::source::Seg;
use crate::model::spec::{BatSpec, CollisionSpec, NumericsSpec};
use crate::results::{Coord, CoordValues, Dim, PointId, ResultShape};
use sha2::{Digest, Sha256};
use std::collections::HashMap;
use yaml_serde::Value;

/// Where a dimension comes from in the study file.
#[derive(Debug, Clone, PartialEq)]
pub enum DimOrigin {
    /// A `grid` axis, by its key.
    Grid { key: String },
    /// The `zip` group with this index.
    Zip { group: usize },
    /// The `points` list.
    Points,
    /// The `sample` block: drawn values.
    Sample,
}

/// One dimension: its name and, per parameter path, one value per index.
#[derive(Debug, Clone, PartialEq)]
pub struct PlanDim {
    pub name: String,
    pub size: usize,
    pub params: Vec<(String, Vec<Value>)>,
    pub origin: DimOrigin,
}

/// One distinct bat of the study (bat + numerics), shared by many points.
#[derive(Debug, Clone, PartialEq)]
pub struct BatChoice {
    /// Canonical JSON of `{"bat": …, "numerics": …}`: the cache key of a prepared bat.
    pub key: String,
    /// Short label, e.g. `r161` or `r161, bat.material.density=700`.
    pub label: String,
    pub bat: BatSpec,
    pub numerics: NumericsSpec,
    /// What the BBCOR protocol fires at it: the ball and hoop of the first point that uses it.
    pub shot: crate::model::measures::metrics::BbcorShot,
}

/// One point of the study.
#[derive(Debug, Clone, PartialEq)]
pub struct Point {
    /// Flat (row-major) index in the result shape.
    pub index: usize,
    /// Stable id: first 8 bytes (big-endian) of SHA-256 of the canonical JSON of `spec`.
    pub id: PointId,
    /// The fully resolved collision.
    pub spec: CollisionSpec,
    /// Index of the point's bat in `Plan::bats()`.
    pub bat: u32,
    /// Whether the study records this point's time histories (`history.only`).
    pub record_history: bool,
}

impl Point {
    /// Canonical JSON of the point's bat + numerics (equals `Plan::bats()[bat].key`).
    pub fn bat_key(&self) -> String {
        bat_key(&self.spec.bat, &self.spec.numerics)
    }
}

/// A point that could not be resolved (only possible for combinations the loader did not
/// check: plans larger than `FULL_CHECK_LIMIT`).
#[derive(Debug, Clone, PartialEq)]
pub struct PointError {
    pub index: usize,
    /// Hash of the unresolved parameters.
    pub id: PointId,
    pub message: String,
}

/// Why a combination of parameters does not make a valid collision.
#[derive(Debug, Clone, PartialEq)]
pub enum ResolveError {
    /// The value tree does not deserialize (`path` dotted, may be empty).
    Shape {
        path: String,
        message: String,
        value: Option<String>,
    },
    /// A physical check failed.
    Check(Violation),
    /// A profile CSV that was not loaded.
    Profile { file: String },
}

impl std::fmt::Display for ResolveError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ResolveError::Shape { path, message, .. } if path.is_empty() => write!(f, "{message}"),
            ResolveError::Shape { path, message, .. } => write!(f, "{path}: {message}"),
            ResolveError::Check(v) => write!(f, "{} = {}: allowed {}", v.path, v.value, v.allowed),
            ResolveError::Profile { file } => write!(f, "profile file `{file}` was not loaded"),
        }
    }
}

/// The lazy plan.
#[derive(Debug, Clone)]
pub struct Plan {
    pub(crate) base: Value,
    /// `history.only`: record histories only where every listed path takes a listed value.
    pub(crate) history_only: Vec<(String, Vec<Value>)>,
    /// The study's `allow_implausible`: skip the plausible ranges.
    pub(crate) allow_implausible: bool,
    /// How many points record a history, when the plan was small enough to count them.
    pub(crate) history_count: Option<usize>,
    pub(crate) dims: Vec<PlanDim>,
    pub(crate) shape: ResultShape,
    /// Profile CSV paths as written → knots.
    pub(crate) profiles: HashMap<String, super::profile::ProfileTable>,
    pub(crate) bat_dims: Vec<usize>,
    pub(crate) bat_of_combo: Vec<u32>,
    pub(crate) bats: Vec<BatChoice>,
}

/// Canonical JSON of bat + numerics.
pub fn bat_key(bat: &BatSpec, numerics: &NumericsSpec) -> String {
    serde_json::json!({ "bat": bat, "numerics": numerics }).to_string()
}

/// The id of a resolved collision: SHA-256 of its canonical JSON (struct field order,
/// shortest round-trip floats), first 8 bytes big-endian. Key order in the YAML and the
/// way a value was written (`0.7` vs `7e-1`) do not matter.
pub fn point_id(spec: &CollisionSpec) -> PointId {
    hash_str(&serde_json::to_string(spec).expect("spec serializes"))
}

fn hash_str(s: &str) -> PointId {
    let d = Sha256::digest(s.as_bytes());
    u64::from_be_bytes(d[..8].try_into().unwrap())
}

/// The first number in `v` that is not finite, with `at` left as its path (`at` as given
/// when there is none).
pub(crate) fn first_non_finite(v: &Value, at: &mut Vec<Seg>) -> Option<f64> {
    let inside = |seg: Seg, x: &Value, at: &mut Vec<Seg>| {
        at.push(seg);
        let found = first_non_finite(x, at);
        if found.is_none() {
            at.pop();
        }
        found
    };
    match v {
        Value::Number(n) => n.as_f64().filter(|x| !x.is_finite()),
        Value::Sequence(items) => {
            (items.iter().enumerate()).find_map(|(i, x)| inside(Seg::Index(i), x, at))
        }
        Value::Mapping(m) => m
            .iter()
            .find_map(|(k, x)| inside(Seg::Key(value_text(k)), x, at)),
        Value::Tagged(t) => first_non_finite(&t.value, at),
        _ => None,
    }
}

/// Path touches path: equal, or one inside the other.
pub(crate) fn related(a: &str, b: &str) -> bool {
    a.is_empty()
        || b.is_empty()
        || a == b
        || a.starts_with(&format!("{b}."))
        || b.starts_with(&format!("{a}."))
}

pub(crate) fn is_bat_path(p: &str) -> bool {
    related(p, "bat") && !p.is_empty() || related(p, "numerics") && !p.is_empty()
}

/// Equal parameter values: numbers within 1e-9 relative (a value typed as `0.6` matches a
/// grid value computed as 0.4 + 20·0.01), anything else exactly.
pub(crate) fn same_value(a: &Value, b: &Value) -> bool {
    match (a.as_f64(), b.as_f64()) {
        (Some(x), Some(y)) => (x - y).abs() <= 1e-9 * x.abs().max(y.abs()).max(1e-300),
        _ => a == b,
    }
}

/// A value as short text (flow YAML-ish JSON).
/// The value a `points` set gives a parameter it leaves out: "keep the base value".
pub fn unset() -> Value {
    Value::Tagged(Box::new(yaml_serde::value::TaggedValue {
        tag: yaml_serde::value::Tag::new("unset"),
        value: Value::Null,
    }))
}

/// Is this the `unset` marker?
pub fn is_unset(v: &Value) -> bool {
    matches!(v, Value::Tagged(t) if t.tag == "unset")
}

pub fn value_text(v: &Value) -> String {
    match v {
        Value::String(s) => s.clone(),
        Value::Number(n) => n.to_string(),
        _ => serde_json::to_string(v).unwrap_or_else(|_| format!("{v:?}")),
    }
}

impl Plan {
    pub fn n_points(&self) -> usize {
        self.shape.n_points()
    }
    pub fn shape(&self) -> &ResultShape {
        &self.shape
    }
    pub fn dims(&self) -> &[PlanDim] {
        &self.dims
    }
    /// The distinct bats, in order of first appearance (row-major over the bat dimensions).
    pub fn bats(&self) -> &[BatChoice] {
        &self.bats
    }
    /// How many points record a history (None: not counted, the plan is large).
    pub fn history_count(&self) -> Option<usize> {
        self.history_count
    }
    /// The base parameters (after `model` was copied in), as a YAML tree.
    pub fn base(&self) -> &Value {
        &self.base
    }

    /// The parameter tree of the point at this multi-index.
    pub fn value_at(&self, multi: &[usize]) -> Value {
        self.value_over(&self.base, multi)
    }

    /// The resolved collision at this multi-index over another base: an optimiser's
    /// candidate design with the study's dimensions.
    pub fn resolve_over(
        &self,
        base: &Value,
        multi: &[usize],
    ) -> Result<CollisionSpec, ResolveError> {
        let mut v = self.value_over(base, multi);
        self.resolve_value(&mut v)
    }

    fn value_over(&self, base: &Value, multi: &[usize]) -> Value {
        let mut v = base.clone();
        for (d, &i) in self.dims.iter().zip(multi) {
            for (path, vals) in &d.params {
                if is_unset(&vals[i]) {
                    continue;
                }
                // Paths were checked at load time.
                let _ = super::paths::set_path(&mut v, path, vals[i].clone());
            }
        }
        v
    }

    /// The resolved collision at this multi-index (deserialized and checked).
    pub fn resolve(&self, multi: &[usize]) -> Result<CollisionSpec, ResolveError> {
        let mut v = self.value_at(multi);
        self.resolve_value(&mut v)
    }

    pub(crate) fn resolve_value(&self, v: &mut Value) -> Result<CollisionSpec, ResolveError> {
        if let Some(Value::String(file)) = super::paths::get_path(v, "bat.profile.csv") {
            let table = self
                .profiles
                .get(file)
                .ok_or_else(|| ResolveError::Profile { file: file.clone() })?
                .clone();
            let _ = super::paths::set_path(v, "bat.profile.knots", knots_value(&table.knots));
            if let Some((from, wall)) = &table.wall {
                wall_from_profile(v, *from, wall)?;
            }
        }
        // A number that is not finite would become `null` on its way through JSON, and
        // `null` means "the preset's value": a drawn or searched value of inf would run
        // silently at the preset's. The study text is checked on load; this holds for
        // every value a block, a sample or a search puts in.
        let mut at = Vec::new();
        if let Some(x) = first_non_finite(v, &mut at) {
            return Err(ResolveError::Shape {
                value: Some(x.to_string()),
                path: super::source::seg_path(&at),
                message: "not a finite number (NaN and infinities are refused)".into(),
            });
        }
        // Through JSON: yaml_serde's Value reads enums only from YAML tags, while a
        // study writes `profile: {knots: …}`.
        let json = serde_json::to_value(&*v).map_err(|e| ResolveError::Shape {
            path: String::new(),
            message: e.to_string(),
            value: None,
        })?;
        let spec = serde_path_to_error::deserialize::<_, CollisionSpec>(json)
            .map_err(|e| {
                let path = path_string(e.path());
                let value = super::paths::get_path(v, &path).map(value_text);
                ResolveError::Shape {
                    path,
                    message: e.into_inner().to_string(),
                    value,
                }
            })?
            .with_preset_hoop();
        if let Some(first) = check_spec(&spec, self.allow_implausible).into_iter().next() {
            return Err(ResolveError::Check(first));
        }
        Ok(spec)
    }

    /// Index of the bat of the point at this multi-index.
    pub fn bat_index(&self, multi: &[usize]) -> u32 {
        let mut combo = 0usize;
        for &d in &self.bat_dims {
            combo = combo * self.dims[d].size + multi[d];
        }
        self.bat_of_combo[combo]
    }

    /// The point with flat index `flat` (row-major, last dimension fastest).
    pub fn point(&self, flat: usize) -> Result<Point, PointError> {
        assert!(flat < self.n_points(), "point index {flat} out of range");
        let multi = self.shape.unravel(flat);
        let mut v = self.value_at(&multi);
        match self.resolve_value(&mut v) {
            Ok(spec) => Ok(Point {
                index: flat,
                id: point_id(&spec),
                record_history: self.records_history(&spec),
                spec,
                bat: self.bat_index(&multi),
            }),
            Err(e) => Err(PointError {
                index: flat,
                id: hash_str(&serde_json::to_string(&v).unwrap_or_default()),
                message: e.to_string(),
            }),
        }
    }

    /// Does `history.only` select this collision?
    pub fn records_history(&self, spec: &CollisionSpec) -> bool {
        if self.history_only.is_empty() {
            return true;
        }
        let Ok(tree) = yaml_serde::to_value(spec) else {
            return false;
        };
        self.history_only.iter().all(|(path, wanted)| {
            super::paths::get_path(&tree, path)
                .is_some_and(|have| wanted.iter().any(|w| same_value(have, w)))
        })
    }

    /// A short description of the point's coordinates, e.g. `impact_z=0.7, swing_omega=-30`.
    pub fn describe(&self, flat: usize) -> String {
        let multi = self.shape.unravel(flat);
        let mut parts = Vec::new();
        for (d, &i) in self.dims.iter().zip(&multi) {
            for (path, vals) in d.params.iter().filter(|(_, vals)| !is_unset(&vals[i])) {
                parts.push(format!("{path}={}", value_text(&vals[i])));
            }
        }
        parts.join(", ")
    }
}

/// Dotted text of a serde_path_to_error path (`""` for the root).
pub(crate) fn path_string(p: &serde_path_to_error::Path) -> String {
    use serde_path_to_error::Segment;
    let mut s = String::new();
    for seg in p.iter() {
        match seg {
            Segment::Seq { index } => s.push_str(&format!("[{index}]")),
            Segment::Map { key } | Segment::Enum { variant: key } => {
                if !s.is_empty() {
                    s.push('.');
                }
                s.push_str(key);
            }
            Segment::Unknown => {}
        }
    }
    s
}

/// Build the shape's coordinate variables of a dimension.
/// A `points` set's `unset` value shows the base value, or NaN / "" where the base has none.
pub(crate) fn dim_to_shape(d: &PlanDim, base: &Value) -> Dim {
    let coords = d
        .params
        .iter()
        .map(|(path, vals)| {
            let base_value = super::paths::get_path(base, path).cloned();
            let vals: Vec<Value> = vals
                .iter()
                .map(|v| match (is_unset(v), &base_value) {
                    (false, _) => v.clone(),
                    (true, Some(b)) => b.clone(),
                    (true, None) => Value::Null,
                })
                .collect();
            let numeric = vals.iter().all(|v| v.is_null() || v.as_f64().is_some())
                && vals.iter().any(|v| v.as_f64().is_some());
            let nums: Option<Vec<f64>> = numeric.then(|| {
                vals.iter()
                    .map(|v| v.as_f64().unwrap_or(f64::NAN))
                    .collect()
            });
            let values = match nums {
                Some(n) => CoordValues::Numbers(n),
                None => CoordValues::Labels(
                    vals.iter()
                        .map(|v| {
                            if v.is_null() {
                                String::new()
                            } else {
                                value_text(v)
                            }
                        })
                        .collect(),
                ),
            };
            let meta = super::paths::meta(path);
            let units = if matches!(values, CoordValues::Labels(_)) {
                ""
            } else {
                meta.units
            };
            Coord {
                name: if matches!(d.origin, DimOrigin::Grid { .. }) {
                    d.name.clone()
                } else {
                    super::paths::coord_name(path)
                },
                path: path.clone(),
                units: units.to_string(),
                long_name: meta.long_name,
                description: meta.description,
                values,
            }
        })
        .collect();
    Dim {
        name: d.name.clone(),
        size: d.size,
        coords,
    }
}

/// `[[a, b], ...]` as a YAML value.
fn knots_value(knots: &[[f64; 2]]) -> Value {
    Value::Sequence(
        knots
            .iter()
            .map(|[a, b]| Value::Sequence(vec![Value::from(*a), Value::from(*b)]))
            .collect(),
    )
}

/// A profile CSV's wall column as the shell (`bat.shell.from` and `.thickness_knots`),
/// refused where the study gives the wall too: one wall, from one place.
fn wall_from_profile(v: &mut Value, from: f64, wall: &[[f64; 2]]) -> Result<(), ResolveError> {
    for path in [
        "bat.shell.thickness",
        "bat.shell.thickness_knots",
        "bat.shell.from",
        "bat.bore",
    ] {
        if super::paths::get_path(v, path).is_some_and(|x| !x.is_null()) {
            return Err(ResolveError::Shape {
                path: path.into(),
                message: "the profile CSV's wall column gives the hollow part already (set one or the other)".into(),
                value: None,
            });
        }
    }
    let _ = super::paths::set_path(v, "bat.shell.from", Value::from(from));
    let _ = super::paths::set_path(v, "bat.shell.thickness_knots", knots_value(wall));
    Ok(())
}
