//! Peak resident memory: a 10-million-point summary-only plan through the driver (null sink),
//! and summary-only studies through the store at two sizes (its memory must not grow with
//! the study).

use super::cases::{load_study, rigid_study_text, Sizes};
use super::measure::{err, peak_rss, reset_peak};
use super::sinks::NullSink;
use super::write_share::{bench_write, WriteShare};
use crate::run::{self, ModelSimulator, RunOptions};
use crate::store;
use serde::Serialize;
use std::path::Path;
use std::sync::atomic::AtomicBool;
use std::time::Instant;

#[derive(Debug, Clone, Serialize)]
pub struct MemoryBench {
    /// Points of the summary-only plan (10 million; fewer with --quick).
    pub plan_points: usize,
    pub plan_seconds: f64,
    pub plan_peak_rss_bytes: Option<u64>,
    pub plan_rss_before_bytes: Option<u64>,
    /// Channel capacity of the driver (records in flight).
    pub channel_capacity: usize,
    /// Summary-only studies through the driver and the real store (rigid model), full size and
    /// four times that: the store keeps one bit per point, and the final file's build holds
    /// at most `build_memory` bytes of summary values (more points → more windows, not more
    /// memory).
    pub build_memory: usize,
    pub store_small_points: usize,
    pub store_small_peak_rss_bytes: Option<u64>,
    pub store_small_rss_before_bytes: Option<u64>,
    pub store_points: usize,
    pub store_seconds: f64,
    pub store_peak_rss_bytes: Option<u64>,
    pub store_rss_before_bytes: Option<u64>,
    /// The history study's peak (same run as `hdf5[1]`).
    pub history_points: usize,
    pub history_peak_rss_bytes: Option<u64>,
    pub history_bytes_in_memory: u64,
}

/// The 10-million-point summary-only plan (rigid model, null sink): memory stays flat.
fn bench_plan_memory(
    sz: &Sizes,
    threads: usize,
) -> Result<(usize, f64, Option<u64>, Option<u64>), String> {
    let [a, b, c] = sz.plan_points;
    let text = rigid_study_text("bench-plan", a, b, c);
    let rss_before = reset_peak();
    let t0 = Instant::now();
    let study = load_study(&text, "bench-plan")?;
    let pool = run::build_pool(threads).map_err(err("pool"))?;
    let bats = run::prepare_bats(&ModelSimulator, &study.plan, &pool);
    let stop = AtomicBool::new(false);
    let (report, _) = run::run_plan(
        &study.plan,
        &ModelSimulator,
        &bats,
        None,
        NullSink,
        &pool,
        &RunOptions {
            jobs: threads,
            ..RunOptions::default()
        },
        &stop,
    )
    .map_err(err("run"))?;
    let t = t0.elapsed().as_secs_f64();
    if report.failed > 0 || report.ok != study.plan.n_points() {
        return Err(format!(
            "bench plan: {} ok, {} failed of {}",
            report.ok,
            report.failed,
            study.plan.n_points()
        ));
    }
    Ok((
        study.plan.n_points(),
        t,
        rss_before.and_then(|_| peak_rss()),
        rss_before,
    ))
}

/// The memory section: the plan above, then the store studies at full size and at four
/// times that. Returns the figures and the smaller store study's wall seconds.
pub(super) fn bench_memory(
    sz: &Sizes,
    threads: usize,
    dir: &Path,
    history: &WriteShare,
) -> Result<(MemoryBench, f64), String> {
    let (plan_points, plan_seconds, plan_peak, plan_before) = bench_plan_memory(sz, threads)?;
    let [a, b, c] = sz.store_points;
    let store_study =
        |name: &str, omegas: usize| load_study(&rigid_study_text(name, a, omegas, c), name);
    // the study at full size and at four times that: the build's window is capped, so the
    // store's memory above the start should not grow between the two
    let small_study = store_study("bench-store", b)?;
    let store_study = store_study("bench-store-large", 4 * b)?;
    let wsm = bench_write("store-small", &small_study, dir, threads)?;
    let wst = bench_write("store", &store_study, dir, threads)?;
    let mb = MemoryBench {
        plan_points,
        plan_seconds,
        plan_peak_rss_bytes: plan_peak,
        plan_rss_before_bytes: plan_before,
        channel_capacity: RunOptions::default().channel_capacity,
        history_points: history.points,
        history_peak_rss_bytes: history.peak_rss_bytes,
        history_bytes_in_memory: history.history_bytes_in_memory,
        build_memory: store::StoreOptions::default().build_memory,
        store_small_points: wsm.points,
        store_small_peak_rss_bytes: wsm.peak_rss_bytes,
        store_small_rss_before_bytes: wsm.rss_before_bytes,
        store_points: wst.points,
        store_seconds: wst.wall_seconds,
        store_peak_rss_bytes: wst.peak_rss_bytes,
        store_rss_before_bytes: wst.rss_before_bytes,
    };
    Ok((mb, wsm.wall_seconds))
}
