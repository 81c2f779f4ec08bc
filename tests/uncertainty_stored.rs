//! `/uncertainty` as `batstudy run` stores it, against closed forms.
//!
//! Brody's rigid bat at rest, hit head-on at z by a ball of speed v and COR e: the ball
//! leaves at v (e − r)/(1 + r), r = m/M_e, 1/M_e = 1/M + (z − z_cm)²/I_cm (Brody 1986;
//! docs/physics.md), and the bat's BBCOR is e itself (docs/layout.md, `/bat`). With e
//! uniform on the ball specification's window [LO, HI], both are linear in one uniform
//! variable u, so their quantiles, mean and standard deviation are known exactly.
//!
//! The bands come from the design, not from a run: the first 2^m Owen-scrambled Sobol
//! points of one dimension put exactly one point in each interval [k/n, (k + 1)/n)
//! (a (0, m, 1)-net; Owen, Ann. Stat. 25, 1541 (1997)). So the k-th smallest u lies in
//! [k/n, (k + 1)/n): NumPy's linear percentile (between the order statistics at
//! (n − 1) p) is within 2/n of p, and the sample mean of u within 1/(2n) of 1/2.
//!
//! The study is small enough that `/summary` is one chunk: the HDF5 1.10 "single chunk"
//! index, which HDF5 1.10.8 read back as the chunk's compressed bytes while the dataset
//! stayed open (the store read it so, and stored garbage in `/uncertainty`; fixed by
//! reading through datasets opened afresh, `Skeleton::into_file`).

mod common;

use batstudy::model::Target;
use batstudy::study::{load_str, LoadOptions};
use std::path::Path;

const V: f64 = 40.0;
const LO: f64 = 0.514;
const HI: f64 = 0.578;
const N: usize = 256;
const Z: [f64; 2] = [0.62, 0.70];
/// The quantiles `/uncertainty` stores (docs/layout.md).
const QUANTILES: [f64; 7] = [0.025, 0.05, 0.25, 0.5, 0.75, 0.95, 0.975];

fn study() -> String {
    format!(
        "name: stored\nmodel: rigid\nbase:\n  ball: {{speed: {V}}}\ngrid:\n  impact.z: [{}, {}]\n\
         sample:\n  n: {N}\n  seed: 5\n  params:\n    ball.law.cor: {{uniform: {{min: {LO}, max: {HI}}}}}\n",
        Z[0], Z[1]
    )
}

/// r = m/M_e at each impact position of the study's rigid bat.
fn mass_ratios(text: &str) -> Vec<f64> {
    let s = load_str(text, Path::new("stored.yaml"), &LoadOptions::default()).unwrap();
    let spec = s.plan.point(0).unwrap().spec;
    let p = Target::prepare(&spec.bat, &spec.numerics)
        .unwrap()
        .properties();
    Z.iter()
        .map(|z| spec.ball.mass * (1.0 / p.mass + (z - p.z_cm).powi(2) / p.moment_of_inertia))
        .collect()
}

fn read(f: &hdf5::File, name: &str) -> Vec<f64> {
    f.dataset(&format!("uncertainty/{name}"))
        .unwrap()
        .read_raw::<f64>()
        .unwrap()
}

/// `q` (7 quantiles), `mean` and `std` of a + b u, u uniform on [0, 1], within the bands
/// the net property gives.
fn check(what: &str, q: &[f64], mean: f64, std: f64, (a, b): (f64, f64)) {
    let n = N as f64;
    for (&got, p) in q.iter().zip(QUANTILES) {
        let want = a + b * p;
        assert!(
            (got - want).abs() <= 2.0 * b / n,
            "{what}: quantile {p}: {got} against {want} ± {}",
            2.0 * b / n
        );
    }
    let want = a + b / 2.0;
    assert!(
        (mean - want).abs() <= b / (2.0 * n),
        "{what}: mean {mean} against {want}"
    );
    let want = b / 12f64.sqrt();
    assert!(
        (std / want - 1.0).abs() < 0.02,
        "{what}: sd {std} against {want}"
    );
}

#[test]
fn the_stored_statistics_are_those_of_the_closed_form() {
    let dir = tempfile::tempdir().unwrap();
    let (yaml, out) = (dir.path().join("s.yaml"), dir.path().join("s.h5"));
    let text = study();
    std::fs::write(&yaml, &text).unwrap();
    common::batstudy_ok(&["run", yaml.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    let f = hdf5::File::open(&out).unwrap();
    assert_eq!(read(&f, "impact_z"), Z);
    let (speed, speed_mean, speed_std) = (
        read(&f, "exit_speed"),
        read(&f, "exit_speed_mean"),
        read(&f, "exit_speed_std"),
    );
    let (cor, cor_mean, cor_std) = (
        read(&f, "bbcor"),
        read(&f, "bbcor_mean"),
        read(&f, "bbcor_std"),
    );
    for (k, r) in mass_ratios(&text).into_iter().enumerate() {
        let q = &speed[7 * k..7 * (k + 1)];
        // v (e − r)/(1 + r) with e = LO + (HI − LO) u
        let line = (V * (LO - r) / (1.0 + r), V * (HI - LO) / (1.0 + r));
        check("exit speed", q, speed_mean[k], speed_std[k], line);
        let q = &cor[7 * k..7 * (k + 1)];
        check("bbcor", q, cor_mean[k], cor_std[k], (LO, HI - LO));
    }
    // every sampled ball is above the limit (LO > 0.50): so is every bat
    assert_eq!(read(&f, "bbcor_max_above_limit"), [1.0]);
}
