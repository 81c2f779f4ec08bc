//! A zlib stream for shuffled chunks made of runs of equal bytes and of bytes that repeat
//! little: one deflate block per byte plane, with Huffman codes of its own (RFC 1951
//! §3.2.7), each run a literal then copies at distance 1, every other byte a literal.
//!
//! Why: the modal coordinates kept to the precision they need
//! (`model::collision::modal_precision`) are f64 whose low bytes are zero, value by value:
//! shuffled, a block of them is long runs of zeros between planes of near-noise and of
//! slowly varying exponents, where a mode's sign and exponent byte repeats until its
//! coordinate changes sign. libdeflate's fastest level spent 140 µs on such a 51 KB block
//! on the development machine (2.5 ns per byte, the zeros as slow as the rest), more than
//! the collision; this takes one pass to count and one to write, the runs found 64 bytes
//! at a time, and comes out the same size within a few percent (docs/performance.md).
//!
//! Any zlib reader reads the stream: HDF5's deflate filter, h5py, xarray.

use super::fixed_deflate::{
    length_symbol, put_run, put_run_block, put_symbol, run_copies, BitWriter, DYNAMIC, FIXED,
    ZLIB_HEADER,
};

/// Runs of equal bytes shorter than this stay literals. A run costs its byte, a length code
/// and its extra bits, and the distance code (about 15 bits); eight literals of a byte
/// frequent enough to repeat cost more. In the planes of signs and exponents of modal
/// coordinates, a mode's byte repeats from one sign change to the next: with runs of any
/// byte (not only zeros) such a plane takes 0.4 KB instead of 1.1 KB.
const MIN_RUN: usize = 8;
/// A stored plane (`put_stored_runs`) breaks its stored blocks only for runs this long: a
/// run between two stored blocks costs two block headers, about 7 bytes. The zeros that end
/// a plane's given bytes (`zlib_padded_planes`) are at least this many, or are given.
const STORED_MIN_RUN: usize = 32;
/// Literal/length symbols (0..=285) and the end of a block.
const SYMBOLS: usize = 286;
const END_OF_BLOCK: usize = 256;
/// The order in which a block's header gives the code-length code's lengths.
const CODE_LENGTH_ORDER: [usize; 19] = [
    16, 17, 18, 0, 8, 7, 9, 6, 10, 5, 11, 4, 12, 3, 13, 2, 14, 1, 15,
];

/// `shuffled` (planes of `plane_len` bytes, the last possibly shorter) as a zlib stream:
/// every plane in blocks that are not final, then an empty final block.
pub fn zlib_planes(shuffled: &[u8], plane_len: usize) -> Vec<u8> {
    zlib_padded_planes(shuffled, plane_len, 0)
}

/// [`zlib_planes`] of planes that each end in `zeros` zero bytes, given without them
/// (`shuffled`: planes of `plane_len` bytes): the stream the whole planes would give, byte
/// for byte. A block of modal coordinates ends in zero rows (the modes past the last one
/// that moved, `store::modal`), a third of its bytes on the bench's studies: neither
/// shuffled, nor scanned, nor summed this way.
pub fn zlib_padded_planes(shuffled: &[u8], plane_len: usize, zeros: usize) -> Vec<u8> {
    if zeros > 0 && zeros < STORED_MIN_RUN {
        // too short to be a run of every kind of plane: the planes as they are, zeros included
        let whole: Vec<u8> = shuffled
            .chunks(plane_len.max(1))
            .flat_map(|p| p.iter().copied().chain(std::iter::repeat_n(0, zeros)))
            .collect();
        return zlib_planes(&whole, plane_len + zeros);
    }
    let mut w = BitWriter::new(Vec::with_capacity(shuffled.len() / 3 + 64));
    w.extend_bytes(&ZLIB_HEADER);
    let mut adler = libdeflater::Adler32::new();
    for plane in shuffled.chunks(plane_len.max(1)) {
        put_plane(&mut w, plane, zeros);
        adler.update(plane);
        add_zeros(&mut adler, zeros);
    }
    w.block_header(true, FIXED);
    put_symbol(&mut w, END_OF_BLOCK);
    let mut out = w.finish();
    out.extend_from_slice(&adler.sum().to_be_bytes());
    out
}

