//! One run of a study as `batstudy run` does it: the bats prepared while the store begins its
//! file, the driver, the real store (journal + final file) in a given directory; and a
//! temporary directory for those files.

use super::measure::{err, machine_stolen, peak_rss, process_cpu_seconds, reset_peak};
use crate::run::{self, ModelSimulator, RunOptions, Sink, StoreSink};
use crate::store;
use crate::study::Study;
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;
use std::time::Instant;

/// What one run through the store took.
#[derive(Debug, Clone, Serialize)]
pub struct StoreRun {
    pub points: usize,
    pub threads: usize,
    /// Bytes of the final file (removed after the run).
    pub file_bytes: u64,
    /// Wall seconds from the bats' preparation to the durable file.
    pub wall_seconds: f64,
    /// CPU seconds of the process over the run (every thread).
    pub cpu_seconds: f64,
    /// Peak resident memory during the run (VmHWM after a reset) and before it, bytes; None
    /// where `/proc/self/clear_refs` is unavailable.
    pub peak_rss_bytes: Option<u64>,
    pub rss_before_bytes: Option<u64>,
    /// The share of the machine's CPU time its host took during the run (`/proc/stat`'s
    /// steal time over the wall time of every CPU); None where it cannot be read. Nonzero
    /// only in a virtual machine: the CPU its host spends on other guests, or on this one's
    /// behalf (its disk, where writing a byte costs the host CPU time).
    pub stolen_share: Option<f64>,
}

impl StoreRun {
    pub fn points_per_second(&self) -> f64 {
        self.points as f64 / self.wall_seconds
    }
}

/// Run `study` on `pool` into `dir/FILE.h5` with the store's sink passed through `wrap`
/// (e.g. to time its calls); the file is removed afterwards. Returns the figures and the
/// sink.
pub fn store_run_with<K: Sink>(
    file: &str,
    study: &Study,
    dir: &Path,
    pool: &rayon::ThreadPool,
    wrap: impl FnOnce(StoreSink) -> K,
) -> Result<(StoreRun, K), String> {
    let threads = pool.current_num_threads();
    let out: PathBuf = dir.join(format!("{file}.h5"));
    let rss_before = reset_peak();
    let c0 = process_cpu_seconds();
    let stolen0 = machine_stolen();
    // from the bats' preparation on, as in `batstudy run` (`cli::run_with`)
    let t0 = Instant::now();
    let (bats, begun) = run::prepare_bats_alongside(&ModelSimulator, &study.plan, pool, || {
        store::begin(&out, &study.plan.shape)
    });
    let history = study.history_request(bats.max_length());
    let info = study.info(bats.variants.clone(), history.clone());
    let session = begun
        .and_then(|b| store::open_begun(&out, &info, &store::StoreOptions::default(), Some(b)))
        .map_err(err("open the results file"))?;
    let opts = RunOptions {
        jobs: threads,
        ..RunOptions::default()
    };
    let stop = AtomicBool::new(false);
    let sink = wrap(StoreSink::new(session));
    let (report, sink) = run::run_plan(
        &study.plan,
        &ModelSimulator,
        &bats,
        history.as_ref(),
        sink,
        pool,
        &opts,
        &stop,
    )
    .map_err(err("run"))?;
    let wall = t0.elapsed().as_secs_f64();
    let cpu = process_cpu_seconds() - c0;
    let stolen_share = match (stolen0, machine_stolen()) {
        (Some(a), Some(b)) => Some((b.seconds - a.seconds) / (wall * b.cpus as f64)),
        _ => None,
    };
    let peak = rss_before.and_then(|_| peak_rss());
    if report.failed > 0 {
        return Err(format!("bench {file}: {} points failed", report.failed));
    }
    let file_bytes = std::fs::metadata(&out).map_or(0, |m| m.len());
    let _ = std::fs::remove_file(&out);
    let run = StoreRun {
        points: study.plan.n_points(),
        threads,
        file_bytes,
        wall_seconds: wall,
        cpu_seconds: cpu,
        peak_rss_bytes: peak,
        rss_before_bytes: rss_before,
        stolen_share,
    };
    Ok((run, sink))
}

/// [`store_run_with`] with the store's own sink.
pub fn store_run(
    file: &str,
    study: &Study,
    dir: &Path,
    pool: &rayon::ThreadPool,
) -> Result<StoreRun, String> {
    store_run_with(file, study, dir, pool, |s| s).map(|(r, _)| r)
}

/// A temporary directory removed on drop (no dev-dependency in the library).
pub struct TempDir(PathBuf);

impl TempDir {
    /// A new directory under `base`.
    pub fn new_in(base: &Path) -> Result<TempDir, String> {
        let nanos = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.as_nanos());
        let p = base.join(format!("batstudy-bench-{}-{nanos}", std::process::id()));
        std::fs::create_dir_all(&p).map_err(err("create a temporary directory"))?;
        Ok(TempDir(p))
    }

    pub fn path(&self) -> &Path {
        &self.0
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}
