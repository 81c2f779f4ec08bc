//! A study's `optimize` block checked and made usable: the design variables (their bounds,
//! start and units), how a design vector becomes a candidate's base parameters, the
//! objective and the limits. Every problem is a located error (file:line:column, field,
//! value, what is allowed), found before anything runs.

#![allow(clippy::result_large_err)] // StudyError: see study/mod.rs

use super::profile_design::{self, ProfileValues};
use super::profile_shape::{self, Shape};
use super::quantity::Quantity;
use super::rules::{rule_limits, Limit};
pub use super::variable::Variable;
use super::variable::{at, bounds_ok, located};
use crate::study::optimize_block::{Aggregate, Constraint, OptimizeBlock, OptimizeMethod};
use crate::study::paths::{known_paths, meta, set_path};
use crate::study::plan::related;
use crate::study::source::Seg;
use crate::study::{Study, StudyError};
use yaml_serde::{Mapping, Value};

/// The objective: a quantity, maximised or minimised, over the grid.
#[derive(Debug, Clone, PartialEq)]
pub struct Objective {
    pub quantity: Quantity,
    pub maximize: bool,
    pub over: Aggregate,
}

/// The optimisation a study asks for.
#[derive(Debug, Clone)]
pub struct Design {
    pub variables: Vec<Variable>,
    pub objective: Objective,
    pub limits: Vec<Limit>,
    pub block: OptimizeBlock,
    /// The profile's knot positions, fixed radii and fixed wall thicknesses (NaN where a
    /// variable; no thicknesses: the study's shell).
    profile: Option<ProfileValues>,
    /// The shape a profile keeps (`optimize.profile.shape`): None, radii free in their
    /// bounds and linear between knots.
    shape: Option<Shape>,
    /// The second objective of a two-objective search (`optimize.pareto`).
    pub pareto: Option<Pareto>,
    /// What this search minimises: the objective, or a Pareto front's second objective.
    pub searched: Searched,
}

/// The second objective of a two-objective search: a quantity, tracked as an unbounded
/// limit (its value is every candidate's), whose front against the objective is traced.
#[derive(Debug, Clone, PartialEq)]
pub struct Pareto {
    pub quantity: Quantity,
    pub maximize: bool,
    /// Searches of the front (at least its points).
    pub points: usize,
    /// Its index among the design's limits.
    pub limit: usize,
}

/// What a search minimises.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Searched {
    /// The objective (negated to maximise).
    Objective,
    /// A limit's value (a Pareto front's second objective, searched alone).
    Limit { index: usize, maximize: bool },
}

impl Design {
    /// The base parameters of the candidate `x` (one value per variable).
    pub fn apply(&self, x: &[f64], base: &Value) -> Value {
        let mut v = base.clone();
        for (var, &xi) in self.variables.iter().zip(x) {
            if var.knot.is_none() {
                let _ = set_path(&mut v, &var.name, Value::from(xi));
            }
        }
        if let Some((z, radius, wall)) = &self.profile {
            let (mut r, mut t) = (radius.clone(), wall.clone());
            for (var, &xi) in self.variables.iter().zip(x) {
                match (var.knot, var.wall, t.as_mut()) {
                    (Some(k), false, _) => r[k] = xi,
                    (Some(k), true, Some(t)) => t[k] = xi,
                    _ => {}
                }
            }
            let as_knots = |values: &[f64]| match self.shape {
                Some(_) => knot_list(&profile_shape::turned(z, values)),
                None => knots(z, values),
            };
            let mut m = Mapping::new();
            m.insert("knots".into(), as_knots(&r));
            let _ = set_path(&mut v, "bat.profile", Value::Mapping(m));
            if let Some(t) = t {
                let _ = set_path(&mut v, "bat.shell.thickness_knots", as_knots(&t));
            }
        }
        v
    }

    /// The start design: the start of every variable (with a profile shape, the start
    /// fractions placed as every candidate's are).
    pub fn start(&self) -> Vec<f64> {
        self.from_unit(&self.start_unit())
    }

