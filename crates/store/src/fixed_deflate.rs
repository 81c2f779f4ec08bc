//! A zlib stream for a small chunk, in one deflate block with the fixed Huffman codes.
//!
//! Why: a history's scalar series (force, compression, …) is one chunk of a few hundred
//! values per point. libdeflate spends about 6.5 µs on such a chunk whatever its size (it
//! clears its hash table and builds dynamic Huffman codes for every call), which is a fifth
//! of the CPU time of a study that records the scalar histories. For inputs this
//! small the fixed codes (RFC 1951 §3.2.6) cost little against dynamic ones, whose table
//! would take a good part of the block, and they need no table at all: one pass finds the
//! runs of equal bytes (the zeros after separation, a constant speed, the slowly changing
//! high bytes of a moving bat), and the symbols go straight out. A hash search for repeats
//! at any distance finds nothing more in these chunks (scalar histories and summaries the
//! same size within 0.2 %) for 4 % of a scalar-history study's CPU. Tests
//! inflate its output with two decoders of their own (libdeflate's, and zlib's inside
//! HDF5's filter in `store::chunks`).
//!
//! Any zlib reader reads the stream: HDF5's deflate filter, h5py, xarray.

/// Largest input taken: what one stored block holds, the fallback when the codes would not
/// shrink it (and chunks this size are not "small": `store::chunks` deflates those with
/// libdeflate).
pub const MAX_INPUT: usize = u16::MAX as usize;

const MIN_MATCH: usize = 3;
const MAX_MATCH: usize = 258;

/// A zlib stream's header (RFC 1950): CMF 0x78 (deflate, 32 KiB window), FLG 0x01 (level
/// "fastest", the one libdeflate writes at levels 0 and 1; 0x7801 is a multiple of 31).
pub const ZLIB_HEADER: [u8; 2] = [0x78, 0x01];

/// RFC 1951 §3.2.4: a stored block of at most 65 535 bytes after `out`, which ends on a byte
/// boundary ([`BitWriter::stored_block`]).
pub fn push_stored_block(out: &mut Vec<u8>, block: &[u8], last: bool) {
    let mut w = BitWriter::new(std::mem::take(out));
    w.stored_block(block, last);
    *out = w.finish();
}

/// A run of `len` (≥ 1) zero bytes as a non-final block with the fixed codes (a literal,
/// then copies at distance 1), then an empty non-final stored block, which brings the
/// stream back to a byte boundary: about 2 bytes per 2 KB of zeros, and 5 more. `out` must
/// end on a byte boundary (after a stored block or the zlib header). The zero rows that pad
/// a block of modal coordinates end each of its byte planes.
pub fn push_zero_run(out: &mut Vec<u8>, len: usize) {
    let mut w = BitWriter::new(std::mem::take(out));
    put_run_block(&mut w, 0, len);
    w.stored_block(&[], false);
    *out = w.finish();
}

/// The block types of RFC 1951 §3.2.3 (BTYPE): stored, the fixed codes, codes of its own.
pub(super) const STORED: u32 = 0;
pub(super) const FIXED: u32 = 1;
pub(super) const DYNAMIC: u32 = 2;

/// A non-final block with the fixed codes that holds a run of `len` (≥ 1) bytes `byte`.
pub(super) fn put_run_block(w: &mut BitWriter, byte: u8, len: usize) {
    w.block_header(false, FIXED);
    put_run(w, byte, len);
    put_symbol(w, 256); // end of block
}

/// A run of `len` (≥ 1) bytes `byte` with the fixed codes: the byte, then copies at
/// distance 1, then what no copy could take.
pub(super) fn put_run(w: &mut BitWriter, byte: u8, len: usize) {
    put_symbol(w, byte.into());
    let left = run_copies(len, |l| put_copy(w, l));
    (0..left).for_each(|_| put_symbol(w, byte.into()));
}

