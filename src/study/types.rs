//! The study file as written: serde + schemars types. `batstudy schema` prints the JSON
//! Schema generated from these types (committed as `schemas/study.schema.json`).

use crate::model::outcome::{
    HistoryCompression, HistoryDisplacement, HistoryField, HistoryPrecision,
};
use crate::model::spec::{CollisionSpec, ModelKind};
use indexmap::IndexMap;
use schemars::{JsonSchema, Schema, SchemaGenerator};
use serde::Deserialize;
use std::borrow::Cow;
use yaml_serde::Value;

/// A parameter study: a base collision and the parameters varied around it.
///
/// How the blocks combine: every block is one or more dimensions of ONE Cartesian
/// product, in this order: each `grid` axis (in file order) is a dimension named by its
/// path with `.` → `_` (`impact.z` → `impact_z`); each `zip` group is one dimension whose
/// parameters vary together (one coordinate per parameter); the `points` list is one
/// dimension. The zip/points dimensions are named `point` when there is only one of them,
/// else `point`, `point_2`, `point_3`, … in order, unless a zip group sets `name`.
/// The number of points is the product of all dimension sizes; the flat index of a
/// point is row-major (the last dimension varies fastest). A parameter path may be set
/// by only one block.
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(title = "batstudy study file")]
pub struct StudyFile {
    /// Short name (letters, digits, `_`, `-`, `.`); names the default output
    /// `results/<name>.h5`.
    pub name: String,
    /// Free text, stored with the results.
    #[serde(default)]
    pub description: String,
    /// Collision model for every point (`wave` or `rigid`); copied into `base.model`.
    /// Default: `base.model`, else `wave`.
    #[serde(default)]
    pub model: Option<ModelKind>,
    /// Every parameter of one collision (see the `CollisionSpec` fields). Fields that a
    /// `grid`, `zip` or `points` block sets may be left out here (e.g. `impact`).
    #[schemars(schema_with = "base_schema")]
    pub base: Value,
    /// Axes of the Cartesian product: dotted parameter path → values.
    #[serde(default)]
    pub grid: IndexMap<String, AxisValues>,
    /// Groups of parameters varied together: each group is one dimension; all its lists
    /// have the same length.
    #[serde(default)]
    pub zip: Vec<ZipGroup>,
    /// An explicit list of parameter sets; one dimension. Either a plain list of sets, or
    /// `{name: DIM, sets: [...]}` to name the dimension. Each set is a map dotted path →
    /// value and sets only what differs from `base` (`{}` is the base itself); a parameter
    /// a set leaves out keeps its base value.
    #[serde(default)]
    pub points: Option<PointsBlock>,
    /// Parameters drawn from distributions (normal, lognormal, uniform; correlated pairs)
    /// on a seeded quasi-random (Sobol) design: one dimension, default name `sample`, whose
    /// coordinates are the drawn values. It comes after every other block's dimensions.
    #[serde(default)]
    pub sample: Option<super::sample::SampleBlock>,
    /// Search a design (`batstudy optimize`): design variables with bounds, an objective
    /// over the study's other dimensions, constraints and rule sets. `batstudy run` runs
    /// the study at its base design and ignores this block.
    #[serde(default)]
    pub optimize: Option<super::optimize_block::OptimizeBlock>,
    /// Time histories to store. Default: summaries only.
    #[serde(default)]
    pub history: Option<HistorySpec>,
    /// Output file. A relative path is relative to the current working directory (as
    /// `-o` is). Default `results/<name>.h5`.
    #[serde(default)]
    pub output: Option<String>,
    /// A what-if study: accept values outside the plausible ranges (docs/study-files.md,
    /// "Plausible ranges"). Recorded in the results file's root attribute
    /// `allow_implausible`. Default false.
    #[serde(default)]
    pub allow_implausible: bool,
}

fn base_schema(gen: &mut SchemaGenerator) -> Schema {
    let mut s = CollisionSpec::json_schema(gen);
    if let Some(obj) = s.as_object_mut() {
        obj.remove("required");
        obj.insert(
            "description".into(),
            "Every parameter of one collision. Fields set by grid/zip/points may be left out."
                .into(),
        );
    }
    s
}

