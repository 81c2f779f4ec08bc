//! The store's hand-written codecs against the library alternatives, on the chunks the store
//! makes (crates/store/README.md).
//!
//! The inputs are real histories: the physics' base case (the R161 bat, a 40 m/s ball, the
//! wave model with its modal integrator) at eight neighbouring impact positions, 0.62 to
//! 0.69 m, recorded as the `batstudy bench` history studies record them (force, compression,
//! ball velocity, rigid motion and the displacement; 200 samples 10 µs apart; f32, the
//! default precision, which rounds the modal coordinates to the step they need). From them,
//! the store's own functions make each chunk:
//!
//! - `modal_group`: a group of eight points' first block of modal coordinates
//!   (`chunks::filtered_group_coordinates`, f64, mode-major, zero rows up to the block's
//!   modes), shuffled: 8 planes of 51 200 bytes. The store codes it with `run_huffman`.
//! - `modal_point`: one point's block (the same coded alone, 8 planes of 6 400 bytes).
//! - `scalar_group`: a group's six scalar series as `chunks::filtered_group` makes them:
//!   force, compression, ball velocity, rigid translation and rotation in f32 (five chunks
//!   of 4 planes of 1 600 bytes), the bat load in f64 as the model rounds it (8 planes of
//!   1 600 bytes). `run_huffman`.
//! - `scalar_point`: the five f32 series of one point of the grid form, one chunk each (800
//!   bytes): `chunks::filtered_whole`, whose small chunks go to `fixed_deflate` (noise
//!   planes stored, the rest one block of the fixed codes).
//! - `grid_point`: one point's displacement on the grid, 200 samples × 85 positions of f32
//!   (`chunks::filtered_whole`: noise planes stored, the rest libdeflate level 1).
//! - `shuffle`: the store's shuffle (8 × 8 transposes) against the byte-by-byte loop of
//!   HDF5's shuffle filter, on the modal group's values.
//!
//! Each codec on the same shuffled bytes: `store` (what the store does), `miniz_rle`
//! (miniz_oxide with the RLE strategy: matches at distance 1 only, as the run coder makes
//! them; at level 2, because at level 1 miniz_oxide 0.8 takes its fast path, which ignores
//! the strategy: its deflate stream is `miniz_1`'s byte for byte, which the sizes' table checks),
//! `miniz_1` (miniz_oxide level 1, default strategy), `miniz_6` (its default level),
//! `libdeflate_1` (libdeflate level 1, what the store uses for summaries and the grid's
//! chunks). Every compressor is made once per thread and reused, as the store reuses
//! its libdeflate compressor. The two `*_point` inputs whose store path shuffles inside
//! (`filtered_whole`) shuffle in every variant, with the store's shuffle. Every output is
//! inflated again (miniz_oxide) and compared with the shuffled bytes before the timings, and
//! the sizes are printed.
//!
//!     cargo bench -p batstudy-store --bench codecs

use batstudy_physics::bat::shapes::n_modes;
use batstudy_physics::outcome::{
    History, HistoryCompression, HistoryDisplacement, HistoryField, HistoryPrecision,
    HistoryRequest,
};
use batstudy_physics::spec::CollisionSpec;
use batstudy_physics::{prepare_bat, simulate};
use batstudy_store::chunks;
use batstudy_store::layout::{HISTORY_DEFLATE_LEVEL, MODAL_HISTORY_GROUP, MODE_BLOCK};
use batstudy_store::modal::{coordinate_block_rows, mode_major_block};
use batstudy_store::run_huffman;
use batstudy_store::shuffle::shuffle_values_into;
use divan::counter::BytesCount;
use divan::Bencher;
use miniz_oxide::deflate::core::{
    compress, create_comp_flags_from_zip_params, CompressionStrategy, CompressorOxide, TDEFLFlush,
    TDEFLStatus,
};
use std::cell::RefCell;
use std::fmt;
use std::sync::OnceLock;

/// Samples of a history (2 ms at 10 µs), as the bench's studies record.
const N_SAMPLES: usize = 200;
/// The displacement grid: 0 to 0.84 m every centimetre (the R161 is 0.84 m long).
const GRID_Z: usize = 85;
/// The level miniz_oxide's RLE strategy is asked at: the lowest that takes it into account
/// (the module's documentation); in RLE mode the level changes nothing else but the
/// compressor's set-up (the sizes' table compares level 6).
const RLE_LEVEL: i32 = 2;

fn main() {
    print_sizes(inputs());
    divan::main();
}

