//! `history.only`: every listed value must be one some point takes, and (for a plan small
//! enough to count) some point must record a history.

use super::error::StudyError;
use super::locate::Ctx;
use super::paths::with_defaults;
use super::plan::{related, value_text, Plan};
use super::source::{keys, Seg};
use super::types::StudyFile;
use yaml_serde::Value;

/// Every value listed in `history.only` must be one that some point takes: a value off
/// the grid (a typo, or 0.703 for 0.70) would silently record nothing. For a plan small
/// enough to count, at least one point must record a history.
pub(super) fn check_history_only(
    cx: &Ctx,
    file: &StudyFile,
    plan: &Plan,
) -> Result<(), StudyError> {
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
pub(super) fn values_taken(plan: &Plan, defaults: &Value, path: &str) -> Option<Vec<Value>> {
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
