//! What the operations share about their inputs and outputs: a study read and checked
//! whole, the located output check, `jobs`, and the output's lock.

#![allow(clippy::result_large_err)] // StudyError: see study/mod.rs

use super::failure::OpError;
use crate::run::Observer;
use crate::store;
use crate::study;
use crate::study::output::check_output;
use crate::study::output::Existing;
use crate::study::LoadOptions;
use crate::study::Study;
use crate::study::StudyError;
use std::path::Path;

/// Where a study's output was named: on the caller's side (a flag, a Python argument), or
/// in the study file (its `output` field, located in messages).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OutputNamed {
    ByCaller,
    ByStudy,
}

impl OutputNamed {
    pub fn of(given: bool) -> Self {
        match given {
            true => OutputNamed::ByCaller,
            false => OutputNamed::ByStudy,
        }
    }
}

/// A results file may be written at `output` as `existing` says: the located error.
pub fn check_output_of(
    study: &Study,
    output: &Path,
    named: OutputNamed,
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
            match named {
                OutputNamed::ByCaller => e.field("--output"),
                OutputNamed::ByStudy => e.field("output").at(study.position_of("output")),
            }
        })
}

/// A small output named by a flag (`flag`), checked before anything runs
/// (`study::output::check_side_output`): the located error names the flag and the path.
pub fn side_output_ok(path: &Path, flag: &str, inputs: &[&Path]) -> Result<(), StudyError> {
    crate::study::output::check_side_output(path, inputs).map_err(|(msg, allowed)| {
        StudyError::new(Path::new("batstudy"), msg)
            .field(flag)
            .value(path.display().to_string())
            .allowed(allowed)
    })
}

/// Replacing (`force`) takes only batstudy's own results files, never another file a user
/// mistyped the path of. Nothing at the path, or a results file of any study, may be
/// replaced.
pub fn check_replaceable(output: &Path) -> Result<(), (String, String)> {
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

/// A study read and checked whole, its `optimize` block included: every front end refuses
/// what a design search would.
pub fn load_checked(path: &Path, max_points: usize) -> Result<Study, StudyError> {
    study::load(path, &LoadOptions { max_points }).and_then(crate::optimize::checked)
}

/// [`load_checked`] for a study given as text (`name` stands for it in messages; relative
/// profile paths are taken from the working folder).
pub fn load_checked_text(text: &str, name: &Path, max_points: usize) -> Result<Study, StudyError> {
    study::load_str(text, name, &LoadOptions { max_points }).and_then(crate::optimize::checked)
}

/// Most worker threads a run may start (without a bound, `-j 100000` would spawn threads
/// until the process ran out of resources). Far above any node's cores.
pub const MAX_JOBS: usize = 4096;

/// Worker threads: the asked number checked, or every core.
pub fn jobs_or_all(jobs: Option<usize>, file: &Path) -> Result<usize, StudyError> {
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
/// process on the same output is refused (bad input) and changes nothing.
pub fn lock_output(
    output: &Path,
    observer: &dyn Observer,
) -> Result<store::lock::OutputLock, OpError> {
    if let Some(dir) = output.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)
            .map_err(|e| OpError::io(format!("cannot create {}: {e}", dir.display())))?;
    }
    let lock = store::lock::OutputLock::acquire(output).map_err(|e| match e {
        store::lock::LockError::Held { .. } => OpError::refused(&e),
        store::lock::LockError::Io { .. } => OpError::io(&e),
    })?;
    if let Some(w) = lock.warning() {
        observer.note(&format!("warning: {w}"));
    }
    Ok(lock)
}
