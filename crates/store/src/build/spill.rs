//! Where a window's records come from: the journal itself (one window), or one spill file
//! per window, split from the journal in a single pass (several windows), so that the
//! journal is read once however many windows the study needs.

use super::grid::BlockGrid;
use crate::error::StoreError;
use crate::journal::{decode_summary, encode_summary, RecordReader, Scan};
use crate::results::PointRecord;
use std::fs::File;
use std::io::{BufReader, BufWriter, Read, Write};
use std::path::{Path, PathBuf};

/// Where a window's records come from.
pub(super) enum Source {
    Journal(RecordReader),
    Spill(SpillReader),
}

impl Source {
    pub(super) fn next(&mut self) -> Result<Option<PointRecord>, StoreError> {
        match self {
            Source::Journal(r) => r.next_summary(),
            Source::Spill(r) => r.next(),
        }
    }
}

/// Path of spill file `k` of the final file `out` (`OUT.h5.partial.spill-K`).
fn spill_path(out: &Path, k: usize) -> PathBuf {
    let mut o = out.as_os_str().to_owned();
    o.push(format!(".spill-{k}"));
    PathBuf::from(o)
}

/// Remove spill files a killed build left next to `out` (best effort).
pub fn remove_stale_spills(out: &Path) {
    let (Some(dir), Some(name)) = (out.parent(), out.file_name()) else {
        return;
    };
    let dir = if dir.as_os_str().is_empty() {
        Path::new(".")
    } else {
        dir
    };
    let prefix = format!("{}.spill-", name.to_string_lossy());
    if let Ok(entries) = std::fs::read_dir(dir) {
        for e in entries.flatten() {
            if e.file_name().to_string_lossy().starts_with(&prefix) {
                let _ = std::fs::remove_file(e.path());
            }
        }
    }
}

/// The journal's summary records split into one file per window by one sequential pass
/// (journal order kept within each file). Removed when dropped.
pub(super) struct Spill {
    paths: Vec<PathBuf>,
}

impl Spill {
    pub(super) fn split(
        journal: &Path,
        scan: &Scan,
        out: &Path,
        blocks: &BlockGrid,
        windows: &[(usize, usize)],
    ) -> Result<Spill, StoreError> {
        let spill = Spill {
            paths: (0..windows.len()).map(|k| spill_path(out, k)).collect(),
        };
        let mut files = Vec::with_capacity(windows.len());
        for p in &spill.paths {
            let f = crate::paths::create_fresh(p, "create a spill file")?;
            files.push(BufWriter::with_capacity(1 << 16, f));
        }
        let n_points = blocks.n_points();
        let mut rr = RecordReader::open(journal, scan)?;
        let mut buf = Vec::new();
        while let Some(rec) = rr.next_summary()? {
            if rec.index >= n_points {
                continue;
            }
            let (b, _) = blocks.locate(rec.index);
            let k = windows.partition_point(|&(b0, _)| b0 <= b) - 1;
            buf.clear();
            encode_summary(&rec, false, &mut buf);
            files[k]
                .write_all(&(buf.len() as u32).to_le_bytes())
                .and_then(|_| files[k].write_all(&buf))
                .map_err(|e| StoreError::io(&spill.paths[k], "write a spill file", e))?;
        }
        for (f, p) in files.into_iter().zip(&spill.paths) {
            f.into_inner()
                .map_err(|e| StoreError::io(p, "write a spill file", e.into_error()))?;
        }
        Ok(spill)
    }

    pub(super) fn reader(&self, k: usize) -> Result<SpillReader, StoreError> {
        let p = &self.paths[k];
        let f = File::open(p).map_err(|e| StoreError::io(p, "open a spill file", e))?;
        Ok(SpillReader {
            r: BufReader::with_capacity(1 << 20, f),
            path: p.clone(),
            buf: Vec::new(),
        })
    }
}

impl Drop for Spill {
    fn drop(&mut self) {
        for p in &self.paths {
            let _ = std::fs::remove_file(p);
        }
    }
}

/// Sequential reading of one spill file.
pub(super) struct SpillReader {
    r: BufReader<File>,
    path: PathBuf,
    buf: Vec<u8>,
}

impl SpillReader {
    fn next(&mut self) -> Result<Option<PointRecord>, StoreError> {
        let mut len = [0u8; 4];
        match self.r.read_exact(&mut len) {
            Ok(()) => {}
            Err(e) if e.kind() == std::io::ErrorKind::UnexpectedEof => return Ok(None),
            Err(e) => return Err(StoreError::io(&self.path, "read a spill file", e)),
        }
        self.buf.resize(u32::from_le_bytes(len) as usize, 0);
        self.r
            .read_exact(&mut self.buf)
            .map_err(|e| StoreError::io(&self.path, "read a spill file", e))?;
        decode_summary(&self.buf)
            .map(|(rec, _)| Some(rec))
            .ok_or_else(|| StoreError::BadRecord {
                path: self.path.clone(),
                what: "undecodable spill record".into(),
            })
    }
}
