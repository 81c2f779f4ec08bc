//! The append-only journal `OUT.h5.journal`: the source of truth while a study runs.
//!
//! Format 3 (little endian):
//! - header: magic `BATSJRN3`, u32 `n` = length of the header JSON, the JSON ([`JournalHeader`]),
//!   u32 CRC-32 of the JSON;
//! - then records, each: u32 magic `REC2`, u32 payload length, u32 CRC-32 of the payload, the
//!   payload: the point's summary ([`encode_summary`]) followed, when it has histories, by
//!   each stored history variable's chunk exactly as the results file stores it: either its
//!   bytes (u32 length, then the shuffled and deflated bytes; `store::encode` makes them on
//!   the workers), or, when the run has already written the chunk into `OUT.h5.partial`,
//!   where it is there (u32 length with [`IN_FILE`] set, u64 offset in that file, u32 CRC-32
//!   of the chunk; `store::by_reference`). The modal coordinates are as many chunks as the
//!   point has blocks of modes (the record's chunks beyond one per variable).
//!
//! Records are only appended. A run killed mid-write leaves at worst a torn last record; a
//! record whose magic, length or checksum is wrong ends the journal (it and everything after it
//! are dropped and truncated away on resume; those points are simply computed again).
//!
//! Format 2 (`BATSJRN2`) is format 3 without chunks in the file, and is read as it is.
//! Format 1 (`BATSJRN1`: histories as raw f64, FNV-1a checksums) is recognised and refused
//! with a message saying to start over with `--force` (issue 22: its histories would have to
//! be compressed again at the end, the very cost format 2 moved to the workers).

use super::error::StoreError;
pub use super::header::JournalHeader;
use super::layout::{self, N_SUMMARY_FLOATS};
use crate::results::PointRecord;
use std::fs::File;
use std::io::{BufReader, IoSlice, Read, Seek, SeekFrom, Write};
use std::os::unix::fs::FileExt;
use std::path::{Path, PathBuf};

const MAGIC: &[u8; 8] = b"BATSJRN3";
const MAGIC_V2: &[u8; 8] = b"BATSJRN2";
const MAGIC_V1: &[u8; 8] = b"BATSJRN1";
const REC_MAGIC: u32 = u32::from_le_bytes(*b"REC2");
/// Bytes before each record's payload: magic, length, checksum.
pub const REC_PREFIX: usize = 12;
/// Records at least this long skip the journal's buffer ([`JournalWriter::append`]).
const DIRECT_RECORD: usize = 16 << 10;
/// Largest accepted record payload (a corrupt length beyond this ends the journal).
const MAX_PAYLOAD: u64 = u32::MAX as u64;

/// Size of the fixed part of an ok record's payload (everything before the histories).
pub(crate) const OK_SUMMARY_LEN: usize = 8 + 8 + 4 + 1 + 8 * N_SUMMARY_FLOATS + 1 + 1;
/// Offset of the ok flag in a payload.
const OK_FLAG_AT: usize = 20;

/// CRC-32 (libdeflate's, several GB/s): the journal's checksum. Format 1's byte-at-a-time
/// FNV-1a ran at about 1 GB/s and was a fifth of a history study's writer time (issue 22).
pub fn checksum(bytes: &[u8]) -> u32 {
    libdeflater::crc32(bytes)
}

/// Encode a record's summary part: everything but its histories, with the flag saying
/// whether histories follow (`has_history`; the caller appends them).
pub fn encode_summary(rec: &PointRecord, has_history: bool, out: &mut Vec<u8>) {
    out.extend_from_slice(&(rec.index as u64).to_le_bytes());
    out.extend_from_slice(&rec.id.to_le_bytes());
    out.extend_from_slice(&rec.bat.to_le_bytes());
    match &rec.result {
        Ok(o) => {
            out.push(1);
            for x in layout::summary_floats(o) {
                out.extend_from_slice(&x.to_le_bytes());
            }
            out.push(o.recontact as u8);
            out.push(has_history as u8);
        }
        Err(msg) => {
            out.push(0);
            out.extend_from_slice(&(msg.len() as u64).to_le_bytes());
            out.extend_from_slice(msg.as_bytes());
        }
    }
}

