//! The final file's bytes sent to the disk while the run goes on.
//!
//! The placer writes each history into `OUT.h5.partial` as the run goes on
//! (`store::placer`), but the kernel keeps those pages dirty until `Session::finish`
//! fsyncs the file: the whole file then goes to the disk after the last point, on the run's
//! critical path (0.024 s of the bench's 0.22 s modal history study, 28 MiB). Asking the
//! kernel to start writing each few MiB as soon as they are written (`sync_file_range` with
//! `SYNC_FILE_RANGE_WRITE`: it starts the writeback and does not wait for it) lets the disk
//! work while the workers compute, and leaves the final fsync only the last few MiB and
//! the metadata.
//!
//! It is only a hint: durability still comes from the final fsync (and from
//! [`Writeback::sync`] before the journal names chunks in the file, `store::by_reference`), so a failed or
//! unsupported request changes nothing but the time (and is ignored), and other systems
//! than Linux skip it.

use std::fs::File;
use std::path::{Path, PathBuf};

/// Bytes written between two requests: large enough that a request costs nothing next to
/// the writing, small enough that the disk starts early.
pub const STEP_BYTES: usize = 2 << 20;

/// The writeback of one file, started every [`STEP_BYTES`] written.
#[derive(Debug)]
pub struct Writeback {
    path: PathBuf,
    /// Opened at the first request (the file exists by then).
    file: Option<File>,
    /// Bytes written since the last request.
    pending: usize,
}

impl Writeback {
    /// The writeback of the file at `path` (which may not exist yet).
    pub fn new(path: &Path) -> Self {
        Self {
            path: path.to_path_buf(),
            file: None,
            pending: 0,
        }
    }

    /// `bytes` more were written to the file: start the writeback of all that is dirty once
    /// a step's worth has been written since the last start.
    pub fn wrote(&mut self, bytes: usize) {
        self.pending += bytes;
        if self.pending < STEP_BYTES {
            return;
        }
        self.pending = 0;
        if let Ok(f) = self.opened() {
            start_writeback(f);
        }
    }

    /// Make the file's bytes durable (`fdatasync`): before a journal record that names them
    /// is (`store::by_reference`).
    pub fn sync(&mut self) -> std::io::Result<()> {
        self.opened()?.sync_data()
    }

    /// The file, opened at the first request that needs it.
    fn opened(&mut self) -> std::io::Result<&File> {
        if self.file.is_none() {
            self.file = Some(File::open(&self.path)?);
        }
        Ok(self.file.as_ref().expect("opened above"))
    }
}

/// Start writing every dirty page of `f` to the disk, without waiting.
#[cfg(target_os = "linux")]
fn start_writeback(f: &File) {
    use std::os::fd::AsRawFd;
    // SAFETY: a plain system call on an open descriptor; offset 0 and length 0 mean the
    // whole file. The result is ignored on purpose (see the module docs).
    unsafe {
        libc::sync_file_range(f.as_raw_fd(), 0, 0, libc::SYNC_FILE_RANGE_WRITE);
    }
}

#[cfg(not(target_os = "linux"))]
fn start_writeback(_: &File) {}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Write;

    /// Requests on a file that is being written leave its bytes as they were written, and
    /// a file that does not exist is no error (the request is only a hint).
    #[test]
    fn requests_change_nothing_but_timing() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("f.bin");
        let mut missing = Writeback::new(&dir.path().join("missing"));
        missing.wrote(STEP_BYTES);
        let mut f = File::create(&path).unwrap();
        let mut wb = Writeback::new(&path);
        let block: Vec<u8> = (0..STEP_BYTES / 2).map(|i| (i * 7 % 251) as u8).collect();
        for _ in 0..5 {
            f.write_all(&block).unwrap();
            wb.wrote(block.len());
        }
        assert!(wb.file.is_some(), "opened at the first request");
        let back = std::fs::read(&path).unwrap();
        assert_eq!(back.len(), 5 * block.len());
        assert!(back.chunks(block.len()).all(|c| c == block.as_slice()));
    }
}
