//! What several commands share: the located output check, loading a study with its exit
//! code, `--jobs`, and the output's lock.

#![allow(clippy::result_large_err)] // StudyError: see study/mod.rs

use super::{EXIT_BAD_INPUT, EXIT_RUN_FAILED};
use crate::store;
use crate::study;
use crate::study::output::check_output;
use crate::study::output::Existing;
use crate::study::LoadOptions;
use crate::study::Study;
use crate::study::StudyError;
use std::path::Path;

pub(super) fn check_output_of(
    study: &Study,
    output: &Path,
    from_cli: bool,
    existing: Existing,
) -> Result<(), StudyError> {
    check_output(output, existing)
        .and_then(|()| match existing {
            Existing::Overwrite => check_replaceable(output),
            _ => Ok(()),
        })
        .map_err(|(msg, allowed)| {
            let e = StudyError::new(&study.path, msg)
                .value(output.display().to_string())
                .allowed(allowed);
            if from_cli {
                e.field("--output")
            } else {
                e.field("output").at(study.position_of("output"))
            }
        })
}

/// A small output named by a flag (`flag`), checked before anything runs
/// (`study::output::check_side_output`): the located error names the flag and the path.
pub(crate) fn side_output_ok(path: &Path, flag: &str, inputs: &[&Path]) -> Result<(), StudyError> {
    crate::study::output::check_side_output(path, inputs).map_err(|(msg, allowed)| {
        StudyError::new(Path::new("batstudy"), msg)
            .field(flag)
            .value(path.display().to_string())
            .allowed(allowed)
    })
}

/// `--force` replaces only batstudy's own results files, never another file a user mistyped
/// the path of. Nothing at the path, or a results file of any study, may be replaced.
pub(super) fn check_replaceable(output: &Path) -> Result<(), (String, String)> {
    if std::fs::symlink_metadata(output).is_err() {
        return Ok(());
    }
    match store::is_results_file(output) {
        Ok(_) => Ok(()),
        Err(e) => Err((
            format!(
                "--force replaces only batstudy's own results files, and this is not one ({e})"
            ),
            "a batstudy results file, or a new path (remove other files yourself)".to_string(),
        )),
    }
}

/// Load a study; on bad input print the located error and give the exit code.
pub(super) fn load_or_report(path: &Path, max_points: usize) -> Result<Study, i32> {
    load_checked(path, max_points).map_err(|e| {
        eprintln!("{e}");
        EXIT_BAD_INPUT
    })
}

/// A study read and checked whole, its `optimize` block included: every command that reads
/// a study (and the Python binding) refuses what `batstudy optimize` would.
pub(super) fn load_checked(path: &Path, max_points: usize) -> Result<Study, StudyError> {
    study::load(path, &LoadOptions { max_points }).and_then(crate::optimize::checked)
}

/// Most worker threads a run may start (without a bound, `-j 100000` would spawn threads
/// until the process ran out of resources). Far above any node's cores.
pub(super) const MAX_JOBS: usize = 4096;
pub(super) use crate::run::MAX_SHARDS;

pub(super) fn jobs_or_all(jobs: Option<usize>, file: &Path) -> Result<usize, StudyError> {
    match jobs {
        Some(j) if !(1..=MAX_JOBS).contains(&j) => Err(StudyError::new(file, "bad --jobs")
            .field("--jobs")
            .value(j.to_string())
            .allowed(format!("a number of threads from 1 to {MAX_JOBS}"))),
        Some(j) => Ok(j),
        None => Ok(std::thread::available_parallelism().map_or(1, |n| n.get())),
    }
}

/// Take the output's lock (`OUT.h5.lock`) before anything of it is touched: a second
/// process on the same output is refused (exit 2) and changes nothing. On failure: the exit
/// code and the message to show.
pub(super) fn lock_output(output: &Path) -> Result<store::lock::OutputLock, (i32, String)> {
    if let Some(dir) = output.parent().filter(|d| !d.as_os_str().is_empty()) {
        if let Err(e) = std::fs::create_dir_all(dir) {
            return Err((
                EXIT_RUN_FAILED,
                format!("error: cannot create {}: {e}", dir.display()),
            ));
        }
    }
    let lock = store::lock::OutputLock::acquire(output).map_err(|e| {
        let code = match e {
            store::lock::LockError::Held { .. } => EXIT_BAD_INPUT,
            store::lock::LockError::Io { .. } => EXIT_RUN_FAILED,
        };
        (code, format!("error: {e}"))
    })?;
    if let Some(w) = lock.warning() {
        eprintln!("warning: {w}");
    }
    Ok(lock)
}