/// A codec, or the library alternative to it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Codec {
    /// What the store does with the chunk.
    Store,
    /// miniz_oxide with the RLE strategy (level 2: see the module's documentation).
    MinizRle,
    /// miniz_oxide at level 1, default strategy.
    Miniz1,
    /// miniz_oxide at level 6 (its default), default strategy.
    Miniz6,
    /// libdeflate at level 1.
    Libdeflate1,
}

const CODECS: [Codec; 5] = [
    Codec::Store,
    Codec::MinizRle,
    Codec::Miniz1,
    Codec::Miniz6,
    Codec::Libdeflate1,
];

impl fmt::Display for Codec {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Codec::Store => "store",
            Codec::MinizRle => "miniz_rle",
            Codec::Miniz1 => "miniz_1",
            Codec::Miniz6 => "miniz_6",
            Codec::Libdeflate1 => "libdeflate_1",
        })
    }
}

/// What the store does with a chunk's values, given its shuffled bytes.
#[derive(Debug, Clone, Copy)]
enum StorePath {
    /// `run_huffman::zlib_planes` of the shuffled bytes (planes of `n` bytes).
    RunHuffman,
    /// `chunks::filtered_whole` of the f32 values (shuffle included).
    FilteredWhole,
}

/// One chunk: its shuffled bytes (what a zlib stream of it holds), the values it was
/// shuffled from (f32 chunks), and the length of a byte plane.
struct Chunk {
    shuffled: Vec<u8>,
    values: Option<Vec<f32>>,
    plane: usize,
}

/// An input: the chunks the store makes of it and what it does with them.
struct Input {
    name: &'static str,
    chunks: Vec<Chunk>,
    path: StorePath,
}

impl Input {
    fn bytes(&self) -> usize {
        self.chunks.iter().map(|c| c.shuffled.len()).sum()
    }
}

struct Inputs {
    modal_group: Input,
    modal_point: Input,
    scalar_group: Input,
    scalar_point: Input,
    grid_point: Input,
    /// The modal group's values, for the shuffle.
    coordinates: Vec<f64>,
    /// The modes each of the group's collisions stepped, and the modes of a block.
    modes: Vec<usize>,
    block: usize,
}

fn inputs() -> &'static Inputs {
    static INPUTS: OnceLock<Inputs> = OnceLock::new();
    INPUTS.get_or_init(make_inputs)
}

/// The history request of the bench's history studies, the displacement in `form`.
fn request(form: HistoryDisplacement) -> HistoryRequest {
    HistoryRequest {
        fields: vec![
            HistoryField::Force,
            HistoryField::Compression,
            HistoryField::BallVelocity,
            HistoryField::Displacement,
            HistoryField::RigidMotion,
        ],
        interval: 1.0e-5,
        n_samples: N_SAMPLES,
        z: (0..GRID_Z).map(|i| i as f64 * 0.01).collect(),
        precision: HistoryPrecision::F32,
        compression: HistoryCompression::Deflate,
        displacement: form,
    }
}

/// `values` shuffled by the store, as f32 or f64 bytes.
fn shuffled<T: chunks::ChunkValue>(values: &[T]) -> Vec<u8> {
    let mut out = vec![0u8; values.len() * T::SIZE];
    shuffle_values_into(values, &mut out);
    out
}

fn f32s(values: &[f64]) -> Vec<f32> {
    values.iter().map(|&x| x as f32).collect()
}

/// The scalar series stored in the request's precision (f32), in the file's order.
const F32_SERIES: usize = 5;

/// A history's scalar series stored in f32, in the file's order (the modal form's bat load
/// is stored in f64, rounded by the model).
fn scalar_series(h: &History) -> [&[f64]; F32_SERIES] {
    [
        &h.force,
        &h.compression,
        &h.ball_velocity,
        &h.rigid_translation,
        &h.rigid_rotation,
    ]
}

/// A group chunk of one series of the group's points (`places`), as the store makes it
/// (`chunks::filtered_group`), checked against `run_huffman` on the store's shuffle.
fn group_chunk<T: chunks::ChunkValue>(places: &[&[f64]], convert: fn(f64) -> T, fill: T) -> Chunk {
    let values: Vec<T> = places
        .iter()
        .flat_map(|a| a.iter().map(|&x| convert(x)))
        .collect();
    let bytes = shuffled(&values);
    let places: Vec<Option<&[f64]>> = places.iter().map(|&a| Some(a)).collect();
    assert_eq!(
        chunks::filtered_group(&places, N_SAMPLES, HISTORY_DEFLATE_LEVEL, convert, fill),
        run_huffman::zlib_planes(&bytes, values.len()),
        "a scalar group's input is the store's"
    );
    Chunk {
        shuffled: bytes,
        values: None,
        plane: values.len(),
    }
}

