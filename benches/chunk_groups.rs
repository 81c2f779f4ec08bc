//! What history chunks spanning k neighbouring points save (docs/performance.md, "Chunks of
//! eight points").
//!
//! The store can give each history point its own chunk of each stored variable (eight chunks
//! a point for a modal history study, each a zlib stream with its own per-plane Huffman
//! codes, block headers and checksum, each placed with its own `H5Dwrite_chunk`), or one
//! chunk to k points neighbouring along the study's last dim (`results::PointGroups`). This
//! runs the `batstudy bench` modal history study (1 800 points: 40 swing speeds × 45 impact
//! positions) once, keeps its histories, and then
//! - encodes every point alone, as the store does with groups of one
//!   (`RecordEncoder::encode`), and every group of k = 4, 8 and 15 points as the store does
//!   with groups of k (`RecordEncoder::encode_group`; never across a swing speed);
//! - checks every group record's chunks, byte for byte, against a prototype written here
//!   apart from the store (each variable's values in the chunk's order, shuffled, coded by
//!   the coder for planes of runs and near-noise, `run_huffman`), and inflates each
//!   prototype chunk and compares it with the store's byte-by-byte shuffle of its values;
//! - writes the single points' chunks with `H5Dwrite_chunk`, one call each, into a scratch
//!   file made as the store makes its results file, and the groups of 8's chunks the same.
//!
//! Everything on one thread, per point, in CPU time of that thread. The encodings run in
//! turn, pass after pass, and each figure is a median over the passes, the differences
//! taken pass by pass; the chunk writes are the least of their passes.
//!
//!     cargo bench --bench chunk_groups

use batstudy::bench::{
    curve_study_text, load_study, thread_cpu_seconds, TempDir, MODAL_HISTORY_BLOCK,
};
use batstudy::model::outcome::HistoryPrecision;
use batstudy::results::{PointGroups, PointRecord};
use batstudy::run::{self, AsIs, ModelSimulator, RunOptions, Sink};
use batstudy::store::layout::{self, HistoryDims, HISTORY_VARS, MODE_BLOCK};
use batstudy::store::modal::{coordinate_blocks, padded_points, ModalExtents};
use batstudy::store::shuffle::{shuffle, shuffle_values_into, ChunkValue};
use batstudy::store::{direct, header, journal, run_huffman, RecordEncoder};
use hdf5::file::FileSpaceStrategy;
use hdf5::plist::{FileAccess, FileCreate};
use libdeflater::Decompressor;
use std::sync::atomic::AtomicBool;

/// Passes of each timed loop.
const PASSES: usize = 15;
/// Points along `impact_z` per chunk, besides one.
const GROUPS: [usize; 3] = [4, 8, 15];
/// The group whose chunks are written.
const WRITTEN_GROUP: usize = 8;

/// A sink that keeps every point, with its histories.
struct Keep(Vec<PointRecord>);

impl Sink for Keep {
    type Encoder = AsIs;
    fn encoder(&self) -> AsIs {
        AsIs
    }
    fn is_done(&self, _: usize) -> bool {
        false
    }
    fn write(&mut self, rec: PointRecord) -> Result<(), String> {
        self.0.push(rec);
        Ok(())
    }
    fn finish(&mut self) -> Result<(), String> {
        Ok(())
    }
}

/// A stored history variable: its index into `HISTORY_VARS` and its stored precision.
type Var = (usize, HistoryPrecision);

/// One point's values of a history variable as its chunk holds them: the samples (or the
/// static shape, padded to the study's shape points), or its first block of modes.
fn point_values(rec: &PointRecord, k: usize, ext: &ModalExtents, nt: usize) -> Vec<f64> {
    let h = rec
        .result
        .as_ref()
        .ok()
        .and_then(|o| o.history.as_ref())
        .expect("a history");
    let a = layout::history_array(h, k);
    match HISTORY_VARS[k].2 {
        HistoryDims::ModeTime => {
            let mut blocks = coordinate_blocks(a, nt, ext.block);
            assert_eq!(
                blocks.len(),
                1,
                "the bench's bats step at most {MODE_BLOCK} modes"
            );
            blocks.pop().expect("a block")
        }
        HistoryDims::ShapePoint => padded_points(a, ext.points),
        _ => a.clone(),
    }
}

/// Every point's values of every stored variable (`point_values`), gathered once outside
/// the timings: both codings start from them.
struct Gathered {
    /// [point][variable] values.
    values: Vec<Vec<Vec<f64>>>,
    vars: Vec<Var>,
}

