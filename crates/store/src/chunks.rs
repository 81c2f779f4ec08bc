//! Summary chunks compressed on every core and written whole (`H5Dwrite_chunk`): the bytes
//! HDF5's shuffle + deflate filters would store, made in parallel instead of by the library
//! one chunk at a time on the writer thread (deflate is most of the time it takes to finish
//! a run, and that time is serial). Any zlib stream is what the deflate filter reads;
//! libdeflate makes one about twice as fast as zlib.

use super::fixed_deflate;
use super::modal::mode_major_block;
use super::run_huffman;
pub use super::shuffle::ChunkValue;
use super::shuffle::{
    fill_at, le_bytes, shuffle, shuffle_modes_at, shuffle_modes_into, shuffle_values_at,
    shuffle_values_into, with_scratch, Planes,
};
use hdf5::Dataset;
use hdf5_sys::h5::{herr_t, hsize_t};
use hdf5_sys::h5i::hid_t;
use libdeflater::{CompressionLvl, Compressor};
use std::borrow::Cow;
use std::cell::RefCell;
use std::ffi::c_void;

extern "C" {
    // libhdf5 ≥ 1.10.2; declared here so as not to depend on the -sys crate's version gates
    fn H5Dwrite_chunk(
        dset_id: hid_t,
        dxpl_id: hid_t,
        filters: u32,
        offset: *const hsize_t,
        data_size: usize,
        buf: *const c_void,
    ) -> herr_t;
    // libhdf5 ≥ 1.10.2; the -sys crate does not declare it
    fn H5Fget_eoa(file_id: hid_t, eoa: *mut u64) -> herr_t;
}

/// A block's values (row-major over `count`) laid out as a whole chunk (row-major over
/// `chunk`, `count ≤ chunk`): an edge block is padded with `fill`, as HDF5 stores it.
fn padded<'a, T: Copy>(values: &'a [T], count: &[usize], chunk: &[usize], fill: T) -> Cow<'a, [T]> {
    if count == chunk {
        return Cow::Borrowed(values);
    }
    let n: usize = chunk.iter().product();
    let mut out = vec![fill; n];
    let mut idx = vec![0usize; count.len()];
    for &v in values {
        let at = idx.iter().zip(chunk).fold(0, |a, (&i, &c)| a * c + i);
        out[at] = v;
        for k in (0..idx.len()).rev() {
            idx[k] += 1;
            if idx[k] < count[k] {
                break;
            }
            idx[k] = 0;
        }
    }
    Cow::Owned(out)
}

/// The bytes HDF5 stores for one chunk of a dataset created with shuffle then deflate(`level`).
pub fn filtered<T: ChunkValue>(
    values: &[T],
    count: &[usize],
    chunk: &[usize],
    fill: T,
    level: u8,
) -> Vec<u8> {
    let whole = padded(values, count, chunk, fill);
    let shuffled = shuffle(&le_bytes(&whole), T::SIZE);
    deflate_planes(&shuffled, T::SIZE, level)
}

/// [`filtered`] for values that fill their chunk (a history: one chunk per point); level 0:
/// the raw values of a dataset without filters. Shuffled
/// straight from the values: the same bytes with one copy less. Runs on the workers
/// (`store::encode`).
pub fn filtered_whole<T: ChunkValue>(values: &[T], level: u8) -> Vec<u8> {
    if level == 0 {
        return le_bytes(values); // no filters: the values as they are
    }
    with_scratch(values.len() * T::SIZE, |out| {
        shuffle_values_into(values, out);
        deflate_planes(out, T::SIZE, level)
    })
}

