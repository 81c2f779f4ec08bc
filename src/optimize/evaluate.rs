//! One candidate evaluated: its design applied to the study's base, every point of the
//! study's grid simulated (on all cores; each point alone, so the result does not depend on
//! the threads), and the objective and every limit's quantity made one number each.
//!
//! The bat's preparation (its modes) is most of a candidate's cost when the grid is small,
//! so prepared bats are kept by their canonical JSON and shared by every point and candidate
//! that has the same bat (a design variable that does not touch the bat, e.g. a swing
//! parameter, prepares it once for the whole search).

use super::design::Design;
use super::quantity::{aggregate, BatQuantity, Quantity, Sweet};
use super::rules::protocol;
use crate::model::measures::sweet::find_sweet_spot;
use crate::model::outcome::Outcome;
use crate::model::spec::CollisionSpec;
use crate::model::{simulate_target, Target};
use crate::store::layout::{summary_floats, SUMMARY_FLOATS};
use crate::study::optimize_block::Aggregate;
use crate::study::Study;
use rayon::prelude::*;
use std::collections::HashMap;
use std::sync::{Arc, Mutex};

/// Prepared bats kept at most (a search moves on; old bats are dropped first).
const CACHE_BATS: usize = 64;

/// What a candidate gave: the objective and each limit's value, or why it failed.
#[derive(Debug, Clone, PartialEq)]
pub struct Evaluation {
    pub objective: f64,
    pub constraints: Vec<f64>,
    pub error: Option<String>,
}

/// Evaluates candidates of one study's design problem.
pub struct Evaluator<'a> {
    pub study: &'a Study,
    pub design: &'a Design,
    bats: Mutex<BatCache>,
}

/// Prepared bats by key, and the keys oldest first.
type BatCache = (HashMap<String, Arc<Target>>, Vec<String>);

/// The points of one candidate: resolved specs, and each one's bat.
struct Grid {
    specs: Vec<CollisionSpec>,
    bats: Vec<Arc<Target>>,
    /// The BBCOR protocol's [BBCOR, wall stress ratio] of each distinct bat and ball, run
    /// once when a quantity first needs it.
    protocol: std::sync::OnceLock<Vec<[f64; 2]>>,
}

impl<'a> Evaluator<'a> {
    pub fn new(study: &'a Study, design: &'a Design) -> Self {
        Evaluator {
            study,
            design,
            bats: Mutex::new((HashMap::new(), Vec::new())),
        }
    }

    /// The candidate `x` (one value per design variable). Call inside the run's pool.
    pub fn evaluate(&self, x: &[f64]) -> Evaluation {
        match self.try_evaluate(x) {
            Ok(e) => e,
            Err(message) => Evaluation {
                objective: f64::NAN,
                constraints: vec![f64::NAN; self.design.limits.len()],
                error: Some(message),
            },
        }
    }

    fn try_evaluate(&self, x: &[f64]) -> Result<Evaluation, String> {
        let grid = self.grid(x)?;
        let outcomes: Vec<Result<Outcome, String>> = grid
            .specs
            .par_iter()
            .zip(grid.bats.par_iter())
            .map(|(s, b)| simulate_target(s, b, None).map_err(|e| e.to_string()))
            .collect();
        let outcomes = outcomes.into_iter().collect::<Result<Vec<_>, _>>()?;
        let o = &self.design.objective;
        let objective = self.value(o.quantity, o.over, &grid, &outcomes);
        if !objective.is_finite() {
            return Err(format!(
                "the objective {} is not a number",
                o.quantity.name()
            ));
        }
        let constraints = self
            .design
            .limits
            .iter()
            .map(|l| self.value(l.quantity, l.over, &grid, &outcomes))
            .collect();
        Ok(Evaluation {
            objective,
            constraints,
            error: None,
        })
    }

    /// Every point of the study's grid at this design, and its prepared bat.
    fn grid(&self, x: &[f64]) -> Result<Grid, String> {
        let plan = &self.study.plan;
        let base = self.design.apply(x, plan.base());
        let mut specs = Vec::with_capacity(plan.n_points());
        for flat in 0..plan.n_points() {
            let m = plan.shape().unravel(flat);
            let spec = plan
                .resolve_over(&base, &m)
                .map_err(|e| format!("point {flat}: {e}"))?;
            specs.push(spec);
        }
        let bats = self.bats(&specs)?;
        Ok(Grid {
            specs,
            bats,
            protocol: std::sync::OnceLock::new(),
        })
    }