/// The copies that write a run of `len` (≥ 1) equal bytes after its first one (a literal):
/// lengths of at most 258, none leaving 1 or 2 bytes, which no copy can take; returns what
/// is left for literals (0 to 2 bytes).
pub(super) fn run_copies(len: usize, mut each: impl FnMut(usize)) -> usize {
    let mut left = len.saturating_sub(1);
    while left >= MIN_MATCH {
        let l = match left > MAX_MATCH && left - MAX_MATCH < MIN_MATCH {
            true => left - MIN_MATCH,
            false => left.min(MAX_MATCH),
        };
        each(l);
        left -= l;
    }
    left
}

/// RFC 1951 §3.2.5: base length of length codes 257..=285 and their extra bits.
const LENGTH_BASE: [u16; 29] = [
    3, 4, 5, 6, 7, 8, 9, 10, 11, 13, 15, 17, 19, 23, 27, 31, 35, 43, 51, 59, 67, 83, 99, 115, 131,
    163, 195, 227, 258,
];
const LENGTH_EXTRA: [u8; 29] = [
    0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0,
];
/// The length code of a copy of `length` (3..=258) bytes: (its index 0..=28 among the
/// codes 257..=285, the number of extra bits, their value). A table: a plane's runs look
/// each copy up twice, to count it and to write it.
pub(super) fn length_symbol(length: usize) -> (u32, u32, u32) {
    let (l, bits, extra) = LENGTH_SYMBOLS[length];
    (u32::from(l), u32::from(bits), u32::from(extra))
}

/// [`length_symbol`] of every length (0 to 2: none): the last base at most the length, its
/// extra bits and the rest.
const LENGTH_SYMBOLS: [(u8, u8, u8); MAX_MATCH + 1] = {
    let mut t = [(0u8, 0u8, 0u8); MAX_MATCH + 1];
    let mut length = MIN_MATCH;
    while length <= MAX_MATCH {
        let mut l = 0;
        while l + 1 < LENGTH_BASE.len() && LENGTH_BASE[l + 1] as usize <= length {
            l += 1;
        }
        t[length] = (
            l as u8,
            LENGTH_EXTRA[l],
            (length - LENGTH_BASE[l] as usize) as u8,
        );
        length += 1;
    }
    t
};

/// Deflate's bit order: fields least-significant bit first, into bytes from their low bit.
pub(super) struct BitWriter {
    out: Vec<u8>,
    acc: u64,
    bits: u32,
}

impl BitWriter {
    /// A writer appending to `out`, on a byte boundary.
    pub(super) fn new(out: Vec<u8>) -> Self {
        BitWriter {
            out,
            acc: 0,
            bits: 0,
        }
    }

    /// A block's header: BFINAL, then its type (BTYPE: [`STORED`], [`FIXED`], [`DYNAMIC`]).
    pub(super) fn block_header(&mut self, last: bool, kind: u32) {
        self.put(u32::from(last), 1);
        self.put(kind, 2);
    }

    /// A stored block (RFC 1951 §3.2.4) of at most 65 535 bytes: its header, padding to the
    /// byte boundary, LEN and its one's complement (little-endian), then the bytes.
    pub(super) fn stored_block(&mut self, block: &[u8], last: bool) {
        let len = u16::try_from(block.len()).expect("a stored block holds at most 65 535 bytes");
        self.block_header(last, STORED);
        self.align();
        self.extend_bytes(&len.to_le_bytes());
        self.extend_bytes(&(!len).to_le_bytes());
        self.extend_bytes(block);
    }

    /// Whole bytes, on a byte boundary (nothing pending).
    pub(super) fn extend_bytes(&mut self, bytes: &[u8]) {
        debug_assert_eq!(self.bits, 0);
        self.out.extend_from_slice(bytes);
    }

    /// `count` ≤ 32 bits of `value` (higher bits zero).
    #[inline]
    pub(super) fn put(&mut self, value: u32, count: u32) {
        self.acc |= u64::from(value) << self.bits;
        self.bits += count;
        if self.bits >= 32 {
            self.out.extend_from_slice(&(self.acc as u32).to_le_bytes());
            self.acc >>= 32;
            self.bits -= 32;
        }
    }