fn gather(recs: &[PointRecord], vars: &[Var], ext: &ModalExtents, nt: usize) -> Gathered {
    let values = recs
        .iter()
        .map(|r| {
            vars.iter()
                .map(|&(k, _)| point_values(r, k, ext, nt))
                .collect()
        })
        .collect();
    Gathered {
        values,
        vars: vars.to_vec(),
    }
}

/// The values of variable `v` of the points `group`, one point after the other, then the
/// dataset's fill value (0 for the modal coordinates, NaN else) for the chunk's `slots`
/// places past the group (a row's last group).
fn joined(g: &Gathered, v: usize, group: std::ops::Range<usize>, slots: usize) -> Vec<f64> {
    let mut out = Vec::new();
    let per = g.values[group.start][v].len();
    for p in &g.values[group.clone()] {
        out.extend_from_slice(&p[v]);
    }
    let fill = match HISTORY_VARS[g.vars[v].0].2 {
        HistoryDims::ModeTime => 0.0,
        _ => f64::NAN,
    };
    out.resize(slots.max(group.len()) * per, fill);
    out
}

/// `values` shuffled (the store's shuffle) and coded as the store codes planes of runs and
/// near-noise.
fn code<T: ChunkValue>(values: &[T]) -> Vec<u8> {
    let mut shuffled = vec![0u8; values.len() * T::SIZE];
    shuffle_values_into(values, &mut shuffled);
    run_huffman::zlib_planes(&shuffled, values.len())
}

/// The chunks of the points `group` in chunks of `slots` places: each variable's values of
/// its points, at its stored precision, shuffled and coded.
fn group_chunks(g: &Gathered, group: std::ops::Range<usize>, slots: usize) -> Vec<Vec<u8>> {
    g.vars
        .iter()
        .enumerate()
        .map(|(v, &(_, precision))| {
            let values = joined(g, v, group.clone(), slots);
            match precision {
                HistoryPrecision::F64 => code(&values),
                HistoryPrecision::F32 => {
                    code(&values.iter().map(|&x| x as f32).collect::<Vec<_>>())
                }
            }
        })
        .collect()
}

/// Inflate a group's chunks and compare them with the values they hold.
fn check_group(chunks: &[Vec<u8>], g: &Gathered, group: std::ops::Range<usize>, slots: usize) {
    for ((v, &(_, precision)), chunk) in g.vars.iter().enumerate().zip(chunks) {
        let values = joined(g, v, group.clone(), slots);
        let (bytes, size): (Vec<u8>, usize) = match precision {
            HistoryPrecision::F64 => (values.iter().flat_map(|x| x.to_le_bytes()).collect(), 8),
            HistoryPrecision::F32 => (
                values
                    .iter()
                    .flat_map(|&x| (x as f32).to_le_bytes())
                    .collect(),
                4,
            ),
        };
        let mut got = vec![0u8; bytes.len()];
        let n = Decompressor::new()
            .zlib_decompress(chunk, &mut got)
            .expect("a zlib stream");
        assert_eq!(n, bytes.len());
        // the store's byte-by-byte shuffle, not the transposes the prototype coded with
        assert!(
            got == shuffle(&bytes, size),
            "a chunk inflates to its values"
        );
    }
}

/// The groups of `k` neighbouring points along `impact_z` (the last dim, `nz` long).
fn groups(n: usize, nz: usize, k: usize) -> Vec<std::ops::Range<usize>> {
    let mut out = Vec::new();
    for row in (0..n).step_by(nz) {
        let mut z = 0;
        while z < nz {
            let end = (z + k).min(nz);
            out.push(row + z..row + end);
            z = end;
        }
    }
    out
}

/// The least of `PASSES` CPU times of this thread, per point of `points`, in µs, that
/// writing `chunks` (one call each, into one chunk of a fresh 1-D dataset each) with
/// `H5Dwrite_chunk` took, into a file made as the store makes its results file (its driver,
/// `store::direct`; no free-space tracking). CPU, not wall time: the driver's own thread
/// writes the disk meanwhile, and the caller waits for it whenever the disk is slower.
fn write_us(dir: &TempDir, name: &str, chunks: &[&[u8]], points: usize) -> f64 {
    let len = chunks.iter().map(|c| c.len()).max().unwrap_or(1);
    let fapl = FileAccess::build()
        .chunk_cache(1, 0, 1.0)
        .libver_v110()
        .finish()
        .expect("access properties");
    let fcpl = FileCreate::build()
        .file_space_strategy(FileSpaceStrategy::None)
        .finish()
        .expect("creation properties");
    let mut best = f64::INFINITY;
    for pass in 0..PASSES {
        let path = dir.path().join(format!("{name}-{pass}.h5"));
        let f = direct::create_excl(&path, &fapl, &fcpl).expect("a scratch file");
        let ds = f
            .new_dataset::<u8>()
            .shape([chunks.len() * len])
            .chunk([len])
            .shuffle()
            .deflate(1)
            .create("values")
            .expect("a dataset");
        let t0 = thread_cpu_seconds();
        for (i, c) in chunks.iter().enumerate() {
            batstudy::store::chunks::write_chunk(&ds, &[i * len], c).expect("a chunk written");
        }
        best = best.min((thread_cpu_seconds() - t0) * 1e6 / points as f64);
    }
    best
}

