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
    closed_form_at(V)
}

/// z_cm and the closed-form best lever arm l* for a ball at speed `v`.
fn closed_form_at(v: f64) -> (f64, f64) {
    let s = load_str(&study(""), Path::new("best.yaml"), &LoadOptions::default()).unwrap();
    let spec = s.plan.point(0).unwrap().spec;
    let p = Target::prepare(&spec.bat, &spec.numerics)
        .unwrap()
        .properties();
    let (a, b) = (
        spec.ball.mass / p.mass,
        spec.ball.mass / p.moment_of_inertia,
    );
    let l = (b * v - (b * b * v * v + OMEGA * OMEGA * b * (1.0 + a)).sqrt()) / (OMEGA * b);
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

/// The study with the ball's speed drawn: 64 speeds, uniform over 30–50 m/s.
fn sampled(extra: &str) -> String {
    let text = study(extra).replace(&format!("  ball: {{speed: {V}}}\n"), "");
    assert!(!text.contains("speed: 40"));
    format!("{text}sample: {{n: 64, seed: 7, params: {{ball.speed: {{uniform: {{min: 30, max: 50}}}}}}}}\n")
}

/// The drawn speeds of a sampled study.
fn drawn_speeds(text: &str) -> Vec<f64> {
    let s = load_str(text, Path::new("best.yaml"), &LoadOptions::default()).unwrap();
    (0..s.plan.n_points())
        .map(|i| s.plan.point(i).unwrap().spec.ball.speed)
        .collect()
}

/// Robust design against the same closed form: at a given lever arm the exit speed is
/// linear in the ball's speed, so its mean over a sample of speeds is the exit speed at the
/// sample's mean speed v̄, and the best point for the mean is l*(v̄).
#[test]
fn the_best_point_for_a_samples_mean_is_the_closed_form_at_its_mean_speed() {
    let text = sampled("");
    let v = drawn_speeds(&text);
    let mean = v.iter().sum::<f64>() / v.len() as f64;
    let (z_cm, l) = closed_form_at(mean);
    let (z, _, _) = best(&text);
    eprintln!(
        "best impact point {z:.6} m, closed form at v = {mean:.4} m/s: {:.6} m",
        z_cm + l
    );
    assert!((z - (z_cm + l)).abs() < 1e-4, "{z} vs {}", z_cm + l);
}

/// A probability constraint, counted: P(approach speed ≤ c) ≥ 0.9 over the sample, with c
/// set so that it binds half way to the unconstrained optimum. The approach speed is
/// v − ω l, so the bound holds for a point exactly when its speed is at most c + ω l; the
/// optimum is the largest l for which 58 of the 64 drawn speeds (⌈0.9 × 64⌉) are.
#[test]
fn a_probability_constraint_holds_for_the_share_of_the_sample_it_names() {
    let v = drawn_speeds(&sampled(""));
    let mean = v.iter().sum::<f64>() / v.len() as f64;
    let (z_cm, l_best) = closed_form_at(mean);
    let mut sorted = v.clone();
    sorted.sort_by(f64::total_cmp);
    let v58 = sorted[57];
    let c = v58 - OMEGA * l_best / 2.0;
    let extra =
        format!("  constraints:\n    - {{quantity: approach_speed, max: {c}, probability: 0.9}}\n");
    let (z, values, margins) = best(&sampled(&extra));
    let l = z - z_cm;
    let share = v.iter().filter(|&&vi| vi - OMEGA * l <= c).count();
    eprintln!(
        "best {z:.6} m; {share} of 64 points within the bound; margin {:.3e}",
        margins[0]
    );
    assert!(
        share >= 58,
        "only {share} of 64 points keep approach speed <= {c}"
    );
    assert!(margins[0] >= 0.0 && values[0] <= c);
    assert!((l - l_best / 2.0).abs() < 1e-3, "{l} vs {}", l_best / 2.0);
}

/// CMA-ES (`method: cma_es`) finds the same closed-form point, and the same seed asks for the
/// same candidates (its record replays).
#[test]
fn cma_es_finds_the_rigid_bats_best_impact_point() {
    let (z_cm, l) = closed_form();
    let text = study("").replace(
        "  max_evaluations: 300\n",
        "  max_evaluations: 300\n  method: cma_es\n  seed: 3\n",
    );
    assert!(text.contains("cma_es"));
    let (z, _, _) = best(&text);
    eprintln!(
        "CMA-ES: best impact point {z:.6} m, closed form {:.6} m",
        z_cm + l
    );
    assert!((z - (z_cm + l)).abs() < 1e-4, "{z} vs {}", z_cm + l);
    assert_eq!(best(&text).0.to_bits(), z.to_bits());
}

/// A two-objective search against the same closed form: exit speed (maximised) against
/// the approach speed v − ω l (minimised), which grows toward the barrel. Every point from
/// the handle end of the bounds (z = 0.40 m, the least approach speed) to the best point
/// z_cm + l* trades one for the other, and every point beyond l* is worse in both: the
/// front is [0.40, z_cm + l*]. The ε-constraint searches end on their caps c_k, at
/// z_k = z_cm + (c_k − v)/(−ω), evenly spaced in approach speed between the two ends.
#[test]
fn a_pareto_front_is_the_closed_forms_trade_off() {
    use batstudy::optimize::pareto::{front, search_pareto};
    let (z_cm, l) = closed_form();
    let z_best = z_cm + l;
    let text = study("  pareto: {minimize: approach_speed, points: 5}\n");
    let s = load_str(&text, Path::new("front.yaml"), &LoadOptions::default()).unwrap();
    let design = design_of(&s).unwrap().unwrap();
    let ev = Evaluator::new(&s, &design);
    let out = search_pareto(
        &design,
        &|x| ev.evaluate(x),
        &|_| Ok(()),
        Vec::new(),
        &AtomicBool::new(false),
    );
    let on = front(&design, &out.candidates);
    let z: Vec<f64> = out.candidates.iter().map(|c| c.x[0]).collect();
    let on_front: Vec<f64> = z
        .iter()
        .zip(&on)
        .filter(|(_, &f)| f)
        .map(|(&z, _)| z)
        .collect();
    eprintln!(
        "{} candidates, {} on the front, z in [{:.4}, {:.4}], best {z_best:.4}",
        z.len(),
        on_front.len(),
        on_front.iter().copied().fold(f64::INFINITY, f64::min),
        on_front.iter().copied().fold(0.0, f64::max)
    );
    assert!(
        on_front
            .iter()
            .all(|&zf| (0.40..=z_best + 1e-3).contains(&zf)),
        "{on_front:?}"
    );
    let approach = |z: f64| V - OMEGA * (z - z_cm);
    let near = |target: f64| on_front.iter().any(|&zf| (zf - target).abs() < 1e-3);
    assert!(near(0.40) && near(z_best), "the anchors: {on_front:?}");
    for k in 1..4 {
        let cap = approach(0.40) + (approach(z_best) - approach(0.40)) * k as f64 / 4.0;
        let zk = z_cm + (cap - V) / -OMEGA;
        assert!(near(zk), "cap {k}: z {zk:.4} not on the front {on_front:?}");
    }
    // no design evaluated twice across the five searches
    let mut bits: Vec<u64> = z.iter().map(|z| z.to_bits()).collect();
    bits.sort_unstable();
    bits.dedup();
    assert_eq!(bits.len(), z.len());
}