/// The stored chunk of a group of points' history series (`store::encode`): each place's
/// values one after the other, `per` a place, in the stored type `T` (`convert`), a place's
/// values short of `per`, or a place without any (`None`), completed with `fill`;
/// shuffled, each byte plane in deflate blocks with its own Huffman codes ([`run_huffman`]);
/// level 0: the raw values. Each place is shuffled straight into its part of the planes.
/// One code and one block header serve the group's points where a chunk of each point's
/// own needs one each (`benches/chunk_groups.rs` measures the saving).
pub fn filtered_group<T: ChunkValue>(
    places: &[Option<&[f64]>],
    per: usize,
    level: u8,
    convert: impl Fn(f64) -> T,
    fill: T,
) -> Vec<u8> {
    let n = places.len() * per;
    if level == 0 {
        let mut v = Vec::with_capacity(n);
        for a in places {
            let a = a.unwrap_or_default();
            v.extend(a.iter().map(|&x| convert(x)));
            v.resize(v.len() + per - a.len(), fill);
        }
        return le_bytes(&v);
    }
    with_scratch(n * T::SIZE, |out| {
        let mut values = Vec::with_capacity(per);
        for (p, a) in places.iter().enumerate() {
            let a = a.unwrap_or_default();
            values.clear();
            values.extend(a.iter().map(|&x| convert(x)));
            shuffle_values_at(
                &values,
                out,
                Planes {
                    len: n,
                    at: p * per,
                },
            );
            let rest = Planes {
                len: n,
                at: p * per + a.len(),
            };
            fill_at(fill, per - a.len(), out, rest);
        }
        run_huffman::zlib_planes(out, n)
    })
}

/// A place of a group chunk of modal coordinates: a point's coordinates (row-major
/// [time][`modes`]) and the modes of them the chunk's block holds.
pub type CoordinatePlace<'a> = (&'a [f64], usize, std::ops::Range<usize>);

/// The stored chunk of one block of a group's modal coordinates: each place's modes
/// mode-major ([mode][time]), then zero rows up to `block` modes (a whole block of zeros
/// for a place without one), shuffled and coded as [`filtered_group`] codes series.
pub fn filtered_group_coordinates(
    places: &[Option<CoordinatePlace>],
    n_samples: usize,
    block: usize,
    level: u8,
) -> Vec<u8> {
    let per = block * n_samples;
    let n = places.len() * per;
    if level == 0 {
        let mut v = Vec::with_capacity(n);
        for p in places {
            match p {
                Some((q, modes, rows)) => {
                    v.extend(mode_major_block(q, *modes, n_samples, rows.clone(), block))
                }
                None => v.resize(v.len() + per, 0.0),
            }
        }
        return le_bytes(&v);
    }
    with_scratch(n * 8, |out| {
        for (p, place) in places.iter().enumerate() {
            let at = p * per;
            let used = match place {
                Some((q, modes, rows)) => {
                    let planes = Planes { len: n, at };
                    shuffle_modes_at(q, *modes, n_samples, rows.clone(), out, planes);
                    rows.len() * n_samples
                }
                None => 0,
            };
            fill_at(
                0.0f64,
                per - used,
                out,
                Planes {
                    len: n,
                    at: at + used,
                },
            );
        }
        run_huffman::zlib_planes(out, n)
    })
}

/// [`filtered_whole`] for values whose bytes are mostly runs of zeros between planes that
/// repeat little (the modal coordinates kept to the precision they need): each
/// byte plane a deflate block with its own Huffman codes ([`run_huffman`]). The stored
/// form of a whole, zero-padded block of coordinates, which [`filtered_coordinates`] makes
/// without the padding (tested against this).
#[cfg(test)]
fn filtered_runs<T: ChunkValue>(values: &[T], level: u8) -> Vec<u8> {
    if level == 0 {
        return le_bytes(values);
    }
    with_scratch(values.len() * T::SIZE, |out| {
        shuffle_values_into(values, out);
        run_huffman::zlib_planes(out, values.len())
    })
}

/// The stored chunk of a block of modal coordinates: modes `rows` of `q` (row-major
/// [time][`modes`], `n_samples` rows), mode-major ([mode][time]), then zero rows up to
/// `block` modes, shuffled and deflated as `filtered_runs` would the whole block; the same
/// bytes, made without the zero rows and without the mode-major copy (the transposed copy,
/// and shuffling and scanning the zero rows, would be a third of encoding a block).
pub fn filtered_coordinates(
    q: &[f64],
    modes: usize,
    n_samples: usize,
    rows: std::ops::Range<usize>,
    block: usize,
    level: u8,
) -> Vec<u8> {
    if level == 0 {
        return le_bytes(&mode_major_block(q, modes, n_samples, rows, block));
    }
    let zeros = block.saturating_sub(rows.len()) * n_samples;
    let n = rows.len() * n_samples;
    with_scratch(8 * n, |out| {
        shuffle_modes_into(q, modes, n_samples, rows, out);
        run_huffman::zlib_padded_planes(out, n, zeros)
    })
}

/// Fewest values in a chunk for its byte planes to be judged one by one (below it the
/// whole chunk is deflated: the cost is small and the statistic noisy).
const PLANE_MIN_VALUES: usize = 1024;

