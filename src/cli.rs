//! The command line: clap types, turned into one validated settings value before anything
//! runs, then a call into the library. Exit codes: 0 all points ok, 1 some points failed
//! (results written), 2 bad input (message on stderr, nothing written), 3 a failure of
//! the run itself (I/O), 130 interrupted (Ctrl-C; resume with `--resume`).

#![allow(clippy::result_large_err)] // StudyError: see study/mod.rs

use crate::model::outcome::HistoryPrecision;
use crate::results::StudyInfo;
use crate::run::{self, ModelSimulator, RunOptions, RunReport, Shard, Simulator, Sink, StoreSink};
use crate::store;
use crate::study::checks::bat_length;
use crate::study::output::{check_output, Existing};
use crate::study::{self, LoadOptions, Study, StudyError, DEFAULT_MAX_POINTS};
use clap::{Args, Parser, Subcommand};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

pub const EXIT_OK: i32 = 0;
pub const EXIT_POINTS_FAILED: i32 = 1;
pub const EXIT_BAD_INPUT: i32 = 2;
pub const EXIT_RUN_FAILED: i32 = 3;
pub const EXIT_INTERRUPTED: i32 = 130;

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
    /// Measure speed, parallel efficiency, HDF5 write share and peak memory (issue 7).
    Bench {
        /// Shrink every case (a few seconds; for tests).
        #[arg(long)]
        quick: bool,
        /// Also write the figures as JSON to this file.
        #[arg(long)]
        json: Option<PathBuf>,
    },
}

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

#[derive(Debug, Args)]
pub struct PlanArgs {
    /// The study file (YAML).
    pub study: PathBuf,
    /// Print every point (index, id, parameters).
    #[arg(long)]
    pub list: bool,
    /// Largest number of points allowed.
    #[arg(long, default_value_t = DEFAULT_MAX_POINTS)]
    pub max_points: usize,
}

/// Everything `run` needs, validated.
#[derive(Debug)]
pub struct RunSettings {
    pub study: Study,
    pub output: PathBuf,
    pub existing: Existing,
    pub options: RunOptions,
    pub quiet: bool,
}

impl RunSettings {
    /// Validate raw flags and the study; touches nothing.
    pub fn from_args(a: &RunArgs) -> Result<RunSettings, StudyError> {
        let study = study::load(
            &a.study,
            &LoadOptions {
                max_points: a.max_points,
            },
        )?;
        let jobs = match a.jobs {
            Some(0) => {
                return Err(StudyError::new(&a.study, "bad --jobs")
                    .field("--jobs")
                    .value("0")
                    .allowed("a number of threads >= 1"))
            }
            Some(j) => j,
            None => std::thread::available_parallelism().map_or(1, |n| n.get()),
        };
        let existing = match (a.resume, a.force) {
            (true, _) => Existing::Resume,
            (_, true) => Existing::Overwrite,
            _ => Existing::Refuse,
        };
        let output = study.output_path(a.output.as_deref());
        check_output_of(&study, &output, a.output.is_some(), existing)?;
        Ok(RunSettings {
            output,
            existing,
            options: RunOptions {
                jobs,
                fail_fast: a.fail_fast,
                progress: !a.quiet,
                shard: a.shard,
                ..RunOptions::default()
            },
            quiet: a.quiet,
            study,
        })
    }
}