    /// The start design as a point of the unit cube: each variable's start scaled by its
    /// bounds, or, with a profile shape, the free knots' places that give their start values
    /// (the nearest that keep the shape).
    pub fn start_unit(&self) -> Vec<f64> {
        let unit = |v: &Variable| (v.start - v.min) / (v.max - v.min);
        let mut u: Vec<f64> = self.variables.iter().map(unit).collect();
        for (z, fixed, wall, shape) in self.shaped_lists() {
            let (bounds, start) = self.knot_bounds(fixed, wall, |_, v| v.start);
            let places = profile_shape::fractions(z, &bounds, &start, &shape);
            self.write_knots(wall, &places, &mut u);
        }
        u
    }

    /// The design of a point `u` of the unit cube (each coordinate clamped to [0, 1]): each
    /// variable at that fraction of its bounds, or, with a profile shape, each free knot at
    /// that fraction of what its bounds and the shape leave it.
    pub fn from_unit(&self, u: &[f64]) -> Vec<f64> {
        let mut x: Vec<f64> = (self.variables.iter().zip(u))
            .map(|(v, &t)| v.min + (v.max - v.min) * t.clamp(0.0, 1.0))
            .collect();
        for (z, fixed, wall, shape) in self.shaped_lists() {
            let (bounds, places) = self.knot_bounds(fixed, wall, |i, _| u[i]);
            let values = profile_shape::place(z, &bounds, &places, &shape);
            self.write_knots(wall, &values, &mut x);
        }
        x
    }

    /// With a profile shape, the knot lists it shapes: (positions, fixed values, whether the
    /// list is the wall's, the shape it keeps; a wall's thickness need not rise).
    fn shaped_lists(&self) -> Vec<(&[f64], &[f64], bool, Shape)> {
        let (Some(shape), Some((z, radius, wall))) = (self.shape, &self.profile) else {
            return Vec::new();
        };
        let radii = Shape {
            max_slope: None,
            ..shape
        };
        let mut lists = vec![(z.as_slice(), radius.as_slice(), false, radii)];
        if let Some(wall) = wall {
            lists.push((z.as_slice(), wall.as_slice(), true, shape.for_wall()));
        }
        lists
    }

    /// One list's knots as bounds (a fixed knot's a point) and, per knot, `of` its variable
    /// (by the variable's index; 0 for a fixed knot).
    fn knot_bounds(
        &self,
        fixed: &[f64],
        wall: bool,
        of: impl Fn(usize, &Variable) -> f64,
    ) -> (Vec<(f64, f64)>, Vec<f64>) {
        let mut bounds: Vec<(f64, f64)> = fixed.iter().map(|&r| (r, r)).collect();
        let mut values = vec![0.0; fixed.len()];
        for (i, v) in self.variables.iter().enumerate() {
            if let (Some(k), true) = (v.knot, v.wall == wall) {
                (bounds[k], values[k]) = ((v.min, v.max), of(i, v));
            }
        }
        (bounds, values)
    }

    /// Per-knot values of one list written to its free knots' variables in `out`.
    fn write_knots(&self, wall: bool, per_knot: &[f64], out: &mut [f64]) {
        for (v, o) in self.variables.iter().zip(out.iter_mut()) {
            if let (Some(k), true) = (v.knot, v.wall == wall) {
                *o = per_knot[k];
            }
        }
    }
}

/// Knots `[[z, r], ...]` as a value.
fn knot_list(k: &[[f64; 2]]) -> Value {
    Value::Sequence(
        k.iter()
            .map(|&[z, r]| Value::Sequence(vec![Value::from(z), Value::from(r)]))
            .collect(),
    )
}

/// `[[z, r], ...]` as a value.
fn knots(z: &[f64], r: &[f64]) -> Value {
    let k: Vec<[f64; 2]> = z.iter().zip(r).map(|(&z, &r)| [z, r]).collect();
    knot_list(&k)
}