/// `n` zero bytes into a running Adler-32 (RFC 1950 §8.2): each leaves the byte sum s1 as
/// it is and adds s1 to s2, so n of them add n·s1 (mod 65521) at once.
fn add_zeros(adler: &mut libdeflater::Adler32, n: usize) {
    const MOD: u64 = 65_521;
    let v = adler.sum();
    let (s1, s2) = (u64::from(v & 0xFFFF), u64::from(v >> 16));
    let s2 = (s2 + (n as u64 % MOD) * s1) % MOD;
    *adler = libdeflater::Adler32::with_initial((s2 << 16 | s1) as u32);
}

/// A run of `len` bytes `byte` from `start`: a plane's last run may reach past the bytes
/// it was given into its trailing zeros.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Run {
    start: usize,
    len: usize,
    byte: u8,
}

/// The runs of at least [`MIN_RUN`] equal bytes in `bytes` followed by `zeros` more zero
/// bytes (none, or at least [`STORED_MIN_RUN`]), 64 bytes at a time: the bytes equal to the
/// one before them as a bit mask, whose changes are found by counting bits (a branch on
/// every 8-byte word would mispredict where runs and other bytes alternate), and a
/// block without a run in it passed whole, the run it may end with carried on.
fn equal_runs(bytes: &[u8], zeros: usize) -> Vec<Run> {
    let mut runs = Vec::new();
    let close = |runs: &mut Vec<Run>, start: usize, end: usize| {
        if end - start >= MIN_RUN {
            runs.push(Run {
                start,
                len: end - start,
                byte: bytes[start],
            });
        }
    };
    // the open run's first byte
    let mut start: Option<usize> = None;
    let whole = bytes.len() / 64 * 64;
    for at in (0..whole).step_by(64) {
        let m = equal_mask(bytes, at);
        // `pos`: how far into the block the run (or the bytes between runs) is followed
        let mut pos = 0;
        if let Some(s) = start {
            let n = (!m).trailing_zeros(); // the open run's bytes in this block
            if n == 64 {
                continue;
            }
            close(&mut runs, s, at + n as usize);
            start = None;
            pos = n;
        }
        if !holds_a_run(m >> pos) {
            // no run in the block but, perhaps, one it ends with, which goes on in the next
            let top = m.leading_ones() as usize;
            start = (top > 0).then(|| at + 63 - top);
            continue;
        }
        while pos < 64 {
            let rest = m >> pos; // the bits shifted in above are bytes unlike their last
            if let Some(s) = start {
                let n = (!rest).trailing_zeros(); // bytes to the next unlike its last
                if pos + n >= 64 {
                    break;
                }
                close(&mut runs, s, at + (pos + n) as usize);
                start = None;
                pos += n;
            } else {
                let n = rest.trailing_zeros(); // to the next byte like its last (64: none)
                if pos + n >= 64 {
                    break;
                }
                pos += n;
                start = Some(at + pos as usize - 1);
            }
        }
    }
    for i in whole.max(1)..bytes.len() {
        match (start, bytes[i] == bytes[i - 1]) {
            (None, true) => start = Some(i - 1),
            (Some(s), false) => {
                close(&mut runs, s, i);
                start = None;
            }
            _ => {}
        }
    }
    if let Some(s) = start {
        close(&mut runs, s, bytes.len());
    }
    if zeros > 0 {
        add_trailing_zeros(&mut runs, bytes, zeros);
    }
    runs
}

/// The plane's `zeros` trailing zeros as the end of its last run, or as a run of their own
/// from its given bytes' last zeros: the runs the whole plane, zeros included, would have.
fn add_trailing_zeros(runs: &mut Vec<Run>, bytes: &[u8], zeros: usize) {
    let end = bytes.len();
    match runs.last_mut() {
        Some(r) if r.byte == 0 && r.start + r.len == end => r.len += zeros,
        _ => {
            let last = bytes.iter().rev().take_while(|&&b| b == 0).count();
            runs.push(Run {
                start: end - last,
                len: last + zeros,
                byte: 0,
            });
        }
    }
}

/// Whether the mask has [`MIN_RUN`] − 1 set bits in a row (a run's bytes after its first):
/// after each step, bit i is set where the bits from i on counted so far all were.
fn holds_a_run(mut m: u64) -> bool {
    const { assert!(MIN_RUN >= 2 && MIN_RUN <= 64) };
    let mut ones = 1;
    while ones < MIN_RUN - 1 {
        let step = ones.min(MIN_RUN - 1 - ones);
        m &= m >> step;
        ones += step;
    }
    m != 0
}