fn check_output_of(
    study: &Study,
    output: &Path,
    from_cli: bool,
    existing: Existing,
) -> Result<(), StudyError> {
    check_output(output, existing).map_err(|(msg, allowed)| {
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

/// Parse the process's arguments and run; returns the exit code.
pub fn main_exit_code() -> i32 {
    let cli = match Cli::try_parse() {
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
    run_command(cli.command)
}

/// Run one subcommand; returns the exit code.
pub fn run_command(cmd: Command) -> i32 {
    match cmd {
        Command::Run(a) => cmd_run(&a),
        Command::Plan(a) => cmd_plan(&a),
        Command::Validate {
            studies,
            max_points,
        } => cmd_validate(&studies, max_points),
        Command::Schema => {
            print!("{}", study::schema_json());
            EXIT_OK
        }
        Command::Bench { quick, json } => {
            crate::bench::main(&crate::bench::BenchOptions { quick }, json.as_deref())
        }
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

fn cmd_validate(files: &[PathBuf], max_points: usize) -> i32 {
    let mut code = EXIT_OK;
    for f in files {
        let res = study::load(f, &LoadOptions { max_points }).and_then(|s| {
            let out = s.output_path(None);
            check_output_of(&s, &out, false, Existing::Overwrite)?;
            Ok(s)
        });
        match res {
            Ok(s) => println!(
                "ok: {}: {} points, {} dimensions, {} bats",
                f.display(),
                s.plan.n_points(),
                s.plan.dims().len(),
                s.plan.bats().len()
            ),
            Err(e) => {
                eprintln!("{e}");
                code = EXIT_BAD_INPUT;
            }
        }
    }
    code
}

/// Rough cost model for `plan`: seconds per point and per bat preparation.
fn cost_per_point(s: &Study) -> (f64, f64) {
    let rigid = matches!(
        s.plan.base().get("model").and_then(|m| m.as_str()),
        Some("rigid")
    );
    if rigid {
        (2e-6, 0.05)
    } else {
        (5e-3, 0.2)
    }
}

fn human_bytes(b: f64) -> String {
    let units = ["B", "KiB", "MiB", "GiB", "TiB"];
    let mut x = b;
    let mut u = 0;
    while x >= 1024.0 && u + 1 < units.len() {
        x /= 1024.0;
        u += 1;
    }
    format!("{x:.1} {}", units[u])
}

fn human_secs(s: f64) -> String {
    if s < 0.1 {
        format!("{:.3} ms", s * 1e3)
    } else if s < 120.0 {
        format!("{s:.1} s")
    } else if s < 7200.0 {
        format!("{:.1} min", s / 60.0)
    } else {
        format!("{:.1} h", s / 3600.0)
    }
}

fn cmd_plan(a: &PlanArgs) -> i32 {
    let s = match study::load(
        &a.study,
        &LoadOptions {
            max_points: a.max_points,
        },
    ) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("{e}");
            return EXIT_BAD_INPUT;
        }
    };
    let plan = &s.plan;
    let n = plan.n_points();
    println!(
        "study {}: {} points, {} distinct bats",
        s.file.name,
        n,
        plan.bats().len()
    );
    if !s.file.description.trim().is_empty() {
        println!("  {}", s.file.description.trim());
    }
    println!("dimensions (row-major, last fastest):");
    for d in &plan.shape().dims {
        println!("  {} [{}]", d.name, d.size);
        for c in &d.coords {
            let vals = match &c.values {
                crate::results::CoordValues::Numbers(v) => {
                    let (lo, hi) = v
                        .iter()
                        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                            (a.min(x), b.max(x))
                        });
                    format!("{lo} .. {hi} {}", c.units)
                }
                crate::results::CoordValues::Labels(l) => l.join(", "),
            };
            println!("    {} ({}): {}", c.name, c.path, vals);
        }
    }
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let (per_point, per_bat) = cost_per_point(&s);
    let secs = (n as f64 * per_point + plan.bats().len() as f64 * per_bat) / cores as f64;
    println!(
        "estimated run time: ~{} on {cores} cores (rough: {} per point)",
        human_secs(secs),
        human_secs(per_point)
    );
    let max_len = plan
        .bats()
        .iter()
        .map(|b| bat_length(&b.bat))
        .fold(0.0, f64::max);
    let mut bytes_per_point = 20.0 * 8.0;
    if let Some(h) = &s.file.history {
        let req = h.request(max_len);
        let width = match h.precision {
            HistoryPrecision::F32 => 4.0,
            HistoryPrecision::F64 => 8.0,
        };
        let series: f64 = req
            .fields
            .iter()
            .map(|f| match f {
                crate::model::outcome::HistoryField::Displacement => req.z.len() as f64,
                crate::model::outcome::HistoryField::RigidMotion => 2.0,
                _ => 1.0,
            })
            .sum();
        bytes_per_point += series * req.n_samples as f64 * width;
    }
    println!(
        "estimated output size: ~{} uncompressed (written to {})",
        human_bytes(bytes_per_point * n as f64),
        s.output_path(None).display()
    );
    if a.list {
        println!("points (index, id, parameters):");
        for i in 0..n {
            match plan.point(i) {
                Ok(p) => println!("{i}\t{:016x}\t{}", p.id, plan.describe(i)),
                Err(e) => println!(
                    "{i}\t{:016x}\t{}\tERROR: {}",
                    e.id,
                    plan.describe(i),
                    e.message
                ),
            }
        }
    }
    EXIT_OK
}

fn cmd_run(a: &RunArgs) -> i32 {
    let settings = match RunSettings::from_args(a) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("{e}");
            return EXIT_BAD_INPUT;
        }
    };
    let stop = Arc::new(AtomicBool::new(false));
    {
        let stop = Arc::clone(&stop);
        let _ = ctrlc::set_handler(move || {
            if stop.swap(true, Ordering::SeqCst) {
                eprintln!("\nsecond interrupt: exiting now (resume with --resume)");
                std::process::exit(EXIT_INTERRUPTED);
            }
            eprintln!("\ninterrupt: finishing the points in flight…");
        });
    }
    let store_options = |existing: Existing| store::StoreOptions {
        resume: existing == Existing::Resume,
        force: existing == Existing::Overwrite,
        run_meta: store::RunMeta {
            threads: settings.options.jobs,
            shard: settings
                .options
                .shard
                .map(|s| format!("{}/{}", s.index, s.count)),
            ..Default::default()
        },
        ..Default::default()
    };
    run_with(
        &settings,
        &ModelSimulator,
        |path, info, existing| {
            store::open(path, info, &store_options(existing))
                .map(StoreSink::new)
                .map_err(|e| e.to_string())
        },
        &stop,
    )
}