/// The study, its `optimize` block (if any) checked as `batstudy optimize` checks it.
pub fn checked(study: Study) -> Result<Study, StudyError> {
    design_of(&study)?;
    Ok(study)
}

/// The largest `optimize.tolerance`: a spread of a hundredth of the start's objective or of
/// a variable's span.
pub const MAX_TOLERANCE: f64 = 0.01;

/// The study's `optimize` block, checked (None: the study has none).
pub fn design_of(study: &Study) -> Result<Option<Design>, StudyError> {
    let Some(block) = study.file.optimize.clone() else {
        return Ok(None);
    };
    if block.max_evaluations == 0 || block.max_evaluations > 100_000 {
        return Err(located(
            study,
            &at(&["max_evaluations"]),
            "`optimize.max_evaluations` out of range".into(),
        )
        .field("optimize.max_evaluations")
        .value(block.max_evaluations.to_string())
        .allowed("1 to 100000 candidates"));
    }
    // both measures are relative (the objective over its start, the variables scaled to
    // [0, 1]): a tolerance near 1 stops a search at its first candidates
    if !(0.0..=MAX_TOLERANCE).contains(&block.tolerance) {
        return Err(located(
            study,
            &at(&["tolerance"]),
            "`optimize.tolerance` out of range".into(),
        )
        .field("optimize.tolerance")
        .value(crate::model::error::number_text(block.tolerance))
        .allowed(format!(
            "0 to {MAX_TOLERANCE} (a relative spread; default 1e-6)"
        )));
    }
    if block.seed.is_some() && block.method != OptimizeMethod::CmaEs {
        return Err(located(
            study,
            &at(&["seed"]),
            "`optimize.seed` is set, but Nelder–Mead draws no random numbers".into(),
        )
        .field("optimize.seed")
        .value(block.seed().to_string())
        .allowed("leave it out, or `method: cma_es`"));
    }
    let mut variables = path_variables(study, &block)?;
    let profile = match &block.profile {
        Some(p) => Some(profile_design::profile_variables(study, p, &mut variables)?),
        None => None,
    };
    let shape = match &block.profile {
        Some(p) => profile_design::shape_of(study, p, &variables)?,
        None => None,
    };
    if variables.is_empty() {
        return Err(located(study, &at(&["variables"]), "the optimize block has no design variable".into())
            .field("optimize.variables")
            .allowed("at least one `path: {min, max}` under `variables`, or a `profile` with a radius `{min, max}`"));
    }
    if block.max_evaluations <= variables.len() {
        return Err(located(
            study,
            &at(&["max_evaluations"]),
            format!(
                "`optimize.max_evaluations` is too small for {} design variables: the first simplex alone takes {}",
                variables.len(),
                variables.len() + 1
            ),
        )
        .field("optimize.max_evaluations")
        .value(block.max_evaluations.to_string())
        .allowed(format!(
            "at least {} (variables + 1) and at most 100000",
            variables.len() + 1
        )));
    }
    check_plausible_bounds(study, &variables)?;
    let objective = objective_of(study, &block)?;
    let mut limits = limits_of(study, &block)?;
    if swing_answers_to_the_bat(study) {
        limits.extend(super::rules::swing_law_limits());
    }
    let pareto = match &block.pareto {
        Some(p) => Some(pareto_of(study, p, &mut limits)?),
        None => None,
    };
    check_solid_wood(study, &block)?;
    let design = Design {
        variables,
        objective,
        limits,
        block,
        profile,
        shape,
        pareto,
        searched: Searched::Objective,
    };
    check_start(study, &design)?;
    Ok(Some(design))
}

/// Whether the study's batter swings each bat at a speed that answers to its moment of
/// inertia (a swing law with an exponent other than 0), read at its first point.
fn swing_answers_to_the_bat(study: &Study) -> bool {
    let plan = &study.plan;
    plan.resolve_over(plan.base(), &plan.shape().unravel(0))
        .ok()
        .and_then(|spec| spec.batter)
        .is_some_and(|b| b.exponent != 0.0)
}

