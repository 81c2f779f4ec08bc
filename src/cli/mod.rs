//! The command line: a thin layer over the library's `operations`. Each command has its
//! own module (`run`, `plan`, `validate`, `merge`, `slurm`, `optimize`, `export-profile`,
//! `card`, `compare`, `fly`; `inspect`, `schema` and `bench` are one call each, below); its
//! raw flags become one request value, checked before anything runs or is written, then
//! one library call whose result is printed and whose ending becomes the exit status
//! (`operations::KINDS`: 0 all points ok, 1 some points failed (results written), 2 bad
//! input (message on stderr, nothing written), 3 a failure of the run itself (I/O), 130
//! interrupted (Ctrl-C; resume with `--resume`)). `progress` draws a run's bar; `common`
//! holds what several commands share.

#![allow(clippy::result_large_err)] // StudyError: see study/mod.rs

use crate::store;
use crate::study::{self, DEFAULT_MAX_POINTS};
use clap::{Parser, Subcommand};
use std::path::PathBuf;

pub mod card;
mod common;
pub mod export;
pub mod fly;
pub mod lab;
pub mod merge;
pub mod optimize;
pub mod plan;
mod progress;
pub mod run;
pub mod slurm;
pub mod validate;

pub use crate::operations::{
    EXIT_BAD_INPUT, EXIT_INTERRUPTED, EXIT_OK, EXIT_POINTS_FAILED, EXIT_RUN_FAILED,
};
pub use merge::MergeArgs;
pub use plan::PlanArgs;
pub use run::RunArgs;
pub use slurm::SlurmArgs;

#[derive(Debug, Parser)]
#[command(
    name = "batstudy",
    version,
    about = "Baseball bat–ball collision parameter studies"
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Run a study: simulate every point on all cores into one HDF5 file.
    Run(RunArgs),
    /// Show what a study expands to: points, axes, estimated run time and output size.
    Plan(PlanArgs),
    /// Check study files without running them.
    Validate {
        /// Study files.
        #[arg(required = true)]
        studies: Vec<PathBuf>,
        /// Largest number of points allowed.
        #[arg(long, default_value_t = DEFAULT_MAX_POINTS)]
        max_points: usize,
    },
    /// Print the JSON Schema of study files.
    Schema,
    /// Show what a results file holds.
    Inspect {
        /// A results file.
        file: PathBuf,
    },
    /// Measure what this machine does: points/s by thread count, parallel efficiency, the
    /// writer's and the disk's headroom, peak memory.
    Bench {
        /// Shrink every case (a few seconds; for tests).
        #[arg(long)]
        quick: bool,
        /// Thread counts to measure, e.g. `1,4,16` (default: 1, 2, 4, … up to every core).
        #[arg(long, value_delimiter = ',', value_name = "LIST")]
        threads: Vec<usize>,
        /// Write the results files and the disk probe under this directory (default: the
        /// system's temporary directory): put it on the disk your studies write to.
        #[arg(long, value_name = "DIR")]
        dir: Option<PathBuf>,
        /// Also write the figures as JSON to this file.
        #[arg(long)]
        json: Option<PathBuf>,
    },
    /// Merge shard files (`run --shard I/N`) into one results file.
    Merge(MergeArgs),
    /// Write Slurm job scripts: an array of shards and a merge job that depends on it.
    Slurm(SlurmArgs),
    /// Search a study's design (its `optimize` block) within its rules; store every
    /// candidate in `/optimize` and the study at the best design.
    Optimize(optimize::OptimizeArgs),
    /// Write a bat of a results file as a profile CSV (outer diameter and wall along the bat,
    /// in m, mm or in) that `bat.profile.csv` reads back as the same bat.
    ExportProfile(export::ExportArgs),
    /// Each bat of a results file as the trade states it: length, weight and drop, balance
    /// point, swing weights, BBCOR with its ball, sweet zone, bending and hoop frequencies,
    /// and the margin to each rule.
    Card(card::CardArgs),
    /// Every bat of one or more results files in one table, a row per bat, in the trade's
    /// units (oz, in, oz in^2): weight and drop, balance point, swing weights, diameter,
    /// BBCOR, sweet zone, bending and hoop frequencies, the rules kept of those for the bat.
    Compare(card::CompareArgs),
    /// One batted ball's flight on its own, as Nathan's trajectory calculator takes it: exit
    /// speed, launch angle, spin and the air (SI, or with a unit: `100mph`, `28deg`,
    /// `2500rpm`, `3ft`, `70F`); prints the carry, apex and hang time, and writes the
    /// trajectory as a CSV with `--trajectory`.
    Fly(fly::FlyArgs),
    /// The bat lab: a local web page where a bat is shaped and hit live (its profile's
    /// knots dragged, its material, ball, pitch and swing set), with the exit speed along
    /// the barrel, BBCOR and the rules, and the bat's card, computed by this library.
    /// Prints the URL to open (127.0.0.1 only, with a random access token).
    Lab(lab::LabArgs),
}

