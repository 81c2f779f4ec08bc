//! The files next to an output `OUT.h5`: its journal `OUT.h5.journal`, the file being
//! finished `OUT.h5.partial` (the build's spill files are `OUT.h5.partial.spill-K`), and an
//! interrupted run's `OUT.h5.partial` set aside for the resume as `OUT.h5.partial.prev`
//! (its journal may name history chunks in it: `store::by_reference`).

use super::error::StoreError;
use std::path::{Path, PathBuf};

/// Path of the journal next to `out`.
pub fn journal_path(out: &Path) -> PathBuf {
    with_suffix(out, ".journal")
}

/// Path of the file being finished next to `out`.
pub fn partial_path(out: &Path) -> PathBuf {
    with_suffix(out, ".partial")
}

/// Path of an interrupted run's file being finished, set aside for the resume.
pub fn previous_partial_path(out: &Path) -> PathBuf {
    with_suffix(out, ".partial.prev")
}

/// Make way for a new `OUT.h5.partial`: one left by an interrupted run is set aside as
/// `OUT.h5.partial.prev` when the run left a journal, which may name history chunks in it,
/// and there is no set-aside file yet (one there already is the file of the run that wrote
/// the journal: only a run's own fresh journal names chunks in its file, and a resume that
/// was itself interrupted left its own `OUT.h5.partial`, which nothing names). Otherwise it
/// is removed. A symbolic link is moved or removed, never followed.
pub fn set_aside_partial(out: &Path) -> Result<(), StoreError> {
    let (partial, prev) = (partial_path(out), previous_partial_path(out));
    let exists = |p: &Path| p.symlink_metadata().is_ok();
    if exists(&journal_path(out)) && exists(&partial) && !exists(&prev) {
        return std::fs::rename(&partial, &prev)
            .map_err(|e| StoreError::io(&partial, "set aside the unfinished file", e));
    }
    remove_if_exists(&partial)
}

fn with_suffix(p: &Path, s: &str) -> PathBuf {
    let mut o = p.as_os_str().to_owned();
    o.push(s);
    PathBuf::from(o)
}

/// Remove `p`; a file that is not there is not an error.
pub fn remove_if_exists(p: &Path) -> Result<(), StoreError> {
    match std::fs::remove_file(p) {
        Ok(()) => Ok(()),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(()),
        Err(e) => Err(StoreError::io(p, "remove", e)),
    }
}

/// Create `p` afresh for writing: whatever is there (a stale file, or a symbolic link
/// planted in a shared folder) is removed, not followed, and the new file is created
/// exclusively (`O_EXCL` follows no link), so no file outside the output is ever written.
pub fn create_fresh(p: &Path, what: &str) -> Result<std::fs::File, StoreError> {
    remove_if_exists(p)?;
    std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(p)
        .map_err(|e| StoreError::io(p, what, e))
}

/// Remove a finished output, its journal and an interrupted run's set-aside file, for a
/// run that replaces them (`--force`). The run does this while it prepares its bats (issue
/// 22: unlinking a 92 MiB file took 56 ms, before the first point); opening the store would
/// do it otherwise.
pub fn discard_output(path: &Path) -> Result<(), StoreError> {
    remove_if_exists(path)?;
    remove_if_exists(&journal_path(path))?;
    remove_if_exists(&previous_partial_path(path))
}