    /// Up to a byte boundary with zero bits (a stored block's padding).
    pub(super) fn align(&mut self) {
        while self.bits > 0 {
            self.out.push(self.acc as u8);
            self.acc >>= 8;
            self.bits = self.bits.saturating_sub(8);
        }
        self.acc = 0;
    }

    /// `bytes` as literals of a code whose (reversed code, length ≤ `longest` ≤ 15) for
    /// byte b is `table[b]`: as many at a time as fit in a word with the 7 bits a byte
    /// boundary can leave pending, each group followed by one 8-byte store of the pending
    /// bits into room made beforehand, advanced by the whole bytes. Appending 4 bytes every
    /// 32 bits takes twice as long; three literals a store whatever the code left
    /// the short codes of a plane of exponents (7 bits) a store for every three.
    pub(super) fn put_literals(&mut self, bytes: &[u8], table: &[(u32, u32); 256], longest: u32) {
        match longest {
            0..=8 => self.put_literals_by::<7>(bytes, table),
            9 => self.put_literals_by::<6>(bytes, table),
            10..=11 => self.put_literals_by::<5>(bytes, table),
            12..=14 => self.put_literals_by::<4>(bytes, table),
            _ => self.put_literals_by::<3>(bytes, table),
        }
    }

    /// [`Self::put_literals`] `K` at a time (K codes and 7 bits fit in 64).
    fn put_literals_by<const K: usize>(&mut self, bytes: &[u8], table: &[(u32, u32); 256]) {
        while self.bits >= 8 {
            self.out.push(self.acc as u8);
            self.acc >>= 8;
            self.bits -= 8;
        }
        let (mut acc, mut bits) = (self.acc, self.bits);
        let mut at = self.out.len();
        // at most 15 bits a literal, and 8 bytes stored past the last whole one
        self.out.resize(at + 2 * bytes.len() + 8, 0);
        let out = &mut self.out[..];
        let groups = bytes.chunks_exact(K);
        let rest = groups.remainder();
        for g in groups {
            for &b in g {
                let (c, l) = table[usize::from(b)];
                acc |= u64::from(c) << bits;
                bits += l;
            }
            out[at..at + 8].copy_from_slice(&acc.to_le_bytes());
            let whole = bits & !7;
            at += (whole / 8) as usize;
            acc >>= whole;
            bits -= whole;
        }
        self.out.truncate(at);
        (self.acc, self.bits) = (acc, bits);
        for &b in rest {
            let (c, l) = table[usize::from(b)];
            self.put(c, l);
        }
    }

    /// The bytes, the last one padded with zero bits.
    pub(super) fn finish(mut self) -> Vec<u8> {
        self.align();
        self.out
    }
}

/// The fixed literal/length code of `symbol` (0..=287): (code, length).
const fn literal_code(symbol: u16) -> (u32, u32) {
    let s = symbol as u32;
    match symbol {
        0..=143 => (0x30 + s, 8),
        144..=255 => (0x190 + s - 144, 9),
        256..=279 => (s - 256, 7),
        _ => (0xC0 + s - 280, 8),
    }
}

/// A Huffman code as it goes out: sent from its most significant bit (RFC 1951 §3.1.1),
/// that is reversed into the LSB-first stream.
const fn reversed(code: u32, length: u32) -> u32 {
    code.reverse_bits() >> (32 - length)
}

/// Every literal/length symbol's reversed fixed code and its length.
const LITERALS: [(u16, u8); 288] = {
    let mut t = [(0u16, 0u8); 288];
    let mut s = 0;
    while s < 288 {
        let (code, length) = literal_code(s as u16);
        t[s] = (reversed(code, length) as u16, length as u8);
        s += 1;
    }
    t
};

/// The longest fixed code of a byte (144–255: 9 bits, RFC 1951 §3.2.6).
const FIXED_LONGEST: u32 = 9;

