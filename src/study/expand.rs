//! The blocks (`grid`, `zip`, `points`) → the dimensions of one Cartesian product → the lazy
//! `Plan`: sizes, profiles, distinct bats, and every value checked against the base.

use super::error::StudyError;
use super::history_only::check_history_only;
use super::history_size::check_history_size;
use super::locate::{dim_elem, located, written_at, Ctx};
use super::paths::{coord_name, set_path, with_defaults};
use super::plan::{
    bat_key, dim_to_shape, is_bat_path, related, value_text, BatChoice, DimOrigin, Plan, PlanDim,
};
use super::source::{keys, Seg};
use super::syntax::{check_base_types, check_param_keys, check_path};
use super::types::{AxisValues, StudyFile};
use crate::results::ResultShape;
use crate::results::{is_reserved, reserved_names};
use std::collections::HashMap;
use std::path::Path;
use yaml_serde::{Mapping, Value};

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
    let base = base_value(cx, file)?;
    let mut names = AutoNames::default();
    let mut dims = grid_dims(cx, file)?;
    dims.extend(zip_dims(cx, file, &mut names)?);
    dims.extend(points_dim(cx, file, &mut names)?);
    dims.extend(super::sample_dim::sample_dim(cx, file)?);
    check_one_block_per_path(cx, file, &dims)?;
    let n = check_size(cx, file, &dims, opts)?;
    let defaults = with_defaults(&base);
    let mut shape = ResultShape {
        dims: dims.iter().map(|d| dim_to_shape(d, &defaults)).collect(),
    };
    k1_units_with_the_power(&mut shape, &dims, &defaults);
    check_stored_names(cx, file, &dims, &shape)?;
    let profiles = load_profiles(cx, file, &base, &dims)?;
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
    let mut unused = check_axis_values(cx, file, &plan)?;
    distinct_bats(cx, file, &mut plan)?;
    super::coords::complete_coords(&mut plan);
    // again with the coordinates just derived (`<dim>_label`, a record's fields), which
    // may meet a name the study gave
    check_stored_names(cx, file, &plan.dims, &plan.shape)?;
    if n <= FULL_CHECK_LIMIT {
        check_every_point(cx, file, &mut plan, &mut unused)?;
    }
    check_unused(cx, file, &plan, &unused)?;
    check_history_size(cx, file, &plan)?;
    if file.history.as_ref().is_some_and(|h| !h.fields.is_empty()) {
        check_history_only(cx, file, &plan)?;
    }
    Ok(plan)
}

/// The `base` block with the top-level `model` merged in.
fn base_value(cx: &Ctx, file: &StudyFile) -> Result<Value, StudyError> {
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
            let bm: Option<crate::model::spec::ModelKind> = yaml_serde::from_value(bm.clone()).ok();
            if bm.is_some() && bm != Some(m) {
                return Err(cx
                    .err(&keys(&["model"]), "`model` and `base.model` disagree")
                    .field("model")
                    .value(format!("{m:?}").to_lowercase())
                    .allowed("one of them, or both the same"));
            }
        }
        let _ = set_path(&mut base, "model", yaml_serde::to_value(m).unwrap());
    }
    Ok(base)
}

/// One dimension per `grid` axis.
fn grid_dims(cx: &Ctx, file: &StudyFile) -> Result<Vec<PlanDim>, StudyError> {
    let mut dims = Vec::new();
    for (key, axis) in &file.grid {
        let at = keys(&["grid", key]);
        check_path(cx, key, &at)?;
        let values = axis.values().map_err(|e| {
            cx.err(&at, e.clone())
                .field(format!("grid.{key}"))
                .value(axis_text(axis))
                .allowed(
                    "a non-empty list, {linspace: [start, stop, n]}, {range: [start, stop, step]}",
                )
        })?;
        if let Some(v) = repeated(&values) {
            return Err(cx
                .err(&at, format!("`grid.{key}` lists a value twice"))
                .field(format!("grid.{key}"))
                .value(value_text(v))
                .allowed("each value once: a coordinate that repeats makes its points ambiguous (selection, the sweet spot along the axis)"));
        }
        dims.push(PlanDim {
            name: coord_name(key),
            size: values.len(),
            params: vec![(key.clone(), values)],
            origin: DimOrigin::Grid { key: key.clone() },
        });
    }
    Ok(dims)
}