/// How this process was started, for what it writes that starts batstudy again (the Slurm
/// scripts). The binary leaves it empty: it is `current_exe()`. The Python wheel's command
/// gives its own (the installed `batstudy` script, or `python -m batstudy`): there,
/// `current_exe()` is the Python interpreter.
#[derive(Debug, Clone, Default)]
pub struct Invocation {
    /// The words that run batstudy (None: this executable's path).
    pub command: Option<Vec<String>>,
}

/// Parse the process's arguments and run; returns the exit code.
pub fn main_exit_code() -> i32 {
    main_exit_code_from(std::env::args_os())
}

/// Parse `args` (the program name first) and run; returns the exit code. The Python
/// package's `batstudy` command calls this with its own argv.
pub fn main_exit_code_from<I, T>(args: I) -> i32
where
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    main_exit_code_as(args, &Invocation::default())
}

/// [`main_exit_code_from`], started as `invocation` says.
pub fn main_exit_code_as<I, T>(args: I, invocation: &Invocation) -> i32
where
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    let cli = match Cli::try_parse_from(args) {
        Ok(c) => c,
        Err(e) => {
            let _ = e.print();
            return if e.use_stderr() {
                EXIT_BAD_INPUT
            } else {
                EXIT_OK
            };
        }
    };
    run_command(cli.command, invocation)
}

/// Run one subcommand; returns the exit code.
pub fn run_command(cmd: Command, invocation: &Invocation) -> i32 {
    match cmd {
        Command::Run(a) => run::cmd_run(&a),
        Command::Plan(a) => plan::cmd_plan(&a),
        Command::Validate {
            studies,
            max_points,
        } => validate::cmd_validate(&studies, max_points),
        Command::Schema => {
            print!("{}", study::schema_json());
            EXIT_OK
        }
        Command::Merge(a) => merge::cmd_merge(&a),
        Command::Slurm(a) => slurm::cmd_slurm(&a, invocation),
        Command::Optimize(a) => optimize::cmd_optimize(&a),
        Command::ExportProfile(a) => export::cmd_export(&a),
        Command::Card(a) => card::cmd_card(&a),
        Command::Compare(a) => card::cmd_compare(&a),
        Command::Fly(a) => fly::cmd_fly(&a),
        Command::Lab(a) => lab::cmd_lab(&a),
        Command::Bench {
            quick,
            threads,
            dir,
            json,
        } => crate::bench::main(
            &crate::bench::BenchOptions {
                quick,
                threads,
                dir,
            },
            json.as_deref(),
        ),
        Command::Inspect { file } => match store::inspect(&file) {
            Ok(text) => {
                print!("{text}");
                EXIT_OK
            }
            Err(e) => {
                eprintln!("error: {e}");
                EXIT_BAD_INPUT
            }
        },
    }
}
