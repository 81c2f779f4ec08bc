//! `batstudy run`: flags → one validated `RunSettings` → the run, under the output's lock.

#![allow(clippy::result_large_err)] // StudyError: see study/mod.rs

use super::common::{check_output_of, jobs_or_all, lock_output};
use super::{EXIT_BAD_INPUT, EXIT_INTERRUPTED, EXIT_OK, EXIT_POINTS_FAILED, EXIT_RUN_FAILED};
use crate::results::StudyInfo;
use crate::run::ModelSimulator;
use crate::run::RunOptions;
use crate::run::RunReport;
use crate::run::Shard;
use crate::run::Simulator;
use crate::run::Sink;
use crate::run::StoreSink;
use crate::store;
use crate::study::output::Existing;
use crate::study::Study;
use crate::study::StudyError;
use crate::study::DEFAULT_MAX_POINTS;
use clap::Args;
use std::path::Path;
use std::path::PathBuf;
use std::sync::atomic::AtomicBool;
use std::sync::atomic::Ordering;
use std::sync::Arc;

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
        // the optimize block too: a file `validate` refuses is refused here
        let study = super::common::load_checked(&a.study, a.max_points)?;
        Self::from_study(study, a)
    }

    /// Validate raw flags for a study already loaded (from a file or from text: the
    /// Python API's `run` takes a dict or YAML text too); touches nothing.
    pub fn from_study(study: Study, a: &RunArgs) -> Result<RunSettings, StudyError> {
        let jobs = jobs_or_all(a.jobs, &study.path)?;
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

/// The exit code of a finished run or merge with `n_failed` failed points (0 or 1).
pub fn exit_code_of_failed(n_failed: usize) -> i32 {
    match n_failed {
        0 => EXIT_OK,
        _ => EXIT_POINTS_FAILED,
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

pub(super) fn cmd_run(a: &RunArgs) -> i32 {
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
    match run_study(a, &stop, None) {
        Err(f) => {
            eprintln!("{}", f.message);
            f.code
        }
        Ok(done) => {
            if !a.quiet {
                let program = std::env::args().next().unwrap_or_else(|| "batstudy".into());
                eprint!("{}", done.report_text(&program));
            }
            exit_code(&done.report)
        }
    }
}

/// Why a run did not happen or broke off: the exit code and the message (what `batstudy
/// run` prints on stderr).
#[derive(Debug, Clone)]
pub struct RunFailure {
    pub code: i32,
    pub message: String,
}

impl RunFailure {
    fn new(code: i32, message: impl Into<String>) -> Self {
        RunFailure {
            code,
            message: message.into(),
        }
    }
}

/// A run that went through (some points may have failed, or it was interrupted).
#[derive(Debug)]
pub struct FinishedRun {
    pub settings: RunSettings,
    pub report: RunReport,
    pub elapsed: std::time::Duration,
}

impl FinishedRun {
    /// The summary `batstudy run` prints; `program` starts the resume command it suggests.
    pub fn report_text(&self, program: &str) -> String {
        report_text(&self.settings, &self.report, self.elapsed, program)
    }
}

/// `batstudy run` without the terminal: validate `a`, take the output's lock, run with
/// `stop` as the interrupt flag (set it to stop early, as Ctrl-C does) and count finished
/// points into `counter`. Prints nothing; the caller shows the failure or report.
pub fn run_study(
    a: &RunArgs,
    stop: &AtomicBool,
    counter: Option<Arc<crate::run::PointCounter>>,
) -> Result<FinishedRun, RunFailure> {
    let settings =
        RunSettings::from_args(a).map_err(|e| RunFailure::new(EXIT_BAD_INPUT, e.to_string()))?;
    run_settings(settings, a.output.is_some(), stop, counter)
}

/// [`run_study`] with validated settings (`output_given`: the output came from the caller,
/// not from the study file, for the located messages).
pub fn run_settings(
    mut settings: RunSettings,
    output_given: bool,
    stop: &AtomicBool,
    counter: Option<Arc<crate::run::PointCounter>>,
) -> Result<FinishedRun, RunFailure> {
    settings.options.counter = counter;
    let _lock = lock_output(&settings.output).map_err(|(code, m)| RunFailure::new(code, m))?;
    // Checked again under the lock: another run may have finished the file meanwhile.
    check_output_of(
        &settings.study,
        &settings.output,
        output_given,
        settings.existing,
    )
    .map_err(|e| RunFailure::new(EXIT_BAD_INPUT, e.to_string()))?;
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
    let (report, elapsed) = run_with(
        &settings,
        &ModelSimulator,
        || {
            match settings.existing {
                Existing::Overwrite => store::discard_output(output)?,
                Existing::Resume => store::check_resumable(output, &settings.study.sha256)?,
                Existing::Refuse => {}
            }
            store::begin(output, shape)
        },
        |path, info, existing, begun| {
            let mut o = store_options(existing);
            o.run_meta.shard_range = settings.options.shard.map(|sh| {
                let r = crate::run::shard_range(&settings.study.plan, info.history.as_ref(), sh);
                (r.start, r.end)
            });
            begun
                .and_then(|b| store::open_begun(path, info, &o, Some(b)))
                .inspect(|s| {
                    if s.recovered.dropped > 0 {
                        // not an error: those points are computed again; said, since it
                        // means the unfinished file was changed or lost bytes
                        eprintln!(
                            "note: {}: {} points whose histories were not intact in the \
                             unfinished file are computed again",
                            path.display(),
                            s.recovered.dropped
                        );
                    }
                })
                .map(StoreSink::new)
                .map_err(|e| match e.is_bad_input() {
                    true => {
                        RunFailure::new(EXIT_BAD_INPUT, format!("error: {}: {e}", path.display()))
                    }
                    false => RunFailure::new(
                        EXIT_RUN_FAILED,
                        run_failed_text(&settings, &format!("{}: {e}", path.display())),
                    ),
                })
        },
        stop,
    )?;
    Ok(FinishedRun {
        settings,
        report,
        elapsed,
    })
}

/// The run itself, against any simulator and sink. `begin` runs while the bats are
/// prepared (the store begins its file there); `open` then creates the sink for the output
/// path with what `begin` made. Returns the report and the time taken.
pub fn run_with<S, K, E, B, F>(
    settings: &RunSettings,
    sim: &S,
    begin: B,
    open: F,
    stop: &AtomicBool,
) -> Result<(RunReport, std::time::Duration), RunFailure>
where
    S: Simulator,
    K: Sink,
    E: Send,
    B: FnOnce() -> E + Send,
    F: FnOnce(&Path, &StudyInfo, Existing, E) -> Result<K, RunFailure>,
{
    let plan = &settings.study.plan;
    let pool = crate::run::build_pool(settings.options.jobs)
        .map_err(|e| RunFailure::new(EXIT_RUN_FAILED, format!("error: {e}")))?;
    if let Some(dir) = settings
        .output
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
    {
        std::fs::create_dir_all(dir).map_err(|e| {
            RunFailure::new(
                EXIT_RUN_FAILED,
                format!("error: cannot create {}: {e}", dir.display()),
            )
        })?;
    }
    let started = std::time::Instant::now();
    let preparing = crate::run::progress::spinner(
        settings.options.progress,
        format!(
            "preparing {} bat{}",
            plan.bats().len(),
            if plan.bats().len() == 1 { "" } else { "s" }
        ),
    );
    let (bats, begun) = crate::run::prepare_bats_alongside(sim, plan, &pool, begin);
    preparing.finish_and_clear();
    swing_law_warnings(plan, &bats.variants);
    let history = settings.study.history_request(bats.max_length());
    let info = settings.study.info(bats.variants.clone(), history.clone());
    let sink = open(&settings.output, &info, settings.existing, begun)?;
    let (report, _sink) = crate::run::run_plan(
        plan,
        sim,
        &bats,
        history.as_ref(),
        sink,
        &pool,
        &settings.options,
        stop,
    )
    .map_err(|e| RunFailure::new(EXIT_RUN_FAILED, run_failed_text(settings, &e.to_string())))?;
    Ok((report, started.elapsed()))
}

/// A study with a batter whose swing answers to the bat (an exponent n > 0 somewhere): a
/// warning for each bat the swing law is extrapolated to. With n = 0 throughout every bat
/// is swung alike and the law plays no part.
fn swing_law_warnings(plan: &crate::study::Plan, bats: &[crate::results::BatVariant]) {
    let batter = crate::study::paths::get_path(plan.base(), "batter");
    if batter.is_none_or(|b| b.is_null()) || !swing_law_used(plan) {
        return;
    }
    for b in bats {
        let moi6 = b.properties.moment_of_inertia_knob6;
        if let Some(why) = crate::model::spec::swing_law_extrapolated(moi6) {
            let label = crate::study::error::printable(&b.label, false);
            eprintln!("warning: bat {label}: {why}");
        }
    }
}

/// Whether some point's batter has an exponent other than 0: the base's (its default 0.27
/// when unset) or a value a dimension sets.
fn swing_law_used(plan: &crate::study::Plan) -> bool {
    let nonzero = |v: &yaml_serde::Value| v.as_f64().is_none_or(|n| n != 0.0);
    let base = crate::study::paths::get_path(plan.base(), "batter.exponent");
    base.is_none_or(|v| v.is_null() || nonzero(v))
        || plan.dims().iter().any(|d| {
            d.params
                .iter()
                .filter(|(path, _)| path == "batter.exponent")
                .any(|(_, values)| values.iter().any(nonzero))
        })
}

/// The message of a run that failed midway (I/O): its cause, a full disk named as such,
/// and the command that finishes it (the journal keeps every finished point).
fn run_failed_text(settings: &RunSettings, error: &str) -> String {
    let dir = match settings.output.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let free = free_bytes(&dir);
    let full = error.contains("No space left") || free.is_some_and(|b| b < 1 << 20);
    let mut t = format!("error: {error}");
    if full {
        t.push_str(&format!(
            "\nno space left on the device that holds {} ({} bytes free)",
            dir.display(),
            free.map_or_else(|| "?".into(), |b| b.to_string())
        ));
    }
    let program = std::env::args().next().unwrap_or_else(|| "batstudy".into());
    t.push_str(&format!(
        "\nthe points finished so far are kept; once the cause is fixed, finish the run with:\n  {program} run {} --resume -o {}",
        settings.study.path.display(),
        settings.output.display()
    ));
    if let Some(sh) = settings.options.shard {
        t.push_str(&format!(" --shard {sh}"));
    }
    t
}

/// Bytes free for this user on the file system holding `dir`.
fn free_bytes(dir: &Path) -> Option<u64> {
    use std::os::unix::ffi::OsStrExt;
    let c = std::ffi::CString::new(dir.as_os_str().as_bytes()).ok()?;
    let mut st: libc::statvfs = unsafe { std::mem::zeroed() };
    // SAFETY: `c` is a NUL-terminated path and `st` a statvfs the call fills in.
    let ok = unsafe { libc::statvfs(c.as_ptr(), &mut st) } == 0;
    ok.then(|| st.f_bavail as u64 * st.f_frsize as u64)
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

fn report_text(
    s: &RunSettings,
    r: &RunReport,
    elapsed: std::time::Duration,
    program: &str,
) -> String {
    use std::fmt::Write;
    let mut t = String::new();
    let _ = writeln!(
        t,
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
        crate::run::progress::duration_text(elapsed.as_secs_f64()),
        crate::run::progress::rate_text((r.ok + r.failed) as u64, elapsed)
    );
    for (i, e) in &r.failures {
        let _ = writeln!(t, "  point {i} ({}): {e}", s.study.plan.describe(*i));
    }
    if r.failed > r.failures.len() {
        let _ = writeln!(t, "  … and {} more failures", r.failed - r.failures.len());
    }
    if r.interrupted || r.aborted {
        // As this process was invoked, so that it can be pasted.
        let mut cmd = format!(
            "{program} run {} --resume -o {}",
            s.study.path.display(),
            s.output.display()
        );
        if let Some(sh) = s.options.shard {
            cmd.push_str(&format!(" --shard {sh}"));
        }
        let _ = writeln!(t, "stopped early; to finish the study run:\n  {cmd}");
    }
    t
}