/// Start a framed record in `out` (empty): room for the prefix, which [`end_frame`] fills.
pub fn begin_frame(out: &mut Vec<u8>) {
    out.clear();
    out.extend_from_slice(&[0u8; REC_PREFIX]);
}

/// Fill the prefix of a record framed by [`begin_frame`] (magic, length, checksum).
pub fn end_frame(out: &mut [u8]) {
    let len = (out.len() - REC_PREFIX) as u32;
    let sum = checksum(&out[REC_PREFIX..]);
    out[0..4].copy_from_slice(&REC_MAGIC.to_le_bytes());
    out[4..8].copy_from_slice(&len.to_le_bytes());
    out[8..12].copy_from_slice(&sum.to_le_bytes());
}

/// Whether `framed` is one whole framed record (magic and length; the checksum is the
/// encoder's and is not recomputed here).
pub fn is_framed(framed: &[u8]) -> bool {
    framed.len() >= REC_PREFIX
        && framed[0..4] == REC_MAGIC.to_le_bytes()
        && u32::from_le_bytes(framed[4..8].try_into().unwrap()) as usize
            == framed.len() - REC_PREFIX
}

/// Append one history variable's stored bytes to a payload.
pub fn put_history_chunk(bytes: &[u8], out: &mut Vec<u8>) {
    out.extend_from_slice(&(bytes.len() as u32).to_le_bytes());
    out.extend_from_slice(bytes);
}

/// Set in a history chunk's length word: the chunk is not in the record but in the results
/// file the run is writing, at the offset that follows (format 3).
pub const IN_FILE: u32 = 1 << 31;

/// One history chunk of a record: its bytes, or where the run wrote them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Piece<'a> {
    Bytes(&'a [u8]),
    /// `len` bytes at offset `at` of `OUT.h5.partial`, whose CRC-32 is `sum`.
    InFile {
        at: u64,
        len: u32,
        sum: u32,
    },
}

/// Append a reference to a history chunk in the results file to a payload ([`Piece::InFile`]).
pub fn put_history_in_file(at: u64, len: u32, sum: u32, out: &mut Vec<u8>) {
    debug_assert!(len < IN_FILE);
    out.extend_from_slice(&(IN_FILE | len).to_le_bytes());
    out.extend_from_slice(&at.to_le_bytes());
    out.extend_from_slice(&sum.to_le_bytes());
}

/// Every history chunk of a payload (after its summary part), bytes or references, or
/// `None` if they do not add up to the payload.
pub fn history_pieces(payload: &[u8]) -> Option<Vec<Piece<'_>>> {
    let mut c = Cursor {
        b: payload,
        p: OK_SUMMARY_LEN,
    };
    let mut out = Vec::new();
    while c.p < payload.len() {
        let word = c.u32()?;
        out.push(match word & IN_FILE {
            0 => Piece::Bytes(c.take(word as usize)?),
            _ => Piece::InFile {
                at: c.u64()?,
                len: word & !IN_FILE,
                sum: c.u32()?,
            },
        });
    }
    Some(out)
}

/// Every history chunk of a payload whose chunks are all in it, or `None` if they do not
/// add up to the payload or one is in the results file (a resume puts those back in the
/// journal first: `store::by_reference`).
pub fn history_chunks(payload: &[u8]) -> Option<Vec<&[u8]>> {
    history_pieces(payload)?
        .into_iter()
        .map(|p| match p {
            Piece::Bytes(b) => Some(b),
            Piece::InFile { .. } => None,
        })
        .collect()
}

/// Whether a payload holds histories of which some are in the results file.
pub(super) fn refers_to_file(payload: &[u8]) -> bool {
    decode_summary(payload).is_some_and(|(_, history)| history) && names_file_chunks(payload)
}

