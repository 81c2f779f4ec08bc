//! Where in the study file: the context that turns a path of keys into a line and column,
//! and the located error of a parameter that a block (or the base) set.

use super::error::allowed_from_serde;
use super::error::{did_you_mean, StudyError};
use super::paths::set_path;
use super::plan::{related, DimOrigin, Plan, PlanDim, ResolveError};
use super::source::{dotted, keys, Seg, SourceMap};
use super::types::StudyFile;
use std::path::Path;
use yaml_serde::{Mapping, Value};

pub(super) struct Ctx<'a> {
    pub(super) file: &'a Path,
    pub(super) src: SourceMap,
}

impl Ctx<'_> {
    /// An error at `at`, or at the nearest place above it; at the document's start
    /// (line 1, column 1) when nothing above it was written (e.g. a missing top key).
    pub(super) fn err(&self, at: &[Seg], msg: impl Into<String>) -> StudyError {
        let pos = self
            .src
            .nearest(at)
            .unwrap_or(super::source::Pos { line: 1, column: 1 });
        StudyError::new(self.file, msg).at(Some(pos))
    }
}

/// Where element `i` of a dimension's parameter `path` was written.
pub(super) fn dim_elem(file: &StudyFile, d: &PlanDim, path: &str, i: usize) -> Vec<Seg> {
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
        DimOrigin::Sample => keys(&["sample", "params", path]),
    }
}

pub(super) fn dim_label(d: &PlanDim, path: &str, i: usize) -> String {
    match &d.origin {
        DimOrigin::Grid { key } => format!("grid axis `{key}`, value #{}", i + 1),
        DimOrigin::Zip { group } => {
            format!("zip group #{} (`{path}`), entry #{}", group + 1, i + 1)
        }
        DimOrigin::Points => format!("points entry #{} (`{path}`)", i + 1),
        DimOrigin::Sample => format!("sample point #{} (`{path}`)", i + 1),
    }
}

/// Turn a resolve error of the combination `multi` into a located StudyError.
pub(super) fn located(
    cx: &Ctx,
    file: &StudyFile,
    plan: &Plan,
    multi: &[usize],
    varied: Option<usize>,
    e: ResolveError,
) -> StudyError {
    let (epath, msg, value, allowed) = what_failed(e);
    let (at, origin) = where_set(file, plan, multi, varied, &epath);
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

/// The failed parameter's path, the message, the value and what is allowed.
fn what_failed(e: ResolveError) -> (String, String, Option<String>, Option<String>) {
    match e {
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
    }
}

/// Where the parameter at `epath` was set for the point at `multi`: the block element
/// (preferring the varied dimension) and its label, else `base`.
fn where_set(
    file: &StudyFile,
    plan: &Plan,
    multi: &[usize],
    varied: Option<usize>,
    epath: &str,
) -> (Vec<Seg>, String) {
    let order = varied.into_iter().chain(0..plan.dims.len());
    for d in order {
        let dim = &plan.dims[d];
        if let Some((p, _)) = dim
            .params
            .iter()
            .find(|(p, _)| related(p, epath) && !epath.is_empty())
        {
            return (
                dim_elem(file, dim, p, multi[d]),
                dim_label(dim, p, multi[d]),
            );
        }
    }
    let mut s = keys(&["base"]);
    s.extend(dotted(epath));
    (s, "base".to_string())
}

/// Where the study sets `field`: in `base`, else the first block value that sets it.
pub(super) fn written_at(file: &StudyFile, plan: &Plan, field: &str) -> Vec<Seg> {
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
