//! The writer's headroom and the disk's: how many workers the one writer thread keeps up
//! with on the history study (the points/s it absorbs, records computed and encoded
//! beforehand, over the points/s one worker computes and encodes them, as in a run), and
//! how many workers' results the disk can make durable; with the displacement on its grid,
//! and in modal form (`modal_*`).

use super::cases::{curve_study_text, load_study, HISTORY_BLOCK, MODAL_HISTORY_BLOCK};
use super::measure::err;
use crate::model::outcome::HistoryRequest;
use crate::results::PointRecord;
use crate::run::{self, ModelSimulator, PreparedBats, Simulator};
use crate::store;
use crate::study::Study;
use serde::Serialize;
use std::path::Path;
use std::time::Instant;

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
    /// Bytes of the journal per point just before the finish (the histories the writer
    /// placed in the file as they came are journalled by their place there, not their bytes).
    pub journal_bytes_per_point: f64,
    /// The disk under the bench's directory: bytes/s of a sequential write made durable
    /// (`fdatasync`), pseudo-random bytes so that no layer can skip them.
    pub disk_bytes_per_second: f64,
    /// MiB written to measure it.
    pub disk_probe_mib: usize,
    /// disk / (file bytes per point × worker): the workers whose results the disk can make
    /// durable once each, the ceiling of any store on this disk.
    pub disk_headroom: f64,
    /// The same history study with the displacement in modal form: the figures above.
    pub modal_file_bytes_per_point: f64,
    pub modal_journal_bytes_per_point: f64,
    pub modal_worker_points_per_second: f64,
    pub modal_worker_encode_share: f64,
    pub modal_writer_points_per_second: f64,
    pub modal_append_points_per_second: f64,
    pub modal_finish_seconds: f64,
    pub modal_headroom: f64,
    pub modal_run_headroom: f64,
    pub modal_disk_headroom: f64,
}

/// The writer's figures on one history study.
struct WriterRun {
    points: usize,
    /// Points/s the writer absorbs (append and finish), and appends alone.
    writer: f64,
    append: f64,
    finish: f64,
    /// Points/s one worker computes and encodes, and the share spent encoding.
    worker: f64,
    encode_share: f64,
    file_bytes_per_point: f64,
    journal_bytes_per_point: f64,
}

/// Seconds spent computing, encoding and appending (the worker's and the writer's sides
/// timed apart, in batches of 64 points: bounded memory).
struct Sides {
    compute: f64,
    encode: f64,
    append: f64,
}

fn simulate_batch(
    study: &Study,
    bats: &PreparedBats<crate::model::Target>,
    history: Option<&HistoryRequest>,
    range: std::ops::Range<usize>,
    batch: &mut Vec<PointRecord>,
) -> Result<(), String> {
    for i in range {
        let p = study.plan.point(i).map_err(|e| e.message)?;
        let bat = bats.handles[p.bat as usize]
            .as_ref()
            .map_err(|e| e.clone())?;
        let result = ModelSimulator.simulate(bat, &p.spec, history.filter(|_| p.record_history));
        batch.push(PointRecord {
            index: i,
            id: p.id,
            bat: p.bat,
            result,
        });
    }
    Ok(())
}

fn compute_encode_append(
    study: &Study,
    bats: &PreparedBats<crate::model::Target>,
    history: Option<&HistoryRequest>,
    session: &mut store::Session,
) -> Result<Sides, String> {
    let encoder = session.encoder();
    let mut sides = Sides {
        compute: 0.0,
        encode: 0.0,
        append: 0.0,
    };
    let n = study.plan.n_points();
    let mut batch: Vec<PointRecord> = Vec::with_capacity(64);
    let mut encoded: Vec<store::EncodedRecord> = Vec::with_capacity(64);
    let mut gather = store::gather::GroupGatherer::new(encoder.groups());
    for start in (0..n).step_by(64) {
        let t0 = Instant::now();
        simulate_batch(study, bats, history, start..(start + 64).min(n), &mut batch)?;
        sides.compute += t0.elapsed().as_secs_f64();
        let t0 = Instant::now();
        // a group at a time, as the runner's workers encode (`store::gather`)
        for rec in batch.drain(..) {
            if let Some(group) = gather.add(rec) {
                encoded.push(encoder.encode_group(group).map_err(err("encode"))?);
            }
        }
        sides.encode += t0.elapsed().as_secs_f64();
        let t0 = Instant::now();
        for rec in encoded.drain(..) {
            session.write_encoded(rec).map_err(err("write"))?;
        }
        sides.append += t0.elapsed().as_secs_f64();
    }
    Ok(sides)
}