/// `variables`: each a known numeric path no block varies, with sound bounds.
fn path_variables(study: &Study, block: &OptimizeBlock) -> Result<Vec<Variable>, StudyError> {
    let mut out = Vec::new();
    for (path, b) in &block.variables {
        let here = at(&["variables", path]);
        let numeric = known_paths().contains_key(path) && !meta(path).units.is_empty();
        if !numeric {
            return Err(
                located(study, &here, format!("`{path}` is not a numeric parameter"))
                    .field(format!("optimize.variables.{path}"))
                    .allowed(
                        "a dotted path of a number, e.g. bat.shell.thickness, bat.material.density",
                    ),
            );
        }
        if let Some(d) = study
            .plan
            .dims()
            .iter()
            .find(|d| d.params.iter().any(|(p, _)| related(p, path)))
        {
            return Err(located(
                study,
                &here,
                format!("`{path}` is also varied by dimension `{}`", d.name),
            )
            .field(format!("optimize.variables.{path}"))
            .allowed("a parameter no grid, zip or points block sets"));
        }
        let start = bounds_ok(b).map_err(|allowed| {
            located(study, &here, format!("bad bounds of `{path}`"))
                .field(format!("optimize.variables.{path}"))
                .value(format!(
                    "min {:?}, max {:?}, start {:?}",
                    b.min, b.max, b.start
                ))
                .allowed(allowed)
        })?;
        out.push(Variable {
            name: path.clone(),
            min: b.min,
            max: b.max,
            start,
            units: meta(path).units.to_string(),
            knot: None,
            wall: false,
        });
    }
    Ok(out)
}

fn quantity_of(
    study: &Study,
    name: &str,
    here: Vec<Seg>,
    field: &str,
) -> Result<Quantity, StudyError> {
    let q = Quantity::parse(name).ok_or_else(|| {
        located(study, &here, format!("unknown quantity `{name}`"))
            .field(field.to_string())
            .value(name.to_string())
            .allowed(Quantity::names().join(", "))
    })?;
    let has_z = study.plan.dims().iter().any(|d| d.name == "impact_z");
    if matches!(q, Quantity::Sweet(_)) && !has_z {
        return Err(located(
            study,
            &here,
            format!("`{name}` needs an `impact_z` dimension"),
        )
        .field(field.to_string())
        .value(name.to_string())
        .allowed("a sweet-spot quantity in a study with a grid axis `impact.z`"));
    }
    Ok(q)
}

fn objective_of(study: &Study, block: &OptimizeBlock) -> Result<Objective, StudyError> {
    let o = &block.objective;
    let (name, maximize, key) = match (&o.maximize, &o.minimize) {
        (Some(n), None) => (n, true, "maximize"),
        (None, Some(n)) => (n, false, "minimize"),
        _ => {
            return Err(located(
                study,
                &at(&["objective"]),
                "the objective needs exactly one of `maximize` and `minimize`".into(),
            )
            .field("optimize.objective")
            .allowed("{maximize: QUANTITY} or {minimize: QUANTITY}"))
        }
    };
    let quantity = quantity_of(
        study,
        name,
        at(&["objective", key]),
        &format!("optimize.objective.{key}"),
    )?;
    check_over(
        study,
        &at(&["objective", "over"]),
        "optimize.objective",
        o.over,
    )?;
    Ok(Objective {
        quantity,
        maximize,
        over: o.over,
    })
}

