//! The `sample` block's means and variances converge at the rates quasi-random
//! points promise, on a problem whose distribution is known in closed form.
//!
//! Brody's rigid bat at rest, hit head-on at z by a ball of speed v and COR e (free bat):
//! the ball leaves at v (e − r)/(1 + r), r = m/M_e, 1/M_e = 1/M + (z − z_cm)²/I_cm
//! (Brody 1986; docs/physics.md). The exit speed is linear in e, so its mean and variance
//! follow from e's: v (μ − r)/(1 + r) and (v/(1 + r))² Var e.
//!
//! - e uniform on the ball specification's window: the exit speed is a smooth (linear)
//!   function of the Sobol coordinate, and Owen-scrambled points integrate smooth functions
//!   with a root-mean-square error falling as N^(−3/2) (Owen, Ann. Stat. 25, 1541 (1997));
//!   the same holds for the population variance (a smooth integrand, minus the square of the
//!   mean's error). Plain Monte Carlo would fall as N^(−1/2).
//! - e normal: the normal quantile is unbounded at the cube's faces, where Owen's rate does
//!   not hold; an integrand growing slower than any power there converges as N^(−1+ε)
//!   (Owen, SIAM Rev. 48, 487 (2006), "Halton sequences avoid the origin"), so the mean's
//!   error is expected to fall as N^(−1), still twice Monte Carlo's exponent.

use batstudy::model::{simulate_target, Target};
use batstudy::study::{load_str, LoadOptions};
use std::path::Path;

const V: f64 = 40.0;
const Z: f64 = 0.70;
const MU: f64 = 0.546;
const SIGMA: f64 = 0.016;

/// The rule book's window of the ball's COR, 0.546 ± 0.032.
const LO: f64 = 0.514;
const HI: f64 = 0.578;

fn study(n: usize, seed: u32, dist: &str) -> String {
    format!(
        "name: conv\nmodel: rigid\nbase:\n  impact: {{z: {Z}}}\n  ball: {{speed: {V}}}\n\
         sample:\n  n: {n}\n  seed: {seed}\n  params:\n    ball.law.cor: {dist}\n"
    )
}

/// The sample mean and population variance of the exit speed.
fn moments(n: usize, seed: u32, dist: &str, target: &Target) -> (f64, f64) {
    let text = study(n, seed, dist);
    let s = load_str(&text, Path::new("conv.yaml"), &LoadOptions::default()).unwrap();
    let v: Vec<f64> = (0..s.plan.n_points())
        .map(|i| {
            let p = s.plan.point(i).unwrap();
            simulate_target(&p.spec, target, None).unwrap().exit_speed
        })
        .collect();
    let mean = v.iter().sum::<f64>() / n as f64;
    let var = v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / n as f64;
    (mean, var)
}

/// Least-squares slope of log(err) against log(n).
fn slope(n: &[usize], err: &[f64]) -> f64 {
    let x: Vec<f64> = n.iter().map(|&k| (k as f64).ln()).collect();
    let y: Vec<f64> = err.iter().map(|e| e.ln()).collect();
    let (mx, my) = (x.iter().sum::<f64>() / 5.0, y.iter().sum::<f64>() / 5.0);
    let sxy: f64 = x.iter().zip(&y).map(|(a, b)| (a - mx) * (b - my)).sum();
    let sxx: f64 = x.iter().map(|a| (a - mx).powi(2)).sum();
    sxy / sxx
}

/// The rigid bat and the exit speed's slope r: v_out = v (e − r)/(1 + r).
fn bat() -> (Target, f64) {
    let text = study(2, 0, "{uniform: {min: 0.5, max: 0.6}}");
    let base = load_str(&text, Path::new("conv.yaml"), &LoadOptions::default()).unwrap();
    let spec = base.plan.point(0).unwrap().spec;
    let target = Target::prepare(&spec.bat, &spec.numerics).unwrap();
    let p = target.properties();
    let inv_me = 1.0 / p.mass + (Z - p.z_cm).powi(2) / p.moment_of_inertia;
    (target, spec.ball.mass * inv_me)
}

const NS: [usize; 5] = [64, 256, 1024, 4096, 16384];

/// Root-mean-square errors of the mean and the variance over 8 seeds, for each of [`NS`].
fn rms_errors(dist: &str, target: &Target, mean: f64, var: f64) -> (Vec<f64>, Vec<f64>) {
    let (mut em, mut ev) = (Vec::new(), Vec::new());
    for &n in &NS {
        let (mut sm, mut sv) = (0.0, 0.0);
        for seed in 0..8u32 {
            let (m, v) = moments(n, seed, dist, target);
            sm += (m - mean).powi(2);
            sv += (v - var).powi(2);
        }
        em.push((sm / 8.0).sqrt());
        ev.push((sv / 8.0).sqrt());
    }
    (em, ev)
}

#[test]
fn a_uniform_cor_converges_as_n_to_the_minus_three_halves() {
    let (target, r) = bat();
    let mean = V * ((LO + HI) / 2.0 - r) / (1.0 + r);
    let var = (V / (1.0 + r)).powi(2) * (HI - LO).powi(2) / 12.0;
    let dist = format!("{{uniform: {{min: {LO}, max: {HI}}}}}");
    let (em, ev) = rms_errors(&dist, &target, mean, var);
    let (a, b) = (slope(&NS, &em), slope(&NS, &ev));
    eprintln!("uniform: rms errors of the mean {em:?} (slope {a:.2}), variance {ev:?} ({b:.2})");
    assert!((-1.7..=-1.3).contains(&a), "mean converges as N^{a:.2}");
    assert!(
        (-1.75..=-1.25).contains(&b),
        "variance converges as N^{b:.2}"
    );
    assert!(em[4] < 1e-6 * var.sqrt(), "{em:?}");
}

#[test]
fn a_normal_cor_converges_as_n_to_the_minus_one() {
    let (target, r) = bat();
    let mean = V * (MU - r) / (1.0 + r);
    let var = (V * SIGMA / (1.0 + r)).powi(2);
    let dist = format!("{{normal: {{mean: {MU}, sd: {SIGMA}}}}}");
    let (em, ev) = rms_errors(&dist, &target, mean, var);
    let (a, b) = (slope(&NS, &em), slope(&NS, &ev));
    eprintln!("normal: rms errors of the mean {em:?} (slope {a:.2}), variance {ev:?} ({b:.2})");
    assert!((-1.3..=-0.85).contains(&a), "mean converges as N^{a:.2}");
    // the variance's integrand grows like log(1/u) at the faces: N^(-1+eps) as well
    assert!((-1.3..=-0.7).contains(&b), "variance converges as N^{b:.2}");
    assert!(em[4] < 1e-4 * var.sqrt(), "{em:?}");
}