/// Whether the history chunks after a payload's summary name some in the results file.
fn names_file_chunks(payload: &[u8]) -> bool {
    history_pieces(payload).is_some_and(|p| p.iter().any(|p| matches!(p, Piece::InFile { .. })))
}

struct Cursor<'a> {
    b: &'a [u8],
    p: usize,
}

impl<'a> Cursor<'a> {
    fn take(&mut self, n: usize) -> Option<&'a [u8]> {
        let s = self.b.get(self.p..self.p.checked_add(n)?)?;
        self.p += n;
        Some(s)
    }
    fn u8(&mut self) -> Option<u8> {
        Some(self.take(1)?[0])
    }
    fn u32(&mut self) -> Option<u32> {
        Some(u32::from_le_bytes(self.take(4)?.try_into().ok()?))
    }
    fn u64(&mut self) -> Option<u64> {
        Some(u64::from_le_bytes(self.take(8)?.try_into().ok()?))
    }
    fn f64(&mut self) -> Option<f64> {
        Some(f64::from_bits(self.u64()?))
    }
}

/// Decode a payload's summary part (an ok record's first [`OK_SUMMARY_LEN`] bytes, a failed
/// record whole): the point without histories, and whether histories follow.
pub fn decode_summary(payload: &[u8]) -> Option<(PointRecord, bool)> {
    let mut c = Cursor { b: payload, p: 0 };
    let index = c.u64()? as usize;
    let id = c.u64()?;
    let bat = c.u32()?;
    let ok = c.u8()?;
    let (result, has_history) = if ok == 1 {
        let mut f = [0.0; N_SUMMARY_FLOATS];
        for x in f.iter_mut() {
            *x = c.f64()?;
        }
        let mut o = layout::outcome_from_floats(&f);
        o.recontact = c.u8()? != 0;
        (Ok(o), c.u8()? != 0)
    } else {
        let n = c.u64()? as usize;
        let s = c.take(n)?;
        (Err(String::from_utf8_lossy(s).into_owned()), false)
    };
    Some((
        PointRecord {
            index,
            id,
            bat,
            result,
        },
        has_history,
    ))
}

/// What a scan reports of one valid record.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RecordMeta {
    pub index: usize,
    pub id: u64,
    pub ok: bool,
    /// Some of its history chunks are in the results file, not in the record.
    pub in_file: bool,
}

/// Result of scanning a journal (the records themselves went to the scan's visitor).
#[derive(Debug, Clone)]
pub struct Scan {
    pub header: JournalHeader,
    /// Byte length of the header (records start here).
    pub header_len: u64,
    /// Byte length of the valid part (header + complete records).
    pub valid_len: u64,
    /// Bytes after the valid part (a torn or corrupt tail).
    pub dropped_bytes: u64,
}

fn read_header(r: &mut impl Read, path: &Path) -> Result<(JournalHeader, u64), StoreError> {
    let bad = |what: &str| StoreError::BadJournal {
        path: path.to_path_buf(),
        what: what.to_string(),
    };
    let mut magic = [0u8; 8];
    r.read_exact(&mut magic)
        .map_err(|_| bad("too short to hold a journal header"))?;
    if &magic == MAGIC_V1 {
        return Err(bad(
            "it was written by an older batstudy (journal format 1), which this version cannot \
             continue; run again with --force to start over",
        ));
    }
    if &magic != MAGIC && &magic != MAGIC_V2 {
        return Err(bad("not a batstudy journal (wrong magic bytes)"));
    }
    let mut n = [0u8; 4];
    r.read_exact(&mut n).map_err(|_| bad("truncated header"))?;
    let n = u32::from_le_bytes(n) as usize;
    if n > 1 << 24 {
        return Err(bad("header length is implausible"));
    }
    let mut json = vec![0u8; n];
    r.read_exact(&mut json)
        .map_err(|_| bad("truncated header"))?;
    let mut sum = [0u8; 4];
    r.read_exact(&mut sum)
        .map_err(|_| bad("truncated header"))?;
    if u32::from_le_bytes(sum) != checksum(&json) {
        return Err(bad("header checksum mismatch"));
    }
    let header: JournalHeader =
        serde_json::from_slice(&json).map_err(|e| bad(&format!("unreadable header: {e}")))?;
    Ok((header, (8 + 4 + n + 4) as u64))
}

