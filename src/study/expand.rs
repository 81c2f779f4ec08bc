//! The blocks (`grid`, `zip`, `points`) → the dimensions of one Cartesian product → the lazy
//! `Plan`: sizes, profiles, distinct bats, and every value checked against the base.

use super::error::StudyError;
use super::history_only::check_history_only;
use super::locate::{dim_elem, located, written_at, Ctx};
use super::paths::{coord_name, set_path, with_defaults};
use super::plan::{
    bat_key, dim_to_shape, is_bat_path, related, value_text, BatChoice, DimOrigin, Plan, PlanDim,
};
use super::source::{keys, Seg};
use super::syntax::{check_base_types, check_param_keys, check_path};
use super::types::StudyFile;
use crate::results::ResultShape;
use serde_yaml_ng::{Mapping, Value};
use std::collections::HashMap;
use std::path::Path;

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

pub(super) fn build_plan(
    cx: &Ctx,
    file: &StudyFile,
    opts: &LoadOptions,
) -> Result<Plan, StudyError> {
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
            // a profile of the user's own is part of what the bat is
            if spec.bat.profile.is_some() {
                match super::paths::get_path(&plan.value_at(&m), "bat.profile.csv") {
                    Some(serde_yaml_ng::Value::String(f)) => {
                        label.push_str(&format!(", profile {f}"));
                    }
                    _ => label.push_str(", custom profile"),
                }
            }
            for &d in &plan.bat_dims {
                for (p, vals) in &plan.dims[d].params {
                    // (a profile is named above)
                    if is_bat_path(p)
                        && !p.starts_with("bat.profile")
                        && p != "bat.preset"
                        && !super::plan::is_unset(&vals[m[d]])
                    {
                        let v = super::coords::short_text(&vals[m[d]]);
                        label.push_str(&format!(", {p}={v}"));
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
    super::coords::complete_coords(&mut plan);
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