/// Shuffled bytes (`size` planes of equal length) as one zlib stream, which is what the
/// deflate filter reads. The planes that hold the low-order bytes of measured or computed
/// floats are noise: deflate spends most of its time on them and saves nothing (on
/// a displacement chunk of 17 000 f32, libdeflate takes 50 µs on each of planes 0 and 1 and
/// they come out at 99.8 % of their size). So the leading planes that look like uniform bytes go in as
/// stored blocks and only the rest is deflated; deflate allows mixing block types in one
/// stream, so every zlib reader (HDF5's filter, h5py, xarray) reads it as before. A plane
/// that ends in a run of zeros (a block of modal coordinates padded with zero rows, issue
/// 37) is judged without them, and the run goes in as a short block of copies.
fn deflate_planes(shuffled: &[u8], size: usize, level: u8) -> Vec<u8> {
    let n = shuffled.len() / size.max(1);
    if n < PLANE_MIN_VALUES {
        return deflate_small(shuffled, n, size, level);
    }
    if size <= 1 {
        return deflate_zlib(shuffled, level);
    }
    let segments = leading_noise(shuffled, n, UNIFORM_PERCENT);
    if segments.is_empty() {
        return deflate_zlib(shuffled, level);
    }
    let (mut out, rest) = leading_segments(shuffled, &segments);
    if !rest.is_empty() {
        // a raw deflate stream of the rest, starting on the byte boundary the stored
        // blocks end on; its last block is the stream's final one
        with_compressor(level, |comp| {
            let start = out.len();
            out.resize(start + comp.deflate_compress_bound(rest.len()), 0);
            let written = comp
                .deflate_compress(rest, &mut out[start..])
                .expect("the output buffer is the compressor's own bound");
            out.truncate(start + written);
        });
    }
    out.extend_from_slice(&libdeflater::adler32(shuffled).to_be_bytes());
    out
}

/// A small chunk (under [`PLANE_MIN_VALUES`] values; a history's scalar series): its
/// leading planes of noise stored and the rest in one block with the fixed codes, without
/// libdeflate's set-up of several µs per call (`fixed_deflate`). The fixed codes find
/// nothing to shorten in the noise planes (the low bytes of a series of f32) and code each
/// of their bytes in 8 or 9 bits; stored they are copied, in 8.
fn deflate_small(shuffled: &[u8], n: usize, size: usize, level: u8) -> Vec<u8> {
    let segments = match size > 1 {
        true => leading_noise(shuffled, n, SMALL_UNIFORM_PERCENT),
        false => Vec::new(),
    };
    if segments.is_empty() {
        return fixed_deflate::zlib_small(shuffled)
            .unwrap_or_else(|| deflate_zlib(shuffled, level));
    }
    let (out, rest) = leading_segments(shuffled, &segments);
    let mut out = match rest.is_empty() {
        true => out,
        false => fixed_deflate::put_fixed_runs(out, rest),
    };
    out.extend_from_slice(&libdeflater::adler32(shuffled).to_be_bytes());
    out
}

/// The zlib header and the leading segments (stored bytes, zero runs) of a chunk; the bytes
/// after them. The last segment is the stream's final block when nothing follows.
fn leading_segments<'a>(shuffled: &'a [u8], segments: &[Segment<'_>]) -> (Vec<u8>, &'a [u8]) {
    let consumed: usize = segments.iter().map(|s| s.len()).sum();
    let rest = &shuffled[consumed..];
    let mut out = Vec::with_capacity(shuffled.len() + 64);
    out.extend_from_slice(&fixed_deflate::ZLIB_HEADER);
    for (k, segment) in segments.iter().enumerate() {
        let last_segment = rest.is_empty() && k + 1 == segments.len();
        match segment {
            Segment::Stored(bytes) => {
                let blocks: Vec<&[u8]> = bytes.chunks(u16::MAX as usize).collect();
                for (i, block) in blocks.iter().enumerate() {
                    let last = last_segment && i + 1 == blocks.len();
                    fixed_deflate::push_stored_block(&mut out, block, last);
                }
            }
            Segment::Zeros(len) => {
                fixed_deflate::push_zero_run(&mut out, *len);
                if last_segment {
                    fixed_deflate::push_stored_block(&mut out, &[], true);
                }
            }
        }
    }
    (out, rest)
}

