//! The append-only journal `OUT.h5.journal`: the source of truth while a study runs.
//!
//! Format (little endian):
//! - header: magic `BATSJRN1`, u32 `n` = length of the header JSON, the JSON ([`JournalHeader`]),
//!   u64 FNV-1a checksum of the JSON;
//! - then records, each: u32 magic `REC1`, u32 payload length, u64 FNV-1a checksum of the
//!   payload, the payload ([`encode_record`]).
//!
//! Records are only appended. A run killed mid-write leaves at worst a torn last record; a
//! record whose magic, length or checksum is wrong ends the journal (it and everything after it
//! are dropped and truncated away on resume; those points are simply computed again).

use super::error::StoreError;
pub use super::header::JournalHeader;
use super::layout::{self, N_SUMMARY_FLOATS};
use crate::model::outcome::History;
use crate::results::PointRecord;
use std::fs::File;
use std::io::{BufReader, Read, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};

const MAGIC: &[u8; 8] = b"BATSJRN1";
const REC_MAGIC: u32 = u32::from_le_bytes(*b"REC1");
const REC_PREFIX: usize = 16;
/// Largest accepted record payload (a corrupt length beyond this ends the journal).
const MAX_PAYLOAD: u64 = 1 << 34;

/// Size of the fixed part of an ok record's payload (everything before the history).
pub(crate) const OK_SUMMARY_LEN: usize = 8 + 8 + 4 + 1 + 8 * N_SUMMARY_FLOATS + 1 + 1;

/// FNV-1a 64-bit checksum.
pub fn fnv1a(bytes: &[u8]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for &b in bytes {
        h ^= b as u64;
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    h
}

/// Encode one record's payload.
pub fn encode_record(rec: &PointRecord, out: &mut Vec<u8>) {
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
            match &o.history {
                None => out.push(0),
                Some(h) => {
                    out.push(1);
                    for k in 0..layout::HISTORY_VARS.len() {
                        let a = layout::history_array(h, k);
                        out.extend_from_slice(&(a.len() as u64).to_le_bytes());
                        for x in a {
                            out.extend_from_slice(&x.to_le_bytes());
                        }
                    }
                }
            }
        }
        Err(msg) => {
            out.push(0);
            out.extend_from_slice(&(msg.len() as u64).to_le_bytes());
            out.extend_from_slice(msg.as_bytes());
        }
    }
}

struct Cursor<'a> {
    b: &'a [u8],
    p: usize,
}