/// A value an axis lists twice (numbers equal as `same_value` takes them), if any.
fn repeated(values: &[Value]) -> Option<&Value> {
    let mut numbers: Vec<(f64, &Value)> = values
        .iter()
        .filter_map(|v| v.as_f64().map(|x| (x, v)))
        .collect();
    numbers.sort_by(|a, b| a.0.total_cmp(&b.0));
    let twice = numbers
        .windows(2)
        .find(|w| super::plan::same_value(w[0].1, w[1].1))
        .map(|w| w[1].1);
    let mut texts = std::collections::HashSet::new();
    twice.or_else(|| {
        values
            .iter()
            .filter(|v| v.as_f64().is_none())
            .find(|v| !texts.insert(value_text(v)))
    })
}

fn axis_text(axis: &AxisValues) -> String {
    match axis {
        AxisValues::List(v) => format!("{} values", v.len()),
        AxisValues::Linspace { start, stop, n } => {
            format!("{{linspace: [{start}, {stop}, {n}]}}")
        }
        AxisValues::Range { start, stop, step } => {
            format!("{{range: [{start}, {stop}, {step}]}}")
        }
    }
}

/// The names of unnamed `zip`/`points` dimensions: `point`, `point_2`, `point_3`, …
#[derive(Default)]
struct AutoNames {
    given: usize,
}

impl AutoNames {
    fn next(&mut self, explicit: Option<&String>) -> String {
        if let Some(n) = explicit {
            return n.clone();
        }
        self.given += 1;
        match self.given {
            1 => "point".to_string(),
            k => format!("point_{k}"),
        }
    }
}

/// One dimension per `zip` group: lists of one length, varied together.
fn zip_dims(cx: &Ctx, file: &StudyFile, names: &mut AutoNames) -> Result<Vec<PlanDim>, StudyError> {
    let mut dims = Vec::new();
    for (g, group) in file.zip.iter().enumerate() {
        let at = vec![Seg::Key("zip".into()), Seg::Index(g)];
        let mut len: Option<(&String, usize)> = None;
        for (path, vals) in &group.params {
            let mut p = at.clone();
            p.push(Seg::Key(path.clone()));
            check_path(cx, path, &p)?;
            if let Some((first, n)) = len.filter(|&(_, n)| n != vals.len()) {
                return Err(cx
                    .err(
                        &p,
                        format!(
                            "zip lists differ in length: `{first}` has {n} values, `{path}` has {}",
                            vals.len()
                        ),
                    )
                    .field(format!("zip[{g}].{path}"))
                    .value(format!("{} values", vals.len()))
                    .allowed(format!("{n} values, like `{first}`")));
            }
            len.get_or_insert((path, vals.len()));
            if vals.is_empty() {
                return Err(cx
                    .err(&p, "empty zip list")
                    .field(format!("zip[{g}].{path}"))
                    .allowed("at least one value"));
            }
        }
        dims.push(PlanDim {
            name: names.next(group.name.as_ref()),
            size: len.map_or(0, |l| l.1),
            params: group.params.clone().into_iter().collect(),
            origin: DimOrigin::Zip { group: g },
        });
    }
    Ok(dims)
}

/// The `points` block's dimension: one index per parameter set.
fn points_dim(
    cx: &Ctx,
    file: &StudyFile,
    names: &mut AutoNames,
) -> Result<Option<PlanDim>, StudyError> {
    let Some(block) = &file.points else {
        return Ok(None);
    };
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
    Ok(Some(PlanDim {
        name: names.next(block.name()),
        size: points.len(),
        params,
        origin: DimOrigin::Points,
    }))
}

/// Each parameter is set by one block only.
fn check_one_block_per_path(
    cx: &Ctx,
    file: &StudyFile,
    dims: &[PlanDim],
) -> Result<(), StudyError> {
    let mut seen: Vec<(&String, &String)> = Vec::new();
    for d in dims {
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
            seen.push((p, &d.name));
        }
    }
    Ok(())
}