/// The name a journal's header is written under before it is renamed into place (and a
/// journal rewritten on resume, `store::by_reference`).
pub(super) fn unfinished_path(path: &Path) -> std::path::PathBuf {
    let mut name = path.as_os_str().to_os_string();
    name.push(".new");
    std::path::PathBuf::from(name)
}

/// The header as it is stored: magic, length, JSON, checksum.
fn header_bytes(header: &JournalHeader) -> Vec<u8> {
    let json = serde_json::to_vec(header).expect("header serialises");
    let mut b = Vec::with_capacity(json.len() + 16);
    b.extend_from_slice(MAGIC);
    b.extend_from_slice(&(json.len() as u32).to_le_bytes());
    b.extend_from_slice(&json);
    b.extend_from_slice(&checksum(&json).to_le_bytes());
    b
}

/// Whether the journal at `path` ends inside its header: its bytes are the start of a
/// header (the magic, then as much of the length, the JSON and the checksum as was written)
/// and no more. Such a journal holds no record: a run killed while an older batstudy created
/// its journal left one, and a resume starts over from it. Any other content is not this.
pub fn ends_in_header(path: &Path) -> Result<bool, StoreError> {
    let io = |e| StoreError::io(path, "read the journal", e);
    let len = std::fs::metadata(path).map_err(io)?.len();
    let mut head = Vec::new();
    File::open(path)
        .map_err(io)?
        .take(12)
        .read_to_end(&mut head)
        .map_err(io)?;
    let magic = head.len().min(8);
    if head[..magic] != MAGIC[..magic] && head[..magic] != MAGIC_V2[..magic] {
        return Ok(false);
    }
    if head.len() < 12 {
        return Ok(true);
    }
    let n = u32::from_le_bytes(head[8..12].try_into().expect("4 bytes")) as u64;
    Ok(n <= 1 << 24 && len < 12 + n + 4)
}

/// A journal's header alone (what a resume checks before it touches anything).
pub fn header(path: &Path) -> Result<JournalHeader, StoreError> {
    let file = File::open(path).map_err(|e| StoreError::io(path, "open the journal", e))?;
    read_header(&mut BufReader::new(file), path).map(|(h, _)| h)
}

/// Read a journal's header and check every record, handing each valid one to `visit` in file
/// order. Memory: one record (the payloads are checksummed, not kept).
pub fn scan(path: &Path, mut visit: impl FnMut(RecordMeta)) -> Result<Scan, StoreError> {
    let file = File::open(path).map_err(|e| StoreError::io(path, "open the journal", e))?;
    let file_len = file
        .metadata()
        .map_err(|e| StoreError::io(path, "stat the journal", e))?
        .len();
    let mut r = BufReader::with_capacity(1 << 20, file);
    let (header, header_len) = read_header(&mut r, path)?;
    let mut pos = header_len;
    let mut payload = Vec::new();
    loop {
        let mut pre = [0u8; REC_PREFIX];
        if pos + REC_PREFIX as u64 > file_len || r.read_exact(&mut pre).is_err() {
            break;
        }
        let (magic, len, sum) = split_prefix(&pre);
        if magic != REC_MAGIC || len > MAX_PAYLOAD || pos + REC_PREFIX as u64 + len > file_len {
            break;
        }
        payload.resize(len as usize, 0);
        if r.read_exact(&mut payload).is_err() || checksum(&payload) != sum {
            break;
        }
        // The whole payload: a failed point's message follows the fixed part and may be
        // longer than OK_SUMMARY_LEN.
        let Some((rec, has_history)) = decode_summary(&payload) else {
            break;
        };
        visit(RecordMeta {
            index: rec.index,
            id: rec.id,
            ok: rec.result.is_ok(),
            in_file: has_history && names_file_chunks(&payload),
        });
        pos += REC_PREFIX as u64 + len;
    }
    Ok(Scan {
        header,
        header_len,
        valid_len: pos,
        dropped_bytes: file_len - pos,
    })
}