/// The `points` block: a plain list of parameter sets, or a named one.
#[derive(Debug, Clone, PartialEq, Deserialize, JsonSchema)]
#[serde(untagged)]
pub enum PointsBlock {
    /// `[{path: value, …}, …]`: the dimension is named `point` (or `point_N`).
    List(
        #[schemars(with = "Vec<IndexMap<String, serde_json::Value>>")] Vec<IndexMap<String, Value>>,
    ),
    /// `{name: case, sets: [{path: value, …}, …]}`.
    Named(NamedPoints),
}

/// A named `points` block.
#[derive(Debug, Clone, PartialEq, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct NamedPoints {
    /// Dimension name (letters, digits, `_`).
    pub name: String,
    /// The parameter sets.
    #[schemars(with = "Vec<IndexMap<String, serde_json::Value>>")]
    pub sets: Vec<IndexMap<String, Value>>,
}

impl PointsBlock {
    /// The dimension name the file gives, if any.
    pub fn name(&self) -> Option<&String> {
        match self {
            PointsBlock::List(_) => None,
            PointsBlock::Named(n) => Some(&n.name),
        }
    }
    /// The parameter sets.
    pub fn sets(&self) -> &[IndexMap<String, Value>] {
        match self {
            PointsBlock::List(s) => s,
            PointsBlock::Named(n) => &n.sets,
        }
    }
    /// Where the sets are in the file (for error positions).
    pub fn sets_key(&self) -> Vec<&'static str> {
        match self {
            PointsBlock::List(_) => vec!["points"],
            PointsBlock::Named(_) => vec!["points", "sets"],
        }
    }
}

/// Values of one grid axis.
#[derive(Debug, Clone, PartialEq)]
pub enum AxisValues {
    /// An explicit list (numbers, or labels for categorical parameters such as `bat.preset`).
    List(Vec<Value>),
    /// `n` evenly spaced values from `start` to `stop`, both included.
    Linspace { start: f64, stop: f64, n: usize },
    /// `start, start + step, …` up to `stop` (included when it lies on the grid), each
    /// value computed as start + k·step (no accumulated rounding).
    Range { start: f64, stop: f64, step: f64 },
}

#[allow(dead_code)]
#[derive(JsonSchema)]
#[serde(untagged)]
enum AxisValuesRepr {
    /// An explicit list of values.
    List(Vec<serde_json::Value>),
    /// `{linspace: [start, stop, n]}`: n evenly spaced values, both ends included.
    Linspace {
        #[schemars(length(equal = 3))]
        linspace: Vec<f64>,
    },
    /// `{range: [start, stop, step]}`: start + k·step up to stop (included when on the grid).
    Range {
        #[schemars(length(equal = 3))]
        range: Vec<f64>,
    },
}

impl JsonSchema for AxisValues {
    fn schema_name() -> Cow<'static, str> {
        "AxisValues".into()
    }
    fn json_schema(gen: &mut SchemaGenerator) -> Schema {
        AxisValuesRepr::json_schema(gen)
    }
}

impl<'de> Deserialize<'de> for AxisValues {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let v = Value::deserialize(d)?;
        AxisValues::from_value(&v).map_err(serde::de::Error::custom)
    }
}

/// Most values one axis may have (the default limit of a whole study's points): a typo
/// such as `{linspace: [0, 1, 1e12]}` is refused before anything is allocated.
pub const MAX_AXIS_VALUES: usize = 10_000_000;

const AXIS_FORMS: &str =
    "a list of values, {linspace: [start, stop, n]} or {range: [start, stop, step]}";

impl AxisValues {
    fn from_value(v: &Value) -> Result<Self, String> {
        match v {
            Value::Sequence(s) => Ok(AxisValues::List(s.clone())),
            Value::Mapping(m) if m.len() == 1 => {
                let (k, args) = m.iter().next().unwrap();
                let kind = k.as_str().unwrap_or("");
                let nums: Option<Vec<f64>> = args
                    .as_sequence()
                    .map(|s| s.iter().map(|x| x.as_f64()).collect())
                    .unwrap_or(None);
                let nums = match nums {
                    Some(n) if n.len() == 3 => n,
                    _ if kind == "linspace" || kind == "range" => {
                        return Err(format!(
                            "`{kind}` takes three numbers [start, stop, {}]",
                            if kind == "range" { "step" } else { "n" }
                        ))
                    }
                    _ => return Err(format!("unknown axis form `{kind}`; expected {AXIS_FORMS}")),
                };
                if kind == "linspace" {
                    let n = nums[2];
                    if !(1.0..=MAX_AXIS_VALUES as f64).contains(&n) || n.fract() != 0.0 {
                        return Err(format!(
                            "linspace count n must be a whole number from 1 to {MAX_AXIS_VALUES}, got {n}"
                        ));
                    }
                    Ok(AxisValues::Linspace {
                        start: nums[0],
                        stop: nums[1],
                        n: n as usize,
                    })
                } else {
                    Ok(AxisValues::Range {
                        start: nums[0],
                        stop: nums[1],
                        step: nums[2],
                    })
                }
            }
            _ => Err(format!("expected {AXIS_FORMS}")),
        }
    }

