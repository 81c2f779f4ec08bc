//! Scaling with threads, and the writer's headroom.
//!
//! - `scaling`: points/s of a summary-only study and of a full-history study, each through the
//!   real driver and store, at 1, 2, 4, … threads up to every core of the machine.
//! - `writer_headroom`: how many workers the one writer thread can keep up with on the
//!   history study: the points/s the store's writer alone absorbs (records computed and
//!   encoded beforehand, then appended to the journal and the final file built, on one
//!   thread) over the points/s one worker computes and encodes them, as in a run.

use super::cases::{curve_study_text, load_study, Sizes, HISTORY_BLOCK, SCALAR_HISTORY_BLOCK};
use super::measure::{err, median};
use super::sinks::run_null_recording;
use super::write_share::bench_write_to;
use crate::results::PointRecord;
use crate::run::{self, ModelSimulator, Simulator};
use crate::store;
use serde::Serialize;
use std::path::Path;
use std::time::Instant;

/// Points/s at one thread count.
#[derive(Debug, Clone, Serialize)]
pub struct ScalingPoint {
    pub threads: usize,
    pub summary_points_per_second: f64,
    pub history_points_per_second: f64,
}

#[derive(Debug, Clone, Serialize)]
pub struct Scaling {
    /// Cores of the machine (the largest thread count measured).
    pub cores: usize,
    pub summary_points: usize,
    pub history_points: usize,
    pub points: Vec<ScalingPoint>,
    /// Parallel efficiency of each study on every core: rate(cores) / (cores · rate(1)).
    pub summary_efficiency: f64,
    pub history_efficiency: f64,
    /// History points/s per core over summary points/s per core, on every core.
    pub history_vs_summary_per_core: f64,
    /// Points/s of the history study on every core with its histories recorded but not
    /// stored (a null sink): what a store that cost nothing would give.
    pub history_compute_points_per_second: f64,
    /// history_compute / summary on every core: the most `history_vs_summary_per_core` can
    /// be with this study, whatever the store (a history point samples the bat 400 times).
    pub history_vs_summary_ceiling: f64,
    /// Points/s of the history study on every core, stored with `history.compression: none`
    /// (no filters: more bytes, far less CPU per point), and its file's size.
    pub history_uncompressed_points_per_second: f64,
    pub history_uncompressed_file_bytes: u64,
    /// The default (deflated) history study's file size.
    pub history_file_bytes: u64,
    /// Points/s on every core of the history study without `displacement` (the scalar
    /// series: force, compression, ball velocity, rigid motion), and per core over the
    /// summary study's.
    pub history_scalar_points_per_second: f64,
    pub history_scalar_vs_summary_per_core: f64,
}

#[derive(Debug, Clone, Serialize)]
pub struct WriterHeadroom {
    pub points: usize,
    /// Points/s the store's writer absorbs on one thread (appending encoded records while
    /// running, then the final file).
    pub writer_points_per_second: f64,
    /// Points/s the writer appends while the run computes (journal only, its periodic
    /// fsyncs included): what it absorbs before the final file.
    pub append_points_per_second: f64,
    /// Seconds to build the final file from the journal and make it durable (fsync).
    pub finish_seconds: f64,
    /// append / worker: the cores the writer keeps up with while the run computes.
    pub run_headroom: f64,
    /// Points/s one worker computes and encodes (histories recorded, compressed).
    pub worker_points_per_second: f64,
    /// Of the worker's time, the share spent encoding (histories compressed).
    pub worker_encode_share: f64,
    /// writer / worker: the number of cores the writer can keep up with.
    pub headroom: f64,
    /// Bytes of the finished file per point (the histories, nearly all of it).
    pub file_bytes_per_point: f64,
    /// The disk under the bench's directory: bytes/s of a sequential write made durable
    /// (`fdatasync`), pseudo-random bytes so that no layer can skip them.
    pub disk_bytes_per_second: f64,
    /// disk / (file bytes per point × worker): the workers whose results the disk can make
    /// durable once each, the ceiling of any store on this disk (issue 22).
    pub disk_headroom: f64,
}

/// 1, 2, 4, … up to `cores`, and `cores` itself.
fn thread_counts(cores: usize) -> Vec<usize> {
    let mut t: Vec<usize> = std::iter::successors(Some(1usize), |&n| Some(n * 2))
        .take_while(|&n| n < cores)
        .collect();
    t.push(cores.max(1));
    t
}

