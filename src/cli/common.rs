//! What several commands share: loading a study with its exit status, the resume command's
//! program name, and Ctrl-C.

use super::EXIT_BAD_INPUT;
use crate::operations;
use crate::study::Study;
use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

pub(super) use crate::operations::files::{check_output_of, side_output_ok, MAX_JOBS};
pub(super) use crate::run::MAX_SHARDS;

/// Load a study; on bad input print the located error and give the exit code.
pub(super) fn load_or_report(path: &Path, max_points: usize) -> Result<Study, i32> {
    operations::load_checked(path, max_points).map_err(|e| {
        eprintln!("{e}");
        EXIT_BAD_INPUT
    })
}

/// The words that started this process, for the resume commands a message suggests.
pub(super) fn program() -> String {
    std::env::args().next().unwrap_or_else(|| "batstudy".into())
}

/// A stop flag the first Ctrl-C sets (the work in flight finishes: `finishing`); a second
/// Ctrl-C exits at once.
pub(super) fn stop_on_ctrl_c(finishing: &'static str) -> Arc<AtomicBool> {
    let stop = Arc::new(AtomicBool::new(false));
    let flag = Arc::clone(&stop);
    let _ = ctrlc::set_handler(move || {
        if flag.swap(true, Ordering::SeqCst) {
            eprintln!("\nsecond interrupt: exiting now (resume with --resume)");
            std::process::exit(super::EXIT_INTERRUPTED);
        }
        eprintln!("\ninterrupt: {finishing}…");
    });
    stop
}
