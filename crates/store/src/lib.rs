//! The HDF5 results store (docs/layout.md): one study → one self-describing HDF5 file.
//!
//! Crash safety: finished points are appended to `OUT.h5.journal` (checksummed records,
//! handed to the OS every 50 ms and fsync'd every second); the journal is the source of truth
//! while a run is in progress. The histories the placer has written into `OUT.h5.partial` are
//! journalled by where they are there, each chunk with its checksum ([`by_reference`]).
//! [`Session::finish`] completes `OUT.h5.partial` from the journal, fsyncs it, renames it to
//! `OUT.h5` and only then removes the journal. A run killed at any moment therefore leaves
//! either a journal (whose torn tail, if any, is dropped on resume; the chunks it names are
//! read back from the killed run's file and checked) or a finished file; `--resume` continues
//! from the journal, or from the finished file's records when no journal is left. The final file's data depend only on the set of records, never on
//! their order or on interruptions, so a resumed run's data equal an uninterrupted run's.
//!
//! Modules, from the bottom up: [`layout`] (names, units), [`error`], [`header`] (what
//! identifies a study's journal and file), [`record`] (a journal record's payload: summaries and history chunks), [`journal`] (the append-only record file),
//! [`dimscale`] (HDF5 dimension scales and helpers), [`chunks`] (chunks compressed in
//! parallel), [`modal`] (the displacement's modal form cut into chunks), [`encode`] (points as journal records, made on the workers), [`gather`] (points handed over one by one gathered into their groups), [`options`] (what the caller passes and gets back), [`paths`] (the files next
//! to an output), [`read`] (reading back), [`check`] (a file's structure checked before HDF5 reads it), [`inspect`] (a file described for a person), [`build`] (journal → HDF5),
//! [`by_reference`] (histories journalled by their place in the file), [`session`] (an open
//! output), [`writeback`] (the final file sent to the disk as it is
//! written), [`merge`](mod@merge) (shards → one file), [`lock`] (one
//! process per output).

mod answers;
pub mod build;
pub mod by_reference;
pub mod card;
pub mod check;
pub mod chunks;
pub mod dimscale;
pub mod direct;
pub mod encode;
pub mod error;
pub mod fixed_deflate;
pub mod gather;
pub mod header;
pub mod inspect;
pub mod journal;
pub mod layout;
pub mod lock;
pub mod merge;
pub mod modal;
pub mod optimize;
pub mod options;
pub mod paths;
pub mod placer;
pub mod pointset;
pub mod read;
pub mod record;
pub mod results;
pub mod run_huffman;
pub mod session;
pub mod shuffle;
pub mod writeback;

pub use encode::{EncodedRecord, RecordEncoder};
pub use error::StoreError;
pub use inspect::inspect;
pub use merge::{merge, merge_check};
pub use options::{iso8601_now, RunMeta, StoreOptions, Summary};
pub use paths::{discard_output, journal_path, partial_path};
pub use read::{
    file_info, for_each_record, is_results_file, present_points, read_results, FileInfo, ReadBack,
};
pub use session::{begin, check_resumable, open, open_begun, BegunFile, Session};
