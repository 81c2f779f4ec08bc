//! Reading a study file: parse (with source positions), check every key, value and
//! combination that can be checked without running, and build the lazy `Plan`.

use super::error::{did_you_mean, StudyError};
use super::paths::{children, coord_name, known_paths, set_path, PathKind};
use super::plan::{
    bat_key, dim_to_shape, is_bat_path, path_string, related, value_text, BatChoice, DimOrigin,
    Plan, PlanDim, ResolveError,
};
use super::source::{dotted, keys, Pos, Seg, SourceMap};
use super::types::StudyFile;
use crate::model::outcome::HistoryRequest;
use crate::results::{BatVariant, ResultShape, StudyInfo};
use serde_yaml_ng::{Mapping, Value};
use sha2::{Digest, Sha256};
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// Default limit on the number of points (`--max-points`).
pub const DEFAULT_MAX_POINTS: usize = 10_000_000;
/// Plans up to this many points have every point resolved and checked at load time;
/// larger plans check every axis value against the base (one axis at a time).
pub const FULL_CHECK_LIMIT: usize = 20_000;
/// Most distinct bats a study may have.
pub const MAX_BATS: usize = 100_000;

/// Options of loading.
#[derive(Debug, Clone)]
pub struct LoadOptions {
    pub max_points: usize,
}

impl Default for LoadOptions {
    fn default() -> Self {
        LoadOptions {
            max_points: DEFAULT_MAX_POINTS,
        }
    }
}

/// A loaded, validated study.
#[derive(Debug, Clone)]
pub struct Study {
    /// The study file's path as given.
    pub path: PathBuf,
    /// Its text, verbatim.
    pub text: String,
    /// Hex SHA-256 of `text`.
    pub sha256: String,
    pub file: StudyFile,
    pub plan: Plan,
}

const TOP_KEYS: &[&str] = &[
    "name",
    "description",
    "model",
    "base",
    "grid",
    "zip",
    "points",
    "history",
    "output",
    "allow_implausible",
];
const HISTORY_KEYS: &[&str] = &[
    "fields",
    "interval",
    "duration",
    "precision",
    "z_step",
    "only",
];

/// Read and validate a study file.
pub fn load(path: &Path, opts: &LoadOptions) -> Result<Study, StudyError> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| StudyError::new(path, format!("cannot read the study file: {e}")))?;
    load_str(&text, path, opts)
}

struct Ctx<'a> {
    file: &'a Path,
    src: SourceMap,
}

impl Ctx<'_> {
    /// An error at `at`, or at the nearest place above it; at the document's start
    /// (line 1, column 1) when nothing above it was written (e.g. a missing top key).
    fn err(&self, at: &[Seg], msg: impl Into<String>) -> StudyError {
        let pos = self
            .src
            .nearest(at)
            .unwrap_or(super::source::Pos { line: 1, column: 1 });
        StudyError::new(self.file, msg).at(Some(pos))
    }
}

/// Validate study text (`path` names it in messages and anchors relative profile paths).
pub fn load_str(text: &str, path: &Path, opts: &LoadOptions) -> Result<Study, StudyError> {
    let cx = Ctx {
        file: path,
        src: SourceMap::build(text),
    };
    // 1. YAML syntax.
    let root: Value = serde_yaml_ng::from_str(text).map_err(|e| {
        let mut err = StudyError::new(path, format!("malformed YAML: {e}"));
        // serde_yaml_ng gives no location for some errors (a second document): the
        // document's start then.
        let (line, column) = e.location().map_or((1, 1), |l| (l.line(), l.column()));
        err.line = Some(line);
        err.column = Some(column);
        err
    })?;
    let Value::Mapping(top) = &root else {
        return Err(cx
            .err(
                &[],
                "a study file is a mapping with `name`, `base`, `grid`, …",
            )
            .allowed(TOP_KEYS.join(", ")));
    };
    // 2. No NaN or infinity anywhere: serde would turn a NaN into `null` on its way
    //    through JSON, and `null` means "the preset's value".
    check_finite(&cx, &root, &mut Vec::new())?;
    // 3. Unknown keys at the top and in `history`.
    check_keys(&cx, top, &[], TOP_KEYS, "study")?;
    if let Some(Value::Mapping(h)) = top.get("history") {
        check_keys(&cx, h, &keys(&["history"]), HISTORY_KEYS, "history")?;
    }
    // 4. Types of the study's own fields.
    let file: StudyFile = serde_path_to_error::deserialize(root.clone()).map_err(|e| {
        let p = path_string(e.path());
        let segs = yaml_segs(e.path());
        let value = get_segs(&root, &segs).map(value_text);
        let msg = e.into_inner().to_string();
        let whole_document = p.is_empty();
        let mut err =
            cx.err(&segs, msg.clone())
                .field(if whole_document { "study".into() } else { p });
        if let Some(v) = value.filter(|_| !whole_document) {
            err = err.value(v);
        }
        if let Some(a) = allowed_from_serde(&msg) {
            err = err.allowed(a);
        }
        err
    })?;
    validate_name(&cx, &file)?;
    validate_history(&cx, &file)?;
    let plan = build_plan(&cx, &file, opts)?;
    Ok(Study {
        path: path.to_path_buf(),
        text: text.to_string(),
        sha256: hex(&Sha256::digest(text.as_bytes())),
        file,
        plan,
    })
}