    /// The axis's values, in order.
    pub fn values(&self) -> Result<Vec<Value>, String> {
        Ok(match self {
            AxisValues::List(v) => {
                if v.is_empty() {
                    return Err("an axis needs at least one value".into());
                }
                v.clone()
            }
            AxisValues::Linspace { start, stop, n } => linspace(*start, *stop, *n)
                .into_iter()
                .map(Value::from)
                .collect(),
            AxisValues::Range { start, stop, step } => range(*start, *stop, *step)?
                .into_iter()
                .map(Value::from)
                .collect(),
        })
    }
}

/// Decimal places of the shortest representation of `x` (None if more than 15 or
/// written with an exponent).
fn decimals(x: f64) -> Option<i32> {
    let s = format!("{x}");
    if s.contains('e') {
        return None;
    }
    let d = s.split_once('.').map(|(_, f)| f.len() as i32).unwrap_or(0);
    (d <= 15).then_some(d)
}

/// `n` values from `start` to `stop`, both ends exact.
pub fn linspace(start: f64, stop: f64, n: usize) -> Vec<f64> {
    if n == 1 {
        return vec![start];
    }
    let m = (n - 1) as f64;
    // Decimal inputs with a decimal step give the same doubles as typing the values.
    if let (Some(a), Some(b)) = (decimals(start), decimals(stop)) {
        let scale = 10f64.powi(a.max(b));
        let (i0, i1) = ((start * scale).round(), (stop * scale).round());
        let span = i1 - i0;
        if i0.abs() < 1e15 && i1.abs() < 1e15 && (span / m).fract() == 0.0 {
            let di = span / m;
            return (0..n).map(|k| (i0 + k as f64 * di) / scale).collect();
        }
    }
    (0..n)
        .map(|k| {
            let t = k as f64 / m;
            start * (1.0 - t) + stop * t
        })
        .collect()
}

/// `start + k·step` for k = 0, 1, … while not past `stop`; `stop` itself when it lies on
/// the grid (within 1e-9 of a step).
pub fn range(start: f64, stop: f64, step: f64) -> Result<Vec<f64>, String> {
    if !(start.is_finite() && stop.is_finite() && step.is_finite()) {
        return Err("range bounds and step must be finite numbers".into());
    }
    if step == 0.0 {
        return Err("range step must not be 0".into());
    }
    let q = (stop - start) / step;
    if q < -1e-9 {
        return Err(format!(
            "range step {step} goes away from stop {stop} (start {start})"
        ));
    }
    let k_max = (q + 1e-9).floor().max(0.0);
    if k_max >= MAX_AXIS_VALUES as f64 {
        return Err(format!(
            "range gives more than {MAX_AXIS_VALUES} values ({})",
            k_max + 1.0
        ));
    }
    let k_max = k_max as usize;
    let on_grid = (q - k_max as f64).abs() <= 1e-9;
    let dec = match (decimals(start), decimals(step)) {
        (Some(a), Some(b)) => {
            let scale = 10f64.powi(a.max(b));
            let (i0, di) = ((start * scale).round(), (step * scale).round());
            (i0.abs() < 1e15 && (i0 + k_max as f64 * di).abs() < 1e15).then_some((scale, i0, di))
        }
        _ => None,
    };
    let mut out: Vec<f64> = (0..=k_max)
        .map(|k| match dec {
            Some((scale, i0, di)) => (i0 + k as f64 * di) / scale,
            None => start + k as f64 * step,
        })
        .collect();
    if on_grid {
        *out.last_mut().unwrap() = stop;
    }
    Ok(out)
}