pub(super) fn split_prefix(pre: &[u8; REC_PREFIX]) -> (u32, u64, u32) {
    (
        u32::from_le_bytes(pre[0..4].try_into().unwrap()),
        u32::from_le_bytes(pre[4..8].try_into().unwrap()) as u64,
        u32::from_le_bytes(pre[8..12].try_into().unwrap()),
    )
}

/// Where a record's payload is in the journal, and its checksum.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RecordPlace {
    pub at: u64,
    pub len: u64,
    pub sum: u32,
}

/// Sequential reading of a scanned journal's valid records, in file order: summaries
/// cheaply (histories are skipped over, not read; [`Self::place`] says where they are).
/// Memory: one record's summary.
pub struct RecordReader {
    r: BufReader<File>,
    path: PathBuf,
    /// Offset of the next unread byte.
    pos: u64,
    /// End of the valid part.
    end: u64,
    payload: Vec<u8>,
    /// Current record: where its payload is, and whether histories follow its summary.
    current: Option<(RecordPlace, bool)>,
}

impl RecordReader {
    /// Open `path`, already scanned as `scan`, at its first record.
    pub fn open(path: &Path, scan: &Scan) -> Result<Self, StoreError> {
        Self::open_with_buffer(path, scan, 1 << 20)
    }

    /// [`Self::open`] with a read buffer of `capacity` bytes: a small one reads little more
    /// than the summaries of records with histories, which are skipped over by seeking
    /// (a large buffer would read them anyway).
    pub fn open_with_buffer(path: &Path, scan: &Scan, capacity: usize) -> Result<Self, StoreError> {
        let mut file = File::open(path).map_err(|e| StoreError::io(path, "open the journal", e))?;
        file.seek(SeekFrom::Start(scan.header_len))
            .map_err(|e| StoreError::io(path, "read the journal", e))?;
        Ok(RecordReader {
            r: BufReader::with_capacity(capacity, file),
            path: path.to_path_buf(),
            pos: scan.header_len,
            end: scan.valid_len,
            payload: Vec::new(),
            current: None,
        })
    }

    fn bad(&self, what: String) -> StoreError {
        StoreError::BadJournal {
            path: self.path.clone(),
            what,
        }
    }

    fn io(&self, e: std::io::Error) -> StoreError {
        StoreError::io(&self.path, "read the journal", e)
    }

    /// Move to the next record and decode its summary (a failed record whole, an ok record
    /// without its histories). `None` at the end of the valid part.
    pub fn next_summary(&mut self) -> Result<Option<PointRecord>, StoreError> {
        if let Some((place, _)) = self.current.take() {
            let next = place.at + place.len;
            self.r
                .seek_relative((next - self.pos) as i64)
                .map_err(|e| self.io(e))?;
            self.pos = next;
        }
        if self.pos >= self.end {
            return Ok(None);
        }
        let mut pre = [0u8; REC_PREFIX];
        self.r.read_exact(&mut pre).map_err(|e| self.io(e))?;
        let (magic, len, sum) = split_prefix(&pre);
        let at = self.pos + REC_PREFIX as u64;
        if magic != REC_MAGIC || at + len > self.end {
            return Err(self.bad(format!(
                "record at byte {} changed after it was scanned",
                self.pos
            )));
        }
        self.pos = at;
        self.payload.clear();
        self.extend((len as usize).min(OK_SUMMARY_LEN))?;
        // failed records keep their message after the fixed part: read them whole
        if self.payload.get(OK_FLAG_AT) == Some(&0) {
            self.extend(len as usize - self.payload.len())?;
        }
        // a record read whole (every record without histories) is checked here; one with
        // histories is checked when they are read ([`read_payload`])
        if self.payload.len() as u64 == len && checksum(&self.payload) != sum {
            return Err(self.bad(format!(
                "record at byte {at} fails its checksum: the journal changed after it was written"
            )));
        }
        let (rec, has_history) = decode_summary(&self.payload)
            .ok_or_else(|| self.bad(format!("undecodable record at byte {at}")))?;
        self.current = Some((RecordPlace { at, len, sum }, has_history));
        Ok(Some(rec))
    }