pub(super) fn bench_scaling(sz: &Sizes, dir: &Path) -> Result<Scaling, String> {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let summary = load_study(
        &curve_study_text("bench-scaling-summary", sz.summary_omegas, ""),
        "scaling",
    )?;
    let history = load_study(
        &curve_study_text("bench-scaling-history", sz.history_omegas, HISTORY_BLOCK),
        "scaling",
    )?;
    let rate = |study: &crate::study::Study, case: &str, threads: usize| -> Result<f64, String> {
        let pool = run::build_pool(threads).map_err(err("pool"))?;
        let walls = (0..sz.parallel_repeats.max(1))
            .map(|k| {
                bench_write_to(
                    case,
                    &format!("{case}-{threads}-{k}"),
                    study,
                    dir,
                    &pool,
                    false,
                )
            })
            .map(|w| w.map(|w| w.wall_seconds))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(study.plan.n_points() as f64 / median(walls))
    };
    let mut points = Vec::new();
    for threads in thread_counts(cores) {
        points.push(ScalingPoint {
            threads,
            summary_points_per_second: rate(&summary, "scaling-summary", threads)?,
            history_points_per_second: rate(&history, "scaling-history", threads)?,
        });
    }
    let (first, last) = (&points[0], &points[points.len() - 1]);
    let n = last.threads as f64;
    // the same history study on every core, its histories computed and dropped
    let pool = run::build_pool(cores).map_err(err("pool"))?;
    let bats = run::prepare_bats(&ModelSimulator, &history.plan, &pool);
    let request = history.history_request(bats.max_length());
    let walls = (0..sz.parallel_repeats.max(1))
        .map(|_| run_null_recording(&history, &bats, request.as_ref(), &pool).map(|(w, _)| w))
        .collect::<Result<Vec<_>, _>>()?;
    let history_compute = history.plan.n_points() as f64 / median(walls);
    let uncompressed = load_study(
        &curve_study_text(
            "bench-scaling-history",
            sz.history_omegas,
            &format!("{HISTORY_BLOCK}  compression: none\n"),
        ),
        "scaling",
    )?;
    let history_uncompressed = rate(&uncompressed, "scaling-history-none", cores)?;
    let scalar = load_study(
        &curve_study_text(
            "bench-scaling-history-scalar",
            sz.history_omegas,
            SCALAR_HISTORY_BLOCK,
        ),
        "scaling",
    )?;
    let history_scalar = rate(&scalar, "scaling-history-scalar", cores)?;
    let size = |case: &str| {
        std::fs::metadata(dir.join(format!("{case}-{cores}-0.h5"))).map_or(0, |m| m.len())
    };
    Ok(Scaling {
        history_compute_points_per_second: history_compute,
        history_vs_summary_ceiling: history_compute / last.summary_points_per_second,
        history_uncompressed_points_per_second: history_uncompressed,
        history_uncompressed_file_bytes: size("scaling-history-none"),
        history_file_bytes: size("scaling-history"),
        history_scalar_points_per_second: history_scalar,
        history_scalar_vs_summary_per_core: history_scalar / last.summary_points_per_second,
        cores,
        summary_points: summary.plan.n_points(),
        history_points: history.plan.n_points(),
        summary_efficiency: last.summary_points_per_second / (n * first.summary_points_per_second),
        history_efficiency: last.history_points_per_second / (n * first.history_points_per_second),
        history_vs_summary_per_core: last.history_points_per_second
            / last.summary_points_per_second,
        points,
    })
}

pub(super) fn bench_writer_headroom(sz: &Sizes, dir: &Path) -> Result<WriterHeadroom, String> {
    let study = load_study(
        &curve_study_text("bench-writer", sz.history_omegas, HISTORY_BLOCK),
        "writer",
    )?;
    let pool = run::build_pool(1).map_err(err("pool"))?;
    let bats = run::prepare_bats(&ModelSimulator, &study.plan, &pool);
    let history = study.history_request(bats.max_length());
    let info = study.info(bats.variants.clone(), history.clone());
    let path = dir.join("writer-headroom.h5");
    let mut session =
        store::open(&path, &info, &store::StoreOptions::default()).map_err(err("open"))?;
    let encoder = session.encoder();
    // Computed, encoded and written in batches (bounded memory); the worker's side
    // (simulate + encode) and the writer's (append + finish) timed on their own.
    let (mut compute, mut encode, mut write) = (0.0, 0.0, 0.0);
    let n = study.plan.n_points();
    let mut batch: Vec<PointRecord> = Vec::with_capacity(64);
    let mut encoded: Vec<store::EncodedRecord> = Vec::with_capacity(64);
    for start in (0..n).step_by(64) {
        let t0 = Instant::now();
        for i in start..(start + 64).min(n) {
            let p = study.plan.point(i).map_err(|e| e.message)?;
            let bat = bats.handles[p.bat as usize]
                .as_ref()
                .map_err(|e| e.clone())?;
            let result = ModelSimulator.simulate(
                bat,
                &p.spec,
                history.as_ref().filter(|_| p.record_history),
            );
            batch.push(PointRecord {
                index: i,
                id: p.id,
                bat: p.bat,
                result,
            });
        }
        compute += t0.elapsed().as_secs_f64();
        let t0 = Instant::now();
        for rec in batch.drain(..) {
            encoded.push(encoder.encode(rec).map_err(err("encode"))?);
        }
        encode += t0.elapsed().as_secs_f64();
        let t0 = Instant::now();
        for rec in encoded.drain(..) {
            session.write_encoded(rec).map_err(err("write"))?;
        }
        write += t0.elapsed().as_secs_f64();
    }
    let append = write;
    let t0 = Instant::now();
    session.finish().map_err(err("finish"))?;
    let finish = t0.elapsed().as_secs_f64();
    write += finish;
    let (writer, worker) = (n as f64 / write, n as f64 / (compute + encode));
    let file_bytes_per_point =
        std::fs::metadata(&path).map_err(err("stat"))?.len() as f64 / n as f64;
    let disk = disk_write_rate(dir, if sz.write_repeats > 1 { 1024 } else { 8 })?;
    Ok(WriterHeadroom {
        points: n,
        writer_points_per_second: writer,
        append_points_per_second: n as f64 / append,
        finish_seconds: finish,
        run_headroom: n as f64 / append / worker,
        worker_points_per_second: worker,
        worker_encode_share: encode / (compute + encode),
        headroom: writer / worker,
        file_bytes_per_point,
        disk_bytes_per_second: disk,
        disk_headroom: disk / (file_bytes_per_point * worker),
    })
}

