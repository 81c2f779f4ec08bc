//! The HDF5 share: what the results store (journal + final file) costs a run, timed inside
//! its calls and against the same plan run with a sink that keeps nothing; the store's files
//! go to a temporary directory.

use super::cases::{curve_study_text, load_study, Sizes, HISTORY_BLOCK};
use super::measure::{err, median, peak_rss, process_cpu_seconds, reset_peak};
use super::sinks::{run_null, TimedSink};
use crate::model::outcome::HistoryRequest;
use crate::run::{self, ModelSimulator, RunOptions, StoreSink};
use crate::store;
use crate::study::Study;
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;
use std::time::Instant;

#[derive(Debug, Clone, Serialize)]
pub struct WriteShare {
    pub case: String,
    pub points: usize,
    pub threads: usize,
    /// Bytes of the final file.
    pub file_bytes: u64,
    /// Wall seconds of the run (driver + store, bats prepared beforehand).
    pub wall_seconds: f64,
    /// Seconds inside the sink's `write`/`idle` calls (journal) and in `finish` (HDF5 file).
    pub journal_seconds: f64,
    pub final_file_seconds: f64,
    /// (journal + final) / wall.
    pub share: f64,
    /// The same in CPU time: process CPU seconds of the run, the store's CPU seconds (writer
    /// thread in `write`/`idle`, caller in `finish`) and their ratio (insensitive to load).
    pub cpu_seconds: f64,
    pub journal_cpu_seconds: f64,
    pub final_file_cpu_seconds: f64,
    pub cpu_share: f64,
    /// Peak resident memory during the run (VmHWM after a reset), bytes; None where
    /// `/proc/self/clear_refs` is unavailable.
    pub peak_rss_bytes: Option<u64>,
    /// Resident memory before the run, bytes.
    pub rss_before_bytes: Option<u64>,
    /// Size of all the study's histories held as f64 (0 for summary-only).
    pub history_bytes_in_memory: u64,
    /// What writing costs the user: the same plan run with a sink that keeps nothing,
    /// back to back with the store run (median wall seconds), and the median over repeats of
    /// (wall − null wall) / wall. `None` where not measured (the history case: one long run).
    pub null_wall_seconds: Option<f64>,
    pub wall_overhead: Option<f64>,
    /// First and third quartiles of the per-pair overheads (the machine's noise).
    pub wall_overhead_quartiles: Option<(f64, f64)>,
    /// Median wall seconds of the untimed store runs paired with the null runs.
    pub untimed_wall_seconds: Option<f64>,
    /// Pairs behind the medians (the other fields are from the timed store run of median
    /// wall time).
    pub repeats: usize,
}

fn history_bytes(h: &HistoryRequest) -> u64 {
    use crate::model::outcome::HistoryField as F;
    let series: usize = h
        .fields
        .iter()
        .map(|f| match f {
            F::Displacement => h.z.len(),
            F::RigidMotion => 2,
            _ => 1,
        })
        .sum();
    (series * h.n_samples * 8) as u64
}

/// Run `study` through the driver and the real store in `dir`; time the store's calls.
pub(super) fn bench_write(
    case: &str,
    study: &Study,
    dir: &Path,
    threads: usize,
) -> Result<WriteShare, String> {
    let pool = run::build_pool(threads).map_err(err("pool"))?;
    bench_write_to(case, case, study, dir, &pool, true)
}

/// `repeats` store runs, each beside a null-sink run of the same plan (the medians of the
/// store walls, the null walls and the per-pair overheads), then a few store runs that time
/// the store's calls: the breakdown comes from the timed run of median wall time. The pairs
/// run untimed: the timing itself costs the store runs a clock system call per call.
pub fn bench_write_vs_null(
    case: &str,
    study: &Study,
    dir: &Path,
    threads: usize,
    repeats: usize,
) -> Result<WriteShare, String> {
    let pool = run::build_pool(threads).map_err(err("pool"))?;
    let (mut stores, mut nulls, mut overheads) = (Vec::new(), Vec::new(), Vec::new());
    // from the bats' preparation on, as in `batstudy run`: the store begins its file while
    // the bats are prepared
    let null_run = || -> Result<f64, String> {
        let t0 = Instant::now();
        let bats = run::prepare_bats(&ModelSimulator, &study.plan, &pool);
        let (run, _) = run_null(study, &bats, &pool)?;
        std::hint::black_box(run);
        Ok(t0.elapsed().as_secs_f64())
    };
    let store_run = |k: usize, timed: bool| {
        bench_write_to(case, &format!("{case}-{k}"), study, dir, &pool, timed)
    };
    let repeats = repeats.max(1);
    for k in 0..repeats {
        // the order alternates within pairs: whichever runs second is measurably faster on
        // this machine, by a few percent either way
        let (null, store) = if k % 2 == 0 {
            let null = null_run()?;
            (null, store_run(k, false)?.wall_seconds)
        } else {
            let store = store_run(k, false)?.wall_seconds;
            (null_run()?, store)
        };
        overheads.push((store - null) / store);
        nulls.push(null);
        stores.push(store);
    }
    let mut timed = (0..(repeats / 8).clamp(1, 9))
        .map(|k| store_run(repeats + k, true))
        .collect::<Result<Vec<_>, _>>()?;
    timed.sort_by(|a, b| a.wall_seconds.total_cmp(&b.wall_seconds));
    let mut w = timed.swap_remove(timed.len() / 2);
    w.null_wall_seconds = Some(median(nulls));
    w.untimed_wall_seconds = Some(median(stores));
    overheads.sort_by(|a, b| a.total_cmp(b));
    let n = overheads.len();
    w.wall_overhead_quartiles = Some((overheads[n / 4], overheads[(3 * n) / 4]));
    w.wall_overhead = Some(median(overheads));
    w.repeats = repeats;
    Ok(w)
}