    fn extend(&mut self, n: usize) -> Result<(), StoreError> {
        let have = self.payload.len();
        self.payload.resize(have + n, 0);
        self.r
            .read_exact(&mut self.payload[have..])
            .map_err(|e| self.io(e))?;
        self.pos += n as u64;
        Ok(())
    }

    /// Where the record last returned by [`Self::next_summary`] is, when it has histories.
    pub fn history_place(&self) -> Option<RecordPlace> {
        self.current.filter(|(_, h)| *h).map(|(p, _)| p)
    }
}

/// Read the payload at `place` of the journal `file` (at `path`) into `out`, checked against
/// its checksum: the journal must not have changed since it was written or scanned.
pub fn read_payload(
    file: &File,
    path: &Path,
    place: RecordPlace,
    out: &mut Vec<u8>,
) -> Result<(), StoreError> {
    out.resize(place.len as usize, 0);
    file.read_exact_at(out, place.at)
        .map_err(|e| StoreError::io(path, "read the journal", e))?;
    if checksum(out) != place.sum {
        return Err(StoreError::BadJournal {
            path: path.to_path_buf(),
            what: format!("record at byte {} changed after it was scanned", place.at),
        });
    }
    Ok(())
}

/// Appends framed records; the caller decides when to flush and sync.
pub struct JournalWriter {
    file: File,
    path: PathBuf,
    buf: Vec<u8>,
    /// Byte length of the header (records start here).
    header_len: u64,
    /// Bytes written and buffered: header and whole records only.
    len: u64,
    /// Whether the journal's directory entry has been made durable.
    entry_durable: bool,
}

impl JournalWriter {
    fn over(file: File, path: &Path, header_len: u64, len: u64, entry_durable: bool) -> Self {
        JournalWriter {
            file,
            path: path.to_path_buf(),
            buf: Vec::with_capacity(1 << 20),
            header_len,
            len,
            entry_durable,
        }
    }

