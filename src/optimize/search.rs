//! The search: argmin's Nelder–Mead simplex on the design variables scaled to [0, 1] by
//! their bounds, minimising the objective (negated to maximise, divided by its value at the
//! start) plus an exact (L1) penalty on every limit's relative violation and on leaving the
//! box. Why Nelder–Mead: a handful of variables, an objective that is smooth but has no
//! gradient we could compute, and one evaluation at a time after the first simplex, which
//! keeps a search deterministic and its record replayable; argmin is the maintained
//! optimisation crate of the Rust ecosystem (MIT/Apache-2.0). `method: cma_es` runs CMA-ES
//! (`super::cmaes`) on the same scaled variables and the same penalised cost instead: the
//! start design first, then λ designs a generation.
//!
//! **Resume by replay.** The search is deterministic: run again, it asks for the same
//! candidates in the same order. Every candidate evaluated is recorded (the caller's
//! `record`); on a resume the recorded ones are answered from the record, bit for bit, and
//! only those after it are computed.
//!
//! **No design twice.** A design asked for again (Nelder–Mead's shrink steps revisit
//! vertices, and scaled points outside the box clamp to one design on its boundary) is
//! answered from the candidates already evaluated, without a new evaluation or record, and
//! does not count against `max_evaluations`.

use super::cmaes::Cmaes;
use super::design::{Design, Searched};
use super::evaluate::Evaluation;
use crate::study::optimize_block::OptimizeMethod;
use argmin::core::{CostFunction, Error, Executor};
use argmin::solver::neldermead::NelderMead;
use std::collections::HashMap;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Mutex;

/// The weight of the exact penalty, per unit of relative violation (the objective is
/// measured relative to its start value, so any Lagrange multiplier of order 1 is
/// dominated).
pub const PENALTY: f64 = 100.0;
/// The first simplex's step along each scaled variable.
pub const SIMPLEX_STEP: f64 = 0.1;
/// CMA-ES's first step size along each scaled variable (a third of the box: Hansen's advice
/// of about a third of the range the optimum may lie in).
pub const CMA_ES_STEP: f64 = 0.3;
/// What a failed candidate costs the search (worse than any feasible one).
const FAILED: f64 = 1e6;

/// Evaluates a design (one value per variable).
pub type EvalFn<'a> = dyn Fn(&[f64]) -> Evaluation + Sync + 'a;
/// Stores a new candidate before the search goes on (an error stops the search).
pub type RecordFn<'a> = dyn Fn(&Candidate) -> Result<(), String> + Sync + 'a;

/// One evaluated candidate, as recorded.
#[derive(Debug, Clone, PartialEq)]
pub struct Candidate {
    /// The scaled design the search asked for (may lie outside [0, 1]).
    pub u: Vec<f64>,
    /// The design evaluated: within the bounds.
    pub x: Vec<f64>,
    pub evaluation: Evaluation,
    /// What the search saw.
    pub penalized: f64,
}

/// Why a search stopped early.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stop {
    /// `max_evaluations` candidates were evaluated.
    Budget,
    /// The stop flag was set (Ctrl-C).
    Interrupted,
    /// The record could not be written.
    Record,
}

/// How a search ended.
#[derive(Debug, Clone, PartialEq)]
pub struct Outcome {
    /// Candidates in the order evaluated (replayed ones included).
    pub candidates: Vec<Candidate>,
    /// Why it stopped: None when the simplex converged (or argmin stopped it).
    pub stopped: Option<Stop>,
    /// How many came from the record.
    pub replayed: usize,
}

/// What the search minimises of an evaluation: the objective's value, or (the second
/// anchor of a Pareto front) a limit's; and whether it is maximised.
fn searched(design: &Design, e: &Evaluation) -> (f64, bool) {
    match design.searched {
        Searched::Objective => (e.objective, design.objective.maximize),
        Searched::Limit { index, maximize } => (
            e.constraints.get(index).copied().unwrap_or(f64::NAN),
            maximize,
        ),
    }
}

/// The objective's scale: the searched value's magnitude at the first candidate (1 if that
/// failed or is 0).
fn objective_scale(design: &Design, e: &Evaluation) -> f64 {
    let a = searched(design, e).0.abs();
    if a.is_finite() && a > 0.0 {
        a
    } else {
        1.0
    }
}

fn key(u: &[f64]) -> Vec<u64> {
    u.iter().map(|x| x.to_bits()).collect()
}

