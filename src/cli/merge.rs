//! `batstudy merge`: flags → a `MergeRequest` → `operations::merge_shards`, its summary on
//! stderr and its exit status.

use super::progress::TerminalBar;
use crate::operations::{self, exit_code_of, MergeRequest};
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

pub(super) fn cmd_merge(a: &MergeArgs) -> i32 {
    let request = MergeRequest {
        output: a.output.clone(),
        shards: a.shards.clone(),
        study: a.study.clone(),
        force: a.force,
        jobs: a.jobs,
    };
    match operations::merge_shards(&request, &TerminalBar::new(false, "points")) {
        Err(e) => {
            eprintln!("{e}");
            e.exit_code()
        }
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
            exit_code_of(operations::outcome_of_failed(sum.n_failed))
        }
    }
}