/// A piece of the leading planes: bytes stored as they are, or a run of zeros.
enum Segment<'a> {
    Stored(&'a [u8]),
    Zeros(usize),
}

impl Segment<'_> {
    fn len(&self) -> usize {
        match self {
            Segment::Stored(b) => b.len(),
            Segment::Zeros(n) => *n,
        }
    }
}

/// [`looks_uniform`]'s bound for a chunk's planes, in percent of uniform bytes' collision
/// probability: 3 % above it (the documentation of [`looks_uniform`]).
const UNIFORM_PERCENT: u128 = 103;

/// The same for a small chunk's planes (a few hundred bytes), whose statistic scatters by
/// 10 % (its standard deviation for 200 uniform bytes): 30 % above it, three deviations.
/// Mistaken either way, a plane is only stored where it could have been coded, or the
/// reverse: the same data, a few bytes more or less.
const SMALL_UNIFORM_PERCENT: u128 = 130;

/// Zero runs shorter than this at a plane's end are left in it (noise ends in a zero byte
/// one time in 256, in 64 of them never).
const MIN_ZERO_RUN: usize = 64;

/// The number of zero bytes `bytes` ends with, eight at a time.
fn trailing_zeros(bytes: &[u8]) -> usize {
    let tail = bytes.len() % 8;
    if bytes[bytes.len() - tail..].iter().any(|&b| b != 0) {
        return bytes[bytes.len() - tail..]
            .iter()
            .rev()
            .take_while(|&&b| b == 0)
            .count();
    }
    let words = bytes[..bytes.len() - tail].chunks_exact(8).rev();
    let zero_words = words
        .clone()
        .take_while(|w| u64::from_ne_bytes((*w).try_into().expect("8 bytes")) == 0)
        .count();
    let partial = words
        .clone()
        .nth(zero_words)
        .map_or(0, |w| w.iter().rev().take_while(|&&b| b == 0).count());
    tail + 8 * zero_words + partial
}

/// The leading planes (each `n` bytes) that are noise, with a plane's trailing run of zeros
/// apart; consecutive stored bytes in one segment, so that a chunk without zero runs is
/// stored exactly as before.
fn leading_noise(shuffled: &[u8], n: usize, percent: u128) -> Vec<Segment<'_>> {
    let mut segments: Vec<Segment> = Vec::new();
    let mut at = 0;
    for plane in shuffled.chunks_exact(n) {
        let zeros = trailing_zeros(plane);
        let zeros = if zeros >= MIN_ZERO_RUN { zeros } else { 0 };
        let data = &plane[..n - zeros];
        if data.len() < MIN_ZERO_RUN || !looks_uniform(data, percent) {
            break;
        }
        match segments.last_mut() {
            Some(Segment::Stored(prev)) => *prev = &shuffled[at - prev.len()..at + data.len()],
            _ => segments.push(Segment::Stored(data)),
        }
        if zeros > 0 {
            segments.push(Segment::Zeros(zeros));
        }
        at += n;
    }
    segments
}

/// Whether a byte plane is as good as uniform noise, which deflate cannot shrink: its bytes
/// collide at most `percent` % as often as uniform bytes would (`run_huffman::
/// collides_within`). At 103 %, entropy coding could save at most about 0.3 % of the plane.
/// Measured on displacement chunks: planes 0 and 1 at 100.4 to 101.1 %, plane 2 (which
/// deflate shrinks by 10 %) at 105.4 to 106.6 %.
fn looks_uniform(plane: &[u8], percent: u128) -> bool {
    let mut counts = [0u32; 256];
    if plane.len() < PLANE_MIN_VALUES {
        // a small chunk's plane (a few hundred bytes, four to seven of them a series): one
        // table, where zeroing four would be most of the count
        plane.iter().for_each(|&b| counts[usize::from(b)] += 1);
    } else {
        let mut tables = [[0u32; 256]; 4];
        run_huffman::count_bytes(plane, &mut tables);
        for (b, c) in counts.iter_mut().enumerate() {
            *c = tables.iter().map(|t| t[b]).sum();
        }
    }
    run_huffman::collides_within(&counts, plane.len(), percent)
}

thread_local! {
    /// One compressor per thread and level: libdeflate's state is a few hundred KiB, too
    /// much to allocate (and fault in) for every chunk.
    static COMPRESSOR: RefCell<Option<(u8, Compressor)>> = const { RefCell::new(None) };
}

