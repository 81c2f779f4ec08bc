//! The optimiser against a problem whose optimum is known in closed form, built
//! from batstudy's own physics, and its constraints honoured at the reported optimum.
//!
//! Brody's rigid bat (mass M, moment of inertia I about its CM) swung at ω, a ball of mass
//! m and speed v hitting it at l = z − z_cm with COR e: the ball leaves at
//! v_out = [(e − r) v − (1 + e) ω l]/(1 + r), r = m/M + m l²/I (Brody 1986; `model::rigid`).
//! Setting dv_out/dl = 0 gives ω b l² − 2 b v l − ω (1 + a) = 0 with a = m/M, b = m/I, whose
//! root on the barrel's side (ω < 0) is l* = [b v − √(b² v² + ω² b (1 + a))]/(ω b),
//! independent of e; at ω = 0 the best point is the CM (the paper's section 2).

use batstudy::model::Target;
use batstudy::optimize::{design_of, search, Evaluator};
use batstudy::study::{load_str, LoadOptions};
use std::path::Path;
use std::sync::atomic::AtomicBool;

const V: f64 = 40.0;
const OMEGA: f64 = -30.0;

fn study(extra: &str) -> String {
    format!(
        "name: best_point\nmodel: rigid\nbase:\n  impact: {{z: 0.6}}\n  ball: {{speed: {V}}}\n  swing: {{omega: {OMEGA}}}\n\
         optimize:\n  max_evaluations: 300\n  tolerance: 1.0e-14\n  variables:\n    impact.z: {{min: 0.40, max: 0.83}}\n\
         \x20 objective: {{maximize: exit_speed}}\n{extra}"
    )
}

/// The best design the search found (its impact position) and its limits' values.
fn best(text: &str) -> (f64, Vec<f64>, Vec<f64>) {
    let s = load_str(text, Path::new("best.yaml"), &LoadOptions::default()).unwrap();
    let design = design_of(&s).unwrap().unwrap();
    let ev = Evaluator::new(&s, &design);
    let out = search(
        &design,
        &|x| ev.evaluate(x),
        &|_| Ok(()),
        Vec::new(),
        &AtomicBool::new(false),
    );
    let feasible = out.candidates.iter().filter(|c| {
        c.evaluation.error.is_none()
            && design
                .limits
                .iter()
                .zip(&c.evaluation.constraints)
                .all(|(l, &v)| l.margin(v) >= 0.0)
    });
    let b = feasible
        .max_by(|a, b| a.evaluation.objective.total_cmp(&b.evaluation.objective))
        .expect("a feasible candidate");
    let margins = design
        .limits
        .iter()
        .zip(&b.evaluation.constraints)
        .map(|(l, &v)| l.margin(v))
        .collect();
    (b.x[0], b.evaluation.constraints.clone(), margins)
}

/// z_cm and the closed-form best lever arm l*.
fn closed_form() -> (f64, f64) {
    let s = load_str(&study(""), Path::new("best.yaml"), &LoadOptions::default()).unwrap();
    let spec = s.plan.point(0).unwrap().spec;
    let p = Target::prepare(&spec.bat, &spec.numerics)
        .unwrap()
        .properties();
    let (a, b) = (
        spec.ball.mass / p.mass,
        spec.ball.mass / p.moment_of_inertia,
    );
    let l = (b * V - (b * b * V * V + OMEGA * OMEGA * b * (1.0 + a)).sqrt()) / (OMEGA * b);
    (p.z_cm, l)
}

#[test]
fn finds_the_rigid_bats_best_impact_point() {
    let (z_cm, l) = closed_form();
    let (z, _, _) = best(&study(""));
    eprintln!("best impact point {z:.6} m, closed form {:.6} m", z_cm + l);
    assert!(
        l > 0.05,
        "the swing moves the best point toward the barrel ({l})"
    );
    assert!((z - (z_cm + l)).abs() < 1e-4, "{z} vs {}", z_cm + l);
}

#[test]
fn a_constraint_is_honoured_and_the_optimum_sits_on_it() {
    // approach speed v − ω l grows toward the barrel: a limit half way to l* binds
    let (z_cm, l) = closed_form();
    let limit = V - OMEGA * l / 2.0;
    let extra = format!("  constraints:\n    - {{quantity: approach_speed, max: {limit}}}\n");
    let (z, values, margins) = best(&study(&extra));
    eprintln!(
        "best {z:.6} m, approach speed {:.6} <= {limit:.6}, margin {:.3e}",
        values[0], margins[0]
    );
    assert!(
        margins[0] >= 0.0,
        "the reported optimum violates its limit: {margins:?}"
    );
    assert!(
        (z - (z_cm + l / 2.0)).abs() < 1e-3,
        "{z} vs the limit at {}",
        z_cm + l / 2.0
    );
    assert!(margins[0] < 1e-3 * limit, "not on the limit: {margins:?}");
}
