//! `batstudy run`: flags → a `RunRequest` → `operations::run_study`, its report on stderr
//! and its exit status.

use super::common::{program, stop_on_ctrl_c};
use super::progress::TerminalBar;
use crate::operations::{self, existing_from, exit_code_of, RunRequest, RunSettings};
use crate::run::{Shard, SharedObserver};
use crate::study::DEFAULT_MAX_POINTS;
use clap::Args;
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct RunArgs {
    /// The study file (YAML).
    pub study: PathBuf,
    /// Output file (default: the study's `output`, else results/<name>.h5).
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    /// Worker threads (default: all cores).
    #[arg(short, long)]
    pub jobs: Option<usize>,
    /// Continue an interrupted run in the same output file (only missing points run).
    #[arg(long, conflicts_with = "force")]
    pub resume: bool,
    /// Replace an existing output file.
    #[arg(long)]
    pub force: bool,
    /// Stop at the first failed point.
    #[arg(long)]
    pub fail_fast: bool,
    /// No progress bar and no summary on stderr.
    #[arg(short, long)]
    pub quiet: bool,
    /// Largest number of points allowed.
    #[arg(long, default_value_t = DEFAULT_MAX_POINTS)]
    pub max_points: usize,
    /// Run the I-th of N disjoint subsets of the points (1 <= I <= N), e.g. 2/8.
    #[arg(long)]
    pub shard: Option<Shard>,
}

impl RunArgs {
    fn request(&self) -> RunRequest {
        RunRequest {
            output: self.output.clone(),
            jobs: self.jobs,
            existing: existing_from(self.resume, self.force),
            fail_fast: self.fail_fast,
            shard: self.shard,
            program: program(),
        }
    }
}

pub(super) fn cmd_run(a: &RunArgs) -> i32 {
    let stop = stop_on_ctrl_c("finishing the points in flight");
    // the optimize block too: a file `validate` refuses is refused here
    let settings = operations::load_checked(&a.study, a.max_points)
        .and_then(|study| RunSettings::new(study, &a.request()));
    let settings = match settings {
        Ok(s) => s,
        Err(e) => {
            eprintln!("{e}");
            return operations::EXIT_BAD_INPUT;
        }
    };
    let bar = SharedObserver::new(TerminalBar::new(!a.quiet, "points"));
    match operations::run_study(settings, &stop, bar) {
        Err(e) => {
            eprintln!("{e}");
            e.exit_code()
        }
        Ok(done) => {
            if !a.quiet {
                eprint!("{}", done.report_text());
            }
            exit_code_of(done.outcome())
        }
    }
}
