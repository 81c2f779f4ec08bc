//! The `optimize` block as written: design variables, an objective over the
//! study's other dimensions, constraints and the built-in rule sets. `batstudy optimize`
//! (`crate::optimize`) runs it; these are only the file's types and their schema.

use indexmap::IndexMap;
use schemars::JsonSchema;
use serde::Deserialize;

/// A design search: `batstudy optimize STUDY` varies the design variables within their
/// bounds to maximise or minimise the objective subject to the constraints. Every other
/// block of the study (`grid`, `zip`, `points`) is the grid each candidate is evaluated on.
#[derive(Debug, Clone, PartialEq, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct OptimizeBlock {
    /// The optimiser: `nelder_mead` (argmin's Nelder–Mead simplex, the default) or `cma_es`
    /// (the covariance matrix adaptation evolution strategy).
    #[serde(default)]
    pub method: OptimizeMethod,
    /// The seed of `cma_es`'s random numbers (the same seed asks for the same candidates).
    /// Default 1. Only with `method: cma_es` (Nelder–Mead draws no random numbers).
    #[serde(default)]
    pub seed: Option<u64>,
    /// Most candidates evaluated (1 to 100000). Default 300.
    #[serde(default = "default_max_evaluations")]
    pub max_evaluations: usize,
    /// Stop when the standard deviation over the simplex of what the search minimises (the
    /// objective over its magnitude at the start design, plus the penalties) falls below
    /// this (`cma_es`: when its step size along its longest axis, in the variables scaled to
    /// [0, 1], does). Default 1e-6.
    #[serde(default = "default_tolerance")]
    pub tolerance: f64,
    /// Numeric parameters varied: dotted path → `{min, max, start}` (`start` defaults to
    /// the middle of the bounds). Each path must be a number the study does not vary
    /// otherwise.
    #[serde(default)]
    pub variables: IndexMap<String, Bounds>,
    /// A bat profile whose knot radii are variables (`bat.profile.knots` of every
    /// candidate).
    #[serde(default)]
    pub profile: Option<ProfileDesign>,
    /// What to maximise or minimise.
    pub objective: Objective,
    /// A second objective, for the front of designs that trade one against the other
    /// (`{minimize: bat.moment_of_inertia_knob6, points: 5}`: lab exit speed against swing
    /// weight). Default: none (one objective).
    #[serde(default)]
    pub pareto: Option<ParetoBlock>,
    /// Bounds on stored quantities, and rule sets by name (`{rules: ncaa_bbcor}`).
    #[serde(default)]
    pub constraints: Vec<Constraint>,
}

fn default_max_evaluations() -> usize {
    300
}
/// `cma_es`'s seed when the block sets none.
pub const DEFAULT_SEED: u64 = 1;

impl OptimizeBlock {
    /// The seed of `cma_es`'s random numbers.
    pub fn seed(&self) -> u64 {
        self.seed.unwrap_or(DEFAULT_SEED)
    }
}
fn default_tolerance() -> f64 {
    1e-6
}

/// The optimiser.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum OptimizeMethod {
    /// Nelder–Mead simplex (argmin), on the variables scaled to [0, 1] by their bounds.
    #[default]
    NelderMead,
    /// CMA-ES (Hansen's (μ/μ_w, λ) strategy), on the same scaled variables: for rugged or
    /// noisy objectives; seeded by `seed`.
    #[serde(rename = "cma_es")]
    CmaEs,
}

/// The second objective of a two-objective search (`optimize.pareto`): the front of the
/// objective against it, traced by the ε-constraint method (one search for each objective
/// alone, then `points` − 2 searches of the objective with the second capped at even steps
/// between the two).
#[derive(Debug, Clone, PartialEq, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ParetoBlock {
    /// The quantity to minimise as the second objective (as the objective's names).
    #[serde(default)]
    pub minimize: Option<String>,
    /// The quantity to maximise as the second objective.
    #[serde(default)]
    pub maximize: Option<String>,
    /// Searches, hence points of the front at least (3 to 50). Default 5.
    #[serde(default = "default_pareto_points")]
    pub points: usize,
}

fn default_pareto_points() -> usize {
    5
}