/// `bytes` as a zlib stream (what HDF5's deflate filter stores), by libdeflate: whole
/// buffers only, about twice as fast as zlib at the same level for the same size (deflate
/// is most of finishing a small study's file).
fn deflate_zlib(bytes: &[u8], level: u8) -> Vec<u8> {
    with_compressor(level, |comp| {
        let mut out = vec![0u8; comp.zlib_compress_bound(bytes.len())];
        let n = comp
            .zlib_compress(bytes, &mut out)
            .expect("the output buffer is the compressor's own bound");
        out.truncate(n);
        out
    })
}

/// Run `f` with this thread's compressor for `level`.
fn with_compressor<R>(level: u8, f: impl FnOnce(&mut Compressor) -> R) -> R {
    COMPRESSOR.with(|c| {
        let mut c = c.borrow_mut();
        if c.as_ref().is_none_or(|(l, _)| *l != level) {
            let lvl = CompressionLvl::new(level.into()).unwrap_or_default();
            *c = Some((level, Compressor::new(lvl)));
        }
        let (_, comp) = c.as_mut().expect("set above");
        f(comp)
    })
}

/// Write a chunk's filtered bytes at its (chunk-aligned) start.
pub fn write_chunk(ds: &Dataset, start: &[usize], bytes: &[u8]) -> hdf5::Result<()> {
    let offset: Vec<hsize_t> = start.iter().map(|&s| s as hsize_t).collect();
    let r = hdf5::sync::sync(|| unsafe {
        H5Dwrite_chunk(
            ds.id(),
            hdf5_sys::h5p::H5P_DEFAULT,
            0,
            offset.as_ptr(),
            bytes.len(),
            bytes.as_ptr().cast(),
        )
    });
    if r < 0 {
        return Err(hdf5::Error::from(
            format!("H5Dwrite_chunk failed on {}", ds.name()).as_str(),
        ));
    }
    Ok(())
}

/// The end of `file`'s allocated space (HDF5's end of allocation, "EOA"), an offset in
/// the file (results files have no user block).
pub fn end_of_allocation(file: hid_t) -> Option<u64> {
    let mut eoa = 0u64;
    // SAFETY: a query on an open file id, into a local
    let r = hdf5::sync::sync(|| unsafe { H5Fget_eoa(file, &mut eoa) });
    (r >= 0).then_some(eoa)
}