/// Refuse a NaN or an infinite number anywhere in the document, at its position.
fn check_finite(cx: &Ctx, v: &Value, at: &mut Vec<Seg>) -> Result<(), StudyError> {
    match v {
        Value::Number(n) => match n.as_f64() {
            Some(x) if !x.is_finite() => Err(cx
                .err(at, "not a finite number")
                .field(seg_path(at))
                .value(value_text(v))
                .allowed("a finite number (NaN and infinities are refused anywhere in a study)")),
            _ => Ok(()),
        },
        Value::Sequence(items) => {
            for (i, x) in items.iter().enumerate() {
                at.push(Seg::Index(i));
                check_finite(cx, x, at)?;
                at.pop();
            }
            Ok(())
        }
        Value::Mapping(m) => {
            for (k, x) in m {
                at.push(Seg::Key(value_text(k)));
                check_finite(cx, x, at)?;
                at.pop();
            }
            Ok(())
        }
        Value::Tagged(t) => check_finite(cx, &t.value, at),
        _ => Ok(()),
    }
}

/// `grid.impact.z[2]` for a path of segments.
fn seg_path(at: &[Seg]) -> String {
    let mut s = String::new();
    for seg in at {
        match seg {
            Seg::Key(k) if s.is_empty() => s.push_str(k),
            Seg::Key(k) => {
                s.push('.');
                s.push_str(k);
            }
            Seg::Index(i) => s.push_str(&format!("[{i}]")),
        }
    }
    s
}

fn hex(b: &[u8]) -> String {
    b.iter().map(|x| format!("{x:02x}")).collect()
}

fn yaml_segs(p: &serde_path_to_error::Path) -> Vec<Seg> {
    use serde_path_to_error::Segment;
    p.iter()
        .filter_map(|s| match s {
            Segment::Seq { index } => Some(Seg::Index(*index)),
            Segment::Map { key } => Some(Seg::Key(key.clone())),
            _ => None,
        })
        .collect()
}

fn get_segs<'a>(v: &'a Value, segs: &[Seg]) -> Option<&'a Value> {
    segs.iter().try_fold(v, |cur, s| match s {
        Seg::Key(k) => cur.get(k.as_str()),
        Seg::Index(i) => cur.get(*i),
    })
}

/// "allowed" text from a serde message (`…, expected X`).
fn allowed_from_serde(msg: &str) -> Option<String> {
    if msg.starts_with("missing field") {
        return Some("this field is required".into());
    }
    msg.split_once(", expected ").map(|(_, a)| match a {
        "f64" | "f32" => "a number".to_string(),
        "usize" | "u64" | "u32" => "a whole number >= 0".to_string(),
        _ => a.to_string(),
    })
}

fn check_keys(
    cx: &Ctx,
    m: &Mapping,
    at: &[Seg],
    allowed: &[&str],
    what: &str,
) -> Result<(), StudyError> {
    for k in m.keys() {
        let key = k.as_str().unwrap_or("");
        if !allowed.contains(&key) {
            let mut p = at.to_vec();
            p.push(Seg::Key(key.to_string()));
            let mut msg = format!("unknown key `{key}` in {what}");
            if let Some(s) = did_you_mean(key, allowed.iter().copied()) {
                msg.push_str(&format!("; did you mean `{s}`?"));
            }
            return Err(cx
                .err(&p, msg)
                .field(key)
                .value(value_text(k))
                .allowed(allowed.join(", ")));
        }
    }
    Ok(())
}