/// The fixed code of every byte as a literal, as [`BitWriter::put_literals`] takes it.
const FIXED_BYTES: [(u32, u32); 256] = {
    let mut t = [(0u32, 0u32); 256];
    let mut b = 0;
    while b < 256 {
        t[b] = (LITERALS[b].0 as u32, LITERALS[b].1 as u32);
        b += 1;
    }
    t
};

#[inline]
pub(super) fn put_symbol(w: &mut BitWriter, symbol: usize) {
    let (code, length) = LITERALS[symbol];
    w.put(u32::from(code), u32::from(length));
}

/// A copy of `length` (3..=258) bytes at distance 1 with the fixed codes: its length code
/// and extra bits, then distance code 0 (5 bits, no extra), in one field.
#[inline]
pub(super) fn put_copy(w: &mut BitWriter, length: usize) {
    let (bits, count) = COPIES[length];
    w.put(bits, count);
}

/// [`put_copy`]'s field for every length (0 to 2: none): one look-up, where two binary
/// searches and a write in four pieces would be a tenth of encoding a scalar series.
const COPIES: [(u32, u32); MAX_MATCH + 1] = {
    let mut t = [(0u32, 0u32); MAX_MATCH + 1];
    let mut length = MIN_MATCH;
    while length <= MAX_MATCH {
        let mut l = 0;
        while l + 1 < LENGTH_BASE.len() && LENGTH_BASE[l + 1] as usize <= length {
            l += 1;
        }
        let (code, code_len) = LITERALS[257 + l];
        let extra_bits = LENGTH_EXTRA[l] as u32;
        let extra = (length - LENGTH_BASE[l] as usize) as u32;
        // distance 1: code 0 in 5 bits (reversed, still 0), no extra bits
        t[length] = (
            code as u32 | extra << code_len,
            code_len as u32 + extra_bits + 5,
        );
        length += 1;
    }
    t
};

/// `bytes` as a zlib stream (RFC 1950): header, one final deflate block with the fixed
/// codes, its runs as copies (or a stored block when that is shorter), Adler-32; `None`
/// above `MAX_INPUT` bytes.
pub fn zlib_small(bytes: &[u8]) -> Option<Vec<u8>> {
    let n = bytes.len();
    if n > MAX_INPUT {
        return None;
    }
    let mut out = Vec::with_capacity(n + n / 8 + 16);
    out.extend_from_slice(&ZLIB_HEADER);
    let mut out = put_fixed_runs(out, bytes);
    if out.len() - ZLIB_HEADER.len() > n + 5 {
        out.truncate(ZLIB_HEADER.len());
        push_stored_block(&mut out, bytes, true);
    }
    out.extend_from_slice(&libdeflater::adler32(bytes).to_be_bytes());
    Some(out)
}

/// `bytes` as one final block with the fixed codes after `out` (on a byte boundary): each
/// run of at least 4 equal bytes a literal then copies at distance 1, the rest literals. No
/// hash search: the repeats of a scalar series' high bytes are runs (a constant speed, a
/// zero force after the contact, a slowly moving bat).
pub fn put_fixed_runs(out: Vec<u8>, bytes: &[u8]) -> Vec<u8> {
    let mut w = BitWriter::new(out);
    w.block_header(true, FIXED);
    // the bytes between runs go out together (`put_literals`); a run is looked for only
    // where four bytes are equal, one comparison of a word (counting the run at every byte
    // would be an eighth of encoding a scalar series). The runs are those found
    // counting from every run's start: a run of four or more starts where its first four
    // bytes are equal, and none starts inside a shorter one.
    let (n, mut i, mut literals) = (bytes.len(), 0, 0);
    while i + 4 <= n {
        let b = bytes[i];
        let four = u32::from_le_bytes(bytes[i..i + 4].try_into().expect("4 bytes"));
        if four != u32::from(b) * 0x0101_0101 {
            i += 1;
            continue;
        }
        let run = 4 + bytes[i + 4..].iter().take_while(|&&x| x == b).count();
        w.put_literals(&bytes[literals..i], &FIXED_BYTES, FIXED_LONGEST);
        put_run(&mut w, b, run);
        literals = i + run;
        i += run;
    }
    w.put_literals(&bytes[literals..], &FIXED_BYTES, FIXED_LONGEST);
    put_symbol(&mut w, 256); // end of block
    w.finish()
}

