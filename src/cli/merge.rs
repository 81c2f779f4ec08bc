//! `batstudy merge`: shard files → one results file, checked first, under the output's lock.

#![allow(clippy::result_large_err)] // StudyError: see study/mod.rs

use super::common::{check_replaceable, jobs_or_all, lock_output};
use super::{EXIT_BAD_INPUT, EXIT_OK, EXIT_POINTS_FAILED, EXIT_RUN_FAILED};
use crate::run::ModelSimulator;
use crate::store;
use crate::study;
use crate::study::output::check_output;
use crate::study::output::Existing;
use crate::study::LoadOptions;
use clap::Args;
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct MergeArgs {
    /// The merged results file.
    #[arg(short, long)]
    pub output: PathBuf,
    /// The shard files (every shard of one study, each once).
    #[arg(required = true)]
    pub shards: Vec<PathBuf>,
    /// The study file (default: re-read from the text stored in the shards; give it when
    /// the study uses profile CSV files at paths relative to a study folder that moved).
    #[arg(long)]
    pub study: Option<PathBuf>,
    /// Replace an existing output file.
    #[arg(long)]
    pub force: bool,
    /// Threads for preparing the bats (default: all cores).
    #[arg(short, long)]
    pub jobs: Option<usize>,
    /// No summary on stderr.
    #[arg(short, long)]
    pub quiet: bool,
}

/// `batstudy merge`: re-read the study from the shards' stored text, prepare its bats (as
/// `run` does), check that the shards are one study and hold every point once, then write
/// one complete results file. Exit 2 (nothing written) when refused.
pub(super) fn cmd_merge(a: &MergeArgs) -> i32 {
    let bad = |msg: String| {
        eprintln!("error: {msg}");
        EXIT_BAD_INPUT
    };
    let mut infos = Vec::new();
    for p in &a.shards {
        match store::file_info(p) {
            Ok(i) => infos.push(i),
            Err(e) => return bad(e.to_string()),
        }
    }
    let first = &infos[0];
    for fi in &infos[1..] {
        if fi.layout_version != first.layout_version {
            return bad(format!(
                "cannot merge files of different layout versions: {} has version {}, {} has version {}",
                first.path.display(),
                first.layout_version,
                fi.path.display(),
                fi.layout_version
            ));
        }
        if fi.study_sha256 != first.study_sha256 {
            return bad(format!(
                "cannot merge shards of different studies: {} is study '{}' (study_sha256 {}), {} is study '{}' (study_sha256 {})",
                first.path.display(),
                first.study_name,
                first.study_sha256,
                fi.path.display(),
                fi.study_name,
                fi.study_sha256
            ));
        }
    }
    if first.layout_version != store::layout::LAYOUT_VERSION {
        return bad(format!(
            "{}: layout version {}, this batstudy writes version {}",
            first.path.display(),
            first.layout_version,
            store::layout::LAYOUT_VERSION
        ));
    }
    let existing = if a.force {
        Existing::Overwrite
    } else {
        Existing::Refuse
    };
    let check = || {
        check_output(&a.output, existing).and_then(|()| match a.force {
            true => check_replaceable(&a.output),
            false => Ok(()),
        })
    };
    if let Err((msg, allowed)) = check() {
        return bad(format!("--output: {msg} (allowed: {allowed})"));
    }
    let _lock = match lock_output(&a.output) {
        Ok(l) => l,
        Err((code, message)) => {
            eprintln!("{message}");
            return code;
        }
    };
    if let Err((msg, allowed)) = check() {
        return bad(format!("--output: {msg} (allowed: {allowed})"));
    }
    let jobs = match jobs_or_all(a.jobs, &a.output) {
        Ok(j) => j,
        Err(e) => return bad(e.to_string()),
    };
    // The study, from the text stored in the shards (relative profile CSVs are found next
    // to the stored study path, or next to --study).
    let (text, path) = match &a.study {
        Some(p) => match std::fs::read_to_string(p) {
            Ok(t) => (t, p.clone()),
            Err(e) => return bad(format!("{}: cannot read the study file: {e}", p.display())),
        },
        None => (first.study_yaml.clone(), PathBuf::from(&first.study_path)),
    };
    let study = match study::load_str(
        &text,
        &path,
        &LoadOptions {
            max_points: usize::MAX,
        },
    ) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("{e}");
            eprintln!(
                "(the study text stored in {}; if it names profile CSV files by relative paths, give the study file with --study)",
                first.path.display()
            );
            return EXIT_BAD_INPUT;
        }
    };
    if study.sha256 != first.study_sha256 {
        return bad(format!(
            "{}: this study file (sha256 {}) is not the shards' study '{}' (study_sha256 {})",
            path.display(),
            study.sha256,
            first.study_name,
            first.study_sha256
        ));
    }
    let pool = match crate::run::build_pool(jobs) {
        Ok(p) => p,
        Err(e) => {
            eprintln!("error: {e}");
            return EXIT_RUN_FAILED;
        }
    };
    let bats = crate::run::prepare_bats(&ModelSimulator, &study.plan, &pool);
    let history = study.history_request(bats.max_length());
    let info = study.info(bats.variants, history);
    let store_err = |e: store::StoreError| match e {
        store::StoreError::Io { .. } | store::StoreError::Hdf5 { .. } => {
            eprintln!("error: {e}");
            EXIT_RUN_FAILED
        }
        e => bad(e.to_string()),
    };
    let plan = &study.plan;
    let point_id = |i: usize| plan.point(i).map_or(0, |p| p.id);
    if let Err(e) = store::merge_check(&a.output, &info, &a.shards, &point_id) {
        return store_err(e);
    }
    if let Some(dir) = a.output.parent().filter(|d| !d.as_os_str().is_empty()) {
        if let Err(e) = std::fs::create_dir_all(dir) {
            eprintln!("error: cannot create {}: {e}", dir.display());
            return EXIT_RUN_FAILED;
        }
    }
    let opts = store::StoreOptions {
        force: a.force,
        run_meta: store::RunMeta {
            threads: jobs,
            ..Default::default()
        },
        ..Default::default()
    };
    match store::merge(&a.output, &info, &a.shards, &opts, &point_id) {
        Err(e) => store_err(e),
        Ok(sum) => {
            if !a.quiet {
                eprintln!(
                    "{}: merged {} files: {} points, {} failed",
                    a.output.display(),
                    a.shards.len(),
                    sum.n_done,
                    sum.n_failed
                );
            }
            if sum.n_failed > 0 {
                EXIT_POINTS_FAILED
            } else {
                EXIT_OK
            }
        }
    }
}