fn limits_of(study: &Study, block: &OptimizeBlock) -> Result<Vec<Limit>, StudyError> {
    let mut out = Vec::new();
    for (i, c) in block.constraints.iter().enumerate() {
        let mut here = at(&["constraints"]);
        here.push(Seg::Index(i));
        match c {
            Constraint::Rules(r) => {
                if r.moi_min.is_some_and(|m| m.is_nan() || m <= 0.0) {
                    return Err(located(study, &here, "`moi_min` must be > 0".into())
                        .field(format!("optimize.constraints[{i}].moi_min"))
                        .allowed("a moment of inertia in kg m^2, > 0"));
                }
                out.extend(rule_limits(r.rules, r.moi_min));
            }
            Constraint::Bound(b) => {
                let mut qat = here.clone();
                qat.push(Seg::Key("quantity".into()));
                let field = format!("optimize.constraints[{i}]");
                let quantity = quantity_of(study, &b.quantity, qat, &field)?;
                if b.min.is_none() && b.max.is_none()
                    || b.min.zip(b.max).is_some_and(|(a, m)| a > m)
                {
                    return Err(located(
                        study,
                        &here,
                        format!("the constraint on `{}` needs a bound", b.quantity),
                    )
                    .field(field)
                    .allowed("`min`, `max` or both (min <= max)"));
                }
                out.push(Limit {
                    quantity,
                    min: b.min,
                    max: b.max,
                    over: bound_over(study, &here, &field, b)?,
                    source: "study".into(),
                });
            }
        }
    }
    Ok(out)
}

/// `pareto`: one quantity to minimise or maximise, 3 to 50 points; tracked as a limit
/// without bounds (appended to `limits`).
fn pareto_of(
    study: &Study,
    p: &crate::study::optimize_block::ParetoBlock,
    limits: &mut Vec<Limit>,
) -> Result<Pareto, StudyError> {
    let (name, maximize, key) = match (&p.minimize, &p.maximize) {
        (Some(n), None) => (n, false, "minimize"),
        (None, Some(n)) => (n, true, "maximize"),
        _ => {
            return Err(located(
                study,
                &at(&["pareto"]),
                "the second objective needs exactly one of `minimize` and `maximize`".into(),
            )
            .field("optimize.pareto")
            .allowed("{minimize: QUANTITY, points: N} or {maximize: QUANTITY, points: N}"))
        }
    };
    let field = format!("optimize.pareto.{key}");
    let quantity = quantity_of(study, name, at(&["pareto", key]), &field)?;
    if !(3..=50).contains(&p.points) {
        return Err(located(
            study,
            &at(&["pareto", "points"]),
            "bad number of points".into(),
        )
        .field("optimize.pareto.points")
        .value(p.points.to_string())
        .allowed("3 to 50 searches"));
    }
    limits.push(Limit {
        quantity,
        min: None,
        max: None,
        over: Aggregate::Mean,
        source: "pareto".into(),
    });
    Ok(Pareto {
        quantity,
        maximize,
        points: p.points,
        limit: limits.len() - 1,
    })
}

/// How a bound's quantity over the grid becomes one number: `over` as written, a
/// probability's quantile (P(Q ≤ b) ≥ p is the p-quantile ≤ b; P(Q ≥ a) ≥ p the upper
/// p-quantile ≥ a), or the worst case.
fn bound_over(
    study: &Study,
    here: &[Seg],
    field: &str,
    b: &crate::study::optimize_block::QuantityBound,
) -> Result<Aggregate, StudyError> {
    let bad = |msg: &str, value: String, allowed: &str| {
        located(study, here, msg.to_string())
            .field(format!("{field}.probability"))
            .value(value)
            .allowed(allowed.to_string())
    };
    if let Some(over) = b.over {
        check_over(study, here, field, over)?;
    }
    let Some(p) = b.probability else {
        let worst = if b.max.is_some() {
            Aggregate::Max
        } else {
            Aggregate::Min
        };
        return Ok(b.over.unwrap_or(worst));
    };
    if !(p > 0.0 && p <= 1.0) {
        return Err(bad(
            "bad probability",
            p.to_string(),
            "a probability 0 < p <= 1",
        ));
    }
    match (b.min, b.max, b.over) {
        (_, _, Some(_)) => Err(bad(
            "a constraint with a `probability` has no `over`",
            p.to_string(),
            "either `probability` or `over`",
        )),
        (Some(_), Some(_), _) => Err(bad(
            "a constraint with a `probability` has one bound",
            p.to_string(),
            "`min` or `max`, not both (two constraints for two bounds)",
        )),
        (None, Some(_), _) => Ok(Aggregate::Quantile(p)),
        _ => Ok(Aggregate::UpperQuantile(p)),
    }
}