/// The run itself, against any simulator and sink (`open` creates the sink for the
/// output path once the bats are prepared). Prints the summary; returns the exit code.
pub fn run_with<S, K, F>(settings: &RunSettings, sim: &S, open: F, stop: &AtomicBool) -> i32
where
    S: Simulator,
    K: Sink,
    F: FnOnce(&Path, &StudyInfo, Existing) -> Result<K, String>,
{
    let plan = &settings.study.plan;
    let pool = match run::build_pool(settings.options.jobs) {
        Ok(p) => p,
        Err(e) => {
            eprintln!("error: {e}");
            return EXIT_RUN_FAILED;
        }
    };
    let bats = run::prepare_bats(sim, plan, &pool);
    let history = settings.study.history_request(bats.max_length());
    let info = settings.study.info(bats.variants.clone(), history.clone());
    if let Some(dir) = settings
        .output
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
    {
        if let Err(e) = std::fs::create_dir_all(dir) {
            eprintln!("error: cannot create {}: {e}", dir.display());
            return EXIT_RUN_FAILED;
        }
    }
    let sink = match open(&settings.output, &info, settings.existing) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("error: {}: {e}", settings.output.display());
            return EXIT_BAD_INPUT;
        }
    };
    let result = run::run_plan(
        plan,
        sim,
        &bats,
        history.as_ref(),
        sink,
        &pool,
        &settings.options,
        stop,
    );
    match result {
        Err(e) => {
            eprintln!("error: {e}");
            EXIT_RUN_FAILED
        }
        Ok((report, _sink)) => {
            if !settings.quiet {
                print_report(settings, &report);
            }
            exit_code(&report)
        }
    }
}

/// Exit code of a finished run.
pub fn exit_code(r: &RunReport) -> i32 {
    if r.interrupted {
        EXIT_INTERRUPTED
    } else if r.failed > 0 || r.aborted {
        EXIT_POINTS_FAILED
    } else {
        EXIT_OK
    }
}

fn print_report(s: &RunSettings, r: &RunReport) {
    eprintln!(
        "{}: {} points: {} ok, {} failed, {} already done{}",
        s.output.display(),
        r.total,
        r.ok,
        r.failed,
        r.skipped,
        if r.remaining() > 0 {
            format!(", {} not run", r.remaining())
        } else {
            String::new()
        }
    );
    for (i, e) in &r.failures {
        eprintln!("  point {i} ({}): {e}", s.study.plan.describe(*i));
    }
    if r.failed > r.failures.len() {
        eprintln!("  … and {} more failures", r.failed - r.failures.len());
    }
    if r.interrupted || r.aborted {
        let mut cmd = format!(
            "batstudy run {} --resume -o {}",
            s.study.path.display(),
            s.output.display()
        );
        if let Some(sh) = s.options.shard {
            cmd.push_str(&format!(" --shard {sh}"));
        }
        eprintln!("stopped early; to finish the study run:\n  {cmd}");
    }
}
