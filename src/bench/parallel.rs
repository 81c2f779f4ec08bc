//! Parallel efficiency: a few thousand points through the real driver (null sink) on one
//! thread and on all cores, and the cost of resolving a point of the plan.

use super::cases::{curve_study_text, load_study, Sizes};
use super::measure::{err, median};
use super::sinks::run_null;
use crate::run::{self, ModelSimulator};
use serde::Serialize;
use std::time::Instant;

#[derive(Debug, Clone, Serialize)]
pub struct ParallelBench {
    pub points: usize,
    pub threads: usize,
    /// Median wall seconds of `run_plan` on 1 thread and on `threads`.
    pub seconds_1: f64,
    pub seconds_n: f64,
    /// Median over repeats of t_1 / (threads · t_n) (wall clock: depends on what else runs).
    pub efficiency: f64,
    /// Median process CPU seconds of the two runs, and their ratio cpu_1 / cpu_n: the work
    /// added by running in parallel (1.0 = none), whatever else shares the machine.
    pub cpu_seconds_1: f64,
    pub cpu_seconds_n: f64,
    pub cpu_efficiency: f64,
    /// Cores the n-thread run actually got on average (cpu_n / t_n).
    pub cores_obtained: f64,
    /// Median µs to resolve one point of the plan (`Plan::point`), one thread.
    pub resolve_us_per_point: f64,
    pub repeats: usize,
}

pub(super) fn bench_parallel(sz: &Sizes, threads: usize) -> Result<ParallelBench, String> {
    let study = load_study(
        &curve_study_text("bench-parallel", sz.parallel_omegas, ""),
        "bench-parallel",
    )?;
    let pool1 = run::build_pool(1).map_err(err("pool"))?;
    let pool_n = run::build_pool(threads).map_err(err("pool"))?;
    let bats = run::prepare_bats(&ModelSimulator, &study.plan, &pool1);
    // warm-up (page faults, lazy statics)
    run_null(&study, &bats, &pool_n)?;
    let (mut t1, mut tn, mut eff) = (Vec::new(), Vec::new(), Vec::new());
    let (mut c1, mut cn, mut ceff, mut cores) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for _ in 0..sz.parallel_repeats {
        let (a, ca) = run_null(&study, &bats, &pool1)?;
        let (b, cb) = run_null(&study, &bats, &pool_n)?;
        t1.push(a);
        tn.push(b);
        eff.push(a / (threads as f64 * b));
        c1.push(ca);
        cn.push(cb);
        ceff.push(ca / cb);
        cores.push(cb / b);
    }
    let n = study.plan.n_points();
    let resolve = {
        let mut v = Vec::new();
        for _ in 0..3 {
            let t0 = Instant::now();
            for i in 0..n.min(2000) {
                std::hint::black_box(study.plan.point(i).ok());
            }
            v.push(t0.elapsed().as_secs_f64() * 1e6 / n.min(2000) as f64);
        }
        median(v)
    };
    Ok(ParallelBench {
        points: n,
        threads,
        seconds_1: median(t1),
        seconds_n: median(tn),
        efficiency: median(eff),
        cpu_seconds_1: median(c1),
        cpu_seconds_n: median(cn),
        cpu_efficiency: median(ceff),
        cores_obtained: median(cores),
        resolve_us_per_point: resolve,
        repeats: sz.parallel_repeats,
    })
}