/// The modal coordinates: the group's chunk of each point's first block, as the store cuts
/// it, and one point's chunk; and the group's coordinates.
fn modal_inputs(histories: &[History], block: usize) -> (Input, Input, Vec<f64>) {
    let level = HISTORY_DEFLATE_LEVEL;
    let places: Vec<_> = histories
        .iter()
        .map(|h| {
            let q = &h.modal.coordinate;
            let rows = coordinate_block_rows(q, N_SAMPLES, block)
                .into_iter()
                .next()
                .expect("a block of modes");
            (q.as_slice(), h.modal.modes, rows)
        })
        .collect();
    let coordinates: Vec<f64> = places
        .iter()
        .flat_map(|(q, modes, rows)| mode_major_block(q, *modes, N_SAMPLES, rows.clone(), block))
        .collect();
    let group = shuffled(&coordinates);
    let n = coordinates.len();
    let stored = chunks::filtered_group_coordinates(
        &places.iter().cloned().map(Some).collect::<Vec<_>>(),
        N_SAMPLES,
        block,
        level,
    );
    assert_eq!(
        stored,
        run_huffman::zlib_planes(&group, n),
        "the modal group's input is the store's"
    );
    let modal_group = Input {
        name: "modal_group",
        chunks: vec![Chunk {
            shuffled: group,
            values: None,
            plane: n,
        }],
        path: StorePath::RunHuffman,
    };
    let (q, modes, rows) = places[0].clone();
    let one = mode_major_block(q, modes, N_SAMPLES, rows.clone(), block);
    let point = shuffled(&one);
    assert_eq!(
        chunks::filtered_coordinates(q, modes, N_SAMPLES, rows, block, level),
        run_huffman::zlib_planes(&point, one.len()),
        "the modal point's input is the store's"
    );
    let modal_point = Input {
        name: "modal_point",
        chunks: vec![Chunk {
            shuffled: point,
            values: None,
            plane: one.len(),
        }],
        path: StorePath::RunHuffman,
    };
    (modal_group, modal_point, coordinates)
}

/// The scalar series of a group: a chunk of each (the bat load in f64, as the modal form
/// stores it).
fn scalar_group_input(histories: &[History]) -> Input {
    let mut group_chunks: Vec<Chunk> = (0..F32_SERIES)
        .map(|s| {
            let places: Vec<_> = histories.iter().map(|h| scalar_series(h)[s]).collect();
            group_chunk(&places, |x| x as f32, f32::NAN)
        })
        .collect();
    let bat_loads: Vec<_> = histories
        .iter()
        .map(|h| h.modal.bat_load.as_slice())
        .collect();
    group_chunks.push(group_chunk(&bat_loads, |x| x, f64::NAN));
    Input {
        name: "scalar_group",
        chunks: group_chunks,
        path: StorePath::RunHuffman,
    }
}

/// One point of the grid form: its scalar series (no bat load) and its displacement.
fn grid_inputs(grid_history: &History) -> (Input, Input) {
    let whole = |v: Vec<f32>| Chunk {
        shuffled: shuffled(&v),
        plane: v.len(),
        values: Some(v),
    };
    let scalar_point = Input {
        name: "scalar_point",
        chunks: scalar_series(grid_history)
            .into_iter()
            .map(|a| whole(f32s(a)))
            .collect(),
        path: StorePath::FilteredWhole,
    };
    assert_eq!(grid_history.displacement.len(), N_SAMPLES * GRID_Z);
    let grid_point = Input {
        name: "grid_point",
        chunks: vec![whole(f32s(&grid_history.displacement))],
        path: StorePath::FilteredWhole,
    };
    (scalar_point, grid_point)
}

fn make_inputs() -> Inputs {
    let spec0 = CollisionSpec::base_case(0.62);
    let bat = prepare_bat(&spec0.bat, &spec0.numerics).expect("the base case's bat");
    let block = MODE_BLOCK.min(n_modes(&bat)).max(1);
    let (modal, grid) = (
        request(HistoryDisplacement::Modal),
        request(HistoryDisplacement::Grid),
    );
    let histories: Vec<History> = (0..MODAL_HISTORY_GROUP)
        .map(|k| {
            let spec = CollisionSpec::base_case(0.62 + 0.01 * k as f64);
            let o = simulate(&spec, &bat, Some(&modal)).expect("a modal history");
            o.history.expect("a history")
        })
        .collect();
    let grid_history = simulate(&spec0, &bat, Some(&grid))
        .expect("a grid history")
        .history
        .expect("a history");
    let (modal_group, modal_point, coordinates) = modal_inputs(&histories, block);
    let (scalar_point, grid_point) = grid_inputs(&grid_history);
    Inputs {
        modal_group,
        modal_point,
        scalar_group: scalar_group_input(&histories),
        scalar_point,
        grid_point,
        coordinates,
        modes: histories.iter().map(|h| h.modal.modes).collect(),
        block,
    }
}