#[cfg(test)]
mod tests {
    use super::*;
    use batstudy_physics::xorshift;

    /// libdeflate's decoder, which shares no code with this encoder (zlib's, inside HDF5's
    /// filter, reads these streams in `store::chunks`' tests).
    fn inflate(stream: &[u8], n: usize) -> Vec<u8> {
        let mut back = vec![0u8; n];
        let got = libdeflater::Decompressor::new()
            .zlib_decompress(stream, &mut back)
            .expect("a valid zlib stream");
        assert_eq!(got, n);
        back
    }

    fn roundtrip(bytes: &[u8]) -> usize {
        let stream = zlib_small(bytes).expect("encodes");
        assert_eq!(inflate(&stream, bytes.len()), bytes);
        stream.len()
    }

    // RFC 1951 §3.2.6: the fixed literal/length code lengths are 8 (0–143), 9 (144–255),
    // 7 (256–279), 8 (280–287), and the codes are consecutive within each range.
    #[test]
    fn fixed_codes_are_the_rfcs() {
        assert_eq!(literal_code(0), (0b0011_0000, 8));
        assert_eq!(literal_code(143), (0b1011_1111, 8));
        assert_eq!(literal_code(144), (0b1_1001_0000, 9));
        assert_eq!(literal_code(255), (0b1_1111_1111, 9));
        assert_eq!(literal_code(256), (0, 7));
        assert_eq!(literal_code(279), (0b001_0111, 7));
        assert_eq!(literal_code(280), (0b1100_0000, 8));
        assert_eq!(literal_code(287), (0b1100_0111, 8));
    }

    // RFC 1951 §3.2.5: every copy length is its code's base plus extra bits that fit, and
    // the code is the last whose base does not pass the length
    #[test]
    fn length_symbols_are_the_rfcs() {
        for length in MIN_MATCH..=MAX_MATCH {
            let (l, bits, extra) = length_symbol(length);
            let base = usize::from(LENGTH_BASE[l as usize]);
            assert_eq!(base + extra as usize, length);
            assert!(extra < 1 << bits || (bits == 0 && extra == 0), "{length}");
            assert!(LENGTH_BASE
                .get(l as usize + 1)
                .is_none_or(|&b| usize::from(b) > length));
        }
        assert_eq!(length_symbol(258), (28, 0, 0)); // code 285, no extra bits
        assert_eq!(length_symbol(257), (27, 5, 30)); // code 284: 227 + 30
    }

    // Runs of every length around the copies' limits (3..=258 and beyond) inflate back and
    // shrink; repeats at other distances, which go out as literals, inflate back too.
    #[test]
    fn every_run_length_and_other_repeats_inflate_back() {
        for length in (MIN_MATCH..=MAX_MATCH).chain([259, 260, 261, 516, 517, 518, 2000]) {
            let mut v: Vec<u8> = (0..40u8).collect();
            v.extend(std::iter::repeat_n(7u8, length + 1));
            // literals below 144 take 8 bits, as many as they had: only the run shrinks
            let n = roundtrip(&v);
            assert!(n <= v.len() + 5 + 6, "run of {length}: {n} bytes");
            // the 40 literals, the run's first byte and end of block, at most 2 bytes a copy
            // of up to 258, the zlib wrapper
            let most = 40 + 2 + 2 * length.div_ceil(MAX_MATCH) + 2 + 6;
            assert!(
                length < 16 || n <= most,
                "run of {length}: {n} bytes, {most} at most"
            );
        }
        let mut x = 1u64;
        for distance in [2usize, 4, 13, 257, 4097, 32768] {
            let mut v: Vec<u8> = (0..distance + 300)
                .map(|_| (xorshift::next(&mut x) % 128) as u8)
                .collect();
            for _ in 0..200 {
                v.push(v[v.len() - distance]);
            }
            roundtrip(&v);
        }
    }

