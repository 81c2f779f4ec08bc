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
//! - a record may instead hold a group: points of consecutive flat indices whose histories
//!   share chunks (each chunk spans the group along the study's last dim). Its payload
//!   begins with a head shaped like a point's summary, whose ok byte is [`GROUP_FLAG`]: u64
//!   flat index of the first point, u32 points, u32 bytes of their summaries, u32 0, the
//!   flag; then each point's summary ([`encode_summary`]); then the group's chunks as
//!   above. A torn tail drops whole groups: a group is stored, and its histories with it,
//!   or none of its points is.
//!
//! Records are only appended. A run killed mid-write leaves at worst a torn last record; a
//! record whose magic, length or checksum is wrong ends the journal (it and everything after it
//! are dropped and truncated away on resume; those points are simply computed again).
//!
//! Format 2 (`BATSJRN2`) is format 3 without chunks in the file, and is read as it is.
//! Format 1 (`BATSJRN1`: histories as raw f64, FNV-1a checksums) is recognised and refused
//! with a message saying to start over with `--force` (its histories would have to be
//! compressed again at the end, the very cost format 2 moves to the workers).

use super::error::StoreError;
pub use super::header::JournalHeader;
pub(super) use super::record::refers_to_file;
pub(crate) use super::record::OK_SUMMARY_LEN;
pub use super::record::{
    decode_points, decode_summary, encode_group_summaries, encode_summary, history_chunks,
    history_pieces, put_history_chunk, put_history_in_file, summary_part, Piece, GROUP_FLAG,
    IN_FILE,
};
use super::record::{names_file_chunks, GROUP_HEAD_LEN, OK_FLAG_AT};
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