thread_local! {
    /// One miniz_oxide compressor per thread and set of flags, reset for each chunk.
    static MINIZ: RefCell<Option<(u32, CompressorOxide)>> = const { RefCell::new(None) };
    /// One libdeflate compressor per thread (level 1), as the store keeps one.
    static LIBDEFLATE: RefCell<Option<libdeflater::Compressor>> = const { RefCell::new(None) };
    /// Each thread's buffer for the chunks shuffled inside a timing.
    static SCRATCH: RefCell<Vec<u8>> = const { RefCell::new(Vec::new()) };
}

/// `bytes` as a zlib stream by miniz_oxide at `level` with `strategy`.
fn miniz(bytes: &[u8], level: i32, strategy: CompressionStrategy) -> Vec<u8> {
    let flags = create_comp_flags_from_zip_params(level, 15, strategy as i32);
    MINIZ.with(|c| {
        let mut c = c.borrow_mut();
        match c.as_mut() {
            Some((f, comp)) if *f == flags => comp.reset(),
            _ => *c = Some((flags, CompressorOxide::new(flags))),
        }
        let (_, comp) = c.as_mut().expect("set above");
        let mut out = vec![0u8; bytes.len() + bytes.len() / 64 + 64];
        let (mut input, mut at) = (bytes, 0);
        loop {
            let (status, read, written) = compress(comp, input, &mut out[at..], TDEFLFlush::Finish);
            at += written;
            match status {
                TDEFLStatus::Done => break,
                TDEFLStatus::Okay => {
                    input = &input[read..];
                    out.resize(out.len() * 2, 0);
                }
                other => panic!("miniz_oxide: {other:?}"),
            }
        }
        out.truncate(at);
        out
    })
}

/// `bytes` as a zlib stream by libdeflate at level 1.
fn libdeflate(bytes: &[u8]) -> Vec<u8> {
    LIBDEFLATE.with(|c| {
        let mut c = c.borrow_mut();
        let comp = c.get_or_insert_with(|| {
            libdeflater::Compressor::new(libdeflater::CompressionLvl::new(1).expect("level 1"))
        });
        let mut out = vec![0u8; comp.zlib_compress_bound(bytes.len())];
        let n = comp
            .zlib_compress(bytes, &mut out)
            .expect("the compressor's own bound");
        out.truncate(n);
        out
    })
}

/// A chunk coded by `codec`: for a chunk given by its values, shuffled first (the store's
/// shuffle, into this thread's buffer), as the store's path does.
fn code(chunk: &Chunk, path: StorePath, codec: Codec) -> Vec<u8> {
    if let (Codec::Store, StorePath::FilteredWhole) = (codec, path) {
        let values = chunk.values.as_deref().expect("the chunk's values");
        return chunks::filtered_whole(values, HISTORY_DEFLATE_LEVEL);
    }
    let library = |bytes: &[u8]| match codec {
        Codec::Store => run_huffman::zlib_planes(bytes, chunk.plane),
        Codec::MinizRle => miniz(bytes, RLE_LEVEL, CompressionStrategy::RLE),
        Codec::Miniz1 => miniz(bytes, 1, CompressionStrategy::Default),
        Codec::Miniz6 => miniz(bytes, 6, CompressionStrategy::Default),
        Codec::Libdeflate1 => libdeflate(bytes),
    };
    match &chunk.values {
        Some(values) => SCRATCH.with(|s| {
            let mut s = s.borrow_mut();
            s.resize(values.len() * 4, 0);
            shuffle_values_into(values, &mut s);
            library(&s)
        }),
        None => library(&chunk.shuffled),
    }
}

/// Every chunk of `input` coded by `codec`: their total size, each checked by inflating it.
fn checked_size(input: &Input, codec: Codec) -> usize {
    input
        .chunks
        .iter()
        .map(|c| {
            let z = code(c, input.path, codec);
            let back = miniz_oxide::inflate::decompress_to_vec_zlib(&z)
                .unwrap_or_else(|e| panic!("{} by {codec}: not a zlib stream: {e:?}", input.name));
            assert!(
                back == c.shuffled,
                "{} by {codec}: inflates to other bytes",
                input.name
            );
            z.len()
        })
        .sum()
}