impl Cursor<'_> {
    fn take(&mut self, n: usize) -> Option<&[u8]> {
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

/// Decode a payload. With `summary_only`, histories are skipped (and may be absent from
/// `payload`, which may then be just the first [`OK_SUMMARY_LEN`] bytes).
pub fn decode_record(payload: &[u8], summary_only: bool) -> Option<PointRecord> {
    let mut c = Cursor { b: payload, p: 0 };
    let index = c.u64()? as usize;
    let id = c.u64()?;
    let bat = c.u32()?;
    let ok = c.u8()?;
    let result = if ok == 1 {
        let mut f = [0.0; N_SUMMARY_FLOATS];
        for x in f.iter_mut() {
            *x = c.f64()?;
        }
        let mut o = layout::outcome_from_floats(&f);
        o.recontact = c.u8()? != 0;
        let has_history = c.u8()? != 0;
        if has_history && !summary_only {
            let mut h = History::default();
            for k in 0..layout::HISTORY_VARS.len() {
                let n = c.u64()? as usize;
                if n > payload.len() / 8 {
                    return None;
                }
                let a = layout::history_array_mut(&mut h, k);
                a.reserve_exact(n);
                for _ in 0..n {
                    a.push(c.f64()?);
                }
            }
            o.history = Some(h);
        }
        Ok(o)
    } else {
        let n = c.u64()? as usize;
        let s = c.take(n)?;
        Err(String::from_utf8_lossy(s).into_owned())
    };
    Some(PointRecord {
        index,
        id,
        bat,
        result,
    })
}

/// What a scan reports of one valid record.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RecordMeta {
    pub index: usize,
    pub id: u64,
    pub ok: bool,
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
    if &magic != MAGIC {
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
    let mut sum = [0u8; 8];
    r.read_exact(&mut sum)
        .map_err(|_| bad("truncated header"))?;
    if u64::from_le_bytes(sum) != fnv1a(&json) {
        return Err(bad("header checksum mismatch"));
    }
    let header: JournalHeader =
        serde_json::from_slice(&json).map_err(|e| bad(&format!("unreadable header: {e}")))?;
    Ok((header, (8 + 4 + n + 8) as u64))
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
        if r.read_exact(&mut payload).is_err() || fnv1a(&payload) != sum {
            break;
        }
        // The whole payload: a failed point's message follows the fixed part and may be
        // longer than OK_SUMMARY_LEN (cutting it made the record undecodable and silently
        // ended the journal there); `summary_only` skips histories, so this stays cheap.
        let Some(rec) = decode_record(&payload, true) else {
            break;
        };
        visit(RecordMeta {
            index: rec.index,
            id: rec.id,
            ok: rec.result.is_ok(),
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

fn split_prefix(pre: &[u8; REC_PREFIX]) -> (u32, u64, u64) {
    (
        u32::from_le_bytes(pre[0..4].try_into().unwrap()),
        u32::from_le_bytes(pre[4..8].try_into().unwrap()) as u64,
        u64::from_le_bytes(pre[8..16].try_into().unwrap()),
    )
}

/// Sequential reading of a scanned journal's valid records, in file order: summaries
/// cheaply (a history is skipped over, not read), and whole records on request. Memory: one
/// record.
pub struct RecordReader {
    r: BufReader<File>,
    path: PathBuf,
    /// Offset of the next unread byte.
    pos: u64,
    /// End of the valid part.
    end: u64,
    payload: Vec<u8>,
    /// Current record: payload offset, length and checksum.
    current: Option<(u64, u64, u64)>,
}

impl RecordReader {
    /// Open `path`, already scanned as `scan`, at its first record.
    pub fn open(path: &Path, scan: &Scan) -> Result<Self, StoreError> {
        let mut file = File::open(path).map_err(|e| StoreError::io(path, "open the journal", e))?;
        file.seek(SeekFrom::Start(scan.header_len))
            .map_err(|e| StoreError::io(path, "read the journal", e))?;
        Ok(RecordReader {
            r: BufReader::with_capacity(1 << 20, file),
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
    /// without its history). `None` at the end of the valid part.
    pub fn next_summary(&mut self) -> Result<Option<PointRecord>, StoreError> {
        if let Some((at, len, _)) = self.current.take() {
            let next = at + len;
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
        self.current = Some((at, len, sum));
        self.payload.clear();
        self.extend((len as usize).min(OK_SUMMARY_LEN))?;
        // failed records keep their message after the fixed part: read them whole
        if self.payload.get(20) == Some(&0) {
            self.extend(len as usize - self.payload.len())?;
        }
        // a record read whole (every record of a summary-only study) is checked here; one
        // with a history is checked when [`Self::whole`] reads the rest
        if self.payload.len() as u64 == len && fnv1a(&self.payload) != sum {
            return Err(self.bad(format!(
                "record at byte {at} fails its checksum: the journal changed after it was written"
            )));
        }
        decode_record(&self.payload, true)
            .map(Some)
            .ok_or_else(|| self.bad(format!("undecodable record at byte {at}")))
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

    /// The whole record last returned by [`Self::next_summary`], history included (its
    /// checksum checked again: the journal must not have changed since the scan).
    pub fn whole(&mut self) -> Result<PointRecord, StoreError> {
        let (at, len, sum) = self
            .current
            .ok_or_else(|| self.bad("no current record".into()))?;
        let rest = (at + len - self.pos) as usize;
        self.extend(rest)?;
        if fnv1a(&self.payload) != sum {
            return Err(self.bad(format!("record at byte {at} changed after it was scanned")));
        }
        decode_record(&self.payload, false)
            .ok_or_else(|| self.bad(format!("undecodable record at byte {at}")))
    }
}

/// Appends records; the caller decides when to flush and sync.
pub struct JournalWriter {
    file: File,
    path: PathBuf,
    buf: Vec<u8>,
    payload: Vec<u8>,
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
            payload: Vec::new(),
            header_len,
            len,
            entry_durable,
        }
    }

    /// Create a new journal (the file must not exist) and write its header. The header
    /// becomes durable with the first [`Self::sync`], like the records: until then a power
    /// loss would lose the records anyway, and a killed process loses nothing handed to the
    /// OS (issue 7: two fsyncs off every run's critical path).
    pub fn create(path: &Path, header: &JournalHeader) -> Result<Self, StoreError> {
        let mut file = std::fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(path)
            .map_err(|e| StoreError::io(path, "create the journal", e))?;
        let json = serde_json::to_vec(header).expect("header serialises");
        let mut b = Vec::with_capacity(json.len() + 20);
        b.extend_from_slice(MAGIC);
        b.extend_from_slice(&(json.len() as u32).to_le_bytes());
        b.extend_from_slice(&json);
        b.extend_from_slice(&fnv1a(&json).to_le_bytes());
        file.write_all(&b)
            .map_err(|e| StoreError::io(path, "write the journal header", e))?;
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

    /// Buffer one record.
    pub fn append(&mut self, rec: &PointRecord) {
        self.payload.clear();
        encode_record(rec, &mut self.payload);
        self.buf.extend_from_slice(&REC_MAGIC.to_le_bytes());
        self.buf
            .extend_from_slice(&(self.payload.len() as u32).to_le_bytes());
        self.buf
            .extend_from_slice(&fnv1a(&self.payload).to_le_bytes());
        self.buf.extend_from_slice(&self.payload);
        self.len += (REC_PREFIX + self.payload.len()) as u64;
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