/// The penalised value of a candidate (design `x` from scaled `u`).
pub fn penalized(design: &Design, u: &[f64], e: &Evaluation, scale: f64) -> f64 {
    let (value, maximize) = searched(design, e);
    if e.error.is_some() || !value.is_finite() {
        return FAILED;
    }
    let sign = if maximize { -1.0 } else { 1.0 };
    let mut f = sign * value / scale;
    for (l, &v) in design.limits.iter().zip(&e.constraints) {
        let m = l.margin(v);
        f += PENALTY
            * if m.is_nan() {
                1.0
            } else {
                (-m).max(0.0) / l.scale()
            };
    }
    let outside: f64 = u.iter().map(|&x| (-x).max(0.0) + (x - 1.0).max(0.0)).sum();
    f + PENALTY * outside
}

/// The design within the bounds of a scaled point.
pub fn unscale(design: &Design, u: &[f64]) -> Vec<f64> {
    design.from_unit(u)
}

/// What a search has done so far.
struct Progress {
    /// Candidates evaluated (or replayed), in order.
    candidates: Vec<Candidate>,
    /// Why it stopped, once it has.
    stopped: Option<Stop>,
    /// How many came from the record.
    replayed: usize,
    /// The objective's scale (its magnitude at the first design answered), once known.
    scale: Option<f64>,
    /// Calls of the cost function so far (argmin's first simplex takes the first n + 1).
    calls: usize,
}

/// What the searches of one run share: every design evaluated, by its bits (a design asked
/// for again, by a shrink step, two scaled points clamped to one design, or a later search
/// of a Pareto front, is answered from it), and the record of an earlier run, by the scaled
/// point asked for.
#[derive(Default)]
pub struct Shared {
    memo: Mutex<HashMap<Vec<u64>, Evaluation>>,
    replay: Mutex<HashMap<Vec<u64>, Candidate>>,
}

impl Shared {
    /// Shared state over the `recorded` candidates of an earlier run.
    pub fn replaying(recorded: Vec<Candidate>) -> Shared {
        Shared {
            memo: Mutex::default(),
            replay: Mutex::new(recorded.into_iter().map(|c| (key(&c.u), c)).collect()),
        }
    }
}

struct Problem<'a> {
    design: &'a Design,
    eval: &'a EvalFn<'a>,
    record: &'a RecordFn<'a>,
    stop: &'a AtomicBool,
    shared: &'a Shared,
    progress: Mutex<Progress>,
}

impl Problem<'_> {
    /// Whether the search has been stopped (budget, Ctrl-C, the record).
    fn has_stopped(&self) -> bool {
        self.progress
            .lock()
            .expect("search state")
            .stopped
            .is_some()
    }

    /// Stop the search. argmin unwraps the costs of its first simplex, so within it the
    /// stop is a cost no vertex can beat, and argmin's first step then meets the error.
    fn halt(&self, why: Stop) -> Result<f64, Error> {
        let mut p = self.progress.lock().expect("search state");
        p.stopped.get_or_insert(why);
        match p.calls <= self.design.variables.len() + 1 {
            true => Ok(f64::INFINITY),
            false => Err(Error::msg(format!("{why:?}"))),
        }
    }

    /// A design evaluated before: its cost at `u` (the penalty for leaving the box is
    /// `u`'s own), without evaluating or recording it again.
    fn seen(&self, u: &[f64], x: &[f64]) -> Option<f64> {
        let e = self.shared.memo.lock().expect("memo").get(&key(x))?.clone();
        let mut p = self.progress.lock().expect("search state");
        let scale = *p
            .scale
            .get_or_insert_with(|| objective_scale(self.design, &e));
        Some(penalized(self.design, u, &e, scale))
    }

    /// A new candidate, taken into the progress; its cost.
    fn push(&self, c: Candidate, replayed: bool) -> f64 {
        let mut p = self.progress.lock().expect("search state");
        p.scale
            .get_or_insert_with(|| objective_scale(self.design, &c.evaluation));
        let f = c.penalized;
        let memo = &self.shared.memo;
        memo.lock()
            .expect("memo")
            .insert(key(&c.x), c.evaluation.clone());
        p.replayed += usize::from(replayed);
        p.candidates.push(c);
        f
    }

    /// Evaluate the design at `u` and record it.
    fn evaluate(&self, u: &[f64], x: Vec<f64>) -> Result<f64, Error> {
        let evaluation = (self.eval)(&x);
        let scale = {
            let p = self.progress.lock().expect("search state");
            p.scale
                .unwrap_or_else(|| objective_scale(self.design, &evaluation))
        };
        let c = Candidate {
            penalized: penalized(self.design, u, &evaluation, scale),
            u: u.to_vec(),
            x,
            evaluation,
        };
        if (self.record)(&c).is_err() {
            return self.halt(Stop::Record);
        }
        Ok(self.push(c, false))
    }
}