/// Bit i set where `bytes[at + i]` equals the byte before it (64 bytes from `at`; the
/// plane's first byte has none).
#[cfg(target_arch = "x86_64")]
fn equal_mask(bytes: &[u8], at: usize) -> u64 {
    use std::arch::x86_64::{
        __m128i, _mm_cmpeq_epi8, _mm_loadu_si128, _mm_movemask_epi8, _mm_slli_si128,
    };
    assert!(bytes.len() >= at + 64);
    // SAFETY: unaligned 16-byte loads inside the 64 bytes from `at` checked above, and from
    // one byte before each but the plane's first (whose bytes before are its own, shifted);
    // SSE2 is always there on x86-64
    let m = unsafe {
        let p = bytes.as_ptr().add(at);
        (0..4).fold(0, |m, k| {
            let here = _mm_loadu_si128(p.add(16 * k).cast::<__m128i>());
            let before = match at + k {
                0 => _mm_slli_si128::<1>(here),
                _ => _mm_loadu_si128(p.add(16 * k).sub(1).cast::<__m128i>()),
            };
            let bits = _mm_movemask_epi8(_mm_cmpeq_epi8(here, before)) as u32 as u64;
            m | bits << (16 * k)
        })
    };
    // the plane's first byte has none before it
    m & !u64::from(at == 0)
}

#[cfg(not(target_arch = "x86_64"))]
fn equal_mask(bytes: &[u8], at: usize) -> u64 {
    (at.max(1)..at + 64).fold(0, |m, i| {
        m | u64::from(bytes[i] == bytes[i - 1]) << (i - at)
    })
}

/// A plane's bytes between its runs, and the runs (the last may reach past `bytes` into the
/// plane's trailing zeros, which are not given).
struct Plane<'a> {
    bytes: &'a [u8],
    runs: Vec<Run>,
}