/// The records of the bench's study, run on one thread, in flat-index order, with what the
/// store knows of them.
struct Fixture {
    recs: Vec<PointRecord>,
    info: batstudy::results::StudyInfo,
    vars: Vec<Var>,
    ext: ModalExtents,
    /// points, z positions of a history, time samples
    n: usize,
    nz: usize,
    nt: usize,
}

fn fixture(bench: bool) -> Fixture {
    let omegas = if bench { 40 } else { 1 };
    let study = load_study(
        &curve_study_text("chunk-groups", omegas, MODAL_HISTORY_BLOCK),
        "chunk-groups",
    )
    .expect("the study");
    let pool = run::build_pool(1).expect("a pool");
    let bats = run::prepare_bats(&ModelSimulator, &study.plan, &pool);
    let request = study.history_request(bats.max_length()).expect("histories");
    let info = study.info(bats.variants.clone(), Some(request.clone()));
    let stop = AtomicBool::new(false);
    let opts = RunOptions {
        jobs: 1,
        ..RunOptions::default()
    };
    let (_, kept) = run::run_plan(
        &study.plan,
        &ModelSimulator,
        &bats,
        Some(&request),
        Keep(Vec::new()),
        &pool,
        &opts,
        &stop,
    )
    .expect("the run");
    let mut recs = kept.0;
    recs.sort_by_key(|r| r.index);
    let vars = header::history_vars(&request)
        .into_iter()
        .map(|k| (k, layout::history_precision(&request, k)))
        .collect();
    Fixture {
        n: recs.len(),
        nz: 45,
        nt: request.n_samples,
        ext: ModalExtents::of(&info),
        recs,
        info,
        vars,
    }
}

/// By group size k: the encoders, the groups of points and their records.
type Encoded = (
    Vec<RecordEncoder>,
    Vec<Vec<std::ops::Range<usize>>>,
    Vec<Vec<batstudy::store::EncodedRecord>>,
);

/// Every group of each k encoded by the store, each checked byte for byte against the
/// prototype's chunks: the encoders, the groups and the records, by k.
fn encode_groups(fx: &Fixture, path: &std::path::Path) -> Encoded {
    let gathered = gather(&fx.recs, &fx.vars, &fx.ext, fx.nt);
    let encoders: Vec<RecordEncoder> = GROUPS
        .iter()
        .map(|&k| RecordEncoder::with_groups(path, &fx.info, PointGroups::new(k, fx.nz)))
        .collect();
    let grouped: Vec<Vec<std::ops::Range<usize>>> =
        GROUPS.iter().map(|&k| groups(fx.n, fx.nz, k)).collect();
    let mut group_records = Vec::new();
    for ((&k, gs), encoder) in GROUPS.iter().zip(&grouped).zip(&encoders) {
        let mut records = Vec::new();
        for g in gs {
            let prototype = group_chunks(&gathered, g.clone(), k);
            check_group(&prototype, &gathered, g.clone(), k);
            let rec = encoder
                .encode_group(fx.recs[g.clone()].to_vec())
                .expect("encoded");
            let stored =
                journal::history_chunks(&rec.framed[journal::REC_PREFIX..]).expect("chunks");
            assert!(
                stored.iter().map(|c| c.to_vec()).eq(prototype),
                "the store's chunks of points {g:?} in groups of {k} are the prototype's"
            );
            records.push(rec);
        }
        group_records.push(records);
    }
    (encoders, grouped, group_records)
}