/// The number of points: at least one, at most `opts.max_points`.
fn check_size(
    cx: &Ctx,
    file: &StudyFile,
    dims: &[PlanDim],
    opts: &LoadOptions,
) -> Result<usize, StudyError> {
    let n = dims.iter().fold(1usize, |n, d| n.saturating_mul(d.size));
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
    Ok(n)
}

/// Where a dimension's name is written (or, unnamed, its block).
fn dim_name_at(d: &PlanDim, file: &StudyFile) -> Vec<Seg> {
    match &d.origin {
        DimOrigin::Grid { key } => keys(&["grid", key]),
        DimOrigin::Zip { group } => {
            let mut at = vec![Seg::Key("zip".into()), Seg::Index(*group)];
            if file.zip[*group].name.is_some() {
                at.push(Seg::Key("name".into()));
            }
            at
        }
        DimOrigin::Points => match file.points.as_ref().and_then(|b| b.name()) {
            Some(_) => keys(&["points", "name"]),
            None => keys(&["points"]),
        },
        DimOrigin::Sample => match file.sample.as_ref().and_then(|b| b.name.as_ref()) {
            Some(_) => keys(&["sample", "name"]),
            None => keys(&["sample"]),
        },
    }
}

/// Dimension and coordinate names become variable names in the results file: each is a
/// plain name (letters, digits, `_`, `-`, `.`, not starting with `.`), used once, and none
/// is a name the file gives its own variables (`exit_speed`, `status`, `a/b` or an empty
/// name would pass validation, then fail the run after every point was computed).
fn check_stored_names(
    cx: &Ctx,
    file: &StudyFile,
    dims: &[PlanDim],
    shape: &ResultShape,
) -> Result<(), StudyError> {
    let mut seen: HashMap<&str, &str> = HashMap::new();
    for (d, sd) in dims.iter().zip(&shape.dims) {
        // a grid axis's coordinate has its dimension's name (its dimension scale)
        let coords = sd.coords.iter().map(|c| &c.name).filter(|&n| *n != sd.name);
        for name in std::iter::once(&sd.name).chain(coords) {
            let problem = if !plain_name(name) {
                Some("a name of letters, digits, `_`, `-`, `.` (not starting with `.`)".to_string())
            } else if is_reserved(name) {
                Some(format!(
                    "a name the results file does not use for its own variables ({})",
                    reserved_names().collect::<Vec<_>>().join(", ")
                ))
            } else {
                seen.insert(name, &d.name)
                    .map(|other| format!("a name not already used (dimension `{other}` uses it)"))
            };
            if let Some(allowed) = problem {
                let what = match name == &d.name {
                    true => format!("a dimension cannot be named `{name}`"),
                    false => format!("dimension `{}` cannot have a coordinate `{name}`", d.name),
                };
                return Err(cx
                    .err(&dim_name_at(d, file), what)
                    .field(format!("name of dimension `{}`", d.name))
                    .value(name.clone())
                    .allowed(allowed));
            }
        }
    }
    Ok(())
}

fn plain_name(name: &str) -> bool {
    !name.is_empty()
        && !name.starts_with('.')
        && name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || "_-.".contains(c))
}

