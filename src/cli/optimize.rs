//! `batstudy optimize`: flags → an `OptimizeRequest` → `operations::optimize_study`, its
//! report on stderr and its exit status.

use super::common::{program, stop_on_ctrl_c};
use super::progress::TerminalBar;
use crate::operations::{self, exit_code_of, OptimizeRequest, EXIT_BAD_INPUT};
use crate::run::SharedObserver;
use crate::study::DEFAULT_MAX_POINTS;
use clap::Args;
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct OptimizeArgs {
    /// The study file (YAML) with an `optimize` block.
    pub study: PathBuf,
    /// Output file (default: the study's `output`, else results/<name>.h5).
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    /// Worker threads (default: all cores).
    #[arg(short, long)]
    pub jobs: Option<usize>,
    /// Continue an interrupted search (its candidates are replayed from OUT.h5.optimize).
    #[arg(long, conflicts_with = "force")]
    pub resume: bool,
    /// Replace an existing output file and start the search over.
    #[arg(long)]
    pub force: bool,
    /// No report on stderr.
    #[arg(short, long)]
    pub quiet: bool,
    /// Largest number of points of the study's grid.
    #[arg(long, default_value_t = DEFAULT_MAX_POINTS)]
    pub max_points: usize,
}

impl OptimizeArgs {
    fn request(&self) -> OptimizeRequest {
        OptimizeRequest {
            study: self.study.clone(),
            output: self.output.clone(),
            jobs: self.jobs,
            resume: self.resume,
            force: self.force,
            max_points: self.max_points,
            program: program(),
        }
    }
}

pub(super) fn cmd_optimize(a: &OptimizeArgs) -> i32 {
    let stop = stop_on_ctrl_c("finishing the candidate in flight");
    let study = match operations::load_checked(&a.study, a.max_points) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("{e}");
            return EXIT_BAD_INPUT;
        }
    };
    let request = a.request();
    let bar = SharedObserver::new(TerminalBar::new(!a.quiet, "candidates"));
    match operations::optimize_study(study, &request, &stop, bar) {
        Err(e) => {
            eprintln!("{e}");
            e.exit_code()
        }
        Ok(done) => {
            if !a.quiet {
                eprint!("{}", operations::optimize::report_text(&done, &request));
            }
            if let Some(m) = done.no_answer() {
                eprintln!("{m}");
            }
            exit_code_of(done.outcome())
        }
    }
}
