//! A two-objective search (`optimize.pareto`): the front of the objective against a second
//! quantity (lab exit speed against swing weight: power against bat control), traced by the
//! ε-constraint method (Haimes, Lasdon & Wismer 1971; Miettinen, *Nonlinear Multiobjective
//! Optimization*, 1999, §3.2): the objective alone, the second alone, then the objective
//! with the second capped at even steps between what the two searches found. Each search is
//! the single-objective search (with its exact penalty, so each ends on its cap), and they
//! share every design evaluated: none is evaluated twice. The front is the candidates no
//! other feasible candidate beats in both.

use super::design::{Design, Searched};
use super::evaluate::Evaluation;
use super::search::{search_shared, Candidate, EvalFn, Outcome, RecordFn, Shared, Stop};
use std::sync::atomic::AtomicBool;

/// Run the front's searches in order, sharing the designs evaluated and the record; the
/// candidates of all of them, in the order evaluated. An interruption or a failed record
/// stops all; a search that spends its budget ends only itself.
pub fn search_pareto(
    design: &Design,
    eval: &EvalFn<'_>,
    record: &RecordFn<'_>,
    recorded: Vec<Candidate>,
    stop: &AtomicBool,
) -> Outcome {
    let Some(p) = &design.pareto else {
        return super::search::search(design, eval, record, recorded, stop);
    };
    let shared = Shared::replaying(recorded);
    let mut all = Outcome {
        candidates: Vec::new(),
        stopped: None,
        replayed: 0,
    };
    let mut second_alone = design.clone();
    second_alone.searched = Searched::Limit {
        index: p.limit,
        maximize: p.maximize,
    };
    let mut searches = vec![design.clone(), second_alone];
    let mut k = 0;
    while k < searches.len() {
        let out = search_shared(&searches[k], eval, record, &shared, stop);
        all.candidates.extend(out.candidates);
        all.replayed += out.replayed;
        match out.stopped {
            Some(Stop::Interrupted | Stop::Record) => {
                all.stopped = out.stopped;
                return all;
            }
            Some(Stop::Budget) => all.stopped = Some(Stop::Budget),
            None => {}
        }
        if k == 1 {
            searches.extend(
                caps(design, &all.candidates)
                    .into_iter()
                    .map(|cap| capped(design, cap)),
            );
        }
        k += 1;
    }
    all
}

/// The design with its second objective capped at `cap` (a bound on the tracked limit).
fn capped(design: &Design, cap: f64) -> Design {
    let mut d = design.clone();
    if let Some(p) = &design.pareto {
        let limit = &mut d.limits[p.limit];
        match p.maximize {
            true => limit.min = Some(cap),
            false => limit.max = Some(cap),
        }
        limit.source = "pareto cap".into();
    }
    d
}

/// The caps of the inner searches: `points` − 2 even steps strictly between the second
/// objective's value at the best feasible candidate for the objective and its best feasible
/// value (none without a feasible candidate).
fn caps(design: &Design, cands: &[Candidate]) -> Vec<f64> {
    let Some(p) = &design.pareto else {
        return Vec::new();
    };
    let scored: Vec<(f64, f64)> = scores(design, cands).into_iter().flatten().collect();
    let at_best = scored
        .iter()
        .max_by(|a, b| a.0.total_cmp(&b.0))
        .map(|f| f.1);
    let best_second = scored.iter().map(|f| f.1).max_by(f64::total_cmp);
    let (Some(from), Some(to)) = (best_second, at_best) else {
        return Vec::new();
    };
    // back from "higher is better" to the second objective's own sign
    let (from, to) = (sign(p.maximize) * from, sign(p.maximize) * to);
    let n = p.points - 1;
    (1..n)
        .map(|k| from + (to - from) * k as f64 / n as f64)
        .collect()
}

/// +1 for a quantity maximised, −1 for one minimised.
fn sign(maximize: bool) -> f64 {
    if maximize {
        1.0
    } else {
        -1.0
    }
}

/// Each candidate's two objectives signed so that higher is better (None: not feasible).
fn scores(design: &Design, cands: &[Candidate]) -> Vec<Option<(f64, f64)>> {
    let Some(p) = &design.pareto else {
        return vec![None; cands.len()];
    };
    let (s1, s2) = (sign(design.objective.maximize), sign(p.maximize));
    cands
        .iter()
        .map(|c| {
            let e = &c.evaluation;
            feasible(design, e).then(|| (s1 * e.objective, s2 * e.constraints[p.limit]))
        })
        .collect()
}

/// Within every limit of the study (the second objective's own, unbounded, always is).
fn feasible(design: &Design, e: &Evaluation) -> bool {
    e.error.is_none()
        && e.objective.is_finite()
        && design
            .limits
            .iter()
            .zip(&e.constraints)
            .all(|(l, &v)| l.margin(v) >= 0.0)
}

/// Which candidates are on the front: feasible, and beaten in both objectives by no other
/// feasible candidate (equal in both counts as not beaten).
pub fn front(design: &Design, cands: &[Candidate]) -> Vec<bool> {
    let points = scores(design, cands);
    points
        .iter()
        .map(|a| match a {
            None => false,
            Some((a1, a2)) => !points
                .iter()
                .flatten()
                .any(|(b1, b2)| b1 >= a1 && b2 >= a2 && (b1 > a1 || b2 > a2)),
        })
        .collect()
}
