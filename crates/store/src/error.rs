//! Store errors: each names the file and what is wrong.

use std::path::{Path, PathBuf};

#[derive(Debug, thiserror::Error)]
pub enum StoreError {
    #[error("{}: cannot {what}: {source}", path.display())]
    Io {
        path: PathBuf,
        what: String,
        source: std::io::Error,
    },
    #[error("{}: HDF5 error while trying to {what}: {source}", path.display())]
    Hdf5 {
        path: PathBuf,
        what: String,
        source: hdf5::Error,
    },
    #[error("{}: output already exists; use --resume to continue it or --force to overwrite it", path.display())]
    Exists { path: PathBuf },
    #[error("{}: cannot resume: {what}", path.display())]
    WrongStudy { path: PathBuf, what: String },
    #[error("{}: cannot merge: {what}", path.display())]
    CannotMerge { path: PathBuf, what: String },
    #[error(
        "{}: damaged journal: {what}; what it holds cannot be resumed: --force starts the output over",
        path.display()
    )]
    BadJournal { path: PathBuf, what: String },
    #[error("{}: not a batstudy results file: {what}", path.display())]
    BadFile { path: PathBuf, what: String },
    #[error("{}: rejected point record: {what}", path.display())]
    BadRecord { path: PathBuf, what: String },
    /// A file begun by `store::begin` handed to a session it was not begun for (a caller's
    /// mistake, not the user's).
    #[error("{}: the results file begun for this run does not match it: {what}", path.display())]
    BegunMismatch { path: PathBuf, what: String },
}

impl StoreError {
    /// Whether the error is the input's (an output that exists, a journal or file of
    /// another study, a damaged journal: exit status 2, nothing written) rather than the
    /// run's (I/O, HDF5: exit status 3).
    pub fn is_bad_input(&self) -> bool {
        matches!(
            self,
            StoreError::Exists { .. }
                | StoreError::WrongStudy { .. }
                | StoreError::CannotMerge { .. }
                | StoreError::BadJournal { .. }
                | StoreError::BadFile { .. }
        )
    }

    pub fn io(path: &Path, what: &str, source: std::io::Error) -> Self {
        StoreError::Io {
            path: path.to_path_buf(),
            what: what.to_string(),
            source,
        }
    }
}

/// Attach a file and an action to an HDF5 result.
pub(crate) trait H5Ctx<T> {
    fn ctx(self, path: &Path, what: &str) -> Result<T, StoreError>;
    /// [`Self::ctx`] with the action made only on failure (a chunk written per history
    /// variable would otherwise name its dataset for every write).
    fn ctx_with(self, path: &Path, what: impl FnOnce() -> String) -> Result<T, StoreError>;
}

impl<T> H5Ctx<T> for hdf5::Result<T> {
    fn ctx(self, path: &Path, what: &str) -> Result<T, StoreError> {
        self.ctx_with(path, || what.to_string())
    }

    fn ctx_with(self, path: &Path, what: impl FnOnce() -> String) -> Result<T, StoreError> {
        self.map_err(|source| StoreError::Hdf5 {
            path: path.to_path_buf(),
            what: what(),
            source,
        })
    }
}