/// The profiles (`bat.profile.csv`) named in `base` or by any block value, read once each.
fn load_profiles(
    cx: &Ctx,
    file: &StudyFile,
    base: &Value,
    dims: &[PlanDim],
) -> Result<HashMap<String, super::profile::ProfileTable>, StudyError> {
    let dir = cx.file.parent().map(Path::to_path_buf).unwrap_or_default();
    let mut profiles = HashMap::new();
    let mut load = |f: &str, at: Vec<Seg>| -> Result<(), StudyError> {
        if profiles.contains_key(f) {
            return Ok(());
        }
        let k = super::profile::load_profile_csv(&dir.join(f)).map_err(|e| {
            cx.err(&at, e)
                .field("bat.profile.csv")
                .value(f.to_string())
                .allowed("a readable CSV with header `z,radius` (m; or `z_mm,radius_mm`, `z_in,radius_in`; an optional `wall` column) or `slice_end_cm,diameter_mm`, relative to the study file")
        })?;
        profiles.insert(f.to_string(), k);
        Ok(())
    };
    if let Some(Value::String(f)) = super::paths::get_path(base, "bat.profile.csv") {
        load(f, keys(&["base", "bat", "profile", "csv"]))?;
    }
    for d in dims {
        for (p, vals) in &d.params {
            for (i, v) in vals.iter().enumerate() {
                let mut probe = Value::Mapping(Mapping::new());
                let _ = set_path(&mut probe, p, v.clone());
                if let Some(Value::String(f)) = super::paths::get_path(&probe, "bat.profile.csv") {
                    load(f, dim_elem(file, d, p, i))?;
                }
            }
        }
    }
    Ok(profiles)
}

/// Every axis value against the base, one dimension at a time; returns the tally of
/// fields the checked points use.
fn check_axis_values(
    cx: &Ctx,
    file: &StudyFile,
    plan: &Plan,
) -> Result<super::unused::Tally, StudyError> {
    let zero = vec![0usize; plan.dims.len()];
    if let Err(e) = plan.resolve(&zero) {
        return Err(located(cx, file, plan, &zero, None, e));
    }
    let mut unused = super::unused::Tally::new();
    unused.add(&plan.value_at(&zero));
    for d in 0..plan.dims.len() {
        for i in 1..plan.dims[d].size {
            let mut m = zero.clone();
            m[d] = i;
            if let Err(e) = plan.resolve(&m) {
                return Err(located(cx, file, plan, &m, Some(d), e));
            }
            unused.add(&plan.value_at(&m));
        }
    }
    Ok(unused)
}

/// The distinct bats (bat + numerics) of every combination of the bat dimensions.
fn distinct_bats(cx: &Ctx, file: &StudyFile, plan: &mut Plan) -> Result<(), StudyError> {
    let combos = plan
        .bat_dims
        .iter()
        .fold(1usize, |c, &d| c.saturating_mul(plan.dims[d].size));
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
        let mut m = vec![0usize; plan.dims.len()];
        let mut rest = c;
        for &d in plan.bat_dims.iter().rev() {
            m[d] = rest % plan.dims[d].size;
            rest /= plan.dims[d].size;
        }
        let spec = plan
            .resolve(&m)
            .map_err(|e| located(cx, file, plan, &m, None, e))?;
        let key = bat_key(&spec.bat, &spec.numerics);
        let idx = match by_key.get(&key) {
            Some(&i) => i,
            None => {
                let i = plan.bats.len() as u32;
                plan.bats.push(BatChoice {
                    label: bat_label(plan, &m, &spec),
                    key: key.clone(),
                    bat: spec.bat.clone(),
                    numerics: spec.numerics.clone(),
                    shot: crate::model::measures::metrics::BbcorShot::of(&spec),
                });
                by_key.insert(key, i);
                i
            }
        };
        bat_of_combo.push(idx);
    }
    plan.bat_of_combo = bat_of_combo;
    Ok(())
}

