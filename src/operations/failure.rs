//! How an operation ends when it is not a plain success, as one table that every front end
//! reads: the command line's exit status, the Python package's exception, and what each
//! means. An operation that did not go through returns an [`OpError`]; one that went
//! through may still end as [`Kind::PointsFailed`] or [`Kind::Interrupted`].

#![allow(clippy::result_large_err)] // StudyError: see study/mod.rs

use crate::study::StudyError;

/// What kind of ending, beyond a plain success.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// Refused before anything was written: a study, a flag, an input file.
    BadInput,
    /// Went through, and some points failed (their messages are stored in `/errors`).
    PointsFailed,
    /// The operation itself failed midway (I/O); what was finished is kept.
    RunFailed,
    /// Stopped early by the caller's stop flag (Ctrl-C); it can be resumed.
    Interrupted,
}

/// One row of [`KINDS`].
#[derive(Debug, Clone, Copy)]
pub struct KindInfo {
    pub kind: Kind,
    /// Its name, as front ends spell it.
    pub name: &'static str,
    /// The command line's exit status.
    pub exit_code: i32,
    /// The Python package's exception (a warning for failed points).
    pub python: &'static str,
    pub meaning: &'static str,
}

/// The command line's exit statuses: a plain success, then one per [`Kind`] (as [`KINDS`]
/// gives them).
pub const EXIT_OK: i32 = 0;
pub const EXIT_POINTS_FAILED: i32 = 1;
pub const EXIT_BAD_INPUT: i32 = 2;
pub const EXIT_RUN_FAILED: i32 = 3;
pub const EXIT_INTERRUPTED: i32 = 130;

/// Every kind, once: docs/python.md and the README's "Exit codes" state this table.
pub const KINDS: [KindInfo; 4] = [
    KindInfo {
        kind: Kind::PointsFailed,
        name: "points_failed",
        exit_code: EXIT_POINTS_FAILED,
        python: "RuntimeWarning",
        meaning: "the results are written; some points failed (their messages are in /errors)",
    },
    KindInfo {
        kind: Kind::BadInput,
        name: "bad_input",
        exit_code: EXIT_BAD_INPUT,
        python: "StudyError",
        meaning: "refused before anything was written; the message names the file, line, \
                  field, value and what is allowed",
    },
    KindInfo {
        kind: Kind::RunFailed,
        name: "run_failed",
        exit_code: EXIT_RUN_FAILED,
        python: "RunError",
        meaning: "the run itself failed (I/O); the finished points are kept and the message \
                  says how to resume",
    },
    KindInfo {
        kind: Kind::Interrupted,
        name: "interrupted",
        exit_code: EXIT_INTERRUPTED,
        python: "KeyboardInterrupt",
        meaning: "stopped early (Ctrl-C); everything finished is written and resume finishes it",
    },
];

impl Kind {
    pub fn info(self) -> &'static KindInfo {
        KINDS
            .iter()
            .find(|k| k.kind == self)
            .expect("every kind has its row")
    }

    pub fn exit_code(self) -> i32 {
        self.info().exit_code
    }
}

/// The exit status of an ending: 0 for a plain success.
pub fn exit_code_of(kind: Option<Kind>) -> i32 {
    kind.map_or(EXIT_OK, Kind::exit_code)
}

/// Why an operation did not go through.
#[derive(Debug, thiserror::Error)]
pub enum OpError {
    /// Bad input with its position (file, line, field, value, what is allowed).
    #[error("{0}")]
    Study(Box<StudyError>),
    /// Bad input that has no place in a study (a held lock, shards of two studies); the
    /// message names what was refused.
    #[error("{0}")]
    BadInput(String),
    /// The operation failed midway (I/O); the message says what is kept and how to go on.
    #[error("{0}")]
    RunFailed(String),
}

impl OpError {
    pub fn kind(&self) -> Kind {
        match self {
            OpError::Study(_) | OpError::BadInput(_) => Kind::BadInput,
            OpError::RunFailed(_) => Kind::RunFailed,
        }
    }

    pub fn exit_code(&self) -> i32 {
        self.kind().exit_code()
    }

    /// An I/O failure, its message prefixed as the command line prints it.
    pub(crate) fn io(message: impl std::fmt::Display) -> OpError {
        OpError::RunFailed(format!("error: {message}"))
    }

    /// Bad input without a study position, prefixed as the command line prints it.
    pub(crate) fn refused(message: impl std::fmt::Display) -> OpError {
        OpError::BadInput(format!("error: {message}"))
    }
}

impl From<StudyError> for OpError {
    fn from(e: StudyError) -> Self {
        OpError::Study(Box::new(e))
    }
}
