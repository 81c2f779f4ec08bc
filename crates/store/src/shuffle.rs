//! HDF5's shuffle filter, made fast: byte j of each of a chunk's n values goes to j·n + its
//! index, so that each byte plane (the values' exponents, their high and low mantissa
//! bytes) is one run that deflate sees whole. Eight values at a time, their bytes an 8 × 8
//! matrix transposed in registers (byte by byte, the stores would be a third of encoding a
//! block of modal coordinates); straight from the modal coordinates as the
//! integrator records them, without the mode-major copy; into a buffer each thread keeps.
//! `store::chunks` deflates what this shuffles.

use std::cell::RefCell;

/// A value stored in a chunk: its little-endian bytes (HDF5's native types here).
pub trait ChunkValue: Copy + Send + Sync {
    const SIZE: usize;
    fn put_le(self, out: &mut Vec<u8>);
    /// The value's little-endian bytes into `out[..SIZE]`.
    fn write_le(self, out: &mut [u8]);
    /// The value's little-endian bytes as the low `SIZE` bytes of a u64 (byte j at 8 j).
    fn le_word(self) -> u64;
}

macro_rules! chunk_value {
    ($($t:ty),*) => {$(
        impl ChunkValue for $t {
            const SIZE: usize = std::mem::size_of::<$t>();
            fn put_le(self, out: &mut Vec<u8>) {
                out.extend_from_slice(&self.to_le_bytes());
            }
            fn write_le(self, out: &mut [u8]) {
                out[..Self::SIZE].copy_from_slice(&self.to_le_bytes());
            }
            #[inline(always)]
            fn le_word(self) -> u64 {
                let mut b = [0u8; 8];
                b[..Self::SIZE].copy_from_slice(&self.to_le_bytes());
                u64::from_le_bytes(b)
            }
        }
    )*};
}
chunk_value!(f64, f32, i8, i32, u64);

/// HDF5's shuffle filter: byte `j` of element `i` goes to `j * n + i`. Byte by byte, apart
/// from [`shuffle_values_into`]'s transposes: what `benches/chunk_groups.rs` checks its
/// chunks against.
pub fn shuffle(bytes: &[u8], size: usize) -> Vec<u8> {
    if size <= 1 {
        return bytes.to_vec();
    }
    let n = bytes.len() / size;
    let mut out = vec![0u8; bytes.len()];
    for (i, e) in bytes.chunks_exact(size).enumerate() {
        for (j, &b) in e.iter().enumerate() {
            out[j * n + i] = b;
        }
    }
    out
}

/// The values' little-endian bytes, one after the other.
pub(super) fn le_bytes<T: ChunkValue>(values: &[T]) -> Vec<u8> {
    let mut raw = Vec::with_capacity(values.len() * T::SIZE);
    for &v in values {
        v.put_le(&mut raw);
    }
    raw
}

/// [`shuffle_values_into`] of `store::modal::mode_major_block``(q, modes, n_samples, rows, ..)` without
/// its zero rows, into `out`, made from `q` as it is: eight samples of a mode gathered, their
/// bytes transposed, each row stored at once. Eight samples at a time of every mode: the
/// eight rows of `q` they come from are read once while they are in the cache (a mode at a
/// time reads the whole history once per mode: 9.6 µs against 6.0 for a bench history of
/// 21 modes).
pub(super) fn shuffle_modes_into(
    q: &[f64],
    modes: usize,
    n_samples: usize,
    rows: std::ops::Range<usize>,
    out: &mut [u8],
) {
    let n = rows.len() * n_samples;
    shuffle_modes_at(q, modes, n_samples, rows, out, Planes { len: n, at: 0 });
}

/// Where a run of values goes in shuffled bytes: each byte plane `len` bytes long, the
/// run's values from value `at` of the planes on (a group chunk holds several points'
/// values one after the other, `store::encode`).
#[derive(Debug, Clone, Copy)]
pub struct Planes {
    pub len: usize,
    pub at: usize,
}

/// [`shuffle_modes_into`] into the planes of a larger chunk, at `planes.at`.
pub(super) fn shuffle_modes_at(
    q: &[f64],
    modes: usize,
    n_samples: usize,
    rows: std::ops::Range<usize>,
    out: &mut [u8],
    planes: Planes,
) {
    let (n, base) = (planes.len, planes.at);
    let whole = n_samples - n_samples % 8;
    for t in (0..whole).step_by(8) {
        let eight = &q[t * modes..(t + 8) * modes];
        for (r, j) in rows.clone().enumerate() {
            let words = std::array::from_fn(|k| eight[k * modes + j].to_bits());
            let at = base + r * n_samples + t;
            for (p, row) in transpose_bytes(words).iter().enumerate() {
                out[p * n + at..][..8].copy_from_slice(&row.to_le_bytes());
            }
        }
    }
    for (r, j) in rows.enumerate() {
        for t in whole..n_samples {
            for (p, b) in q[t * modes + j].to_le_bytes().into_iter().enumerate() {
                out[p * n + base + r * n_samples + t] = b;
            }
        }
    }
}