/// Bounds of a design variable.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Bounds {
    pub min: f64,
    pub max: f64,
    /// First guess. Default: the middle of the bounds.
    #[serde(default)]
    pub start: Option<f64>,
}

/// A knot's radius: a fixed number, or a variable with bounds.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, JsonSchema)]
#[serde(untagged)]
pub enum Knot {
    Fixed(f64),
    Free(Bounds),
}

/// A profile design: knots at fixed positions whose radii may be variables.
#[derive(Debug, Clone, PartialEq, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ProfileDesign {
    /// Knot positions, m from the knob, increasing from 0.
    pub z: Vec<f64>,
    /// Outer radius at each knot, m: a number (fixed) or `{min, max, start}` (a variable).
    pub radius: Vec<Knot>,
    /// A hollow bat's wall thickness at each knot, m (fixed or a variable), linear between
    /// knots (`bat.shell.thickness_knots` of every candidate). Default: the study's shell.
    #[serde(default)]
    pub thickness: Option<Vec<Knot>>,
    /// A profile a lathe can turn: every candidate's radii (and wall thicknesses) are the
    /// shape-preserving cubic (PCHIP) through its knots, sampled every 5 mm, the radii never
    /// falling over `rising` and the knots' curvature at most `max_curvature`. Default: none
    /// (the radii free within their bounds, linear between knots).
    #[serde(default)]
    pub shape: Option<ProfileShape>,
}

/// The shape every candidate profile keeps (`optimize.profile.shape`).
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ProfileShape {
    /// `[z_start, z_end]`, m from the knob: the radius never falls from one knot to the next
    /// within this span (the taper and the barrel). Default: no such span.
    #[serde(default)]
    pub rising: Option<[f64; 2]>,
    /// The largest curvature |d²r/dz²| of the parabola through any three neighbouring knots,
    /// 1/m (> 0). Default: unbounded.
    #[serde(default)]
    pub max_curvature: Option<f64>,
    /// The largest change of a hollow bat's wall thickness between neighbouring knots per
    /// metre between them, m/m (> 0; `optimize.profile.thickness` needed): a wall a maker can
    /// draw, without a thin band beside a thick one. Default: unbounded.
    #[serde(default)]
    pub max_wall_slope: Option<f64>,
}

/// How a quantity over the study's grid becomes one number.
#[derive(Debug, Clone, Copy, PartialEq, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Aggregate {
    /// The mean over the grid's points (or curves, for sweet-spot quantities).
    Mean,
    /// The smallest value.
    Min,
    /// The largest value.
    Max,
    /// `{quantile: q}` (0 < q ≤ 1): the smallest value v with at least a fraction q of the
    /// values at or below it (the inverse of the values' distribution function; over a
    /// `sample`, e.g. the exit speed 95 % of the sampled balls reach is `{quantile: 0.05}`).
    Quantile(f64),
    /// The largest value v with at least a fraction p of the values at or above it: how a
    /// constraint `{min: a, probability: p}` is checked (not written in a study).
    #[serde(skip)]
    #[schemars(skip)]
    UpperQuantile(f64),
}

/// `mean`, `min`, `max` or `{quantile: q}` (a YAML map, as the schema says; the YAML
/// library would otherwise want a tag).
impl<'de> Deserialize<'de> for Aggregate {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        use serde::de::Error;
        let v = serde_json::Value::deserialize(d)?;
        let quantile = v
            .as_object()
            .filter(|m| m.len() == 1)
            .and_then(|m| m.get("quantile"));
        match (v.as_str(), quantile.and_then(|q| q.as_f64())) {
            (Some("mean"), _) => Ok(Aggregate::Mean),
            (Some("min"), _) => Ok(Aggregate::Min),
            (Some("max"), _) => Ok(Aggregate::Max),
            (None, Some(q)) => Ok(Aggregate::Quantile(q)),
            _ => Err(D::Error::custom(format!(
                "`over` is `mean`, `min`, `max` or `{{quantile: q}}`, not {v}"
            ))),
        }
    }
}

impl Aggregate {
    /// Its name as stored (`mean`, `min`, `max`, `quantile 0.05`, `upper quantile 0.95`).
    pub fn name(&self) -> String {
        match self {
            Aggregate::Mean => "mean".into(),
            Aggregate::Min => "min".into(),
            Aggregate::Max => "max".into(),
            Aggregate::Quantile(q) => format!("quantile {q}"),
            Aggregate::UpperQuantile(p) => format!("upper quantile {p}"),
        }
    }
}

