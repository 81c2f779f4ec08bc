//! Checks of what is written, before any point is resolved: no NaN or infinity, known keys
//! and parameter paths, a valid name and history block, and the types written in `base`.

use super::error::allowed_from_serde;
use super::error::{did_you_mean, StudyError};
use super::locate::Ctx;
use super::paths::{children, known_paths, set_path, PathKind};
use super::plan::{first_non_finite, path_string, value_text};
use super::source::{dotted, keys, seg_path, Seg};
use super::types::StudyFile;
use yaml_serde::{Mapping, Value};

pub(super) const TOP_KEYS: &[&str] = &[
    "name",
    "description",
    "model",
    "base",
    "grid",
    "zip",
    "points",
    "sample",
    "optimize",
    "history",
    "output",
    "allow_implausible",
];
pub(super) const HISTORY_KEYS: &[&str] = &[
    "fields",
    "interval",
    "duration",
    "precision",
    "compression",
    "displacement",
    "z_step",
    "only",
];

/// Refuse a NaN or an infinite number anywhere in the document, at its position.
pub(super) fn check_finite(cx: &Ctx, v: &Value, at: &mut Vec<Seg>) -> Result<(), StudyError> {
    match first_non_finite(v, at) {
        Some(x) => Err(cx
            .err(at, "not a finite number")
            .field(seg_path(at))
            .value(value_text(&Value::from(x)))
            .allowed("a finite number (NaN and infinities are refused anywhere in a study)")),
        None => Ok(()),
    }
}

pub(super) fn yaml_segs(p: &serde_path_to_error::Path) -> Vec<Seg> {
    use serde_path_to_error::Segment;
    p.iter()
        .filter_map(|s| match s {
            Segment::Seq { index } => Some(Seg::Index(*index)),
            Segment::Map { key } => Some(Seg::Key(key.clone())),
            _ => None,
        })
        .collect()
}

pub(super) fn get_segs<'a>(v: &'a Value, segs: &[Seg]) -> Option<&'a Value> {
    segs.iter().try_fold(v, |cur, s| match s {
        Seg::Key(k) => cur.get(k.as_str()),
        Seg::Index(i) => cur.get(*i),
    })
}

pub(super) fn check_keys(
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
pub(super) fn check_param_keys(
    cx: &Ctx,
    v: &Value,
    prefix: &str,
    at: &[Seg],
) -> Result<(), StudyError> {
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
pub(super) fn check_path(cx: &Ctx, path: &str, at: &[Seg]) -> Result<(), StudyError> {
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

pub(super) fn validate_name(cx: &Ctx, f: &StudyFile) -> Result<(), StudyError> {
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

pub(super) fn validate_history(cx: &Ctx, f: &StudyFile) -> Result<(), StudyError> {
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
    let longest = crate::model::collision::wave::MAX_TIME;
    if h.interval * h.n_samples() as f64 > longest {
        return bad(
            "duration",
            h.duration,
            format!("at most {longest} s (the longest time a collision is simulated)"),
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
    for (i, f) in h.fields.iter().enumerate() {
        if h.fields[..i].contains(f) {
            let name = serde_json::to_value(f).map_or(String::new(), |v| value_text_json(&v));
            return Err(cx
                .err(
                    &[
                        Seg::Key("history".into()),
                        Seg::Key("fields".into()),
                        Seg::Index(i),
                    ],
                    "a history field is listed twice",
                )
                .field(format!("history.fields[{i}]"))
                .value(name)
                .allowed("each field once"));
        }
    }
    for path in h.only.keys() {
        check_path(cx, path, &keys(&["history", "only", path]))?;
    }
    Ok(())
}

/// Every value written in `base` has the right type, even where a block overrides it
/// (`base.ball.speed: fast` under a `ball.speed` grid would otherwise pass unnoticed).
/// Fields left out of `base` are not asked for: blocks may set them.
pub(super) fn check_base_types(cx: &Ctx, base: &Value) -> Result<(), StudyError> {
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

fn value_text_json(v: &serde_json::Value) -> String {
    v.as_str().map_or_else(|| v.to_string(), str::to_string)
}
