//! Merge shard files (`run --shard I/N`) into one results file: checked first, under the
//! output's lock, bit for bit the file one process would have written.

#![allow(clippy::result_large_err)] // StudyError: see study/mod.rs

use super::failure::OpError;
use super::files::{check_replaceable, jobs_or_all, lock_output};
use crate::run::{ModelSimulator, Observer};
use crate::store;
use crate::study;
use crate::study::output::check_output;
use crate::study::output::Existing;
use crate::study::LoadOptions;
use crate::study::Study;
use std::path::PathBuf;

/// What a caller asks of a merge.
#[derive(Debug, Clone)]
pub struct MergeRequest {
    /// The merged results file.
    pub output: PathBuf,
    /// The shard files (every shard of one study, each once).
    pub shards: Vec<PathBuf>,
    /// The study file (None: re-read from the text stored in the shards; needed when the
    /// study names profile CSV files by paths relative to a study folder that moved).
    pub study: Option<PathBuf>,
    /// Replace an existing output file.
    pub force: bool,
    /// Threads for preparing the bats (None: every core).
    pub jobs: Option<usize>,
}

fn bad(msg: String) -> OpError {
    OpError::refused(msg)
}

fn failed(msg: String) -> OpError {
    OpError::io(msg)
}

/// Merge the shards: re-read the study from the shards' stored text, prepare its bats (as
/// `run` does), check that the shards are one study and hold every point once with its own
/// id, then write one complete results file. Refused (bad input): nothing written.
pub fn merge_shards(a: &MergeRequest, observer: &dyn Observer) -> Result<store::Summary, OpError> {
    if a.shards.is_empty() {
        return Err(bad("no shard files given".into()));
    }
    let first = shards_of_one_study(&a.shards)?;
    let existing = match a.force {
        true => Existing::Overwrite,
        false => Existing::Refuse,
    };
    let check = || {
        check_output(&a.output, existing)
            .and_then(|()| match a.force {
                true => check_replaceable(&a.output),
                false => Ok(()),
            })
            .map_err(|(msg, allowed)| bad(format!("--output: {msg} (allowed: {allowed})")))
    };
    check()?;
    let _lock = lock_output(&a.output, observer)?;
    check()?; // again under the lock: another process may have written it meanwhile
    let jobs = jobs_or_all(a.jobs, &a.output).map_err(|e| bad(e.to_string()))?;
    let study = the_shards_study(a, &first)?;
    let pool = crate::run::build_pool(jobs).map_err(|e| failed(e.to_string()))?;
    let bats = crate::run::prepare_bats(&ModelSimulator, &study.plan, &pool);
    let history = study.history_request(bats.max_length());
    let info = study.info(bats.variants, history);
    let store_err = |e: store::StoreError| match e.is_bad_input() {
        true => bad(e.to_string()),
        false => failed(e.to_string()),
    };
    let plan = &study.plan;
    let point_id = |i: usize| plan.point(i).map_or(0, |p| p.id);
    store::merge_check(&a.output, &info, &a.shards, &point_id).map_err(store_err)?;
    if let Some(dir) = a.output.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)
            .map_err(|e| failed(format!("cannot create {}: {e}", dir.display())))?;
    }
    let opts = store::StoreOptions {
        force: a.force,
        run_meta: store::RunMeta {
            threads: jobs,
            ..Default::default()
        },
        ..Default::default()
    };
    store::merge(&a.output, &info, &a.shards, &opts, &point_id).map_err(store_err)
}

/// Every shard readable, of one layout version and one study (by its sha256); returns the
/// first one's description.
fn shards_of_one_study(shards: &[PathBuf]) -> Result<store::FileInfo, OpError> {
    let mut infos = Vec::new();
    for p in shards {
        infos.push(store::file_info(p).map_err(|e| bad(e.to_string()))?);
    }
    let first = infos.swap_remove(0);
    for fi in &infos {
        if fi.layout_version != first.layout_version {
            return Err(bad(format!(
                "cannot merge files of different layout versions: {} has version {}, {} has version {}",
                first.path.display(),
                first.layout_version,
                fi.path.display(),
                fi.layout_version
            )));
        }
        if fi.study_sha256 != first.study_sha256 {
            return Err(bad(format!(
                "cannot merge shards of different studies: {} is study '{}' (study_sha256 {}), {} is study '{}' (study_sha256 {})",
                first.path.display(),
                first.study_name,
                first.study_sha256,
                fi.path.display(),
                fi.study_name,
                fi.study_sha256
            )));
        }
    }
    if first.layout_version != store::layout::LAYOUT_VERSION {
        return Err(bad(format!(
            "{}: layout version {}, this batstudy writes version {}",
            first.path.display(),
            first.layout_version,
            store::layout::LAYOUT_VERSION
        )));
    }
    Ok(first)
}

/// The study, from the text stored in the shards (relative profile CSVs are found next to
/// the stored study path, or next to `--study`), which must be the shards' own (its
/// sha256 is the one they were run with: a shard's stored text cannot be swapped).
fn the_shards_study(a: &MergeRequest, first: &store::FileInfo) -> Result<Study, OpError> {
    let (text, path) = match &a.study {
        Some(p) => match std::fs::read_to_string(p) {
            Ok(t) => (t, p.clone()),
            Err(e) => {
                return Err(bad(format!(
                    "{}: cannot read the study file: {e}",
                    p.display()
                )))
            }
        },
        None => (first.study_yaml.clone(), PathBuf::from(&first.study_path)),
    };
    let opts = LoadOptions {
        max_points: usize::MAX,
    };
    let study = study::load_str(&text, &path, &opts).map_err(|e| {
        OpError::BadInput(format!(
            "{e}\n(the study text stored in {}; if it names profile CSV files by relative paths, give the study file with --study)",
            first.path.display()
        ))
    })?;
    if study.sha256 != first.study_sha256 {
        return Err(bad(format!(
            "{}: this study (sha256 {}) is not the shards' study '{}' (study_sha256 {})",
            path.display(),
            study.sha256,
            first.study_name,
            first.study_sha256
        )));
    }
    Ok(study)
}