/// `count` copies of `value` into the planes of a chunk, at `planes.at`: each plane's run
/// set to the value's byte (the fill value of a group chunk's empty places).
pub(super) fn fill_at<T: ChunkValue>(value: T, count: usize, out: &mut [u8], planes: Planes) {
    let mut e = [0u8; 16];
    value.write_le(&mut e);
    for (p, &b) in e[..T::SIZE].iter().enumerate() {
        out[p * planes.len + planes.at..][..count].fill(b);
    }
}

/// HDF5's shuffle of `values` (byte j of value i at j·n + i) into `out`, eight values at a time: the
/// eight values' bytes as an 8 × 8 byte matrix, transposed in registers, each row then
/// stored at once (byte by byte, the stores would be a third of encoding a block of modal
/// coordinates; gathering each row by shifts, a quarter of it). Public for
/// `benches/chunk_groups.rs`, which shuffles chunks of a layout the store does not write.
pub fn shuffle_values_into<T: ChunkValue>(values: &[T], out: &mut [u8]) {
    let len = values.len();
    shuffle_values_at(values, out, Planes { len, at: 0 });
}

/// [`shuffle_values_into`] into the planes of a larger chunk, at `planes.at`.
pub(super) fn shuffle_values_at<T: ChunkValue>(values: &[T], out: &mut [u8], planes: Planes) {
    let (n, base) = (planes.len, planes.at);
    let whole = values.len() - values.len() % 8;
    for (b, eight) in values[..whole].chunks_exact(8).enumerate() {
        let rows = transpose_bytes(std::array::from_fn(|k| eight[k].le_word()));
        for (j, row) in rows.iter().enumerate().take(T::SIZE) {
            out[j * n + base + 8 * b..][..8].copy_from_slice(&row.to_le_bytes());
        }
    }
    let mut e = [0u8; 16];
    for (i, &v) in values.iter().enumerate().skip(whole) {
        v.write_le(&mut e);
        for (j, &b) in e[..T::SIZE].iter().enumerate() {
            out[j * n + base + i] = b;
        }
    }
}

/// [`shuffle_values_into`] a new buffer.
#[cfg(test)]
fn shuffle_values<T: ChunkValue>(values: &[T]) -> Vec<u8> {
    let mut out = vec![0u8; values.len() * T::SIZE];
    shuffle_values_into(values, &mut out);
    out
}

thread_local! {
    /// Each thread's buffer for the shuffled bytes of the chunk it encodes: allocated and
    /// zeroed once, where a buffer a chunk would cost a tenth of a block's encoding.
    static SCRATCH: RefCell<Vec<u8>> = const { RefCell::new(Vec::new()) };
}

/// `f` on this thread's scratch buffer, `len` bytes long (every byte is `f`'s to write).
pub(super) fn with_scratch<R>(len: usize, f: impl FnOnce(&mut [u8]) -> R) -> R {
    SCRATCH.with(|s| {
        let mut s = s.borrow_mut();
        if s.len() < len {
            s.resize(len, 0);
        }
        f(&mut s[..len])
    })
}

/// The transpose of an 8 × 8 byte matrix whose row k is word k (byte j at bits 8j): word j
/// of the result holds byte j of every row, row k's at bits 8k. On x86-64, whose SSE2 is
/// always there, three rounds of byte, 16-bit and 32-bit interleaves of rows taken two to
/// a register (the swaps in general-purpose registers below, the other targets' transpose,
/// take most of shuffling a block of modal coordinates on x86-64).
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn transpose_bytes(w: [u64; 8]) -> [u64; 8] {
    use std::arch::x86_64::{
        __m128i, _mm_cvtsi128_si64, _mm_set_epi64x, _mm_unpackhi_epi16, _mm_unpackhi_epi32,
        _mm_unpackhi_epi64, _mm_unpackhi_epi8, _mm_unpacklo_epi16, _mm_unpacklo_epi32,
        _mm_unpacklo_epi8,
    };
    // safe calls from Rust 1.87 on, where SSE2 is enabled (always, on x86-64)
    #[allow(unused_unsafe)]
    unsafe {
        let pair = |lo: u64, hi: u64| _mm_set_epi64x(hi as i64, lo as i64);
        // rows (0, 2) with (1, 3): bytes of rows 0 and 1 interleaved, then of 2 and 3
        let (r0, r1, r2, r3) = (
            pair(w[0], w[2]),
            pair(w[1], w[3]),
            pair(w[4], w[6]),
            pair(w[5], w[7]),
        );
        let (t0, t1) = (_mm_unpacklo_epi8(r0, r1), _mm_unpackhi_epi8(r0, r1));
        let (t2, t3) = (_mm_unpacklo_epi8(r2, r3), _mm_unpackhi_epi8(r2, r3));
        // bytes 0–3 (u0, u2) and 4–7 (u1, u3) of rows 0–3 (u0, u1) and 4–7 (u2, u3)
        let (u0, u1) = (_mm_unpacklo_epi16(t0, t1), _mm_unpackhi_epi16(t0, t1));
        let (u2, u3) = (_mm_unpacklo_epi16(t2, t3), _mm_unpackhi_epi16(t2, t3));
        let words = [
            _mm_unpacklo_epi32(u0, u2),
            _mm_unpackhi_epi32(u0, u2),
            _mm_unpacklo_epi32(u1, u3),
            _mm_unpackhi_epi32(u1, u3),
        ];
        let lo = |x: __m128i| _mm_cvtsi128_si64(x) as u64;
        let hi = |x: __m128i| _mm_cvtsi128_si64(_mm_unpackhi_epi64(x, x)) as u64;
        std::array::from_fn(|j| match j % 2 {
            0 => lo(words[j / 2]),
            _ => hi(words[j / 2]),
        })
    }
}