/// A group of parameters varied together: `{name: optional, path: [values…], …}`.
#[derive(Debug, Clone, PartialEq)]
pub struct ZipGroup {
    /// Dimension name (default `point`, `point_2`, …).
    pub name: Option<String>,
    /// Path → values, all of the same length.
    pub params: IndexMap<String, Vec<Value>>,
}

impl JsonSchema for ZipGroup {
    fn schema_name() -> Cow<'static, str> {
        "ZipGroup".into()
    }
    fn json_schema(_: &mut SchemaGenerator) -> Schema {
        schemars::json_schema!({
            "description": "Parameters varied together: dotted path -> list of values, all lists of one length. Optional `name`: the dimension's name.",
            "type": "object",
            "properties": { "name": { "type": "string" } },
            "additionalProperties": { "type": "array" }
        })
    }
}

impl<'de> Deserialize<'de> for ZipGroup {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        use serde::de::Error;
        let m = IndexMap::<String, Value>::deserialize(d)?;
        let mut name = None;
        let mut params = IndexMap::new();
        for (k, v) in m {
            if k == "name" {
                name = Some(
                    v.as_str()
                        .ok_or_else(|| D::Error::custom("zip group `name` must be a string"))?
                        .to_string(),
                );
            } else {
                let list = v.as_sequence().ok_or_else(|| {
                    D::Error::custom(format!("zip parameter `{k}` must be a list of values"))
                })?;
                params.insert(k, list.clone());
            }
        }
        if params.is_empty() {
            return Err(D::Error::custom("a zip group needs at least one parameter"));
        }
        Ok(ZipGroup { name, params })
    }
}

/// Which time histories to keep.
#[derive(Debug, Clone, PartialEq, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct HistorySpec {
    /// Histories to record.
    pub fields: Vec<HistoryField>,
    /// Sampling interval in s (> 0).
    pub interval: f64,
    /// Duration in s from first contact (>= interval).
    pub duration: f64,
    /// Stored precision, `f32` (default) or `f64`.
    #[serde(default = "default_precision")]
    pub precision: HistoryPrecision,
    /// Compression of the stored histories: `deflate` (default: HDF5's shuffle + deflate
    /// level 1, the smallest file) or `none` (no filters: a third more bytes when the bat's
    /// displacement is stored, in about 40 % of the CPU time per history point; faster
    /// when the disk keeps up, i.e. with few cores per disk). The data are the same.
    #[serde(default)]
    pub compression: HistoryCompression,
    /// How the bat's `displacement` is stored: `modal` (default: the modal integrator's
    /// coordinates per sample, the force on the bat and a static shape per history, the
    /// mode shapes once per bat; y(z, t) follows exactly at any z, from about a quarter of
    /// the bytes, docs/layout.md) or `grid` (y(z, t) on the `z_step` grid, computed while
    /// the collision runs). The Verlet integrator records `grid` only.
    #[serde(default)]
    pub displacement: HistoryDisplacement,
    /// Spacing in m of the z grid on which `displacement` is sampled (from the knob).
    /// Default 0.01.
    #[serde(default = "default_z_step")]
    pub z_step: f64,
    /// Record histories only at points whose parameters take one of the listed values:
    /// dotted path → list (e.g. `{impact.z: [0.60], model: [wave]}`); every condition must
    /// hold. Other points store NaN (and cost no disk: unwritten chunks are not allocated).
    /// Default: every point. The rigid model never has histories.
    #[serde(default)]
    #[schemars(with = "IndexMap<String, Vec<serde_json::Value>>")]
    pub only: IndexMap<String, Vec<Value>>,
}

fn default_precision() -> HistoryPrecision {
    HistoryPrecision::F32
}

fn default_z_step() -> f64 {
    0.01
}

impl HistorySpec {
    /// Number of samples: duration / interval, rounded.
    pub fn n_samples(&self) -> usize {
        (self.duration / self.interval).round() as usize
    }
    /// z positions 0, z_step, … up to `max_length` (included when on the grid).
    pub fn z(&self, max_length: f64) -> Vec<f64> {
        range(0.0, max_length, self.z_step).unwrap_or_default()
    }
    /// The request handed to the model, for bats up to `max_length` m long.
    pub fn request(&self, max_length: f64) -> crate::model::outcome::HistoryRequest {
        crate::model::outcome::HistoryRequest {
            fields: self.fields.clone(),
            interval: self.interval,
            n_samples: self.n_samples(),
            precision: self.precision,
            compression: self.compression,
            displacement: self.displacement,
            z: if self.fields.contains(&HistoryField::Displacement) {
                self.z(max_length)
            } else {
                Vec::new()
            },
        }
    }
}

