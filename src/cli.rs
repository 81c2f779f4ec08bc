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
    /// Measure speed, parallel efficiency, HDF5 write share and peak memory.
    Bench {
        /// Shrink every case (a few seconds; for tests).
        #[arg(long)]
        quick: bool,
        /// Also write the figures as JSON to this file.
        #[arg(long)]
        json: Option<PathBuf>,
    },
    /// Merge shard files (`run --shard I/N`) into one results file.
    Merge(MergeArgs),
    /// Write Slurm job scripts: an array of shards and a merge job that depends on it.
    Slurm(SlurmArgs),
}

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

#[derive(Debug, Args)]
pub struct SlurmArgs {
    /// The study file (YAML).
    pub study: PathBuf,
    /// Number of shards (array tasks).
    #[arg(long)]
    pub shards: usize,
    /// Time limit of each array task (Slurm format, e.g. 02:00:00 or 1-00:00:00).
    #[arg(long)]
    pub time: Option<String>,
    /// Time limit of the merge job (default: --time).
    #[arg(long)]
    pub merge_time: Option<String>,
    /// Slurm partition.
    #[arg(long)]
    pub partition: Option<String>,
    /// Cores per array task (its rayon threads).
    #[arg(long, default_value_t = 1)]
    pub cpus_per_task: usize,
    /// Memory per task (Slurm format, e.g. 4G).
    #[arg(long)]
    pub mem: Option<String>,
    /// The merged results file (default: the study's `output`, else results/<name>.h5).
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    /// Folder for the scripts, the shard files and the logs (default: slurm/<name>).
    #[arg(long)]
    pub dir: Option<PathBuf>,
    /// Largest number of points allowed.
    #[arg(long, default_value_t = DEFAULT_MAX_POINTS)]
    pub max_points: usize,
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
        let output = match (a.shard, &a.output) {
            (Some(sh), None) => shard_output(&study.output_path(None), sh),
            _ => study.output_path(a.output.as_deref()),
        };
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

/// Default output of a shard: the study's output with `.shard-I-of-N.h5` for `.h5`
/// (`results/<name>.shard-I-of-N.h5`).
pub fn shard_output(study_output: &Path, shard: Shard) -> PathBuf {
    let s = study_output.display().to_string();
    let stem = s.strip_suffix(".h5").unwrap_or(&s);
    PathBuf::from(format!(
        "{stem}.shard-{}-of-{}.h5",
        shard.index, shard.count
    ))
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
        Command::Merge(a) => cmd_merge(&a),
        Command::Slurm(a) => cmd_slurm(&a),
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
                "ok: {}: {} points, {} dimensions, {} bats{}",
                f.display(),
                s.plan.n_points(),
                s.plan.dims().len(),
                s.plan.bats().len(),
                match s.plan.history_count() {
                    Some(h) => format!(", {h} histories"),
                    None => String::new(),
                }
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
/// Seconds per point and per bat preparation, measured on a few points spread over the plan
/// (the first run of a bat includes preparing it), and the share of points that record
/// histories (from a larger sample: resolving a point is cheap).
fn measured_costs(s: &Study) -> (f64, f64, f64) {
    let plan = &s.plan;
    let n = plan.n_points();
    let spread = |k: usize| (0..k.min(n)).map(move |i| i * n / k.min(n));
    let (mut simulate_secs, mut prepare_secs, mut timed) = (0.0, 0.0, 0usize);
    for i in spread(8) {
        let Ok(p) = plan.point(i) else { continue };
        let start = std::time::Instant::now();
        let Ok((_, bat)) = ModelSimulator.prepare(&p.spec.bat, &p.spec.numerics) else {
            continue;
        };
        let prepared = start.elapsed().as_secs_f64();
        let start = std::time::Instant::now();
        let history = s.history_request(bat_length(&p.spec.bat));
        let _ =
            ModelSimulator.simulate(&bat, &p.spec, history.as_ref().filter(|_| p.record_history));
        simulate_secs += start.elapsed().as_secs_f64();
        prepare_secs += prepared;
        timed += 1;
    }
    let sampled: Vec<bool> = spread(2000)
        .filter_map(|i| plan.point(i).ok().map(|p| p.record_history))
        .collect();
    let history_share = sampled.iter().filter(|r| **r).count() as f64 / sampled.len().max(1) as f64;
    let timed = timed.max(1) as f64;
    (simulate_secs / timed, prepare_secs / timed, history_share)
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

/// Load a study; on bad input print the located error and give the exit code.
fn load_or_report(path: &Path, max_points: usize) -> Result<Study, i32> {
    study::load(path, &LoadOptions { max_points }).map_err(|e| {
        eprintln!("{e}");
        EXIT_BAD_INPUT
    })
}

fn cmd_plan(a: &PlanArgs) -> i32 {
    let s = match load_or_report(&a.study, a.max_points) {
        Ok(s) => s,
        Err(code) => return code,
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
    let (per_point, per_bat, history_share) = measured_costs(&s);
    let secs = (n as f64 * per_point + plan.bats().len() as f64 * per_bat) / cores as f64;
    println!(
        "estimated run time: ~{} on {cores} cores ({} per point, {} per bat, measured on a sample)",
        human_secs(secs),
        human_secs(per_point),
        human_secs(per_bat)
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
        bytes_per_point += history_share * series * req.n_samples as f64 * width;
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
    let _lock = match lock_output(&settings.output) {
        Ok(l) => l,
        Err(code) => return code,
    };
    // Checked again under the lock: another run may have finished the file meanwhile.
    if let Err(e) = check_output_of(
        &settings.study,
        &settings.output,
        a.output.is_some(),
        settings.existing,
    ) {
        eprintln!("{e}");
        return EXIT_BAD_INPUT;
    }
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
    let output = &settings.output;
    let shape = &settings.study.plan.shape;
    run_with(
        &settings,
        &ModelSimulator,
        || store::begin(output, shape),
        |path, info, existing, begun| {
            let mut o = store_options(existing);
            o.run_meta.shard_range = settings.options.shard.map(|sh| {
                let r = run::shard_range(&settings.study.plan, info.history.as_ref(), sh);
                (r.start, r.end)
            });
            begun
                .and_then(|b| store::open_begun(path, info, &o, Some(b)))
                .map(StoreSink::new)
                .map_err(|e| e.to_string())
        },
        &stop,
    )
}

/// The run itself, against any simulator and sink. `begin` runs while the bats are
/// prepared (the store begins its file there); `open` then creates the sink for the output
/// path with what `begin` made. Prints the summary; returns the exit code.
pub fn run_with<S, K, E, B, F>(
    settings: &RunSettings,
    sim: &S,
    begin: B,
    open: F,
    stop: &AtomicBool,
) -> i32
where
    S: Simulator,
    K: Sink,
    E: Send,
    B: FnOnce() -> E + Send,
    F: FnOnce(&Path, &StudyInfo, Existing, E) -> Result<K, String>,
{
    let plan = &settings.study.plan;
    let pool = match run::build_pool(settings.options.jobs) {
        Ok(p) => p,
        Err(e) => {
            eprintln!("error: {e}");
            return EXIT_RUN_FAILED;
        }
    };
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
    let started = std::time::Instant::now();
    let preparing = run::progress::spinner(
        settings.options.progress,
        format!(
            "preparing {} bat{}",
            plan.bats().len(),
            if plan.bats().len() == 1 { "" } else { "s" }
        ),
    );
    let (bats, begun) = run::prepare_bats_alongside(sim, plan, &pool, begin);
    preparing.finish_and_clear();
    let history = settings.study.history_request(bats.max_length());
    let info = settings.study.info(bats.variants.clone(), history.clone());
    let sink = match open(&settings.output, &info, settings.existing, begun) {
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
                print_report(settings, &report, started.elapsed());
            }
            exit_code(&report)
        }
    }
}

/// Take the output's lock (`OUT.h5.lock`) before anything of it is touched: a second
/// process on the same output is refused (exit 2) and changes nothing.
fn lock_output(output: &Path) -> Result<store::lock::OutputLock, i32> {
    if let Some(dir) = output.parent().filter(|d| !d.as_os_str().is_empty()) {
        if let Err(e) = std::fs::create_dir_all(dir) {
            eprintln!("error: cannot create {}: {e}", dir.display());
            return Err(EXIT_RUN_FAILED);
        }
    }
    store::lock::OutputLock::acquire(output).map_err(|e| {
        eprintln!("error: {e}");
        match e {
            store::lock::LockError::Held { .. } => EXIT_BAD_INPUT,
            store::lock::LockError::Io { .. } => EXIT_RUN_FAILED,
        }
    })
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

fn print_report(s: &RunSettings, r: &RunReport, elapsed: std::time::Duration) {
    eprintln!(
        "{}: {} points: {} ok, {} failed, {} already done{}; {} ({})",
        s.output.display(),
        r.total,
        r.ok,
        r.failed,
        r.skipped,
        if r.remaining() > 0 {
            format!(", {} not run", r.remaining())
        } else {
            String::new()
        },
        run::progress::duration_text(elapsed.as_secs_f64()),
        run::progress::rate_text((r.ok + r.failed) as u64, elapsed)
    );
    for (i, e) in &r.failures {
        eprintln!("  point {i} ({}): {e}", s.study.plan.describe(*i));
    }
    if r.failed > r.failures.len() {
        eprintln!("  … and {} more failures", r.failed - r.failures.len());
    }
    if r.interrupted || r.aborted {
        // As this process was invoked, so that it can be pasted.
        let program = std::env::args().next().unwrap_or_else(|| "batstudy".into());
        let mut cmd = format!(
            "{program} run {} --resume -o {}",
            s.study.path.display(),
            s.output.display()
        );
        if let Some(sh) = s.options.shard {
            cmd.push_str(&format!(" --shard {sh}"));
        }
        eprintln!("stopped early; to finish the study run:\n  {cmd}");
    }
}

fn jobs_or_all(jobs: Option<usize>, file: &Path) -> Result<usize, StudyError> {
    match jobs {
        Some(0) => Err(StudyError::new(file, "bad --jobs")
            .field("--jobs")
            .value("0")
            .allowed("a number of threads >= 1")),
        Some(j) => Ok(j),
        None => Ok(std::thread::available_parallelism().map_or(1, |n| n.get())),
    }
}

/// `batstudy merge`: re-read the study from the shards' stored text, prepare its bats (as
/// `run` does), check that the shards are one study and hold every point once, then write
/// one complete results file. Exit 2 (nothing written) when refused.
fn cmd_merge(a: &MergeArgs) -> i32 {
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
    if let Err((msg, allowed)) = check_output(&a.output, existing) {
        return bad(format!("--output: {msg} (allowed: {allowed})"));
    }
    let _lock = match lock_output(&a.output) {
        Ok(l) => l,
        Err(code) => return code,
    };
    if let Err((msg, allowed)) = check_output(&a.output, existing) {
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
    let pool = match run::build_pool(jobs) {
        Ok(p) => p,
        Err(e) => {
            eprintln!("error: {e}");
            return EXIT_RUN_FAILED;
        }
    };
    let bats = run::prepare_bats(&ModelSimulator, &study.plan, &pool);
    let history = study.history_request(bats.max_length());
    let info = study.info(bats.variants, history);
    let store_err = |e: store::StoreError| match e {
        store::StoreError::Io { .. } | store::StoreError::Hdf5 { .. } => {
            eprintln!("error: {e}");
            EXIT_RUN_FAILED
        }
        e => bad(e.to_string()),
    };
    if let Err(e) = store::merge_check(&a.output, &info, &a.shards) {
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
    match store::merge(&a.output, &info, &a.shards, &opts) {
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

/// An absolute path (relative ones against the working folder; nothing is resolved).
fn absolute(p: &Path) -> PathBuf {
    if p.is_absolute() {
        p.to_path_buf()
    } else {
        std::env::current_dir()
            .map(|d| d.join(p))
            .unwrap_or_else(|_| p.to_path_buf())
    }
}

/// `batstudy slurm`: write the job array, merge job and submit scripts.
fn cmd_slurm(a: &SlurmArgs) -> i32 {
    let study = match load_or_report(&a.study, a.max_points) {
        Ok(s) => s,
        Err(code) => return code,
    };
    let flag = |name: &str, value: String, allowed: &str| {
        eprintln!(
            "{}",
            StudyError::new(&a.study, format!("bad {name}"))
                .field(name)
                .value(value)
                .allowed(allowed)
        );
        EXIT_BAD_INPUT
    };
    if a.shards == 0 {
        return flag("--shards", "0".into(), "a number of shards >= 1");
    }
    if a.cpus_per_task == 0 {
        return flag("--cpus-per-task", "0".into(), "a number of cores >= 1");
    }
    for (name, v) in [("--time", &a.time), ("--merge-time", &a.merge_time)] {
        if let Some(t) = v.as_ref().filter(|t| !crate::slurm::valid_time(t)) {
            return flag(
                name,
                t.clone(),
                "a Slurm time limit: MM, HH:MM:SS, D-HH or D-HH:MM:SS",
            );
        }
    }
    if let Some(m) = a.mem.as_ref().filter(|m| !crate::slurm::valid_mem(m)) {
        return flag("--mem", m.clone(), "a size such as 4G or 500M");
    }
    if let Some(p) = a
        .partition
        .as_ref()
        .filter(|p| !crate::slurm::sbatch_safe(p))
    {
        return flag("--partition", p.clone(), "a partition name");
    }
    let binary = match std::env::current_exe().and_then(|p| p.canonicalize()) {
        Ok(p) => p,
        Err(e) => {
            eprintln!("error: cannot find the batstudy binary's path: {e}");
            return EXIT_RUN_FAILED;
        }
    };
    let study_path = match a.study.canonicalize() {
        Ok(p) => p,
        Err(e) => return flag("STUDY", format!("{} ({e})", a.study.display()), "a file"),
    };
    let name = study.file.name.clone();
    let dir = absolute(
        &a.dir
            .clone()
            .unwrap_or_else(|| PathBuf::from("slurm").join(&name)),
    );
    if !crate::slurm::sbatch_safe(&dir.display().to_string()) {
        return flag(
            "--dir",
            dir.display().to_string(),
            "a folder path without spaces, quotes, `$`, `#` or `;` (it goes into #SBATCH lines)",
        );
    }
    let output = absolute(&study.output_path(a.output.as_deref()));
    if let Err((msg, allowed)) = check_output(&output, Existing::Refuse) {
        if output.exists() {
            eprintln!("warning: {msg}: the merge job will refuse to replace it; remove it or choose another -o before submitting");
        } else {
            return flag("--output", output.display().to_string(), &allowed);
        }
    }
    let n = study.plan.n_points();
    if a.shards > n {
        eprintln!(
            "warning: {} shards for {n} points: {} shards will be empty",
            a.shards,
            a.shards - n
        );
    }
    let job = crate::slurm::SlurmJob {
        binary,
        study: study_path,
        name,
        shards: a.shards,
        merge_time: a.merge_time.clone().or_else(|| a.time.clone()),
        time: a.time.clone(),
        partition: a.partition.clone(),
        cpus_per_task: a.cpus_per_task,
        mem: a.mem.clone(),
        output,
        dir,
    };
    match job.write() {
        Ok(paths) => {
            for p in &paths {
                println!("wrote {}", p.display());
            }
            println!(
                "submit with: bash {}   ({} array tasks of {} cores, then the merge into {})",
                job.dir.join("submit.sh").display(),
                job.shards,
                job.cpus_per_task,
                job.output.display()
            );
            EXIT_OK
        }
        Err(e) => {
            eprintln!(
                "error: cannot write the scripts into {}: {e}",
                job.dir.display()
            );
            EXIT_RUN_FAILED
        }
    }
}