/// The history study of `block` with `omegas` swing speeds on one thread, into `dir`.
fn writer_run(name: &str, block: &str, omegas: usize, dir: &Path) -> Result<WriterRun, String> {
    let study = load_study(&curve_study_text(name, omegas, block), name)?;
    let pool = run::build_pool(1).map_err(err("pool"))?;
    let bats = run::prepare_bats(&ModelSimulator, &study.plan, &pool);
    let history = study.history_request(bats.max_length());
    let info = study.info(bats.variants.clone(), history.clone());
    let path = dir.join(format!("{name}.h5"));
    let mut session =
        store::open(&path, &info, &store::StoreOptions::default()).map_err(err("open"))?;
    let s = compute_encode_append(&study, &bats, history.as_ref(), &mut session)?;
    let journal_bytes = session.journal_bytes() as f64;
    let t0 = Instant::now();
    session.finish().map_err(err("finish"))?;
    let finish = t0.elapsed().as_secs_f64();
    let n = study.plan.n_points() as f64;
    let file_bytes_per_point = std::fs::metadata(&path).map_err(err("stat"))?.len() as f64 / n;
    let _ = std::fs::remove_file(&path);
    Ok(WriterRun {
        points: study.plan.n_points(),
        writer: n / (s.append + finish),
        append: n / s.append,
        finish,
        worker: n / (s.compute + s.encode),
        encode_share: s.encode / (s.compute + s.encode),
        file_bytes_per_point,
        journal_bytes_per_point: journal_bytes / n,
    })
}

/// The history study with `omegas` swing speeds on one thread, the displacement on its grid
/// and in modal form; then the disk probe.
pub(super) fn bench_writer_headroom(
    omegas: usize,
    disk_mib: usize,
    dir: &Path,
) -> Result<WriterHeadroom, String> {
    let g = writer_run("bench-writer", HISTORY_BLOCK, omegas, dir)?;
    let m = writer_run("bench-writer-modal", MODAL_HISTORY_BLOCK, omegas, dir)?;
    let disk = disk_write_rate(dir, disk_mib)?;
    Ok(WriterHeadroom {
        points: g.points,
        writer_points_per_second: g.writer,
        append_points_per_second: g.append,
        finish_seconds: g.finish,
        run_headroom: g.append / g.worker,
        worker_points_per_second: g.worker,
        worker_encode_share: g.encode_share,
        headroom: g.writer / g.worker,
        file_bytes_per_point: g.file_bytes_per_point,
        journal_bytes_per_point: g.journal_bytes_per_point,
        disk_bytes_per_second: disk,
        disk_probe_mib: disk_mib,
        disk_headroom: disk / (g.file_bytes_per_point * g.worker),
        modal_file_bytes_per_point: m.file_bytes_per_point,
        modal_journal_bytes_per_point: m.journal_bytes_per_point,
        modal_worker_points_per_second: m.worker,
        modal_worker_encode_share: m.encode_share,
        modal_writer_points_per_second: m.writer,
        modal_append_points_per_second: m.append,
        modal_finish_seconds: m.finish,
        modal_headroom: m.writer / m.worker,
        modal_run_headroom: m.append / m.worker,
        modal_disk_headroom: disk / (m.file_bytes_per_point * m.worker),
    })
}

/// Bytes/s of writing `mib` MiB to a new file in `dir` and making them durable
/// (`fdatasync`), as a finished results file must be: what a store on this disk can
/// sustain, whatever its design. A GiB in the full bench: less is absorbed by caches below
/// the file system (a virtual disk took 256 MiB at 1.4 GB/s and 1 GiB at 0.5–1.4 GB/s).
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