    // Random inputs of many sizes and alphabets (from pure noise, which goes out stored, to
    // two symbols) inflate back.
    #[test]
    fn random_inputs_inflate_back() {
        let mut x = 0x1234_5678u64;
        for size in [
            0usize, 1, 2, 3, 4, 5, 17, 200, 800, 1000, 4096, 8000, 65_535,
        ] {
            for alphabet in [256u64, 16, 2] {
                let v: Vec<u8> = (0..size)
                    .map(|_| (xorshift::next(&mut x) % alphabet) as u8)
                    .collect();
                let n = roundtrip(&v);
                // stored when the fixed codes would not shrink it: never more than 5 bytes
                // over the input plus the zlib wrapper (RFC 1951 §3.2.4)
                assert!(n <= size + 5 + 6, "{size} {alphabet}: {n}");
            }
        }
        assert_eq!(zlib_small(&vec![0u8; MAX_INPUT + 1]), None);
    }

    // Inputs built from random pieces (runs, copies from random distances, noise, a small
    // alphabet), the shapes a chunk's shuffled planes take, inflate back: 3 000 of them.
    #[test]
    fn random_structured_inputs_inflate_back() {
        let mut x = 0xDEAD_BEEFu64;
        let mut next = |m: u64| xorshift::next(&mut x) % m;
        for _ in 0..3_000 {
            let target = next(9_000) as usize;
            let mut v: Vec<u8> = Vec::with_capacity(target + 300);
            while v.len() < target {
                let len = 1 + next(300) as usize;
                match next(4) {
                    0 => {
                        let b = next(256) as u8;
                        v.extend(std::iter::repeat_n(b, len));
                    }
                    1 if !v.is_empty() => {
                        let distance = 1 + next(v.len() as u64) as usize;
                        for _ in 0..len {
                            v.push(v[v.len() - distance]);
                        }
                    }
                    2 => v.extend((0..len).map(|_| next(256) as u8)),
                    _ => v.extend((0..len).map(|_| next(3) as u8)),
                }
            }
            roundtrip(&v);
        }
    }

    // A zero run between stored blocks, in a stream libdeflate reads back: every length
    // around the copies' limits, after a header and between noise.
    #[test]
    fn zero_runs_between_stored_blocks_inflate_back() {
        let mut x = 7u64;
        for len in [
            1usize, 2, 3, 4, 257, 258, 259, 260, 261, 516, 517, 518, 5000,
        ] {
            let noise: Vec<u8> = (0..100).map(|_| xorshift::next(&mut x) as u8).collect();
            let mut stream = ZLIB_HEADER.to_vec();
            push_zero_run(&mut stream, len);
            push_stored_block(&mut stream, &noise, false);
            push_zero_run(&mut stream, len);
            push_stored_block(&mut stream, &noise, true);
            let mut whole = vec![0u8; len];
            whole.extend_from_slice(&noise);
            whole.extend(std::iter::repeat_n(0u8, len));
            whole.extend_from_slice(&noise);
            stream.extend_from_slice(&libdeflater::adler32(&whole).to_be_bytes());
            assert_eq!(inflate(&stream, whole.len()), whole, "{len}");
            assert!(
                stream.len() < 2 * 100 + 2 * 12 + 16 + 2 * len / 100,
                "{len}"
            );
        }
    }

    // Runs (the zeros of a force after separation) shrink: 800 zero bytes take 1 literal and
    // ⌈799/258⌉ = 4 matches of 7+5 bits (+ extra bits), about 8 bytes in all.
    #[test]
    fn runs_shrink() {
        let n = roundtrip(&[0u8; 800]);
        assert!(n <= 2 + 10 + 4, "{n}");
    }
}