/// The JSON Schema of study files, pretty-printed with a trailing newline.
pub fn schema_json() -> String {
    let schema = schemars::schema_for!(StudyFile);
    let mut root = schema.as_value().clone();
    // The plausible ranges bound `base` unless the study sets `allow_implausible: true`.
    if let Some(obj) = root.as_object_mut() {
        obj.insert(
            "if".into(),
            serde_json::json!({
                "properties": {"allow_implausible": {"const": true}},
                "required": ["allow_implausible"]
            }),
        );
        obj.insert(
            "else".into(),
            serde_json::json!({
                "properties": {"base": crate::model::plausible::schema_overlay()}
            }),
        );
    }
    allow_quantities(&mut root);
    serde_json::to_string_pretty(&root).expect("schema serializes") + "\n"
}

/// Every number of the schema may also be written with a unit (`34in`, `90mph`): the study
/// loader turns it into SI and refuses a unit its field does not take (`study::quantities`);
/// the schema accepts the form, so that an editor does not flag it.
fn allow_quantities(v: &mut serde_json::Value) {
    use serde_json::Value as J;
    match v {
        J::Object(obj) => {
            let numeric = match obj.get("type") {
                Some(J::String(t)) => t == "number",
                Some(J::Array(ts)) => ts.iter().any(|t| t == "number"),
                _ => false,
            };
            if numeric {
                let original = J::Object(std::mem::take(obj));
                obj.insert(
                    "anyOf".into(),
                    serde_json::json!([original, {"type": "string", "pattern": quantity_pattern()}]),
                );
                return;
            }
            for child in obj.values_mut() {
                allow_quantities(child);
            }
        }
        J::Array(items) => items.iter_mut().for_each(allow_quantities),
        _ => {}
    }
}

/// A number with one of the units of `model::units`, as a JSON-schema pattern.
fn quantity_pattern() -> String {
    let mut suffixes: Vec<String> = crate::model::units::SI_UNITS
        .iter()
        .flat_map(|si| crate::model::units::units_of(si))
        .map(|u| u.suffix.replace('^', "\\^"))
        .collect();
    suffixes.sort();
    suffixes.dedup();
    format!(
        "^\\s*[-+]?([0-9]+\\.?[0-9]*|\\.[0-9]+)([eE][-+]?[0-9]+)?\\s*({})\\s*$",
        suffixes.join("|")
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    // the stop is included when it lies on the grid, computed without accumulating rounding
    #[test]
    fn range_endpoints_exact() {
        let v = range(0.40, 0.84, 0.01).unwrap();
        assert_eq!(v.len(), 45);
        assert_eq!(v[0], 0.40);
        assert_eq!(v[1], 0.41);
        assert_eq!(v[44], 0.84);
        assert_eq!(v[30], 0.70);
        let v = range(0.0, -60.0, -10.0).unwrap();
        assert_eq!(v, vec![0.0, -10.0, -20.0, -30.0, -40.0, -50.0, -60.0]);
        let v = range(0.0, 1.0, 0.3).unwrap();
        assert_eq!(v.len(), 4);
        assert_eq!(v[3], 0.9);
        assert!(range(0.0, 1.0, -0.1).is_err());
        assert!(range(0.0, 1.0, 0.0).is_err());
    }

    #[test]
    fn linspace_endpoints_exact() {
        let v = linspace(0.5, 0.8, 4);
        assert_eq!(v, vec![0.5, 0.6, 0.7, 0.8]);
        let v = linspace(0.0, 1.0, 3);
        assert_eq!(v, vec![0.0, 0.5, 1.0]);
        let v = linspace(0.1, 0.2, 7);
        assert_eq!(v.len(), 7);
        assert_eq!(v[0], 0.1);
        assert_eq!(v[6], 0.2);
        assert_eq!(linspace(3.0, 3.0, 1), vec![3.0]);
    }
}