/// A bat's short label: its preset, its own profile, and the bat values its dimensions set.
fn bat_label(plan: &Plan, m: &[usize], spec: &crate::model::spec::CollisionSpec) -> String {
    // the preset as a study names it (`alloy_bbcor`)
    let mut label = serde_json::to_value(spec.bat.preset)
        .ok()
        .and_then(|v| v.as_str().map(str::to_string))
        .unwrap_or_default();
    // a profile of the user's own is part of what the bat is
    if spec.bat.profile.is_some() {
        match super::paths::get_path(&plan.value_at(m), "bat.profile.csv") {
            Some(Value::String(f)) => label.push_str(&format!(", profile {f}")),
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
    label
}

/// Small plans: every point resolved and checked, and the exact number of histories.
fn check_every_point(
    cx: &Ctx,
    file: &StudyFile,
    plan: &mut Plan,
    unused: &mut super::unused::Tally,
) -> Result<(), StudyError> {
    let wants_history = file.history.as_ref().is_some_and(|h| !h.fields.is_empty());
    let mut histories = 0usize;
    for flat in 0..plan.n_points() {
        let m = plan.shape.unravel(flat);
        let spec = plan
            .resolve(&m)
            .map_err(|e| located(cx, file, plan, &m, None, e))?;
        if wants_history
            && spec.model == crate::model::spec::ModelKind::Wave
            && plan.records_history(&spec)
        {
            histories += 1;
            check_displacement_form(cx, file, plan, flat, &spec)?;
        }
        unused.add(&plan.value_at(&m));
    }
    if wants_history {
        plan.history_count = Some(histories);
    }
    Ok(())
}

/// The displacement's modal form is the modal integrator's state: a point that
/// records it with the Verlet integrator is refused, naming the point.
fn check_displacement_form(
    cx: &Ctx,
    file: &StudyFile,
    plan: &Plan,
    flat: usize,
    spec: &crate::model::spec::CollisionSpec,
) -> Result<(), StudyError> {
    use crate::model::outcome::{HistoryDisplacement, HistoryField};
    let Some(h) = &file.history else {
        return Ok(());
    };
    if h.displacement != HistoryDisplacement::Modal
        || !h.fields.contains(&HistoryField::Displacement)
        || spec.numerics.integrator != crate::model::spec::Integrator::Verlet
    {
        return Ok(());
    }
    Err(cx
        .err(
            &keys(&["history"]),
            format!(
                "point {} records the displacement in modal form with the Verlet integrator, which has no modes",
                plan.describe(flat)
            ),
        )
        .field("history.displacement")
        .value("modal")
        .allowed("grid, for a study with the Verlet integrator (`history.displacement: grid`)"))
}

/// A field set where no point uses it is an error (it would silently do nothing).
fn check_unused(
    cx: &Ctx,
    file: &StudyFile,
    plan: &Plan,
    unused: &super::unused::Tally,
) -> Result<(), StudyError> {
    if let Some(i) = file.history.as_ref().and_then(|h| {
        h.fields
            .iter()
            .position(|f| *f == crate::model::outcome::HistoryField::Trajectory)
    }) {
        if !unused.flies {
            return Err(cx
                .err(
                    &[
                        Seg::Key("history".into()),
                        Seg::Key("fields".into()),
                        Seg::Index(i),
                    ],
                    "`trajectory` is asked for, but no point of the study flies its batted ball",
                )
                .field(format!("history.fields[{i}]"))
                .value("trajectory")
                .allowed("a `flight` block (in base or a block), or leave `trajectory` out"));
        }
    }
    let Some(rule) = unused.unused() else {
        return Ok(());
    };
    Err(cx
        .err(
            &written_at(file, plan, rule.field),
            format!(
                "`{}` is set, but no point of the study uses it: it is used only {}",
                rule.field, rule.used_when
            ),
        )
        .field(rule.field)
        .allowed(format!("leave it out (it is used only {})", rule.used_when)))
}

/// The loading coefficient `ball.law.k1` is in N/m^α: where every point has the same α (the
/// study sets it and sweeps it nowhere), its coordinate's units carry that power, `N m^-1.5`,
/// which unit libraries (pint, UDUNITS) parse; where α varies the units stay `N m^-alpha`.
fn k1_units_with_the_power(shape: &mut ResultShape, dims: &[PlanDim], defaults: &Value) {
    const ALPHA: &str = "ball.law.alpha";
    let swept = dims
        .iter()
        .any(|d| d.params.iter().any(|(p, _)| p == ALPHA));
    let alpha = super::paths::get_path(defaults, ALPHA).and_then(Value::as_f64);
    let (false, Some(alpha)) = (swept, alpha) else {
        return;
    };
    for coord in shape.dims.iter_mut().flat_map(|d| d.coords.iter_mut()) {
        if coord.path == "ball.law.k1" && !coord.units.is_empty() {
            coord.units = format!("N m^-{alpha}");
        }
    }
}