    /// Create a new journal (the file must not exist) and write its header. The header
    /// becomes durable with the first [`Self::sync`], like the records: until then a power
    /// loss would lose the records anyway, and a killed process loses nothing handed to the
    /// OS (issue 7: two fsyncs off every run's critical path).
    ///
    /// The header is written under a temporary name and renamed into place, so a journal never
    /// exists without its whole header: a run killed while it creates its journal leaves none
    /// (a killed run's `--resume` once met a 0-byte journal and refused it as damaged).
    pub fn create(path: &Path, header: &JournalHeader) -> Result<Self, StoreError> {
        if path.exists() {
            return Err(StoreError::io(
                path,
                "create the journal",
                std::io::Error::from(std::io::ErrorKind::AlreadyExists),
            ));
        }
        let temp = unfinished_path(path);
        // a stale one from a killed run: removed, never followed (issue 31)
        match std::fs::remove_file(&temp) {
            Err(e) if e.kind() != std::io::ErrorKind::NotFound => {
                return Err(StoreError::io(&temp, "remove a stale journal", e))
            }
            _ => {}
        }
        let mut file = std::fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&temp)
            .map_err(|e| StoreError::io(&temp, "create the journal", e))?;
        let b = header_bytes(header);
        if let Err(e) = file.write_all(&b) {
            // a journal without its header could never be resumed: leave none behind
            // (issue 31: a full disk left a 0-byte journal that only --force got past)
            drop(file);
            let _ = std::fs::remove_file(&temp);
            return Err(StoreError::io(path, "write the journal header", e));
        }
        std::fs::rename(&temp, path).map_err(|e| StoreError::io(path, "create the journal", e))?;
        let n = b.len() as u64;
        Ok(JournalWriter::over(file, path, n, n, false))
    }

    /// Open an existing, scanned journal for appending after its valid part (a torn tail is
    /// cut off first).
    pub fn append_to(path: &Path, scan: &Scan) -> Result<Self, StoreError> {
        let valid_len = scan.valid_len;
        let mut file = std::fs::OpenOptions::new()
            .write(true)
            .open(path)
            .map_err(|e| StoreError::io(path, "open the journal for appending", e))?;
        file.set_len(valid_len)
            .and_then(|_| file.sync_all())
            .and_then(|_| file.seek(SeekFrom::Start(valid_len)).map(|_| ()))
            .map_err(|e| StoreError::io(path, "cut the journal's torn tail", e))?;
        Ok(JournalWriter::over(
            file,
            path,
            scan.header_len,
            valid_len,
            true,
        ))
    }

    /// Bytes written and buffered: the header and every record appended.
    pub fn bytes(&self) -> u64 {
        self.len
    }

    /// What a scan of this journal would find once it is flushed: the header it was created
    /// (or scanned) with and every record appended. The writer knows its own extent, so
    /// finishing a run need not read the journal twice (issue 7).
    pub fn extent(&self, header: JournalHeader) -> Scan {
        Scan {
            header,
            header_len: self.header_len,
            valid_len: self.len,
            dropped_bytes: 0,
        }
    }

    /// Append one framed record ([`begin_frame`] … [`end_frame`]; `store::encode` makes
    /// them on the workers). A small one is buffered; a large one (a history record) is
    /// handed to the OS at once with what is buffered, from the caller's memory: copying it
    /// into the buffer first, and from there into the page cache once the buffer had long
    /// left the CPU's caches, was three quarters of the writer thread's copying (issue 22).
    pub fn append(&mut self, framed: &[u8]) -> Result<(), StoreError> {
        debug_assert!(is_framed(framed));
        if framed.len() >= DIRECT_RECORD {
            let mut parts = [IoSlice::new(&self.buf), IoSlice::new(framed)];
            let mut parts = &mut parts[..];
            IoSlice::advance_slices(&mut parts, 0); // drops an empty buffer's slice
            while !parts.is_empty() {
                let n = self
                    .file
                    .write_vectored(parts)
                    .map_err(|e| StoreError::io(&self.path, "append to the journal", e))?;
                if n == 0 {
                    let e = std::io::Error::from(std::io::ErrorKind::WriteZero);
                    return Err(StoreError::io(&self.path, "append to the journal", e));
                }
                IoSlice::advance_slices(&mut parts, n);
            }
            self.buf.clear();
        } else {
            self.buf.extend_from_slice(framed);
        }
        self.len += framed.len() as u64;
        Ok(())
    }

    pub fn buffered_bytes(&self) -> usize {
        self.buf.len()
    }

    /// Hand the buffered records to the OS (survives the process being killed).
    pub fn flush(&mut self) -> Result<(), StoreError> {
        if !self.buf.is_empty() {
            self.file
                .write_all(&self.buf)
                .map_err(|e| StoreError::io(&self.path, "append to the journal", e))?;
            self.buf.clear();
        }
        Ok(())
    }

    /// Flush and make durable (survives power loss).
    pub fn sync(&mut self) -> Result<(), StoreError> {
        self.flush()?;
        self.file
            .sync_data()
            .map_err(|e| StoreError::io(&self.path, "sync the journal", e))?;
        if !self.entry_durable {
            sync_parent_dir(&self.path);
            self.entry_durable = true;
        }
        Ok(())
    }
}

/// Best effort: make a created/renamed/removed directory entry durable.
pub fn sync_parent_dir(path: &Path) {
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    if let Ok(d) = File::open(dir) {
        let _ = d.sync_all();
    }
}