/// Check the keys of a parameter tree (`base`) against the `CollisionSpec` paths.
fn check_param_keys(cx: &Ctx, v: &Value, prefix: &str, at: &[Seg]) -> Result<(), StudyError> {
    let Value::Mapping(m) = v else { return Ok(()) };
    for (k, sub) in m {
        let key = value_text(k);
        let full = if prefix.is_empty() {
            key.clone()
        } else {
            format!("{prefix}.{key}")
        };
        let mut p = at.to_vec();
        p.push(Seg::Key(key.clone()));
        match known_paths().get(&full) {
            None => {
                let cands = children(prefix);
                let mut msg = format!("unknown parameter `{full}`");
                if let Some(s) = did_you_mean(&key, cands.iter().copied()) {
                    msg.push_str(&format!("; did you mean `{s}`?"));
                }
                let where_ = if prefix.is_empty() {
                    "base".to_string()
                } else {
                    format!("`{prefix}`")
                };
                return Err(cx
                    .err(&p, msg)
                    .field(full.clone())
                    .value(key)
                    .allowed(format!("fields of {where_}: {}", cands.join(", "))));
            }
            Some(PathKind::Record) => check_param_keys(cx, sub, &full, &p)?,
            Some(PathKind::Leaf) => {}
        }
    }
    Ok(())
}