/// The objective: exactly one of `maximize` and `minimize`, naming a quantity.
#[derive(Debug, Clone, PartialEq, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Objective {
    /// A quantity to maximise: a `/summary` variable (`exit_speed`, `carry`, …), a
    /// `/sweet_spot` one as `sweet_spot.NAME` (`sweet_spot.exit_speed`, `sweet_spot.width`,
    /// `sweet_spot.carry`), or a bat's as `bat.NAME` (`bat.mass`, …).
    #[serde(default)]
    pub maximize: Option<String>,
    /// A quantity to minimise (as `maximize`).
    #[serde(default)]
    pub minimize: Option<String>,
    /// How the quantity over the study's grid becomes one number. Default `mean`.
    #[serde(default = "default_over")]
    pub over: Aggregate,
}

fn default_over() -> Aggregate {
    Aggregate::Mean
}

/// A constraint: a bound on a quantity, or a rule set by name.
#[derive(Debug, Clone, PartialEq, JsonSchema)]
#[serde(untagged)]
pub enum Constraint {
    /// `{rules: ncaa_bbcor}` or `{rules: mlb_wood}`: the rule book's limits
    /// (docs/study-files.md, "Rule sets").
    Rules(RulesConstraint),
    /// `{quantity: NAME, min: a, max: b, over: max}`: the quantity (as in the objective)
    /// within [min, max] (either may be left out). `over` defaults to the worst case: the
    /// grid's largest value against `max`, its smallest against `min`.
    Bound(QuantityBound),
}

/// Told apart by their keys (`rules` or `quantity`), so that a mistake inside one form is
/// reported as that form's (an unknown rule set, a misspelt bound) and not as "no form
/// matched".
impl<'de> Deserialize<'de> for Constraint {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        use serde::de::Error;
        let v = serde_json::Value::deserialize(d)?;
        let has = |k: &str| v.as_object().is_some_and(|m| m.contains_key(k));
        let form = |e: serde_json::Error| D::Error::custom(e.to_string());
        match (has("rules"), has("quantity")) {
            (true, false) => serde_json::from_value(v).map(Constraint::Rules).map_err(form),
            (false, true) => serde_json::from_value(v).map(Constraint::Bound).map_err(form),
            _ => Err(D::Error::custom(
                "a constraint is either `{rules: ncaa_bbcor | mlb_wood}` or `{quantity: NAME, min: a, max: b}`",
            )),
        }
    }
}

/// A rule set by name.
#[derive(Debug, Clone, PartialEq, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RulesConstraint {
    pub rules: RuleSet,
    /// `ncaa_bbcor`: the minimum moment of inertia about the 6-in point of the bat's length
    /// class, kg·m² (the BBCOR standard's table). Default: no MOI limit.
    #[serde(default)]
    pub moi_min: Option<f64>,
}

/// A bound on a quantity.
#[derive(Debug, Clone, PartialEq, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct QuantityBound {
    pub quantity: String,
    #[serde(default)]
    pub min: Option<f64>,
    #[serde(default)]
    pub max: Option<f64>,
    #[serde(default)]
    pub over: Option<Aggregate>,
    /// The bound need hold only with at least this probability (0 < p ≤ 1) over the study's
    /// points (e.g. a `sample` of balls and billets): `{quantity: bat.bbcor, max: 0.50,
    /// probability: 0.95}` is P(BBCOR ≤ 0.50) ≥ 0.95. One bound only, and no `over`.
    #[serde(default)]
    pub probability: Option<f64>,
}

/// The rule sets built in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum RuleSet {
    /// NCAA / NFHS BBCOR bats: BBCOR ≤ 0.50, length − weight ≥ −3 (in − oz), barrel
    /// diameter ≤ 2 5/8 in, and the minimum moment of inertia about the 6-in point.
    NcaaBbcor,
    /// MLB wood bats (Official Baseball Rules 3.02(a)): one piece of solid wood, diameter
    /// ≤ 2.61 in, length ≤ 42 in.
    MlbWood,
}