impl CostFunction for Problem<'_> {
    type Param = Vec<f64>;
    type Output = f64;
    fn cost(&self, u: &Vec<f64>) -> Result<f64, Error> {
        let (n, stopped) = {
            let mut p = self.progress.lock().expect("search state");
            p.calls += 1;
            (p.candidates.len(), p.stopped)
        };
        if let Some(why) = stopped {
            return self.halt(why);
        }
        let x = unscale(self.design, u);
        if let Some(f) = self.seen(u, &x) {
            return Ok(f);
        }
        if n >= self.design.block.max_evaluations {
            return self.halt(Stop::Budget);
        }
        if let Some(c) = self.shared.replay.lock().expect("replay").remove(&key(u)) {
            return Ok(self.push(c, true));
        }
        if self.stop.load(Ordering::SeqCst) {
            return self.halt(Stop::Interrupted);
        }
        self.evaluate(u, x)
    }
}

/// The first simplex: the start and one step along each scaled variable (backwards where
/// a step forwards would leave the box).
fn simplex(design: &Design) -> Vec<Vec<f64>> {
    let u0 = design.start_unit();
    let mut s = vec![u0.clone()];
    for k in 0..u0.len() {
        let mut u = u0.clone();
        u[k] += if u0[k] + SIMPLEX_STEP <= 1.0 {
            SIMPLEX_STEP
        } else {
            -SIMPLEX_STEP
        };
        s.push(u);
    }
    s
}

/// Run the search. `eval` evaluates a design; `record` stores a new candidate before the
/// search goes on (a failure stops it); `recorded` are the candidates of an earlier run of
/// the same search, answered without evaluating. The first candidate's objective sets the
/// scale, so a resumed search must replay it (the caller passes the record whole).
pub fn search(
    design: &Design,
    eval: &EvalFn<'_>,
    record: &RecordFn<'_>,
    recorded: Vec<Candidate>,
    stop: &AtomicBool,
) -> Outcome {
    search_shared(design, eval, record, &Shared::replaying(recorded), stop)
}

/// [`search`] with the designs evaluated and the record shared with other searches of the
/// same run (a Pareto front's): a design one of them evaluated is answered without a new
/// evaluation or record, and does not count against this search's `max_evaluations`.
pub fn search_shared(
    design: &Design,
    eval: &EvalFn<'_>,
    record: &RecordFn<'_>,
    shared: &Shared,
    stop: &AtomicBool,
) -> Outcome {
    let problem = Problem {
        design,
        eval,
        record,
        stop,
        shared,
        progress: Mutex::new(Progress {
            candidates: Vec::new(),
            stopped: None,
            replayed: 0,
            scale: None,
            calls: 0,
        }),
    };
    match design.block.method {
        OptimizeMethod::NelderMead => nelder_mead(design, &problem),
        OptimizeMethod::CmaEs => cma_es(design, &problem),
    }
    let p = problem.progress.into_inner().expect("search state");
    Outcome {
        candidates: p.candidates,
        stopped: p.stopped,
        replayed: p.replayed,
    }
}

/// argmin's Nelder–Mead from the first simplex.
fn nelder_mead(design: &Design, problem: &Problem) {
    let solver = NelderMead::new(simplex(design))
        .with_sd_tolerance(design.block.tolerance)
        .expect("a tolerance >= 0");
    let iters = 10 * design.block.max_evaluations as u64;
    // argmin's own stop (converged, max_iters) or ours (an error from `cost`, recorded in
    // the state): what was evaluated is the answer either way
    let _ = Executor::new(problem, solver)
        .configure(|s| s.max_iters(iters))
        .run();
}

/// CMA-ES from the start design (evaluated first: it sets the objective's scale), a
/// generation at a time, until the budget, a stop, or its spread falls below the tolerance.
fn cma_es(design: &Design, problem: &Problem) {
    let start = design.start_unit();
    let mut es = Cmaes::new(&start, CMA_ES_STEP, design.block.seed());
    if problem.cost(&start).is_err() || problem.has_stopped() {
        return;
    }
    while es.spread() >= design.block.tolerance {
        let generation = es.ask();
        let mut costs = Vec::with_capacity(generation.len());
        for u in &generation {
            match problem.cost(u) {
                Ok(c) if !problem.has_stopped() => costs.push(c),
                _ => return,
            }
        }
        es.tell(&generation, &costs);
    }
}

impl CostFunction for &Problem<'_> {
    type Param = Vec<f64>;
    type Output = f64;
    fn cost(&self, u: &Vec<f64>) -> Result<f64, Error> {
        (*self).cost(u)
    }
}