/// [`write_chunk`] into a dataset of `file`, and the offset in the file where the chunk's
/// bytes went, when it is known: the results file allocates everything at its end
/// (`FileSpaceStrategy::None`, `build::skeleton`), so a chunk that moved the end of
/// allocation by exactly its own length lies at the old end. A write that allocated
/// something else too (a dataset's first chunk creates its chunk index) gives `None`.
/// The journal records chunks by this offset instead of their bytes (`store::by_reference`),
/// and a resume checks the bytes it finds there against their checksum, so an offset that
/// were wrong would only cost the point's recomputation.
///
/// `eoa` is the end of allocation before the write, when the caller knows it (None: asked
/// of the file), and is left at the end after it: a point's chunks written one after the
/// other ask the file once each, not twice (asked twice, the queries are a seventh of
/// placing a modal history).
pub fn write_chunk_at_end(
    ds: &Dataset,
    file: hid_t,
    start: &[usize],
    bytes: &[u8],
    eoa: &mut Option<u64>,
) -> hdf5::Result<Option<u64>> {
    let before = eoa.or_else(|| end_of_allocation(file));
    // not known again until the write has succeeded: a failed one may have allocated
    *eoa = None;
    write_chunk(ds, start, bytes)?;
    let after = end_of_allocation(file);
    *eoa = after;
    Ok(match (before, after) {
        (Some(b), Some(a)) if a.checked_sub(b) == Some(bytes.len() as u64) => Some(b),
        _ => None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    // A block of modal coordinates made from the coordinates as they are, without its zero
    // rows, is byte for byte the chunk of its mode-major, zero-padded copy (the stream the
    // whole planes give, Adler-32 included): for sample counts that are and are not
    // multiples of eight, zero tails shorter than a run, −0.0, and coordinates rounded to a
    // power-of-two step (low bytes zero, as stored).
    #[test]
    fn coordinate_chunks_are_those_of_their_padded_blocks() {
        use crate::modal::{coordinate_block_rows, coordinate_blocks};
        let mut x = 0x9E37_79B9_7F4A_7C15_u64;
        let mut next = move || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        for (n_samples, modes, used, block) in [
            (200, 21, 21, 32),
            (200, 40, 37, 32),
            (13, 5, 4, 4),
            (3, 6, 5, 4),
            (8, 3, 3, 3),
        ] {
            let mut q = vec![0.0; n_samples * modes];
            for t in 0..n_samples {
                for j in 0..used {
                    let step = 2f64.powi(-20 - j as i32);
                    q[t * modes + j] = (next() * 1e-3 / step).round() * step;
                }
            }
            q[n_samples * modes - 1] = -0.0; // a value (in the last mode, past `used`)
            for level in [0, 1] {
                let whole: Vec<Vec<u8>> = coordinate_blocks(&q, n_samples, block)
                    .iter()
                    .map(|b| match level {
                        0 => le_bytes(b),
                        _ => filtered_runs(b, level),
                    })
                    .collect();
                let direct: Vec<Vec<u8>> = coordinate_block_rows(&q, n_samples, block)
                    .into_iter()
                    .map(|rows| filtered_coordinates(&q, modes, n_samples, rows, block, level))
                    .collect();
                assert_eq!(
                    direct, whole,
                    "{n_samples} samples, {modes} modes, level {level}"
                );
            }
        }
    }

    // The workers' history chunks (`filtered_whole`) are the same bytes as the general
    // chunk filter (`filtered`) makes of the same values.
    #[test]
    fn whole_chunks_are_filtered_as_before() {
        let v: Vec<f32> = (0..1000).map(|i| (i as f32 * 0.37).sin()).collect();
        assert_eq!(
            filtered_whole(&v, 1),
            filtered(&v, &[1000], &[1000], f32::NAN, 1)
        );
        let w: Vec<f64> = (0..999).map(|i| (i as f64).sqrt()).collect();
        assert_eq!(
            filtered_whole(&w, 1),
            filtered(&w, &[1, 999], &[1, 999], f64::NAN, 1)
        );
    }

    /// Values like a history's: a smooth signal whose low-order bytes are noise.
    fn smooth_f32(n: usize) -> Vec<f32> {
        (0..n)
            .map(|i| {
                let x = i as f64;
                (1e-3 * (x * 0.013).sin() + 2e-4 * (x * 0.0011).cos()) as f32
            })
            .collect()
    }

    /// Bytes of `model::xorshift`: uniform for this purpose.
    fn noise(n: usize) -> Vec<u8> {
        batstudy_physics::xorshift::bytes(0x9E37_79B9_7F4A_7C15, n)
    }

    /// A dataset of `shape` with HDF5's shuffle and deflate(1) filters, a chunk per row (the
    /// whole of a 1-D one), as the store creates its variables.
    fn filtered_dataset<T: hdf5::H5Type>(
        file: &hdf5::File,
        name: &str,
        shape: &[usize],
    ) -> hdf5::Dataset {
        let mut chunk = shape.to_vec();
        if chunk.len() > 1 {
            chunk[0] = 1;
        }
        file.new_dataset::<T>()
            .shape(shape.to_vec())
            .chunk(chunk)
            .shuffle()
            .deflate(1)
            .create(name)
            .unwrap()
    }

    // Noise is uniform; a constant, a ramp over a few values and the exponent byte of
    // smooth floats are not.
    #[test]
    fn only_noise_planes_look_uniform() {
        assert!(looks_uniform(&noise(17_000), UNIFORM_PERCENT));
        assert!(looks_uniform(&noise(1_024), UNIFORM_PERCENT));
        assert!(!looks_uniform(&[7u8; 4096], UNIFORM_PERCENT));
        let ramp: Vec<u8> = (0..4096).map(|i| (i % 97) as u8).collect();
        assert!(!looks_uniform(&ramp, UNIFORM_PERCENT)); // 97 values: 2.6 times the uniform collision rate
        let v = smooth_f32(17_000);
        let shuffled = shuffle(&le_bytes(&v), 4);
        let planes: Vec<bool> = shuffled
            .chunks_exact(17_000)
            .map(|p| looks_uniform(p, UNIFORM_PERCENT))
            .collect();
        assert!(planes[0] && !planes[3], "planes {planes:?}");
    }

    // The stream with stored planes is a valid zlib stream of the shuffled bytes, and HDF5's
    // own deflate filter (zlib, not libdeflate) reads the chunk back as the values
    // (RFC 1950/1951; the HDF5 filter pipeline: shuffle, then deflate).
    #[test]
    fn chunks_with_stored_planes_read_back_through_hdf5() {
        let n = 17_000;
        let v = smooth_f32(n);
        let bytes = filtered_whole(&v, 1);
        let shuffled = shuffle(&le_bytes(&v), 4);
        assert_ne!(bytes, deflate_zlib(&shuffled, 1), "no plane was stored");
        let mut inflated = vec![0u8; shuffled.len()];
        let got = libdeflater::Decompressor::new()
            .zlib_decompress(&bytes, &mut inflated)
            .unwrap();
        assert_eq!((got, &inflated), (shuffled.len(), &shuffled));
        // not larger than deflating every plane (the stored planes do not compress)
        assert!(bytes.len() <= deflate_zlib(&shuffled, 1).len() + 64);

        let dir = tempfile::tempdir().unwrap();
        let file = hdf5::File::create(dir.path().join("planes.h5")).unwrap();
        let ds = filtered_dataset::<f32>(&file, "v", &[2, n]);
        let noisy: Vec<f32> = noise(4 * n)
            .chunks_exact(4)
            .map(|b| f32::from_le_bytes([b[0], b[1], b[2], 0x3f]))
            .collect();
        write_chunk(&ds, &[0, 0], &bytes).unwrap();
        write_chunk(&ds, &[1, 0], &filtered_whole(&noisy, 1)).unwrap();
        let back = ds.read_raw::<f32>().unwrap();
        assert_eq!(&back[..n], &v[..]);
        assert_eq!(&back[n..], &noisy[..]);
    }

    // A block of modal coordinates: 21 rows of noisy f64 and 11 zero rows,
    // mode-major. Each noise plane goes in stored without its zeros, which take a few bytes;
    // HDF5's own filter reads the chunk back, and so do chunks with zeros in every plane, in
    // the last plane only, and a whole block of zeros.
    #[test]
    fn zero_padded_blocks_read_back_through_hdf5() {
        let (rows, used, t) = (32, 21, 200);
        let block = |used: usize| -> Vec<f64> {
            let mut v = vec![0.0; rows * t];
            for (i, x) in v[..used * t].iter_mut().enumerate() {
                *x = 1e-4 * (i as f64 * 0.0123).sin() + 1e-7 * (i as f64).sqrt();
            }
            v
        };
        let v = block(used);
        let bytes = filtered_whole(&v, 1);
        let shuffled = shuffle(&le_bytes(&v), 8);
        // the noise planes' bytes stored, their zeros nearly free: far less than deflating
        // every plane costs, and no more bytes than the data planes themselves
        let deflated_all = deflate_zlib(&shuffled, 1);
        assert!(bytes.len() < used * t * 8, "{} bytes", bytes.len());
        assert!(bytes.len() <= deflated_all.len() + 64);
        let dir = tempfile::tempdir().unwrap();
        let file = hdf5::File::create(dir.path().join("modal.h5")).unwrap();
        let cases = [v.clone(), block(1), block(rows), vec![0.0; rows * t]];
        let ds = filtered_dataset::<f64>(&file, "q", &[cases.len(), rows, t]);
        for (k, c) in cases.iter().enumerate() {
            write_chunk(&ds, &[k, 0, 0], &filtered_whole(c, 1)).unwrap();
        }
        let back = ds.read_raw::<f64>().unwrap();
        assert_eq!(back, cases.concat());
    }

    // Zeros at the end of a plane, counted eight bytes at a time as one at a time would.
    #[test]
    fn trailing_zeros_count_as_bytes_do() {
        for len in [0usize, 1, 7, 8, 9, 64, 100] {
            for nonzero_at in [None, Some(0), Some(len / 2), Some(len.saturating_sub(1))] {
                let mut v = vec![0u8; len];
                if let (Some(k), true) = (nonzero_at, len > 0) {
                    v[k] = 3;
                }
                let want = v.iter().rev().take_while(|&&b| b == 0).count();
                assert_eq!(trailing_zeros(&v), want, "{len} {nonzero_at:?}");
            }
        }
    }

    // Every plane noise, 280 000 bytes in all where a stored block holds 65 535: the stream
    // is five stored blocks, the last one final, and inflates to the shuffled bytes.
    #[test]
    fn all_noise_chunks_are_stored_blocks_only() {
        let n = 70_000;
        let v: Vec<f32> = noise(4 * n)
            .chunks_exact(4)
            .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            .collect();
        let bytes = filtered_whole(&v, 1);
        let shuffled = shuffle(&le_bytes(&v), 4);
        // zlib header, the bytes with 5 bytes of header per stored block, Adler-32
        assert_eq!(bytes.len(), 2 + 4 * n + 5 * 5 + 4);
        let mut inflated = vec![0u8; shuffled.len()];
        let got = libdeflater::Decompressor::new()
            .zlib_decompress(&bytes, &mut inflated)
            .unwrap();
        assert_eq!((got, &inflated), (shuffled.len(), &shuffled));
    }

    // Small chunks go out with fixed Huffman codes (`store::fixed_deflate`); HDF5's
    // deflate filter (zlib's inflate, RFC 1950/1951) reads them back: a force history that
    // ends in zeros, a constant, noise (stored), a force whose low planes are noise during
    // the contact (those planes stored, the rest with the fixed codes), an f64
    // series of that kind, and a few f64 summaries.
    #[test]
    fn small_chunks_read_back_through_hdf5() {
        let force: Vec<f32> = (0..200)
            .map(|i| {
                if i < 90 {
                    (i as f32 * 0.035).sin() * 3.1e3
                } else {
                    0.0
                }
            })
            .collect();
        let constant = vec![-27.25f32; 200];
        let noisy_force: Vec<f32> = noise(800)
            .chunks_exact(4)
            .enumerate()
            .map(|(i, b)| match i < 70 {
                true => f32::from_le_bytes([b[0], b[1], b[2] & 0x7f, 0x45]),
                false => 0.0,
            })
            .collect();
        let shuffled = shuffle(&le_bytes(&noisy_force), 4);
        assert_ne!(
            filtered_whole(&noisy_force, 1),
            fixed_deflate::zlib_small(&shuffled).unwrap(),
            "a plane was stored"
        );
        let noisy: Vec<f32> = noise(800)
            .chunks_exact(4)
            .map(|b| f32::from_le_bytes([b[0], b[1], b[2], 0x3f]))
            .collect();
        let dir = tempfile::tempdir().unwrap();
        let file = hdf5::File::create(dir.path().join("small.h5")).unwrap();
        let ds = filtered_dataset::<f32>(&file, "v", &[4, 200]);
        let rows = [&force, &constant, &noisy, &noisy_force];
        for (row, values) in rows.into_iter().enumerate() {
            let bytes = filtered_whole(values, 1);
            assert_eq!(bytes[..2], fixed_deflate::ZLIB_HEADER);
            write_chunk(&ds, &[row, 0], &bytes).unwrap();
        }
        // the zeros and the constant shrink; noise does not grow by more than a block header
        assert!(filtered_whole(&force, 1).len() < 700);
        assert!(filtered_whole(&constant, 1).len() < 40);
        assert!(filtered_whole(&noisy, 1).len() <= 800 + 2 + 5 + 4);
        let back = ds.read_raw::<f32>().unwrap();
        assert_eq!(back, [force, constant, noisy, noisy_force].concat());
        let load: Vec<f64> = noise(200)
            .iter()
            .map(|&b| 1.0 + f64::from(b) / 7.0)
            .collect();
        let ld = filtered_dataset::<f64>(&file, "w", &[1, 200]);
        write_chunk(&ld, &[0, 0], &filtered_whole(&load, 1)).unwrap();
        assert_eq!(ld.read_raw::<f64>().unwrap(), load);

        let summary: Vec<f64> = (0..45).map(|i| 30.0 + (i as f64 * 0.1).cos()).collect();
        let sd = filtered_dataset::<f64>(&file, "s", &[45]);
        write_chunk(&sd, &[0], &filtered(&summary, &[45], &[45], f64::NAN, 1)).unwrap();
        assert_eq!(sd.read_raw::<f64>().unwrap(), summary);
    }

    // An edge block keeps its values at their places in the whole chunk; the rest is fill.
    #[test]
    fn edge_block_is_padded_in_place() {
        let v = padded(&[1, 2, 3, 4], &[2, 2], &[3, 3], 0);
        assert_eq!(&*v, &[1, 2, 0, 3, 4, 0, 0, 0, 0]);
    }
}
