//! The sinks the benchmark runs the driver with: one that keeps nothing (the baseline), one
//! that times the calls into another (the store); and one null-sink run of a study.

use super::measure::{err, process_cpu_seconds, thread_cpu_seconds};
use crate::results::PointRecord;
use crate::run::{self, AsIs, Encode, ModelSimulator, RunOptions, Sink};
use crate::study::Study;
use std::sync::atomic::AtomicBool;
use std::time::{Duration, Instant};

/// A sink that keeps nothing.
pub(super) struct NullSink;

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

/// A sink that times the calls into another (wall and CPU time of the calling thread; each
/// call runs on one thread), or, switched off, only passes them on: reading a thread's CPU
/// clock is a system call (~0.6 µs here), two per record, which the store runs compared with
/// null runs must not pay (a bias of about 0.5 % of the small study's wall against the store).
pub(super) struct TimedSink<K> {
    inner: K,
    on: bool,
    /// Wall and CPU seconds in `write`/`idle` (the journal) and in `finish` (the final file).
    pub(super) journal: Duration,
    pub(super) finish: Duration,
    pub(super) journal_cpu: f64,
    pub(super) finish_cpu: f64,
}

impl<K> TimedSink<K> {
    pub(super) fn new(inner: K, on: bool) -> Self {
        TimedSink {
            inner,
            on,
            journal: Duration::ZERO,
            finish: Duration::ZERO,
            journal_cpu: 0.0,
            finish_cpu: 0.0,
        }
    }
}

fn timed<R>(on: bool, wall: &mut Duration, cpu: &mut f64, f: impl FnOnce() -> R) -> R {
    if !on {
        return f();
    }
    let c0 = thread_cpu_seconds();
    let t0 = Instant::now();
    let r = f();
    *wall += t0.elapsed();
    *cpu += thread_cpu_seconds() - c0;
    r
}

impl<K: Sink> Sink for TimedSink<K> {
    type Encoder = K::Encoder;
    fn encoder(&self) -> K::Encoder {
        self.inner.encoder()
    }
    fn is_done(&self, index: usize) -> bool {
        self.inner.is_done(index)
    }
    fn write(&mut self, rec: <K::Encoder as Encode>::Record) -> Result<(), String> {
        let inner = &mut self.inner;
        timed(self.on, &mut self.journal, &mut self.journal_cpu, || {
            inner.write(rec)
        })
    }
    fn idle(&mut self) -> Result<(), String> {
        let inner = &mut self.inner;
        timed(self.on, &mut self.journal, &mut self.journal_cpu, || {
            inner.idle()
        })
    }
    fn finish(&mut self) -> Result<(), String> {
        let inner = &mut self.inner;
        timed(self.on, &mut self.finish, &mut self.finish_cpu, || {
            inner.finish()
        })
    }
}

/// Wall and CPU seconds of one null-sink run.
pub(super) fn run_null(
    study: &Study,
    bats: &run::PreparedBats<crate::model::Target>,
    pool: &rayon::ThreadPool,
) -> Result<(f64, f64), String> {
    run_null_recording(study, bats, None, pool)
}

/// [`run_null`], the points recording `history` (computed, then dropped by the sink).
pub(super) fn run_null_recording(
    study: &Study,
    bats: &run::PreparedBats<crate::model::Target>,
    history: Option<&crate::model::outcome::HistoryRequest>,
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
        &RunOptions::default(),
        &stop,
    )
    .map_err(err("run"))?;
    let t = t0.elapsed().as_secs_f64();
    let c = process_cpu_seconds() - c0;
    if report.failed > 0 {
        return Err(format!("bench run: {} points failed", report.failed));
    }
    Ok((t, c))
}