/// The sizes of every input by every codec, each output checked.
fn print_sizes(inputs: &Inputs) {
    eprintln!(
        "modes stepped {:?}, {} a block; codec sizes (bytes; every output inflated and \
         compared with its input):",
        inputs.modes, inputs.block
    );
    eprint!("{:<14}{:>9}", "input", "raw");
    for codec in CODECS {
        eprint!("{:>14}", codec.to_string());
    }
    eprintln!();
    for input in [
        &inputs.modal_group,
        &inputs.modal_point,
        &inputs.scalar_group,
        &inputs.scalar_point,
        &inputs.grid_point,
    ] {
        eprint!("{:<14}{:>9}", input.name, input.bytes());
        for codec in CODECS {
            eprint!("{:>14}", checked_size(input, codec));
        }
        // miniz_oxide's RLE strategy at level 1 (ignored) and at level 6 (the same parse)
        let with = |level, strategy| -> Vec<Vec<u8>> {
            let chunks = input.chunks.iter();
            chunks
                .map(|c| miniz(&c.shuffled, level, strategy))
                .collect()
        };
        let (rle_1, plain_1) = (
            with(1, CompressionStrategy::RLE),
            with(1, CompressionStrategy::Default),
        );
        let rle_6: usize = with(6, CompressionStrategy::RLE).iter().map(Vec::len).sum();
        // the zlib headers differ (their level field); the deflate streams
        let same = rle_1.iter().zip(&plain_1).all(|(a, b)| a[2..] == b[2..]);
        eprintln!(
            "    miniz RLE at level 1: {} miniz_1's deflate stream; at level 6: {rle_6} B",
            if same { "the same as" } else { "not" }
        );
    }
}

/// Times `codec` on every chunk of `input`, per byte of shuffled input.
fn bench_codec(bencher: Bencher, input: &Input, codec: Codec) {
    bencher
        .counter(BytesCount::new(input.bytes()))
        .bench_local(|| {
            for c in &input.chunks {
                divan::black_box(code(divan::black_box(c), input.path, codec));
            }
        });
}

#[divan::bench(args = CODECS)]
fn modal_group(bencher: Bencher, codec: Codec) {
    bench_codec(bencher, &inputs().modal_group, codec);
}

#[divan::bench(args = CODECS)]
fn modal_point(bencher: Bencher, codec: Codec) {
    bench_codec(bencher, &inputs().modal_point, codec);
}

#[divan::bench(args = CODECS)]
fn scalar_group(bencher: Bencher, codec: Codec) {
    bench_codec(bencher, &inputs().scalar_group, codec);
}

#[divan::bench(args = CODECS)]
fn scalar_point(bencher: Bencher, codec: Codec) {
    bench_codec(bencher, &inputs().scalar_point, codec);
}

#[divan::bench(args = CODECS)]
fn grid_point(bencher: Bencher, codec: Codec) {
    bench_codec(bencher, &inputs().grid_point, codec);
}

/// HDF5's shuffle filter's algorithm: byte `j` of value `i` to `j * n + i`, a byte at a time.
fn shuffle_bytewise(bytes: &[u8], size: usize, out: &mut [u8]) {
    let n = bytes.len() / size;
    for (i, value) in bytes.chunks_exact(size).enumerate() {
        for (j, &b) in value.iter().enumerate() {
            out[j * n + i] = b;
        }
    }
}

/// The store's shuffle against the byte-by-byte loop, on the modal group's f64 values.
#[divan::bench_group]
mod shuffle {
    use super::*;

    #[divan::bench]
    fn store(bencher: Bencher) {
        let values = &inputs().coordinates;
        let mut out = vec![0u8; values.len() * 8];
        bencher
            .counter(BytesCount::new(out.len()))
            .bench_local(|| shuffle_values_into(divan::black_box(values.as_slice()), &mut out));
        assert!(out == inputs().modal_group.chunks[0].shuffled);
    }

    #[divan::bench]
    fn bytewise(bencher: Bencher) {
        let values = &inputs().coordinates;
        let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
        let mut out = vec![0u8; bytes.len()];
        bencher
            .counter(BytesCount::new(out.len()))
            .bench_local(|| shuffle_bytewise(divan::black_box(&bytes), 8, &mut out));
        assert!(out == inputs().modal_group.chunks[0].shuffled);
    }
}