/// [`transpose_bytes`] in general-purpose registers, in three rounds of swaps: the
/// off-diagonal 4 × 4 blocks, then the 2 × 2 blocks within them, then single bytes.
#[cfg_attr(target_arch = "x86_64", cfg(test))]
#[inline(always)]
fn transpose_bytes_swapped(mut w: [u64; 8]) -> [u64; 8] {
    for (shift, mask, pairs) in [
        (
            32,
            0x0000_0000_FFFF_FFFF_u64,
            [(0, 4), (1, 5), (2, 6), (3, 7)],
        ),
        (16, 0x0000_FFFF_0000_FFFF, [(0, 2), (1, 3), (4, 6), (5, 7)]),
        (8, 0x00FF_00FF_00FF_00FF, [(0, 1), (2, 3), (4, 5), (6, 7)]),
    ] {
        for (a, b) in pairs {
            let t = ((w[a] >> shift) ^ w[b]) & mask;
            w[a] ^= t << shift;
            w[b] ^= t;
        }
    }
    w
}

#[cfg(not(target_arch = "x86_64"))]
use transpose_bytes_swapped as transpose_bytes;

#[cfg(test)]
mod tests {
    use super::*;
    use batstudy_physics::xorshift;

    // HDF5's shuffle transposes bytes (H5Zshuffle.c): for two 2-byte elements AB CD the
    // stored bytes are A C B D.
    #[test]
    fn shuffle_transposes_bytes() {
        assert_eq!(shuffle(&[1, 2, 3, 4], 2), vec![1, 3, 2, 4]);
        assert_eq!(shuffle(&[1, 2, 3], 1), vec![1, 2, 3]);
    }

    // Both 8 × 8 byte transposes are the transpose by definition (byte k of word j of the
    // result is byte j of word k), on words of random bytes, zeros and all ones.
    #[test]
    fn byte_transposes_transpose() {
        let mut x = 0x2545_f491_4f6c_dd1d_u64;
        let mut next = move || xorshift::next(&mut x);
        let by_definition = |w: [u64; 8]| -> [u64; 8] {
            std::array::from_fn(|j| {
                (0..8).fold(0, |acc, k| acc | ((w[k] >> (8 * j)) & 0xFF) << (8 * k))
            })
        };
        let mut cases: Vec<[u64; 8]> = (0..200).map(|_| std::array::from_fn(|_| next())).collect();
        cases.push([0; 8]);
        cases.push([u64::MAX; 8]);
        cases.push(std::array::from_fn(|k| {
            0x0706_0504_0302_0100 + 0x0808_0808_0808_0808 * k as u64
        }));
        for w in cases {
            assert_eq!(transpose_bytes(w), by_definition(w), "{w:x?}");
            assert_eq!(transpose_bytes_swapped(w), by_definition(w), "{w:x?}");
        }
    }

    // Eight values at a time, the shuffle is the byte by byte one, for every value type and
    // for lengths around the blocks of eight.
    #[test]
    fn word_shuffle_is_the_byte_shuffle() {
        for n in [0usize, 1, 7, 8, 9, 16, 1001] {
            let f: Vec<f64> = (0..n).map(|i| (i as f64 * 0.7).sin() * 1e-3).collect();
            assert_eq!(shuffle_values(&f), shuffle(&le_bytes(&f), 8), "f64 {n}");
            let g: Vec<f32> = f.iter().map(|&x| x as f32).collect();
            assert_eq!(shuffle_values(&g), shuffle(&le_bytes(&g), 4), "f32 {n}");
            let i: Vec<i32> = (0..n as i32).map(|k| k * 7919 - 3).collect();
            assert_eq!(shuffle_values(&i), shuffle(&le_bytes(&i), 4), "i32 {n}");
            let b: Vec<i8> = (0..n).map(|k| k as i8).collect();
            assert_eq!(shuffle_values(&b), shuffle(&le_bytes(&b), 1), "i8 {n}");
        }
    }
}