impl<'a> Plane<'a> {
    /// Each piece of bytes between runs, then the run after it (of length 0 after the last).
    fn pieces(&self) -> impl Iterator<Item = (&'a [u8], Run)> + '_ {
        let bytes = self.bytes;
        let end = Run {
            start: bytes.len(),
            len: 0,
            byte: 0,
        };
        let mut at = 0;
        self.runs.iter().copied().chain([end]).map(move |run| {
            // after a run into the trailing zeros, `at` is past the bytes: an empty piece
            let piece = &bytes[at.min(run.start)..run.start];
            at = run.start + run.len;
            (piece, run)
        })
    }

    /// The plane with only its runs of at least `len` bytes, and the one into its trailing
    /// zeros (which are not in its bytes).
    fn with_runs_of(self, len: usize) -> Self {
        let end = self.bytes.len();
        let runs = self
            .runs
            .into_iter()
            .filter(|r| r.len >= len || r.start + r.len > end)
            .collect();
        Plane { runs, ..self }
    }
}

/// One plane (`bytes`, then `zeros` zero bytes: none, or at least [`STORED_MIN_RUN`]): its
/// runs of equal bytes as copies, the rest as literals of a Huffman code of its own (one
/// dynamic block), or stored when that code would save little (breaking for long runs
/// only), or with the fixed codes when there is little but runs.
fn put_plane(w: &mut BitWriter, bytes: &[u8], zeros: usize) {
    let plane = Plane {
        bytes,
        runs: equal_runs(bytes, zeros),
    };
    // a plane of runs and a few bytes is coded before anything is counted (the tables alone
    // are 5 KB to clear)
    let data: usize = plane.pieces().map(|(piece, _)| piece.len()).sum();
    if data < FIXED_BELOW {
        return put_fixed(w, &plane);
    }
    let mut freq = [0u32; SYMBOLS];
    let mut tables = [[0u32; 256]; 4];
    for (piece, run) in plane.pieces() {
        count_bytes(piece, &mut tables);
        if run.len > 0 {
            let b = usize::from(run.byte);
            freq[b] += 1;
            freq[b] += run_copies(run.len, |l| freq[257 + length_symbol(l).0 as usize] += 1) as u32;
        }
    }
    for (b, f) in freq[..256].iter_mut().enumerate() {
        *f += tables.iter().map(|t| t[b]).sum::<u32>();
    }
    freq[END_OF_BLOCK] = 1;
    if collides_within(&freq[..256], data, STORED_PERCENT) {
        return put_stored_runs(w, &plane.with_runs_of(STORED_MIN_RUN));
    }
    put_dynamic(w, &plane, &code_lengths(&freq, 15));
}

/// Planes whose bytes collide at most this many percent of uniform bytes' rate are stored,
/// copied instead of coded: a code would save little ([`collides_within`]). Measured on the
/// bench's coordinate blocks (100 of them): plane 6 collides at 122 to 136 % (10th to 90th
/// percentile) and a code saves nothing; plane 5 at 186 to 348 %, where a code saved 3 % of
/// its bytes (116 B a block) for 5.5 of the 52 µs a block took (at the earlier 250 %, half
/// its blocks were coded); planes 3 and 4 (900 to 2 200 %) a code shrinks by a fifth.
const STORED_PERCENT: u128 = 400;

/// Whether bytes with these counts (`n` in all) collide at most `percent` % as often as
/// uniform bytes would: Σ c(c − 1) / (n(n − 1)) is an unbiased estimate of the collision
/// probability Σ p² (1/256 for uniform bytes). Near uniform, entropy coding saves
/// 8 − H ≈ (256 Σ p² − 1) / (2 ln 2) bits a byte. Integers keep the decision the same on
/// every machine.
pub(super) fn collides_within(counts: &[u32], n: usize, percent: u128) -> bool {
    // Σ c(c − 1) < (Σ c)²: in 64 bits when Σ c < 2³², a sum the compiler vectorises
    // (in 128 bits it would be a twelfth of encoding a scalar series)
    let total: u64 = counts.iter().map(|&c| u64::from(c)).sum();
    let pairs: u128 = match total < 1 << 32 {
        true => counts
            .iter()
            .map(|&c| u64::from(c) * u64::from(c.saturating_sub(1)))
            .sum::<u64>()
            .into(),
        false => counts
            .iter()
            .map(|&c| u128::from(c) * u128::from(c.saturating_sub(1)))
            .sum(),
    };
    let n = n as u128;
    // 256 Σ c(c − 1) ≤ (percent / 100) n(n − 1)
    pairs * 256 * 100 <= percent * n * n.saturating_sub(1)
}

/// Byte counts, in four tables so that neighbouring equal bytes do not wait on each
/// other's count.
pub(super) fn count_bytes(bytes: &[u8], tables: &mut [[u32; 256]; 4]) {
    let quads = bytes.chunks_exact(4);
    for &b in quads.remainder() {
        tables[0][b as usize] += 1;
    }
    for q in quads {
        for (t, &b) in tables.iter_mut().zip(q) {
            t[b as usize] += 1;
        }
    }
}

/// Planes with fewer bytes than this between their runs go in a block with the fixed
/// codes: a code of their own would cost more to build than it could save.
const FIXED_BELOW: usize = 256;

/// A plane in one block with the fixed codes.
fn put_fixed(w: &mut BitWriter, plane: &Plane) {
    w.block_header(false, FIXED);
    for (piece, run) in plane.pieces() {
        piece.iter().for_each(|&b| put_symbol(w, b.into()));
        if run.len > 0 {
            put_run(w, run.byte, run.len);
        }
    }
    put_symbol(w, END_OF_BLOCK);
}

/// A plane whose bytes are as good as noise: each piece in stored blocks, each run in a
/// block with the fixed codes.
fn put_stored_runs(w: &mut BitWriter, plane: &Plane) {
    for (piece, run) in plane.pieces() {
        for block in piece.chunks(u16::MAX as usize) {
            w.stored_block(block, false);
        }
        if run.len > 0 {
            put_run_block(w, run.byte, run.len);
        }
    }
}

/// A plane in one dynamic block with the literal/length code `lit`.
fn put_dynamic(w: &mut BitWriter, plane: &Plane, lit: &[u8]) {
    let codes = canonical_codes(lit);
    // one distance code (distance 1), of length 1, whether or not a copy uses it
    put_header(w, lit, &[1]);
    let table: [(u32, u32); 256] = std::array::from_fn(|b| (codes[b], u32::from(lit[b])));
    let longest = lit[..256].iter().copied().max().unwrap_or(0).into();
    for (piece, run) in plane.pieces() {
        w.put_literals(piece, &table, longest);
        if run.len > 0 {
            // the byte, then copies at distance 1, then what no copy could take
            let (code, len) = table[usize::from(run.byte)];
            w.put(code, len);
            let left = run_copies(run.len, |l| {
                let (sym, extra_bits, extra) = length_symbol(l);
                let s = 257 + sym as usize;
                w.put(codes[s], lit[s].into());
                w.put(extra, extra_bits);
                w.put(0, 1); // distance code 0: the one code, 0
            });
            (0..left).for_each(|_| w.put(code, len));
        }
    }
    w.put(codes[END_OF_BLOCK], lit[END_OF_BLOCK].into());
}

/// A dynamic block's header (never the last block: `zlib_planes` ends every stream with an
/// empty one): BFINAL 0, BTYPE 10, the code lengths run-length coded.
fn put_header(w: &mut BitWriter, lit: &[u8], dist: &[u8]) {
    let n_lit = 257 + lit[257..].iter().rposition(|&l| l > 0).map_or(0, |p| p + 1);
    let lengths: Vec<u8> = lit[..n_lit].iter().chain(dist).copied().collect();
    let rle = length_runs(&lengths);
    let mut freq = [0u32; 19];
    rle.iter().for_each(|&(s, _)| freq[s as usize] += 1);
    let cl = code_lengths(&freq, 7);
    let cl_codes = canonical_codes(&cl);
    let n_cl = 4.max(
        CODE_LENGTH_ORDER
            .iter()
            .rposition(|&s| cl[s] > 0)
            .map_or(0, |p| p + 1),
    );
    w.block_header(false, DYNAMIC);
    w.put((n_lit - 257) as u32, 5);
    w.put((dist.len() - 1) as u32, 5);
    w.put((n_cl - 4) as u32, 4);
    CODE_LENGTH_ORDER[..n_cl]
        .iter()
        .for_each(|&s| w.put(cl[s].into(), 3));
    for (s, extra) in rle {
        w.put(cl_codes[s as usize], cl[s as usize].into());
        match s {
            16 => w.put(extra.into(), 2),
            17 => w.put(extra.into(), 3),
            18 => w.put(extra.into(), 7),
            _ => {}
        }
    }
}

/// Code lengths as the code-length alphabet's symbols (RFC 1951 §3.2.7): 0–15 as they are,
/// 16 repeats the previous 3–6 times, 17 and 18 give 3–10 and 11–138 zeros; (symbol, extra).
fn length_runs(lengths: &[u8]) -> Vec<(u8, u8)> {
    let mut out = Vec::new();
    let mut i = 0;
    while i < lengths.len() {
        let l = lengths[i];
        let run = lengths[i..].iter().take_while(|&&x| x == l).count();
        let mut left = run;
        if l == 0 {
            while left >= 11 {
                let n = left.min(138);
                out.push((18, (n - 11) as u8));
                left -= n;
            }
            if left >= 3 {
                out.push((17, (left - 3) as u8));
                left = 0;
            }
        } else {
            out.push((l, 0));
            left -= 1;
            while left >= 3 {
                let n = left.min(6);
                out.push((16, (n - 3) as u8));
                left -= n;
            }
        }
        out.extend(std::iter::repeat_n((l, 0), left));
        i += run;
    }
    out
}

/// Lengths of a Huffman code for `freq` (0: the symbol is absent), none longer than
/// `limit`; at least two symbols get a code (a code of one symbol is incomplete, which
/// zlib refuses for the code-length code). Over-long codes are shortened as miniz and zlib
/// do: cut to the limit, then the Kraft sum restored by lengthening the longest codes below
/// it, the most frequent symbols keeping the shortest codes.
fn code_lengths(freq: &[u32], limit: u8) -> Vec<u8> {
    // (frequency, symbol) packed in one word: sorted as integers
    let mut packed = [0u64; SYMBOLS];
    let mut n = 0;
    for (s, &f) in freq.iter().enumerate() {
        if f > 0 {
            packed[n] = u64::from(f) << 16 | s as u64;
            n += 1;
        }
    }
    let by_buckets = n >= COUNTED_FROM;
    for (s, &f) in freq.iter().enumerate() {
        if n >= 2 {
            break;
        }
        if f == 0 {
            packed[n] = 1 << 16 | s as u64;
            n += 1;
        }
    }
    let used = &mut packed[..n];
    match by_buckets {
        true => sort_by_frequency(used),
        false => used.sort_unstable(),
    }
    let limit = usize::from(limit);
    let mut count = [0u32; 16];
    huffman_depths(used, |d| count[d.min(limit)] += 1);
    // Kraft's sum over 2^limit, brought back to 1: each pass takes one unit off
    let kraft: u64 = (1..=limit)
        .map(|l| u64::from(count[l]) << (limit - l))
        .sum();
    for _ in 0..kraft.saturating_sub(1 << limit) {
        count[limit] -= 1;
        let l = (1..limit)
            .rev()
            .find(|&l| count[l] > 0)
            .expect("a shorter code");
        count[l] -= 1;
        count[l + 1] += 2;
    }
    // lengths by count, shortest to the most frequent (`used` is ascending)
    let mut lengths = vec![0u8; freq.len()];
    let mut l = 1;
    for &p in used.iter().rev() {
        while count[l] == 0 {
            l += 1;
        }
        count[l] -= 1;
        lengths[(p & 0xFFFF) as usize] = l as u8;
    }
    lengths
}

/// Codes over at least this many symbols are sorted by counting ([`sort_by_frequency`]);
/// fewer (the code-length code's 19) are compared, which costs less than the buckets.
const COUNTED_FROM: usize = 64;

/// Frequencies below this are sorted by counting, one bucket each; the rest share the last
/// bucket and are compared.
const BUCKETS: usize = 256;

/// `packed` (frequency << 16 | symbol, the symbols ascending) sorted as integers: placed by
/// frequency into buckets in the order given (so that equal frequencies stay by symbol),
/// the frequencies of [`BUCKETS`] − 1 and over compared in the last (a comparison sort
/// would be a third of the time a plane's code takes; most of a plane's frequencies are
/// small).
fn sort_by_frequency(packed: &mut [u64]) {
    let bucket = |p: u64| (p >> 16).min(BUCKETS as u64 - 1) as usize;
    let mut start = [0u16; BUCKETS];
    packed.iter().for_each(|&p| start[bucket(p)] += 1);
    let mut at = 0;
    for s in start.iter_mut() {
        let count = *s;
        *s = at;
        at += count;
    }
    let mut sorted = [0u64; SYMBOLS];
    for &p in packed.iter() {
        let b = bucket(p);
        sorted[usize::from(start[b])] = p;
        start[b] += 1;
    }
    let (sorted, last) = (&mut sorted[..packed.len()], usize::from(start[BUCKETS - 2]));
    sorted[last..].sort_unstable();
    packed.copy_from_slice(sorted);
}

/// The depth of each leaf of a Huffman tree over `used` (packed frequency and symbol,
/// ascending), handed to `each`.
fn huffman_depths(used: &[u64], mut each: impl FnMut(usize)) {
    // Two queues: the leaves (sorted) and the merged nodes (made in ascending order); the
    // nodes' weights and parents only. On the stack, and the lighter of the two heads taken
    // without a branch (a leaf on a tie): an exhausted queue's head weighs more than any
    // node, so that which queue gives the next node is a select, where a branch would
    // mispredict half the time (1.2 of the 2.3 µs a code takes with the branch). Both
    // children of a node are chosen from the two heads of each queue, read at once: the
    // second choice does not wait on reading what the first left (one after the other, the
    // merges are a chain of dependent reads, half of a plane's code).
    let n = used.len();
    let mut leaves = [u64::MAX; SYMBOLS + 2];
    leaves[..n]
        .iter_mut()
        .zip(used)
        .for_each(|(l, &u)| *l = u >> 16);
    let mut weight = [u64::MAX; SYMBOLS + 1];
    let mut parent = [0u16; 2 * SYMBOLS];
    let (mut leaf, mut node) = (0, 0);
    for made in 0..n - 1 {
        let (l0, l1) = (leaves[leaf], leaves[leaf + 1]);
        let (n0, n1) = (weight[node], weight[node + 1]);
        // the first child: a leaf on a tie; the second, from what the first left
        let first_leaf = l0 <= n0;
        let (wa, a) = match first_leaf {
            true => (l0, leaf),
            false => (n0, n + node),
        };
        let (lw, nw) = match first_leaf {
            true => (l1, n0),
            false => (l0, n1),
        };
        let (leaf1, node1) = (
            leaf + usize::from(first_leaf),
            node + usize::from(!first_leaf),
        );
        let second_leaf = lw <= nw;
        let (wb, b) = match second_leaf {
            true => (lw, leaf1),
            false => (nw, n + node1),
        };
        leaf = leaf1 + usize::from(second_leaf);
        node = node1 + usize::from(!second_leaf);
        weight[made] = wa + wb;
        parent[a] = (n + made) as u16;
        parent[b] = (n + made) as u16;
    }
    let mut depth = [0u16; 2 * SYMBOLS];
    for i in (0..2 * n - 2).rev() {
        depth[i] = depth[usize::from(parent[i])] + 1;
    }
    depth[..n].iter().for_each(|&d| each(usize::from(d)));
}

/// The canonical codes of `lengths` (RFC 1951 §3.2.2), bit-reversed for the LSB-first stream.
fn canonical_codes(lengths: &[u8]) -> Vec<u32> {
    let mut count = [0u32; 16];
    lengths
        .iter()
        .filter(|&&l| l > 0)
        .for_each(|&l| count[l as usize] += 1);
    let mut next = [0u32; 16];
    let mut code = 0;
    for l in 1..16 {
        code = (code + count[l - 1]) << 1;
        next[l] = code;
    }
    lengths
        .iter()
        .map(|&l| match l {
            0 => 0,
            l => {
                let c = next[l as usize];
                next[l as usize] += 1;
                c.reverse_bits() >> (32 - u32::from(l))
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use libdeflater::Decompressor;

    fn inflate(z: &[u8], n: usize) -> Vec<u8> {
        let mut out = vec![0u8; n];
        let got = Decompressor::new()
            .zlib_decompress(z, &mut out)
            .expect("a zlib stream");
        assert_eq!(got, n);
        out
    }

    // Planes of every kind inflate to themselves (libdeflate's decoder): zeros, runs at
    // every edge, noise, one repeated byte, a plane of one byte, runs of 258 ± 1 and 2.
    #[test]
    fn planes_inflate_to_themselves() {
        let mut x = 0x2545_f491_4f6c_dd1d_u64;
        let mut noise = |n: usize| -> Vec<u8> {
            (0..n)
                .map(|_| {
                    x ^= x << 13;
                    x ^= x >> 7;
                    x ^= x << 17;
                    (x >> 24) as u8
                })
                .collect()
        };
        let mut cases: Vec<(Vec<u8>, usize)> = vec![
            (vec![0; 6400], 800),
            (vec![7; 999], 1000),
            (vec![], 10),
            (vec![3], 1),
            (noise(4096), 512),
        ];
        for run in [7, 8, 9, 31, 32, 33, 258, 259, 260, 261, 262, 517, 2200] {
            for byte in [0, 0xA5] {
                let mut v = noise(100);
                v.extend(std::iter::repeat_n(byte, run));
                v.extend(noise(77));
                v.extend(std::iter::repeat_n(byte, run));
                cases.push((v.clone(), v.len()));
                cases.push((v.clone(), 64));
            }
        }
        // noise with runs of other bytes inside, short and long: a stored plane keeps the
        // long ones only
        let mut mixed = noise(3000);
        for (at, byte, len) in [(100, 9, 8), (700, 0xFF, 40), (1500, 3, 300), (2990, 1, 10)] {
            mixed[at..at + len].fill(byte);
        }
        cases.push((mixed.clone(), mixed.len()));
        // noise with zero runs inside: stored pieces between blocks of copies
        let mut stored = noise(5000);
        stored.extend(std::iter::repeat_n(0, 300));
        stored.extend(noise(5000));
        stored.extend(std::iter::repeat_n(0, 40));
        cases.push((stored.clone(), stored.len()));
        cases.push((noise(70_000), 70_000));
        let mut partial = noise(3000);
        partial.iter_mut().step_by(3).for_each(|b| *b &= 0xF0);
        cases.push((partial, 1000));
        for (bytes, plane) in cases {
            let z = zlib_planes(&bytes, plane);
            assert_eq!(inflate(&z, bytes.len()), bytes, "{} bytes", bytes.len());
        }
    }

    // Runs: found at any offset, of any byte, at least MIN_RUN long, exactly delimited.
    #[test]
    fn runs_are_exact() {
        for (byte, lead, run, tail) in [
            (0, 0, 40, 3),
            (0, 5, 32, 0),
            (7, 13, 100, 9),
            (0, 3, MIN_RUN - 1, 3),
            (200, 8, 64, 1),
            (1, 70, MIN_RUN, 2),
        ] {
            let mut v: Vec<u8> = (0..lead).map(|i| (i % 2 + 3) as u8).collect();
            v.extend(std::iter::repeat_n(byte, run));
            v.extend(std::iter::repeat_n(9, tail.min(1)));
            v.extend((1..tail).map(|i| (i % 2 + 10) as u8));
            let want = match run >= MIN_RUN {
                true => vec![Run {
                    start: lead,
                    len: run,
                    byte,
                }],
                false => vec![],
            };
            assert_eq!(equal_runs(&v, 0), want, "{byte} {lead} {run} {tail}");
        }
    }

    // Runs as a byte-by-byte scan of the whole plane (its trailing zeros included) finds
    // them, on planes of every kind: sparse and dense runs of zeros and of other bytes,
    // runs across the 64-byte blocks and from the plane's first byte, trailing zeros.
    #[test]
    fn runs_are_those_of_a_byte_scan() {
        fn by_bytes(bytes: &[u8], zeros: usize) -> Vec<Run> {
            let mut v = bytes.to_vec();
            v.extend(std::iter::repeat_n(0, zeros));
            let mut runs = Vec::new();
            let mut i = 0;
            while i < v.len() {
                let n = v[i..].iter().take_while(|&&b| b == v[i]).count();
                if n >= MIN_RUN {
                    runs.push(Run {
                        start: i,
                        len: n,
                        byte: v[i],
                    });
                }
                i += n;
            }
            runs
        }
        let mut state = 37;
        let mut rng = || batstudy_physics::xorshift::next(&mut state);
        for case in 0..800 {
            let len = (rng() % 700) as usize;
            // runs of random bytes and lengths between random bytes from an alphabet of
            // `alphabet`: small ones make short runs of their own
            let alphabet = [2, 5, 50, 256][case % 4];
            let mut v = Vec::with_capacity(len);
            while v.len() < len {
                let b = (rng() % alphabet) as u8;
                match rng() % 8 {
                    0 => v.extend(std::iter::repeat_n(b, (rng() % 90) as usize)),
                    _ => v.push(b),
                }
            }
            v.truncate(len);
            let zeros = [0, 0, 40, 200][(case / 4) % 4];
            assert_eq!(equal_runs(&v, zeros), by_bytes(&v, zeros), "case {case}");
        }
    }

    // The bucket sort gives what a comparison sort gives: frequencies small and large,
    // ties, one symbol, every symbol.
    #[test]
    fn frequencies_sort_as_integers() {
        let mut state = 7;
        let mut rng = || batstudy_physics::xorshift::next(&mut state);
        for case in 0..400 {
            let n = 1 + case % SYMBOLS;
            let top = [3u64, 300, 70_000][case % 3];
            let mut packed = Vec::new();
            for s in 0..SYMBOLS as u64 {
                if packed.len() < n && (rng() % 3 > 0 || n == SYMBOLS) {
                    packed.push((1 + rng() % top) << 16 | s);
                }
            }
            let mut want = packed.clone();
            want.sort_unstable();
            sort_by_frequency(&mut packed);
            assert_eq!(packed, want, "case {case}");
        }
    }

    // Where the limit does not bind, the codes are optimal: their cost Σ f·l is that of Huffman's construction
    // by repeatedly merging the two lightest weights (a binary heap, Huffman 1952), whose
    // cost is the sum of the merged weights; for frequencies few, many, tied and skewed.
    #[test]
    fn codes_cost_what_huffmans_construction_costs() {
        use std::cmp::Reverse;
        use std::collections::BinaryHeap;
        let mut state = 11;
        let mut rng = || batstudy_physics::xorshift::next(&mut state);
        for case in 0..300 {
            let n = 2 + case % (SYMBOLS - 1);
            // within a factor of three of each other, or absent: no code is longer than the limit
            let top = [2u64, 40, 5_000][case % 3];
            let freq: Vec<u32> = (0..n)
                .map(|_| match rng() % 5 {
                    0 => 0,
                    _ => (top / 2 + rng() % top) as u32,
                })
                .collect();
            if freq.iter().filter(|&&f| f > 0).count() < 2 {
                continue;
            }
            let lengths = code_lengths(&freq, 15);
            let cost: u64 = freq
                .iter()
                .zip(&lengths)
                .map(|(&f, &l)| u64::from(f) * u64::from(l))
                .sum();
            let mut heap: BinaryHeap<Reverse<u64>> = freq
                .iter()
                .filter(|&&f| f > 0)
                .map(|&f| Reverse(u64::from(f)))
                .collect();
            let mut want = 0;
            while heap.len() > 1 {
                let (Reverse(a), Reverse(b)) = (heap.pop().unwrap(), heap.pop().unwrap());
                want += a + b;
                heap.push(Reverse(a + b));
            }
            assert_eq!(cost, want, "case {case}: {n} symbols");
        }
    }

    // The code lengths satisfy Kraft's equality within the limit, on skewed frequencies
    // (a Fibonacci sequence would need codes of 25 bits).
    #[test]
    fn lengths_are_limited_and_complete() {
        let mut fib = vec![1u32, 1];
        while fib.len() < 30 {
            fib.push(fib[fib.len() - 1] + fib[fib.len() - 2]);
        }
        for limit in [7u8, 15] {
            let l = code_lengths(&fib, limit);
            assert!(l.iter().all(|&x| (1..=limit).contains(&x)));
            let kraft: f64 = l.iter().map(|&x| 0.5f64.powi(x.into())).sum();
            assert_eq!(kraft, 1.0, "limit {limit}");
        }
        assert_eq!(
            code_lengths(&[0, 5, 0], 7),
            vec![1, 1, 0],
            "one symbol gets a partner"
        );
    }
}
