//! The search: argmin's Nelder–Mead simplex on the design variables scaled to [0, 1] by
//! their bounds, minimising the objective (negated to maximise, divided by its value at the
//! start) plus an exact (L1) penalty on every limit's relative violation and on leaving the
//! box. Why Nelder–Mead: a handful of variables, an objective that is smooth but has no
//! gradient we could compute, and one evaluation at a time after the first simplex, which
//! keeps a search deterministic and its record replayable; argmin is the maintained
//! optimisation crate of the Rust ecosystem (MIT/Apache-2.0).
//!
//! **Resume by replay.** The search is deterministic: run again, it asks for the same
//! candidates in the same order. Every candidate evaluated is recorded (the caller's
//! `record`); on a resume the recorded ones are answered from the record, bit for bit, and
//! only those after it are computed.

use super::design::Design;
use super::evaluate::Evaluation;
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
/// What a failed candidate costs the search (worse than any feasible one).
const FAILED: f64 = 1e6;

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

/// The objective's scale: its magnitude at the first candidate (1 if that failed or is 0).
fn objective_scale(e: &Evaluation) -> f64 {
    let a = e.objective.abs();
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
    if e.error.is_some() || !e.objective.is_finite() {
        return FAILED;
    }
    let sign = if design.objective.maximize { -1.0 } else { 1.0 };
    let mut f = sign * e.objective / scale;
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
    design
        .variables
        .iter()
        .zip(u)
        .map(|(v, &x)| v.min + (v.max - v.min) * x.clamp(0.0, 1.0))
        .collect()
}

struct Problem<'a> {
    design: &'a Design,
    eval: &'a (dyn Fn(&[f64]) -> Evaluation + Sync),
    record: &'a (dyn Fn(&Candidate) -> Result<(), String> + Sync),
    stop: &'a AtomicBool,
    replay: Mutex<HashMap<Vec<u64>, Candidate>>,
    state: Mutex<(Vec<Candidate>, Option<Stop>, usize, f64)>,
}

impl CostFunction for Problem<'_> {
    type Param = Vec<f64>;
    type Output = f64;
    fn cost(&self, u: &Vec<f64>) -> Result<f64, Error> {
        let halt = |s: Stop| {
            self.state.lock().expect("search state").1 = Some(s);
            Err(Error::msg(format!("{s:?}")))
        };
        let (n, scale) = {
            let st = self.state.lock().expect("search state");
            (st.0.len(), st.3)
        };
        if n >= self.design.block.max_evaluations {
            return halt(Stop::Budget);
        }
        if let Some(c) = self.replay.lock().expect("replay").remove(&key(u)) {
            let mut st = self.state.lock().expect("search state");
            st.2 += 1;
            let f = c.penalized;
            st.0.push(c);
            return Ok(f);
        }
        if self.stop.load(Ordering::SeqCst) {
            return halt(Stop::Interrupted);
        }
        let x = unscale(self.design, u);
        let evaluation = (self.eval)(&x);
        let scale = match n {
            0 => objective_scale(&evaluation),
            _ => scale,
        };
        let c = Candidate {
            penalized: penalized(self.design, u, &evaluation, scale),
            u: u.clone(),
            x,
            evaluation,
        };
        if (self.record)(&c).is_err() {
            return halt(Stop::Record);
        }
        let mut st = self.state.lock().expect("search state");
        st.3 = if n == 0 { scale } else { st.3 };
        let f = c.penalized;
        st.0.push(c);
        Ok(f)
    }
}

/// The first simplex: the start and one step along each scaled variable (backwards where
/// a step forwards would leave the box).
fn simplex(design: &Design) -> Vec<Vec<f64>> {
    let u0: Vec<f64> = design
        .variables
        .iter()
        .map(|v| (v.start - v.min) / (v.max - v.min))
        .collect();
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
    eval: &(dyn Fn(&[f64]) -> Evaluation + Sync),
    record: &(dyn Fn(&Candidate) -> Result<(), String> + Sync),
    recorded: Vec<Candidate>,
    stop: &AtomicBool,
) -> Outcome {
    let scale = recorded
        .first()
        .map_or(1.0, |c| objective_scale(&c.evaluation));
    let replay = recorded.into_iter().map(|c| (key(&c.u), c)).collect();
    let problem = Problem {
        design,
        eval,
        record,
        stop,
        replay: Mutex::new(replay),
        state: Mutex::new((Vec::new(), None, 0, scale)),
    };
    let solver = NelderMead::new(simplex(design))
        .with_sd_tolerance(design.block.tolerance)
        .expect("a tolerance >= 0");
    let iters = 10 * design.block.max_evaluations as u64;
    // argmin's own stop (converged, max_iters) or ours (an error from `cost`, recorded in
    // the state): what was evaluated is the answer either way
    let _ = Executor::new(&problem, solver)
        .configure(|s| s.max_iters(iters))
        .run();
    let (candidates, stopped, replayed, _) = problem.state.into_inner().expect("search state");
    Outcome {
        candidates,
        stopped,
        replayed,
    }
}

impl CostFunction for &Problem<'_> {
    type Param = Vec<f64>;
    type Output = f64;
    fn cost(&self, u: &Vec<f64>) -> Result<f64, Error> {
        (*self).cost(u)
    }
}