/// CRC-32 (libdeflate's, several GB/s): the journal's checksum. Format 1's byte-at-a-time
/// FNV-1a runs at about 1 GB/s and would be a fifth of a history study's writer time.
pub fn checksum(bytes: &[u8]) -> u32 {
    libdeflater::crc32(bytes)
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
    open_journal(path)?
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

/// A journal opened for reading, once it is known to be a regular file: a pipe planted at
/// its path would block the open until a writer came, a device never end.
pub fn open_journal(path: &Path) -> Result<File, StoreError> {
    if !super::check::is_regular(path, "open the journal")? {
        return Err(StoreError::BadJournal {
            path: path.to_path_buf(),
            what: super::check::NOT_REGULAR.into(),
        });
    }
    File::open(path).map_err(|e| StoreError::io(path, "open the journal", e))
}

/// A journal's header alone (what a resume checks before it touches anything).
pub fn header(path: &Path) -> Result<JournalHeader, StoreError> {
    let file = open_journal(path)?;
    read_header(&mut BufReader::new(file), path).map(|(h, _)| h)
}

/// Read a journal's header and check every record, handing each valid one to `visit` in file
/// order. Memory: one record (the payloads are checksummed, not kept).
pub fn scan(path: &Path, mut visit: impl FnMut(RecordMeta)) -> Result<Scan, StoreError> {
    let file = open_journal(path)?;
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
        let (Some(points), Some((_, history))) = (decode_points(&payload), summary_part(&payload))
        else {
            break;
        };
        let in_file = history && names_file_chunks(&payload);
        for (rec, _) in points {
            visit(RecordMeta {
                index: rec.index,
                id: rec.id,
                ok: rec.result.is_ok(),
                in_file,
            });
        }
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
/// cheaply (histories are skipped over, not read; [`Self::history_place`] says where they
/// are), one point at a time (a group record's points one after the other). Memory: one
/// record's summaries.
pub struct RecordReader {
    r: BufReader<File>,
    path: PathBuf,
    /// Offset of the next unread byte.
    pos: u64,
    /// End of the valid part.
    end: u64,
    payload: Vec<u8>,
    /// Current record: where its payload is, and whether histories follow its summaries.
    current: Option<(RecordPlace, bool)>,
    /// The current record's points not returned yet (a group's after its first).
    pending: std::collections::VecDeque<PointRecord>,
    /// The point last returned is its record's first.
    at_first: bool,
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
        let mut file = open_journal(path)?;
        file.seek(SeekFrom::Start(scan.header_len))
            .map_err(|e| StoreError::io(path, "read the journal", e))?;
        Ok(RecordReader {
            r: BufReader::with_capacity(capacity, file),
            path: path.to_path_buf(),
            pos: scan.header_len,
            end: scan.valid_len,
            payload: Vec::new(),
            current: None,
            pending: Default::default(),
            at_first: false,
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

    /// Move to the next point and decode its summary (a failed point whole, an ok point
    /// without its histories): the next of the current group's points, else the next
    /// record's first. `None` at the end of the valid part.
    pub fn next_summary(&mut self) -> Result<Option<PointRecord>, StoreError> {
        if let Some(rec) = self.pending.pop_front() {
            self.at_first = false;
            return Ok(Some(rec));
        }
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
        self.read_summary_part(len as usize)?;
        // a record read whole (every record without histories) is checked here; one with
        // histories is checked when they are read ([`read_payload`])
        if self.payload.len() as u64 == len && checksum(&self.payload) != sum {
            return Err(self.bad(format!(
                "record at byte {at} fails its checksum: the journal changed after it was written"
            )));
        }
        let Some(points) = decode_points(&self.payload) else {
            return Err(self.bad(format!("undecodable record at byte {at}")));
        };
        let history = points.iter().any(|(_, h)| *h);
        self.current = Some((RecordPlace { at, len, sum }, history));
        let mut points = points.into_iter().map(|(p, _)| p);
        let first = points.next().expect("a record holds a point");
        self.pending.extend(points);
        self.at_first = true;
        Ok(Some(first))
    }

    /// Read the summary part of a payload of `len` bytes into `self.payload`: a failed
    /// point's record whole (its message follows the fixed part), an ok point's fixed part,
    /// a group's head and its points' summaries.
    fn read_summary_part(&mut self, len: usize) -> Result<(), StoreError> {
        self.payload.clear();
        self.extend(len.min(OK_SUMMARY_LEN))?;
        let want = match self.payload.get(OK_FLAG_AT) {
            Some(&0) => len,
            Some(&GROUP_FLAG) if self.payload.len() >= GROUP_HEAD_LEN => {
                let summaries = u32::from_le_bytes(self.payload[12..16].try_into().expect("4"));
                (GROUP_HEAD_LEN + summaries as usize).min(len)
            }
            _ => 0,
        };
        self.extend(want.saturating_sub(self.payload.len()))
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

    /// Where the record of the point last returned by [`Self::next_summary`] is, when it
    /// has histories and that point is its first (a group's record is named once).
    pub fn history_place(&self) -> Option<RecordPlace> {
        match self.at_first {
            true => self.current.filter(|(_, h)| *h).map(|(p, _)| p),
            false => None,
        }
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
    /// OS (two fsyncs off every run's critical path).
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
        // a stale one from a killed run: removed, never followed
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
            // (a 0-byte journal left by a full disk could only be got past with --force)
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
    /// finishing a run need not read the journal twice.
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
    /// left the CPU's caches, would be three quarters of the writer thread's copying.
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

/// Write `bytes` to a temporary file of this process beside `path`, sync it, rename it over
/// `path` and make the rename durable: a reader, or a second process writing the same path,
/// sees the old file or one whole new one, never a mixture or a part.
pub fn write_whole(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    use std::io::Write;
    let mut name = path.file_name().unwrap_or_default().to_os_string();
    name.push(format!(".{}.tmp", std::process::id()));
    let tmp = path.with_file_name(name);
    let written = std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&tmp)
        .and_then(|mut f| {
            f.write_all(bytes)?;
            f.sync_all()
        })
        .and_then(|()| std::fs::rename(&tmp, path));
    match written {
        Ok(()) => sync_parent_dir(path),
        Err(_) => {
            let _ = std::fs::remove_file(&tmp);
        }
    }
    written
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::layout;
    use batstudy_physics::outcome::Outcome;

    fn ok(index: usize, exit_speed: f64) -> PointRecord {
        PointRecord {
            index,
            id: 100 + index as u64,
            bat: (index % 2) as u32,
            result: Ok(Outcome {
                exit_speed,
                ..Default::default()
            }),
        }
    }

    fn failed(index: usize, msg: &str) -> PointRecord {
        PointRecord {
            index,
            id: 100 + index as u64,
            bat: 0,
            result: Err(msg.into()),
        }
    }

    /// A point as the journal keeps it, bit for bit (its NaNs compare).
    fn key(p: &PointRecord) -> (usize, u64, u32, Result<Vec<u64>, String>) {
        let floats = p.result.as_ref().map_err(Clone::clone).map(|o| {
            layout::summary_floats(o)
                .iter()
                .map(|x| x.to_bits())
                .collect()
        });
        (p.index, p.id, p.bat, floats)
    }

    /// A framed record of one point, with these chunks when it has histories.
    fn point_record(p: &PointRecord, chunks: &[&[u8]]) -> Vec<u8> {
        let mut f = Vec::new();
        begin_frame(&mut f);
        encode_summary(p, !chunks.is_empty(), &mut f);
        chunks.iter().for_each(|c| put_history_chunk(c, &mut f));
        end_frame(&mut f);
        f
    }

    /// A framed group record: its points, then the group's chunks, the second named in the
    /// results file.
    fn group_record(points: &[PointRecord], history: &[bool], chunk: &[u8]) -> Vec<u8> {
        let mut f = Vec::new();
        begin_frame(&mut f);
        encode_group_summaries(points, history, &mut f);
        put_history_chunk(chunk, &mut f);
        put_history_in_file(4096, 77, 0xdead_beef, &mut f);
        end_frame(&mut f);
        f
    }

    fn header() -> JournalHeader {
        JournalHeader {
            layout_version: layout::LAYOUT_VERSION,
            study_name: "t".into(),
            study_sha256: "0".into(),
            dims: vec![("impact_z".into(), 12)],
            history: None,
            n_bats: 2,
            history_group: 1,
        }
    }

    /// A group record's points come back one by one, in order, with their results; its
    /// chunks come after all their summaries; a reader names its place once, at its first
    /// point. Point records before and after it read as before.
    #[test]
    fn a_group_record_reads_back_point_by_point() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("j");
        let members = [ok(4, 30.5), failed(5, "no contact"), ok(6, 31.25)];
        let group = group_record(&members, &[true, false, true], &[7u8; 300]);
        let payload = &group[REC_PREFIX..];
        let (chunks_at, history) = summary_part(payload).unwrap();
        assert!(history);
        let pieces = history_pieces(payload).unwrap();
        assert_eq!(pieces[0], Piece::Bytes(&[7u8; 300]));
        assert_eq!(
            pieces[1],
            Piece::InFile {
                at: 4096,
                len: 77,
                sum: 0xdead_beef
            }
        );
        assert_eq!(chunks_at, payload.len() - (4 + 300) - 16);
        assert!(refers_to_file(payload) && history_chunks(payload).is_none());

        let mut w = JournalWriter::create(&path, &header()).unwrap();
        w.append(&point_record(&ok(0, 29.0), &[&[1, 2, 3]]))
            .unwrap();
        w.append(&group).unwrap();
        w.append(&point_record(&failed(9, "panic"), &[])).unwrap();
        w.flush().unwrap();

        let mut seen = Vec::new();
        let scan = scan(&path, |m| seen.push((m.index, m.ok, m.in_file))).unwrap();
        assert_eq!(
            seen,
            [
                (0, true, false),
                (4, true, true),
                (5, false, true),
                (6, true, true),
                (9, false, false)
            ]
        );
        let mut rr = RecordReader::open_with_buffer(&path, &scan, 64).unwrap();
        let mut got = Vec::new();
        while let Some(rec) = rr.next_summary().unwrap() {
            got.push((rec.clone(), rr.history_place().is_some()));
        }
        let want = [
            ok(0, 29.0),
            members[0].clone(),
            members[1].clone(),
            members[2].clone(),
        ];
        for (g, w) in got.iter().zip(&want) {
            assert_eq!(key(&g.0), key(w));
        }
        let places: Vec<bool> = got.iter().map(|g| g.1).collect();
        assert_eq!(places, [true, true, false, false, false]);
        assert_eq!(key(&got[4].0), key(&failed(9, "panic")));
    }

    /// A journal cut anywhere inside a group record keeps none of its points (the torn tail
    /// is dropped whole), and a group whose points do not increase is no record.
    #[test]
    fn a_torn_group_drops_all_its_points() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("j");
        let mut w = JournalWriter::create(&path, &header()).unwrap();
        w.append(&point_record(&ok(0, 29.0), &[])).unwrap();
        let members = [ok(1, 30.0), ok(2, 30.5)];
        w.append(&group_record(&members, &[true, true], &[5u8; 40]))
            .unwrap();
        w.flush().unwrap();
        let whole = std::fs::read(&path).unwrap();
        let group_len = group_record(&members, &[true, true], &[5u8; 40]).len();
        for cut in [1, REC_PREFIX + 3, REC_PREFIX + 30, group_len - 1] {
            std::fs::write(&path, &whole[..whole.len() - group_len + cut]).unwrap();
            let mut seen = Vec::new();
            let s = scan(&path, |m| seen.push(m.index)).unwrap();
            assert_eq!(seen, [0], "cut {cut} bytes into the group");
            assert_eq!(s.dropped_bytes, cut as u64);
        }
        let mut apart = group_record(&members, &[true, true], &[5u8; 40]);
        let second = REC_PREFIX + GROUP_HEAD_LEN + OK_SUMMARY_LEN;
        apart[second..second + 8].copy_from_slice(&1u64.to_le_bytes());
        end_frame(&mut apart);
        assert!(decode_points(&apart[REC_PREFIX..]).is_none());
    }
}
