//! The operations a user runs, whatever the front end: run a study to a results file (and
//! resume it), search a design, merge shards, export a bat's profile, make the bats'
//! cards. Each takes one checked settings or request value and returns a typed result or
//! an [`OpError`]; progress and notes go to an observer (`run::Observer`). Nothing here
//! parses flags, prints or knows an exit status beyond the one table of endings
//! (`failure::KINDS`): the command line (`cli`), the Python binding and any other front
//! end call this and map the endings their own way.

pub mod bat_files;
pub mod failure;
pub mod files;
pub mod merge;
pub mod optimize;
pub mod run;

pub use bat_files::{cards, cards_of_files, export_profile};
pub use failure::{
    exit_code_of, Kind, KindInfo, OpError, EXIT_BAD_INPUT, EXIT_INTERRUPTED, EXIT_OK,
    EXIT_POINTS_FAILED, EXIT_RUN_FAILED, KINDS,
};
pub use files::{load_checked, load_checked_text, OutputNamed};
pub use merge::{merge_shards, MergeRequest};
pub use optimize::{optimize_study, FinishedSearch, OptimizeRequest};
pub use run::{
    existing_from, outcome_of, outcome_of_failed, run_study, run_with, shard_output, FinishedRun,
    RunRequest, RunSettings,
};