    /// The prepared bat of every point: from the cache, or prepared now, the distinct new
    /// bats on every core (a sample of billets is a new bat at every sampled point), and
    /// kept in the order they first appear (so the cache is the same whatever the threads).
    fn bats(&self, specs: &[CollisionSpec]) -> Result<Vec<Arc<Target>>, String> {
        let keys: Vec<String> = specs
            .par_iter()
            .map(|s| crate::study::plan::bat_key(&s.bat, &s.numerics))
            .collect();
        let mut new: Vec<usize> = Vec::new();
        {
            let cache = self.bats.lock().expect("bat cache");
            let mut seen = std::collections::HashSet::new();
            for (i, k) in keys.iter().enumerate() {
                if !cache.0.contains_key(k) && seen.insert(k) {
                    new.push(i);
                }
            }
        }
        let prepared: Vec<_> = new
            .par_iter()
            .map(|&i| Target::prepare(&specs[i].bat, &specs[i].numerics).map(Arc::new))
            .collect();
        let prepared = prepared
            .into_iter()
            .collect::<Result<Vec<_>, _>>()
            .map_err(|e| e.to_string())?;
        let mut fresh: HashMap<&String, Arc<Target>> = HashMap::new();
        let mut cache = self.bats.lock().expect("bat cache");
        for (&i, t) in new.iter().zip(prepared) {
            fresh.insert(&keys[i], Arc::clone(&t));
            if cache.1.len() >= CACHE_BATS {
                let old = cache.1.remove(0);
                cache.0.remove(&old);
            }
            cache.0.insert(keys[i].clone(), t);
            cache.1.push(keys[i].clone());
        }
        Ok(keys
            .iter()
            .map(|k| fresh.get(k).or_else(|| cache.0.get(k)).map(Arc::clone))
            .collect::<Option<Vec<_>>>()
            .expect("every bat prepared"))
    }

    /// One quantity over the grid, aggregated.
    fn value(&self, q: Quantity, over: Aggregate, grid: &Grid, outcomes: &[Outcome]) -> f64 {
        let values: Vec<f64> = match q {
            Quantity::Summary(k) => outcomes.iter().map(|o| summary_floats(o)[k]).collect(),
            Quantity::Sweet(s) => self.sweet_values(s, outcomes),
            Quantity::Bat(BatQuantity::Bbcor) => self.protocol_values(grid, 0),
            Quantity::Bat(BatQuantity::WallStressRatio) => self.protocol_values(grid, 1),
            Quantity::Bat(b) => grid.bats.iter().map(|t| b.of(&t.properties())).collect(),
        };
        aggregate(&values, over)
    }

    /// The sweet-spot quantity of every curve along `impact_z`.
    fn sweet_values(&self, s: Sweet, outcomes: &[Outcome]) -> Vec<f64> {
        let plan = &self.study.plan;
        let dims = &plan.shape().dims;
        let Some(iz) = dims.iter().position(|d| d.name == "impact_z") else {
            return Vec::new();
        };
        let z: Vec<f64> = match &dims[iz].coords[0].values {
            crate::results::CoordValues::Numbers(z) => z.clone(),
            _ => return Vec::new(),
        };
        let mut order: Vec<usize> = (0..z.len()).collect();
        order.sort_by(|&a, &b| z[a].total_cmp(&z[b]));
        let zs: Vec<f64> = order.iter().map(|&q| z[q]).collect();
        let stride: usize = dims[iz + 1..].iter().map(|d| d.size).product();
        let outer = plan.n_points() / (z.len() * stride);
        let carry = SUMMARY_FLOATS
            .iter()
            .position(|d| d.name == "carry")
            .expect("carry");
        let mut out = Vec::new();
        for hi in 0..outer {
            for lo in 0..stride {
                let at = |q: usize| &outcomes[hi * z.len() * stride + q * stride + lo];
                let curve: Vec<f64> = match s {
                    Sweet::Carry | Sweet::CarryPosition => order
                        .iter()
                        .map(|&q| summary_floats(at(q))[carry])
                        .collect(),
                    Sweet::ExitSpeedLab => order.iter().map(|&q| at(q).exit_speed_lab).collect(),
                    _ => order.iter().map(|&q| at(q).exit_speed).collect(),
                };
                let spot = find_sweet_spot(&zs, &curve);
                out.push(spot.map_or(f64::NAN, |p| match s {
                    Sweet::Position | Sweet::CarryPosition => p.position,
                    Sweet::ExitSpeed | Sweet::ExitSpeedLab | Sweet::Carry => p.exit_speed,
                    Sweet::Width => p.width,
                }));
            }
        }
        out
    }

    /// The protocol's BBCOR (`which` 0) or wall stress ratio (1) of each distinct bat and
    /// ball of the grid (a sample of balls certifies the bat with each of them), the scans
    /// on every core, with the stress when the design asks for it anywhere.
    fn protocol_values(&self, grid: &Grid, which: usize) -> Vec<f64> {
        let stress = self.needs_stress();
        let values = grid.protocol.get_or_init(|| {
            let mut seen: std::collections::HashSet<(*const Target, String)> = Default::default();
            let distinct: Vec<(&CollisionSpec, &Arc<Target>)> = grid
                .specs
                .iter()
                .zip(&grid.bats)
                .filter(|(s, t)| seen.insert((Arc::as_ptr(t), format!("{:?}", s.ball))))
                .collect();
            distinct
                .par_iter()
                .map(|(s, t)| protocol(s, t, stress))
                .collect()
        });
        values.iter().map(|v| v[which]).collect()
    }

    /// Whether the objective or a limit is the wall's stress.
    fn needs_stress(&self) -> bool {
        let stress = Quantity::Bat(BatQuantity::WallStressRatio);
        self.design.objective.quantity == stress
            || self.design.limits.iter().any(|l| l.quantity == stress)
    }
}