/// A quantile's fraction within (0, 1].
fn check_over(study: &Study, here: &[Seg], field: &str, over: Aggregate) -> Result<(), StudyError> {
    match over {
        Aggregate::Quantile(q) if !(q > 0.0 && q <= 1.0) => {
            Err(located(study, here, "bad quantile".into())
                .field(format!("{field}.over.quantile"))
                .value(q.to_string())
                .allowed("a fraction 0 < q <= 1"))
        }
        _ => Ok(()),
    }
}

/// `mlb_wood`: one piece of solid wood, so no shell, bore or fill anywhere.
fn check_solid_wood(study: &Study, block: &OptimizeBlock) -> Result<(), StudyError> {
    let mlb = block.constraints.iter().position(|c| {
        matches!(c, Constraint::Rules(r) if r.rules == crate::study::optimize_block::RuleSet::MlbWood)
    });
    let Some(i) = mlb else { return Ok(()) };
    let zero = vec![0; study.plan.dims().len()];
    let Ok(spec) = study.plan.resolve(&zero) else {
        return Ok(());
    };
    if !spec.bat.is_solid_wood() {
        let mut here = at(&["constraints"]);
        here.push(Seg::Index(i));
        return Err(located(
            study,
            &here,
            "`mlb_wood` needs a bat of one piece of solid wood".into(),
        )
        .field("base.bat")
        .value(format!("{:?}", spec.bat.preset).to_lowercase())
        .allowed("bat.preset r161 (wood) without shell, bore or fill"));
    }
    Ok(())
}

/// Each variable's bounds within its parameter's plausible range (a knot's radius within a
/// bat's), unless the study allows implausible values: a search would otherwise spend its
/// whole budget on candidates every point of which is refused.
fn check_plausible_bounds(study: &Study, variables: &[Variable]) -> Result<(), StudyError> {
    if study.file.allow_implausible {
        return Ok(());
    }
    for v in variables {
        let range = match v.knot {
            Some(_) if v.wall => crate::model::plausible::range_of("bat.shell.thickness"),
            Some(_) => crate::model::plausible::range_of(crate::model::plausible::PROFILE_RADIUS),
            None => crate::model::plausible::range_of(&v.name),
        };
        let Some(r) = range else { continue };
        if v.min < r.min || v.max > r.max {
            let here = match v.knot {
                Some(_) if v.wall => at(&["profile", "thickness"]),
                Some(_) => at(&["profile", "radius"]),
                None => at(&["variables", &v.name]),
            };
            return Err(located(
                study,
                &here,
                format!("the bounds of `{}` leave its plausible range", v.name),
            )
            .field(format!("optimize.variables.{}", v.name))
            .value(format!("min {:?}, max {:?}", v.min, v.max))
            .allowed(format!(
                "bounds within {} to {} {} ({}); a what-if study beyond it sets `allow_implausible: true`",
                r.min, r.max, r.unit, r.reason
            )));
        }
    }
    Ok(())
}

/// The start design must resolve at every point of the study's grid.
fn check_start(study: &Study, design: &Design) -> Result<(), StudyError> {
    let base = design.apply(&design.start(), study.plan.base());
    let n = study.plan.n_points().min(crate::study::FULL_CHECK_LIMIT);
    for flat in 0..n {
        let m = study.plan.shape().unravel(flat);
        if let Err(e) = study.plan.resolve_over(&base, &m) {
            return Err(located(
                study,
                &at(&["variables"]),
                format!("the start design does not make a valid collision: {e}"),
            )
            .field("optimize")
            .allowed("start values (and fixed knots) that give a valid bat at every point"));
        }
    }
    // and the whole study at the start, as the search's last run loads it
    let max_points = study.plan.n_points().max(1);
    super::at_design::study_at(study, design, &design.start(), max_points).map(|_| ())
}