/// One store run on `pool` (the null runs it is compared with use the same pool: a pool
/// built for each store run alone made its threads start cold, a bias of about 1 % against
/// the store on the small study).
pub(super) fn bench_write_to(
    case: &str,
    file: &str,
    study: &Study,
    dir: &Path,
    pool: &rayon::ThreadPool,
    timed: bool,
) -> Result<WriteShare, String> {
    let threads = pool.current_num_threads();
    let out: PathBuf = dir.join(format!("{file}.h5"));
    let rss_before = reset_peak();
    let c0 = process_cpu_seconds();
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
    let sink = TimedSink::new(StoreSink::new(session), timed);
    let stop = AtomicBool::new(false);
    let opts = RunOptions {
        jobs: threads,
        ..RunOptions::default()
    };
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
    let peak = rss_before.and_then(|_| peak_rss());
    if report.failed > 0 {
        return Err(format!("bench {case}: {} points failed", report.failed));
    }
    let n = study.plan.n_points();
    let journal = sink.journal.as_secs_f64();
    let fin = sink.finish.as_secs_f64();
    Ok(WriteShare {
        case: case.to_string(),
        points: n,
        threads,
        file_bytes: std::fs::metadata(&out).map_or(0, |m| m.len()),
        wall_seconds: wall,
        journal_seconds: journal,
        final_file_seconds: fin,
        share: (journal + fin) / wall,
        cpu_seconds: cpu,
        journal_cpu_seconds: sink.journal_cpu,
        final_file_cpu_seconds: sink.finish_cpu,
        cpu_share: (sink.journal_cpu + sink.finish_cpu) / cpu,
        peak_rss_bytes: peak,
        rss_before_bytes: rss_before,
        history_bytes_in_memory: history.as_ref().map_or(0, history_bytes) * n as u64,
        null_wall_seconds: None,
        wall_overhead: None,
        wall_overhead_quartiles: None,
        untimed_wall_seconds: None,
        repeats: 1,
    })
}

/// The three HDF5 cases, in the report's order: the summary-only study and ten times its
/// points (each against a null sink), and the history study (timed calls only).
pub(super) fn bench_hdf5(
    sz: &Sizes,
    dir: &Path,
    threads: usize,
) -> Result<(WriteShare, WriteShare, WriteShare), String> {
    let summary_study = load_study(
        &curve_study_text("bench-summary", sz.summary_omegas, ""),
        "bench-summary",
    )?;
    let history_study = load_study(
        &curve_study_text("bench-history", sz.history_omegas, HISTORY_BLOCK),
        "bench-history",
    )?;
    let ws = bench_write_vs_null("summary", &summary_study, dir, threads, sz.write_repeats)?;
    let wh = bench_write("history", &history_study, dir, threads)?;
    // ten times the points: the store's fixed cost (file skeleton, fsyncs) spread thinner
    let large_study = load_study(
        &curve_study_text("bench-summary-large", 10 * sz.summary_omegas, ""),
        "bench-summary-large",
    )?;
    let wl = bench_write_vs_null(
        "summary-large",
        &large_study,
        dir,
        threads,
        sz.write_repeats.div_ceil(2).min(24),
    )?;
    Ok((ws, wh, wl))
}

/// A temporary directory removed on drop (no dev-dependency in the library).
pub(super) struct TempDir(PathBuf);

impl TempDir {
    pub(super) fn path(&self) -> &Path {
        &self.0
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

pub(super) fn tempfile_dir() -> Result<TempDir, String> {
    let base = std::env::temp_dir();
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_nanos());
    let p = base.join(format!("batstudy-bench-{}-{nanos}", std::process::id()));
    std::fs::create_dir_all(&p).map_err(err("create a temporary directory"))?;
    Ok(TempDir(p))
}