/// Check a dotted path written in `grid`/`zip`/`points`.
fn check_path(cx: &Ctx, path: &str, at: &[Seg]) -> Result<(), StudyError> {
    if known_paths().contains_key(path) {
        return Ok(());
    }
    let all: Vec<&str> = known_paths().keys().map(String::as_str).collect();
    let mut msg = format!("unknown parameter path `{path}`");
    if let Some(s) = did_you_mean(path, all.iter().copied()) {
        msg.push_str(&format!("; did you mean `{s}`?"));
    }
    let parent = path.rsplit_once('.').map(|(p, _)| p).unwrap_or("");
    let sib = children(parent);
    let allowed = if sib.is_empty() || !known_paths().contains_key(parent) && !parent.is_empty() {
        "a dotted parameter path such as impact.z, swing.omega, bat.material.density".to_string()
    } else {
        let pre = if parent.is_empty() {
            String::new()
        } else {
            format!("{parent}.")
        };
        sib.iter()
            .map(|s| format!("{pre}{s}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    Err(cx.err(at, msg).field(path).value(path).allowed(allowed))
}

fn validate_name(cx: &Ctx, f: &StudyFile) -> Result<(), StudyError> {
    let ok = !f.name.is_empty()
        && !f.name.starts_with('.')
        && f.name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || "_-.".contains(c));
    if ok {
        return Ok(());
    }
    Err(cx
        .err(&keys(&["name"]), "bad study name")
        .field("name")
        .value(f.name.clone())
        .allowed("letters, digits, `_`, `-`, `.` (not starting with `.`)"))
}

fn validate_history(cx: &Ctx, f: &StudyFile) -> Result<(), StudyError> {
    let Some(h) = &f.history else { return Ok(()) };
    let bad = |k: &str, v: f64, allowed: String| {
        Err(cx
            .err(&keys(&["history", k]), format!("bad history.{k}"))
            .field(format!("history.{k}"))
            .value(v.to_string())
            .allowed(allowed))
    };
    if !(h.interval > 0.0 && h.interval.is_finite()) {
        return bad(
            "interval",
            h.interval,
            "a finite number of seconds > 0".into(),
        );
    }
    if !(h.duration >= h.interval && h.duration.is_finite()) {
        return bad(
            "duration",
            h.duration,
            format!(">= history.interval ({} s)", h.interval),
        );
    }
    if h.n_samples() > 10_000_000 {
        return bad(
            "duration",
            h.duration,
            "at most 1e7 samples (duration / interval)".into(),
        );
    }
    if !(h.z_step > 0.0 && h.z_step <= 1.0) {
        return bad("z_step", h.z_step, "0 < z_step <= 1 m".into());
    }
    for path in h.only.keys() {
        check_path(cx, path, &keys(&["history", "only", path]))?;
    }
    Ok(())
}

/// Where element `i` of a dimension's parameter `path` was written.
fn dim_elem(file: &StudyFile, d: &PlanDim, path: &str, i: usize) -> Vec<Seg> {
    match &d.origin {
        DimOrigin::Grid { key } => {
            let mut s = keys(&["grid", key]);
            if matches!(file.grid.get(key), Some(super::types::AxisValues::List(_))) {
                s.push(Seg::Index(i));
            }
            s
        }
        DimOrigin::Zip { group } => vec![
            Seg::Key("zip".into()),
            Seg::Index(*group),
            Seg::Key(path.into()),
            Seg::Index(i),
        ],
        DimOrigin::Points => vec![
            Seg::Key("points".into()),
            Seg::Index(i),
            Seg::Key(path.into()),
        ],
    }
}

fn dim_label(d: &PlanDim, path: &str, i: usize) -> String {
    match &d.origin {
        DimOrigin::Grid { key } => format!("grid axis `{key}`, value #{}", i + 1),
        DimOrigin::Zip { group } => {
            format!("zip group #{} (`{path}`), entry #{}", group + 1, i + 1)
        }
        DimOrigin::Points => format!("points entry #{} (`{path}`)", i + 1),
    }
}

/// Turn a resolve error of the combination `multi` into a located StudyError.
fn located(
    cx: &Ctx,
    file: &StudyFile,
    plan: &Plan,
    multi: &[usize],
    varied: Option<usize>,
    e: ResolveError,
) -> StudyError {
    let (epath, msg, value, allowed) = match e {
        ResolveError::Shape {
            path,
            message,
            value,
        } => {
            let mut allowed = allowed_from_serde(&message);
            let mut msg = message.clone();
            let mut path = path;
            if let Some(f) = message
                .strip_prefix("missing field `")
                .and_then(|r| r.split('`').next())
            {
                path = if path.is_empty() {
                    f.to_string()
                } else {
                    format!("{path}.{f}")
                };
            }
            if let (Some(rest), true) = (
                message.strip_prefix("unknown variant `"),
                message.contains("expected"),
            ) {
                let word = rest.split('`').next().unwrap_or("");
                let opts: Vec<&str> = message.split('`').skip(3).step_by(2).collect();
                if let Some(s) = did_you_mean(word, opts.iter().copied()) {
                    msg.push_str(&format!("; did you mean `{s}`?"));
                }
                allowed = Some(opts.join(", "));
            }
            (path, msg, value, allowed)
        }
        ResolveError::Check(v) => (
            v.path.clone(),
            if let Some(m) = v.message {
                m
            } else if v.value == "missing" {
                format!(
                    "missing field `{}`",
                    v.path.rsplit('.').next().unwrap_or(&v.path)
                )
            } else {
                format!("`{}` out of range", v.path)
            },
            Some(v.value).filter(|v| !v.is_empty()),
            Some(v.allowed),
        ),
        ResolveError::Profile { file: f } => (
            "bat.profile.csv".into(),
            format!("profile `{f}` not loaded"),
            None,
            None,
        ),
    };
    // Which block set this parameter? Prefer the varied dimension.
    let order: Vec<usize> = varied.into_iter().chain(0..plan.dims.len()).collect();
    let mut at = None;
    let mut origin = String::from("base");
    for d in order {
        let dim = &plan.dims[d];
        if let Some((p, _)) = dim
            .params
            .iter()
            .find(|(p, _)| related(p, &epath) && !epath.is_empty())
        {
            at = Some(dim_elem(file, dim, p, multi[d]));
            origin = dim_label(dim, p, multi[d]);
            break;
        }
    }
    let at = at.unwrap_or_else(|| {
        let mut s = keys(&["base"]);
        s.extend(dotted(&epath));
        s
    });
    let mut err = cx
        .err(&at, format!("{msg} (set in {origin})"))
        .field(if epath.is_empty() {
            "base".to_string()
        } else {
            epath
        });
    if let Some(v) = value {
        err = err.value(v);
    }
    if let Some(a) = allowed {
        err = err.allowed(a);
    }
    err
}

fn build_plan(cx: &Ctx, file: &StudyFile, opts: &LoadOptions) -> Result<Plan, StudyError> {
    // Base.
    let mut base = match &file.base {
        Value::Null => Value::Mapping(Mapping::new()),
        Value::Mapping(_) => file.base.clone(),
        other => {
            return Err(cx
                .err(
                    &keys(&["base"]),
                    "`base` must be a mapping of collision parameters",
                )
                .field("base")
                .value(value_text(other))
                .allowed("a mapping with bat, ball, swing, hoop, impact, numerics, model"))
        }
    };
    check_param_keys(cx, &base, "", &keys(&["base"]))?;
    check_base_types(cx, &base)?;
    if let Some(m) = file.model {
        if let Some(bm) = base.get("model") {
            let bm: Option<crate::model::spec::ModelKind> =
                serde_yaml_ng::from_value(bm.clone()).ok();
            if bm.is_some() && bm != Some(m) {
                return Err(cx
                    .err(&keys(&["model"]), "`model` and `base.model` disagree")
                    .field("model")
                    .value(format!("{m:?}").to_lowercase())
                    .allowed("one of them, or both the same"));
            }
        }
        let _ = set_path(&mut base, "model", serde_yaml_ng::to_value(m).unwrap());
    }

    // Dimensions.
    let mut dims: Vec<PlanDim> = Vec::new();
    for (key, axis) in &file.grid {
        let at = keys(&["grid", key]);
        check_path(cx, key, &at)?;
        let values = axis.values().map_err(|e| {
            cx.err(&at, e.clone())
                .field(format!("grid.{key}"))
                .value(match axis {
                    super::types::AxisValues::List(v) => format!("{} values", v.len()),
                    super::types::AxisValues::Linspace { start, stop, n } => {
                        format!("{{linspace: [{start}, {stop}, {n}]}}")
                    }
                    super::types::AxisValues::Range { start, stop, step } => {
                        format!("{{range: [{start}, {stop}, {step}]}}")
                    }
                })
                .allowed(
                    "a non-empty list, {linspace: [start, stop, n]}, {range: [start, stop, step]}",
                )
        })?;
        dims.push(PlanDim {
            name: coord_name(key),
            size: values.len(),
            params: vec![(key.clone(), values)],
            origin: DimOrigin::Grid { key: key.clone() },
        });
    }
    let n_point_blocks = file.zip.len() + usize::from(file.points.is_some());
    let mut auto = 0usize;
    let mut next_name = |explicit: Option<&String>| {
        if let Some(n) = explicit {
            return n.clone();
        }
        auto += 1;
        if auto == 1 {
            "point".to_string()
        } else {
            format!("point_{auto}")
        }
    };
    let _ = n_point_blocks;
    for (g, group) in file.zip.iter().enumerate() {
        let at = vec![Seg::Key("zip".into()), Seg::Index(g)];
        let mut len = None;
        let mut params = Vec::new();
        for (path, vals) in &group.params {
            let mut p = at.clone();
            p.push(Seg::Key(path.clone()));
            check_path(cx, path, &p)?;
            match len {
                None => len = Some((path.clone(), vals.len())),
                Some((ref first, n)) if n != vals.len() => {
                    return Err(cx
                        .err(&p, format!("zip lists differ in length: `{first}` has {n} values, `{path}` has {}", vals.len()))
                        .field(format!("zip[{g}].{path}"))
                        .value(format!("{} values", vals.len()))
                        .allowed(format!("{n} values, like `{first}`")));
                }
                _ => {}
            }
            if vals.is_empty() {
                return Err(cx
                    .err(&p, "empty zip list")
                    .field(format!("zip[{g}].{path}"))
                    .allowed("at least one value"));
            }
            params.push((path.clone(), vals.clone()));
        }
        let size = len.map(|l| l.1).unwrap_or(0);
        dims.push(PlanDim {
            name: next_name(group.name.as_ref()),
            size,
            params,
            origin: DimOrigin::Zip { group: g },
        });
    }
    if let Some(block) = &file.points {
        let points = block.sets();
        let at = keys(&block.sets_key());
        if points.is_empty() {
            return Err(cx
                .err(&at, "`points` is empty")
                .field("points")
                .allowed("at least one parameter set"));
        }
        // The union of the paths the sets name, in order of first appearance; a set that
        // leaves a path out keeps the base value there (marked `UNSET`).
        let mut paths: Vec<String> = Vec::new();
        for (i, set) in points.iter().enumerate() {
            for k in set.keys() {
                let mut q = at.clone();
                q.push(Seg::Index(i));
                q.push(Seg::Key(k.clone()));
                check_path(cx, k, &q)?;
                if !paths.contains(k) {
                    paths.push(k.clone());
                }
            }
        }
        let params = paths
            .iter()
            .map(|k| {
                let values = points
                    .iter()
                    .map(|s| s.get(k).cloned().unwrap_or_else(super::plan::unset))
                    .collect();
                (k.clone(), values)
            })
            .collect();
        dims.push(PlanDim {
            name: next_name(block.name()),
            size: points.len(),
            params,
            origin: DimOrigin::Points,
        });
    }
    // One block per path; unique dimension and coordinate names.
    let mut seen: Vec<(String, String)> = Vec::new();
    for d in &dims {
        for (p, _) in &d.params {
            if let Some((q, dn)) = seen.iter().find(|(q, _)| related(q, p)) {
                let at = dim_elem(file, d, p, 0);
                return Err(cx
                    .err(
                        &at[..at.len().min(2)],
                        format!("`{p}` is also set by dimension `{dn}` (`{q}`)"),
                    )
                    .field(p.clone())
                    .allowed("each parameter set by one block only"));
            }
            seen.push((p.clone(), d.name.clone()));
        }
    }
    let mut names: HashMap<String, usize> = HashMap::new();
    for d in &dims {
        if names.insert(d.name.clone(), 1).is_some() {
            return Err(cx
                .err(
                    &keys(&["zip"]),
                    format!("two dimensions are named `{}`", d.name),
                )
                .field("zip.name")
                .value(d.name.clone())
                .allowed("unique names"));
        }
    }
    // Size.
    let mut n: usize = 1;
    for d in &dims {
        n = n.saturating_mul(d.size);
    }
    if n > opts.max_points {
        let sizes: Vec<String> = dims
            .iter()
            .map(|d| format!("{} {}", d.name, d.size))
            .collect();
        let at = if file.grid.is_empty() {
            keys(&["zip"])
        } else {
            keys(&["grid"])
        };
        return Err(cx
            .err(
                &at,
                format!(
                    "the study expands to {n} points ({}), more than the limit",
                    sizes.join(" × ")
                ),
            )
            .field("grid")
            .value(n.to_string())
            .allowed(format!(
                "at most {} points (raise with --max-points)",
                opts.max_points
            )));
    }
    if n == 0 {
        return Err(cx
            .err(&[], "the study has no points")
            .field("grid")
            .allowed("at least one point"));
    }
    let defaults = with_defaults(&base);
    let shape = ResultShape {
        dims: dims.iter().map(|d| dim_to_shape(d, &defaults)).collect(),
    };

    // Profiles: from base and from any block value.
    let dir = cx.file.parent().map(Path::to_path_buf).unwrap_or_default();
    let mut profiles = HashMap::new();
    let mut load_profile = |f: &str, at: Vec<Seg>| -> Result<(), StudyError> {
        if profiles.contains_key(f) {
            return Ok(());
        }
        let p = dir.join(f);
        let k = super::profile::load_profile_csv(&p).map_err(|e| {
            cx.err(&at, e)
                .field("bat.profile.csv")
                .value(f.to_string())
                .allowed("a readable CSV with header `z,radius` (m) or `slice_end_cm,diameter_mm`, relative to the study file")
        })?;
        profiles.insert(f.to_string(), k);
        Ok(())
    };
    if let Some(Value::String(f)) = super::paths::get_path(&base, "bat.profile.csv") {
        load_profile(f, keys(&["base", "bat", "profile", "csv"]))?;
    }
    for d in &dims {
        for (p, vals) in &d.params {
            for (i, v) in vals.iter().enumerate() {
                let mut probe = Value::Mapping(Mapping::new());
                let _ = set_path(&mut probe, p, v.clone());
                if let Some(Value::String(f)) = super::paths::get_path(&probe, "bat.profile.csv") {
                    load_profile(f, dim_elem(file, d, p, i))?;
                }
            }
        }
    }

    let bat_dims: Vec<usize> = (0..dims.len())
        .filter(|&d| dims[d].params.iter().any(|(p, _)| is_bat_path(p)))
        .collect();
    let history_only = file
        .history
        .as_ref()
        .map(|h| h.only.iter().map(|(k, v)| (k.clone(), v.clone())).collect())
        .unwrap_or_default();
    let mut plan = Plan {
        base,
        history_only,
        allow_implausible: file.allow_implausible,
        history_count: None,
        dims,
        shape,
        profiles,
        bat_dims,
        bat_of_combo: Vec::new(),
        bats: Vec::new(),
    };

    // Every axis value against the base (one dimension at a time).
    let zero = vec![0usize; plan.dims.len()];
    if let Err(e) = plan.resolve(&zero) {
        return Err(located(cx, file, &plan, &zero, None, e));
    }
    let mut unused = super::unused::Tally::new();
    unused.add(&plan.value_at(&zero));
    for d in 0..plan.dims.len() {
        for i in 1..plan.dims[d].size {
            let mut m = zero.clone();
            m[d] = i;
            if let Err(e) = plan.resolve(&m) {
                return Err(located(cx, file, &plan, &m, Some(d), e));
            }
            unused.add(&plan.value_at(&m));
        }
    }
    // Distinct bats.
    let mut combos: usize = 1;
    for &d in &plan.bat_dims {
        combos = combos.saturating_mul(plan.dims[d].size);
    }
    if combos > MAX_BATS {
        return Err(cx
            .err(
                &keys(&["grid"]),
                format!("the study has {combos} bat variants"),
            )
            .field("grid")
            .value(combos.to_string())
            .allowed(format!("at most {MAX_BATS} distinct bats")));
    }
    let mut by_key: HashMap<String, u32> = HashMap::new();
    let mut bat_of_combo = Vec::with_capacity(combos);
    for c in 0..combos {
        let mut m = zero.clone();
        let mut rest = c;
        for &d in plan.bat_dims.iter().rev() {
            m[d] = rest % plan.dims[d].size;
            rest /= plan.dims[d].size;
        }
        let spec = plan
            .resolve(&m)
            .map_err(|e| located(cx, file, &plan, &m, None, e))?;
        let key = bat_key(&spec.bat, &spec.numerics);
        let next = plan.bats.len() as u32;
        let idx = *by_key.entry(key.clone()).or_insert_with(|| {
            let mut label = format!("{:?}", spec.bat.preset).to_lowercase();
            for &d in &plan.bat_dims {
                for (p, vals) in &plan.dims[d].params {
                    if is_bat_path(p) && !super::plan::is_unset(&vals[m[d]]) {
                        label.push_str(&format!(", {p}={}", value_text(&vals[m[d]])));
                    }
                }
            }
            plan.bats.push(BatChoice {
                key,
                label,
                bat: spec.bat.clone(),
                numerics: spec.numerics.clone(),
            });
            next
        });
        bat_of_combo.push(idx);
    }
    plan.bat_of_combo = bat_of_combo;
    // Small plans: every point (and the exact number of histories they record).
    let wants_history = file.history.as_ref().is_some_and(|h| !h.fields.is_empty());
    if n <= FULL_CHECK_LIMIT {
        let mut histories = 0usize;
        for flat in 0..n {
            let m = plan.shape.unravel(flat);
            match plan.resolve(&m) {
                Err(e) => return Err(located(cx, file, &plan, &m, None, e)),
                Ok(spec) => {
                    if wants_history
                        && spec.model == crate::model::spec::ModelKind::Wave
                        && plan.records_history(&spec)
                    {
                        histories += 1;
                    }
                }
            }
            unused.add(&plan.value_at(&m));
        }
        if wants_history {
            plan.history_count = Some(histories);
        }
    }
    if let Some(rule) = unused.unused() {
        return Err(cx
            .err(
                &written_at(file, &plan, rule.field),
                format!(
                    "`{}` is set, but no point of the study uses it: it is used only {}",
                    rule.field, rule.used_when
                ),
            )
            .field(rule.field)
            .allowed(format!("leave it out (it is used only {})", rule.used_when)));
    }
    if wants_history {
        check_history_only(cx, file, &plan)?;
    }
    Ok(plan)
}

/// Every value written in `base` has the right type, even where a block overrides it
/// (`base.ball.speed: fast` under a `ball.speed` grid would otherwise pass unnoticed).
/// Fields left out of `base` are not asked for: blocks may set them.
fn check_base_types(cx: &Ctx, base: &Value) -> Result<(), StudyError> {
    let mut probe = base.clone();
    if super::paths::get_path(&probe, "impact.z").is_none() {
        let _ = set_path(&mut probe, "impact.z", Value::from(0.5));
    }
    let Ok(json) = serde_json::to_value(&probe) else {
        return Ok(());
    };
    let Err(e) = serde_path_to_error::deserialize::<_, crate::model::spec::CollisionSpec>(json)
    else {
        return Ok(());
    };
    let path = path_string(e.path());
    let message = e.into_inner().to_string();
    if message.starts_with("missing field") {
        return Ok(());
    }
    let mut at = keys(&["base"]);
    at.extend(dotted(&path));
    let mut err = cx
        .err(&at, format!("{message} (in base)"))
        .field(path.clone());
    if let Some(v) = super::paths::get_path(base, &path) {
        err = err.value(value_text(v));
    }
    if let Some(a) = allowed_from_serde(&message) {
        err = err.allowed(a);
    }
    Err(err)
}

/// Where the study sets `field`: in `base`, else the first block value that sets it.
fn written_at(file: &StudyFile, plan: &Plan, field: &str) -> Vec<Seg> {
    let set = |v: Option<&Value>| v.is_some_and(|v| !v.is_null());
    if set(super::paths::get_path(&plan.base, field)) {
        let mut s = keys(&["base"]);
        s.extend(dotted(field));
        return s;
    }
    for d in &plan.dims {
        for (p, vals) in &d.params {
            if !related(p, field) {
                continue;
            }
            for (i, v) in vals.iter().enumerate() {
                let mut probe = Value::Mapping(Mapping::new());
                let _ = set_path(&mut probe, p, v.clone());
                if set(super::paths::get_path(&probe, field)) {
                    return dim_elem(file, d, p, i);
                }
            }
        }
    }
    keys(&["base"])
}

/// Every value listed in `history.only` must be one that some point takes: a value off
/// the grid (a typo, or 0.703 for 0.70) would silently record nothing. For a plan small
/// enough to count, at least one point must record a history.
fn check_history_only(cx: &Ctx, file: &StudyFile, plan: &Plan) -> Result<(), StudyError> {
    let Some(h) = &file.history else {
        return Ok(());
    };
    let defaults = with_defaults(&plan.base);
    for (path, wanted) in &h.only {
        let Some(taken) = values_taken(plan, &defaults, path) else {
            continue; // set inside a record by a block: not comparable value by value
        };
        for (i, w) in wanted.iter().enumerate() {
            if !taken.iter().any(|t| super::plan::same_value(t, w)) {
                let mut shown: Vec<String> = taken.iter().take(12).map(value_text).collect();
                if taken.len() > 12 {
                    shown.push(format!("… ({} values)", taken.len()));
                }
                return Err(cx
                    .err(
                        &[
                            Seg::Key("history".into()),
                            Seg::Key("only".into()),
                            Seg::Key(path.clone()),
                            Seg::Index(i),
                        ],
                        format!("history.only: no point of the study has `{path}` = {}: this value would record no history", value_text(w)),
                    )
                    .field(format!("history.only.{path}"))
                    .value(value_text(w))
                    .allowed(if shown.is_empty() {
                        format!("a value `{path}` takes in the study (it is not set)")
                    } else {
                        format!("values `{path}` takes in the study: {}", shown.join(", "))
                    }));
            }
        }
    }
    if plan.history_count == Some(0) {
        return Err(cx
            .err(
                &keys(&["history", "only"]),
                "history.only: no point of the study meets every condition at once (the rigid model never records histories)",
            )
            .field("history.only")
            .allowed("conditions that some wave-model point meets together"));
    }
    Ok(())
}

/// The values `path` takes over the study: a block's values where a block sets it (with
/// the base value too where a `points` set leaves it out), else the base value with its
/// defaults. None when a block sets a record that contains `path`, or a field inside it.
fn values_taken(plan: &Plan, defaults: &Value, path: &str) -> Option<Vec<Value>> {
    let base_value = || super::paths::get_path(defaults, path).cloned();
    for d in &plan.dims {
        for (p, vals) in &d.params {
            if p == path {
                let mut out: Vec<Value> = Vec::new();
                for v in vals {
                    if super::plan::is_unset(v) {
                        out.extend(base_value());
                    } else {
                        out.push(v.clone());
                    }
                }
                return Some(out);
            }
            if related(p, path) {
                return None;
            }
        }
    }
    Some(base_value().into_iter().collect())
}

impl Study {
    /// The output path: `-o` if given, else the study's `output`, else `results/<name>.h5`
    /// (relative paths are relative to the current working directory).
    pub fn output_path(&self, cli_override: Option<&Path>) -> PathBuf {
        if let Some(p) = cli_override {
            return p.to_path_buf();
        }
        match &self.file.output {
            Some(o) => PathBuf::from(o),
            None => PathBuf::from("results").join(format!("{}.h5", self.file.name)),
        }
    }

    /// The history request for bats up to `max_length` m long (None: summaries only).
    pub fn history_request(&self, max_length: f64) -> Option<HistoryRequest> {
        self.file
            .history
            .as_ref()
            .filter(|h| !h.fields.is_empty())
            .map(|h| h.request(max_length))
    }

    /// What the store needs before the first point.
    pub fn info(&self, bats: Vec<BatVariant>, history: Option<HistoryRequest>) -> StudyInfo {
        StudyInfo {
            name: self.file.name.clone(),
            description: self.file.description.clone(),
            study_text: self.text.clone(),
            study_sha256: self.sha256.clone(),
            study_path: self.path.display().to_string(),
            shape: self.plan.shape.clone(),
            history,
            bats,
            allow_implausible: self.file.allow_implausible,
        }
    }

    /// Position of a top-level key in the file (for messages about `output`).
    pub fn position_of(&self, key: &str) -> Option<Pos> {
        SourceMap::build(&self.text).get(&keys(&[key]))
    }
}

/// The base tree with every defaulted field filled in (as far as the base deserializes
/// with a placeholder impact), so that coordinates show the values points really use.
fn with_defaults(base: &Value) -> Value {
    let mut v = base.clone();
    if super::paths::get_path(&v, "impact.z").is_none() {
        let _ = set_path(&mut v, "impact.z", Value::from(0.0));
    }
    serde_json::to_value(&v)
        .ok()
        .and_then(|j| serde_json::from_value::<crate::model::spec::CollisionSpec>(j).ok())
        .and_then(|spec| serde_yaml_ng::to_value(spec).ok())
        .unwrap_or_else(|| base.clone())
}