/// Bytes/s of writing `mib` MiB to a new file in `dir` and making them durable
/// (`fdatasync`), as a finished results file must be: what a store on this disk can
/// sustain, whatever its design. A GiB in the full bench: less is absorbed by caches below
/// the file system (a virtual disk here took 256 MiB at 1.4 GB/s and 1 GiB at 0.5–1.4 GB/s).
fn disk_write_rate(dir: &Path, mib: usize) -> Result<f64, String> {
    use std::io::Write;
    // pseudo-random bytes: a block no layer can compress or deduplicate
    let block = crate::model::xorshift::bytes(0x2545_F491_4F6C_DD1D, 1 << 20);
    let path = dir.join("disk-probe");
    let t0 = Instant::now();
    let mut f = std::fs::File::create(&path).map_err(err("create the disk probe"))?;
    for _ in 0..mib {
        f.write_all(&block).map_err(err("write the disk probe"))?;
    }
    f.sync_data().map_err(err("sync the disk probe"))?;
    let seconds = t0.elapsed().as_secs_f64();
    drop(f);
    let _ = std::fs::remove_file(&path);
    Ok((mib << 20) as f64 / seconds)
}

/// The smallest useful study, one 45-point exit-speed curve, as a whole `batstudy run`
/// process (start, study, bat, collisions, the file, exit), against the NumPy reference.
#[derive(Debug, Clone, Serialize)]
pub struct CurveProcess {
    pub points: usize,
    pub runs: usize,
    pub median_ms: f64,
    pub min_ms: f64,
    /// `batstudy --version` as a process: what starting and ending one costs.
    pub version_median_ms: f64,
    /// The NumPy reference's time for the same curve on one thread.
    pub numpy_reference_seconds: f64,
    /// numpy_reference_seconds / median.
    pub speedup_vs_numpy: f64,
}

/// The NumPy reference's 45-point curve on one thread (issue 22).
const NUMPY_CURVE_SECONDS: f64 = 4.1;

/// [`CurveProcess`], when this process is the `batstudy` binary (not when a test runs the
/// bench): runs it as a child on every core, alternating with `--version`.
pub(super) fn bench_curve_process(sz: &Sizes, dir: &Path) -> Result<Option<CurveProcess>, String> {
    let exe = std::env::current_exe().map_err(err("current_exe"))?;
    if exe.file_stem().is_none_or(|s| s != "batstudy") {
        return Ok(None);
    }
    let study = dir.join("curve-process.yaml");
    std::fs::write(&study, curve_study_text("curve-process", 1, "")).map_err(err("write"))?;
    let out = dir.join("curve-process.h5");
    let time = |args: &[&std::ffi::OsStr]| -> Result<f64, String> {
        let t0 = Instant::now();
        let st = std::process::Command::new(&exe)
            .args(args)
            .stdout(std::process::Stdio::null())
            .status()
            .map_err(err("spawn"))?;
        let ms = t0.elapsed().as_secs_f64() * 1e3;
        if !st.success() {
            return Err(format!("curve process exited with {st}"));
        }
        Ok(ms)
    };
    let run_args = [
        "run".as_ref(),
        study.as_os_str(),
        "-o".as_ref(),
        out.as_os_str(),
        "--force".as_ref(),
        "--quiet".as_ref(),
    ];
    let runs = if sz.write_repeats > 1 { 25 } else { 3 };
    let (mut curve, mut version) = (Vec::new(), Vec::new());
    for _ in 0..runs {
        curve.push(time(&run_args)?);
        version.push(time(&["--version".as_ref()])?);
    }
    let min_ms = curve.iter().copied().fold(f64::INFINITY, f64::min);
    let median_ms = median(curve);
    Ok(Some(CurveProcess {
        points: 45,
        runs,
        median_ms,
        min_ms,
        version_median_ms: median(version),
        numpy_reference_seconds: NUMPY_CURVE_SECONDS,
        speedup_vs_numpy: NUMPY_CURVE_SECONDS * 1e3 / median_ms,
    }))
}