/// µs of CPU a point to encode, [pass][variant]: one point a chunk, then groups of each k.
/// Every variant in turn, pass after pass, so that what the machine does meanwhile falls on
/// all alike; the records are copied before the clock starts (the encoder takes them by
/// value); CPU time of this thread, so that what another process takes does not count.
fn time_passes(
    fx: &Fixture,
    single: &RecordEncoder,
    encoders: &[RecordEncoder],
    grouped: &[Vec<std::ops::Range<usize>>],
) -> Vec<Vec<f64>> {
    let us = |t: f64| (thread_cpu_seconds() - t) * 1e6 / fx.n as f64;
    let mut passes: Vec<Vec<f64>> = Vec::new();
    for _ in 0..PASSES {
        let copies = std::hint::black_box(fx.recs.to_vec());
        let t = thread_cpu_seconds();
        let e: Vec<_> = copies
            .into_iter()
            .map(|r| single.encode(r).expect("encoded"))
            .collect();
        let mut row = vec![us(t)];
        std::hint::black_box(e);
        for (gs, encoder) in grouped.iter().zip(encoders) {
            let copies: Vec<Vec<PointRecord>> =
                std::hint::black_box(gs.iter().map(|g| fx.recs[g.clone()].to_vec()).collect());
            let t = thread_cpu_seconds();
            let e: Vec<_> = copies
                .into_iter()
                .map(|g| encoder.encode_group(g).expect("encoded"))
                .collect();
            row.push(us(t));
            std::hint::black_box(e);
        }
        passes.push(row);
    }
    passes
}

fn report_encoding(
    fx: &Fixture,
    passes: &[Vec<f64>],
    encoded: &[batstudy::store::EncodedRecord],
    group_records: &[Vec<batstudy::store::EncodedRecord>],
) {
    let median = |mut v: Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    let column = |c: usize| median(passes.iter().map(|r| r[c]).collect());
    let against_one = |c: usize| median(passes.iter().map(|r| r[c] - r[0]).collect());
    let bytes = |e: &[batstudy::store::EncodedRecord]| {
        e.iter().map(|e| e.framed.len()).sum::<usize>() as f64 / fx.n as f64
    };
    println!(
        "{} points, {} stored variables, {} samples, blocks of {MODE_BLOCK} modes; medians of {PASSES} passes",
        fx.n,
        fx.vars.len(),
        fx.nt
    );
    println!(
        "the store, one point a chunk : {:6.1} µs of CPU a point to encode, {:7.0} B a point with its journal framing",
        column(0),
        bytes(encoded)
    );
    for (v, (&k, records)) in GROUPS.iter().zip(group_records).enumerate() {
        println!(
            "the store, chunks of {k:2} points: {:6.1} µs of CPU a point to encode ({:+5.1} against one point a chunk, pass by pass), {:7.0} B a point",
            column(v + 1),
            against_one(v + 1),
            bytes(records)
        );
    }
}

/// H5Dwrite_chunk: every chunk of the single points, one call each, against every chunk of
/// the groups of WRITTEN_GROUP.
fn report_writes(
    n: usize,
    encoded: &[batstudy::store::EncodedRecord],
    group_records: &[Vec<batstudy::store::EncodedRecord>],
) {
    let dir = TempDir::new_in(&std::env::temp_dir()).expect("a scratch directory");
    let pieces = |e: &[batstudy::store::EncodedRecord]| -> Vec<Vec<u8>> {
        e.iter()
            .flat_map(|e| {
                journal::history_chunks(&e.framed[journal::REC_PREFIX..])
                    .expect("chunks")
                    .into_iter()
                    .map(<[u8]>::to_vec)
            })
            .collect()
    };
    let written = GROUPS
        .iter()
        .position(|&k| k == WRITTEN_GROUP)
        .expect("a group of 8");
    let (one, eight) = (pieces(encoded), pieces(&group_records[written]));
    let one_slices: Vec<&[u8]> = one.iter().map(Vec::as_slice).collect();
    let eight_slices: Vec<&[u8]> = eight.iter().map(Vec::as_slice).collect();
    let w1 = write_us(&dir, "one", &one_slices, n);
    let w8 = write_us(&dir, "eight", &eight_slices, n);
    println!(
        "H5Dwrite_chunk, {:.2} chunks a point: {w1:.1} µs of CPU a point; groups of {WRITTEN_GROUP}, {:.2} chunks a point: {w8:.1} µs of CPU a point",
        one.len() as f64 / n as f64,
        eight.len() as f64 / n as f64
    );
}

fn main() {
    let fx = fixture(std::env::args().any(|a| a == "--bench"));
    // every point alone, and every group of k, as the store encodes them
    let path = std::env::temp_dir().join("chunk-groups.h5");
    let single = RecordEncoder::with_groups(&path, &fx.info, PointGroups::single());
    let encoded: Vec<_> = fx
        .recs
        .iter()
        .map(|r| single.encode(r.clone()).expect("encoded"))
        .collect();
    let (encoders, grouped, group_records) = encode_groups(&fx, &path);
    let passes = time_passes(&fx, &single, &encoders, &grouped);
    report_encoding(&fx, &passes, &encoded, &group_records);
    report_writes(fx.n, &encoded, &group_records);
}
