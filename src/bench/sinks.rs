//! A sink that keeps nothing (the baseline: what a run computes, with no store), and one run
//! of a study through the driver into it.

use super::measure::{err, process_cpu_seconds};
use crate::model::outcome::HistoryRequest;
use crate::results::PointRecord;
use crate::run::{self, AsIs, ModelSimulator, RunOptions, Sink};
use crate::study::Study;
use std::sync::atomic::AtomicBool;
use std::time::Instant;

/// A sink that keeps nothing.
pub struct NullSink;

impl Sink for NullSink {
    type Encoder = AsIs;
    fn encoder(&self) -> AsIs {
        AsIs
    }
    fn is_done(&self, _index: usize) -> bool {
        false
    }
    fn write(&mut self, rec: PointRecord) -> Result<(), String> {
        std::hint::black_box(rec);
        Ok(())
    }
    fn finish(&mut self) -> Result<(), String> {
        Ok(())
    }
}

/// Wall and CPU seconds (all threads) of one run of `study` through the driver into a
/// [`NullSink`], its points recording `history` (computed, then dropped), the bats prepared
/// beforehand.
pub fn null_run(
    study: &Study,
    bats: &run::PreparedBats<crate::model::Target>,
    history: Option<&HistoryRequest>,
    pool: &rayon::ThreadPool,
) -> Result<(f64, f64), String> {
    let stop = AtomicBool::new(false);
    let c0 = process_cpu_seconds();
    let t0 = Instant::now();
    let (report, _) = run::run_plan(
        &study.plan,
        &ModelSimulator,
        bats,
        history,
        NullSink,
        pool,
        &RunOptions {
            jobs: pool.current_num_threads(),
            ..RunOptions::default()
        },
        &stop,
    )
    .map_err(err("run"))?;
    let t = t0.elapsed().as_secs_f64();
    let c = process_cpu_seconds() - c0;
    if report.failed > 0 || report.ok != study.plan.n_points() {
        return Err(format!(
            "bench run: {} ok, {} failed of {}",
            report.ok,
            report.failed,
            study.plan.n_points()
        ));
    }
    Ok((t, c))
}
