//! The HDF5 share: what the results store (journal + final file) adds to a run's wall time,
//! store runs paired with runs of the same plan into a sink that keeps nothing, and where
//! the store's time goes (its calls timed in a few more runs).

use crate::bench::measure::{err, median, thread_cpu_seconds};
use crate::bench::sinks::null_run;
use crate::bench::store_run::{store_run_with, StoreRun};
use crate::run::{self, Encode, ModelSimulator, Sink};
use crate::study::Study;
use serde::Serialize;
use std::path::Path;
use std::time::{Duration, Instant};

#[derive(Debug, Clone, Serialize)]
pub struct WriteShare {
    pub case: String,
    pub points: usize,
    pub threads: usize,
    /// Pairs behind the medians.
    pub pairs: usize,
    /// Median wall seconds of the store runs and of the null-sink runs (bats prepared in
    /// both, as in `batstudy run`).
    pub store_wall_seconds: f64,
    pub null_wall_seconds: f64,
    /// Median over the pairs of (store − null) / store, and its quartiles (the noise).
    pub wall_overhead: f64,
    pub wall_overhead_quartiles: (f64, f64),
    /// From the timed store run of median wall time: wall seconds inside the sink's
    /// `write`/`idle` (journal) and `finish` (final file), their share of the wall, the
    /// same in CPU time (insensitive to load), and the file's size.
    pub journal_seconds: f64,
    pub final_file_seconds: f64,
    pub share: f64,
    pub cpu_seconds: f64,
    pub journal_cpu_seconds: f64,
    pub final_file_cpu_seconds: f64,
    pub cpu_share: f64,
    pub file_bytes: u64,
}

/// A sink that times the calls into another (wall and CPU time of the calling thread). Only
/// in the timed runs: reading a thread's CPU clock is a system call (~0.6 µs), two per
/// record, which the runs paired with null runs must not pay.
struct TimedSink<K> {
    inner: K,
    journal: Duration,
    finish: Duration,
    journal_cpu: f64,
    finish_cpu: f64,
}

fn timed<R>(wall: &mut Duration, cpu: &mut f64, f: impl FnOnce() -> R) -> R {
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
        timed(&mut self.journal, &mut self.journal_cpu, || {
            inner.write(rec)
        })
    }
    fn idle(&mut self) -> Result<(), String> {
        let inner = &mut self.inner;
        timed(&mut self.journal, &mut self.journal_cpu, || inner.idle())
    }
    fn finish(&mut self) -> Result<(), String> {
        let inner = &mut self.inner;
        timed(&mut self.finish, &mut self.finish_cpu, || inner.finish())
    }
}

/// A store run whose store calls are timed.
fn timed_run(
    file: &str,
    study: &Study,
    dir: &Path,
    pool: &rayon::ThreadPool,
) -> Result<(StoreRun, TimedSink<run::StoreSink>), String> {
    store_run_with(file, study, dir, pool, |inner| TimedSink {
        inner,
        journal: Duration::ZERO,
        finish: Duration::ZERO,
        journal_cpu: 0.0,
        finish_cpu: 0.0,
    })
}

/// `pairs` store runs of `study` on `threads`, each beside a null-sink run of the same plan
/// (the order alternates within pairs: whichever runs second tends to be a few percent
/// faster), then a few timed store runs for the breakdown. The null runs share the store
/// runs' pool (a pool built per run starts its threads cold, a bias against the store).
pub fn write_share(
    case: &str,
    study: &Study,
    dir: &Path,
    threads: usize,
    pairs: usize,
) -> Result<WriteShare, String> {
    let pool = run::build_pool(threads).map_err(err("pool"))?;
    let null = || -> Result<f64, String> {
        let t0 = Instant::now();
        let bats = run::prepare_bats(&ModelSimulator, &study.plan, &pool);
        null_run(study, &bats, None, &pool)?;
        Ok(t0.elapsed().as_secs_f64())
    };
    let store = || store_run_with(case, study, dir, &pool, |s| s).map(|(r, _)| r.wall_seconds);
    let pairs = pairs.max(1);
    let (mut stores, mut nulls, mut overheads) = (Vec::new(), Vec::new(), Vec::new());
    for k in 0..pairs {
        let (n, s) = if k % 2 == 0 {
            (null()?, store()?)
        } else {
            let s = store()?;
            (null()?, s)
        };
        overheads.push((s - n) / s);
        nulls.push(n);
        stores.push(s);
    }
    let mut timed = (0..(pairs / 8).clamp(1, 9))
        .map(|_| timed_run(case, study, dir, &pool))
        .collect::<Result<Vec<_>, _>>()?;
    timed.sort_by(|a, b| a.0.wall_seconds.total_cmp(&b.0.wall_seconds));
    let (run, sink) = timed.swap_remove(timed.len() / 2);
    overheads.sort_by(|a, b| a.total_cmp(b));
    let quartiles = (overheads[pairs / 4], overheads[(3 * pairs) / 4]);
    let (journal, fin) = (sink.journal.as_secs_f64(), sink.finish.as_secs_f64());
    Ok(WriteShare {
        case: case.to_string(),
        points: run.points,
        threads,
        pairs,
        store_wall_seconds: median(stores),
        null_wall_seconds: median(nulls),
        wall_overhead: median(overheads),
        wall_overhead_quartiles: quartiles,
        journal_seconds: journal,
        final_file_seconds: fin,
        share: (journal + fin) / run.wall_seconds,
        cpu_seconds: run.cpu_seconds,
        journal_cpu_seconds: sink.journal_cpu,
        final_file_cpu_seconds: sink.finish_cpu,
        cpu_share: (sink.journal_cpu + sink.finish_cpu) / run.cpu_seconds,
        file_bytes: run.file_bytes,
    })
}
