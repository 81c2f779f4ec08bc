//! Run a study to a results file: the settings checked before anything is touched, the
//! output's lock held throughout, the bats prepared while the file begins, every point run
//! on the pool and stored as it finishes; a resume runs only the missing points, and a
//! stopped run keeps everything finished.

#![allow(clippy::result_large_err)] // StudyError: see study/mod.rs

use super::failure::{Kind, OpError};
use super::files::{check_output_of, jobs_or_all, lock_output, OutputNamed};
use crate::results::StudyInfo;
use crate::run::{ModelSimulator, Observer, RunOptions, RunReport, Shard, SharedObserver};
use crate::run::{Simulator, Sink, StoreSink};
use crate::store;
use crate::study::output::Existing;
use crate::study::{Study, StudyError};
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;

/// What a caller asks of a run, before it is checked.
#[derive(Debug, Clone)]
pub struct RunRequest {
    /// The results file (None: the study's `output`, else `results/<name>.h5`; a shard's
    /// `results/<name>.shard-I-of-N.h5`).
    pub output: Option<PathBuf>,
    /// Worker threads (None: every core).
    pub jobs: Option<usize>,
    /// What to do with a results file already at the output.
    pub existing: Existing,
    /// Stop at the first failed point.
    pub fail_fast: bool,
    /// Run only this shard's points.
    pub shard: Option<Shard>,
    /// The words that start this front end's run again, for the resume command that
    /// messages suggest (`batstudy`, or the path the binary was started by).
    pub program: String,
}

impl Default for RunRequest {
    fn default() -> Self {
        RunRequest {
            output: None,
            jobs: None,
            existing: Existing::Refuse,
            fail_fast: false,
            shard: None,
            program: "batstudy".into(),
        }
    }
}

/// What to do with an output file that exists, from a front end's two switches.
pub fn existing_from(resume: bool, force: bool) -> Existing {
    match (resume, force) {
        (true, _) => Existing::Resume,
        (_, true) => Existing::Overwrite,
        _ => Existing::Refuse,
    }
}

/// Everything a run needs, checked.
#[derive(Debug)]
pub struct RunSettings {
    pub study: Study,
    pub output: PathBuf,
    pub named: OutputNamed,
    pub existing: Existing,
    pub options: RunOptions,
    pub program: String,
}

impl RunSettings {
    /// Check a request for a study already loaded; touches nothing.
    pub fn new(study: Study, r: &RunRequest) -> Result<RunSettings, StudyError> {
        let jobs = jobs_or_all(r.jobs, &study.path)?;
        let output = match (r.shard, &r.output) {
            (Some(sh), None) => shard_output(&study.output_path(None), sh),
            _ => study.output_path(r.output.as_deref()),
        };
        let named = OutputNamed::of(r.output.is_some());
        check_output_of(&study, &output, named, r.existing)?;
        Ok(RunSettings {
            output,
            named,
            existing: r.existing,
            options: RunOptions {
                jobs,
                fail_fast: r.fail_fast,
                shard: r.shard,
                ..RunOptions::default()
            },
            program: r.program.clone(),
            study,
        })
    }

    /// The command that finishes this run.
    fn resume_command(&self) -> String {
        let mut cmd = format!(
            "{} run {} --resume -o {}",
            self.program,
            self.study.path.display(),
            self.output.display()
        );
        if let Some(sh) = self.options.shard {
            cmd.push_str(&format!(" --shard {sh}"));
        }
        cmd
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

/// A run that went through (some points may have failed, or it was interrupted).
#[derive(Debug)]
pub struct FinishedRun {
    pub settings: RunSettings,
    pub report: RunReport,
    pub elapsed: std::time::Duration,
}

impl FinishedRun {
    /// How it ended beyond a plain success (None: every point computed).
    pub fn outcome(&self) -> Option<Kind> {
        outcome_of(&self.report)
    }

    /// The summary a front end shows: counts, time and rate, the failures, and the command
    /// that finishes a run stopped early.
    pub fn report_text(&self) -> String {
        report_text(&self.settings, &self.report, self.elapsed)
    }
}

/// How a run's report ends beyond a plain success.
pub fn outcome_of(r: &RunReport) -> Option<Kind> {
    if r.interrupted {
        Some(Kind::Interrupted)
    } else if r.failed > 0 || r.aborted {
        Some(Kind::PointsFailed)
    } else {
        None
    }
}

/// How many failed points end a finished operation as.
pub fn outcome_of_failed(n_failed: usize) -> Option<Kind> {
    (n_failed > 0).then_some(Kind::PointsFailed)
}

/// Run `settings`: take the output's lock, check the output again under it, prepare the
/// bats, run every point with `stop` as the interrupt flag (set it to stop early, as
/// Ctrl-C does), telling `observer` the phases, the progress and any note.
pub fn run_study(
    mut settings: RunSettings,
    stop: &AtomicBool,
    observer: SharedObserver,
) -> Result<FinishedRun, OpError> {
    settings.options.observer = observer.clone();
    let _lock = lock_output(&settings.output, &*observer)?;
    // Checked again under the lock: another run may have finished the file meanwhile.
    check_output_of(
        &settings.study,
        &settings.output,
        settings.named,
        settings.existing,
    )?;
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
        |path, info, existing, begun| open_sink(&settings, &*observer, path, info, existing, begun),
        stop,
    )?;
    Ok(FinishedRun {
        settings,
        report,
        elapsed,
    })
}

/// The store's sink for the output, from what `store::begin` made.
fn open_sink(
    settings: &RunSettings,
    observer: &dyn Observer,
    path: &Path,
    info: &StudyInfo,
    existing: Existing,
    begun: Result<store::BegunFile, store::StoreError>,
) -> Result<StoreSink, OpError> {
    let options = store::StoreOptions {
        resume: existing == Existing::Resume,
        force: existing == Existing::Overwrite,
        run_meta: store::RunMeta {
            threads: settings.options.jobs,
            shard: settings
                .options
                .shard
                .map(|s| format!("{}/{}", s.index, s.count)),
            shard_range: settings.options.shard.map(|sh| {
                let r = crate::run::shard_range(&settings.study.plan, info.history.as_ref(), sh);
                (r.start, r.end)
            }),
            ..Default::default()
        },
        ..Default::default()
    };
    begun
        .and_then(|b| store::open_begun(path, info, &options, Some(b)))
        .inspect(|s| {
            if s.recovered.dropped > 0 {
                // not an error: those points are computed again; said, since it means the
                // unfinished file was changed or lost bytes
                observer.note(&format!(
                    "note: {}: {} points whose histories were not intact in the unfinished \
                     file are computed again",
                    path.display(),
                    s.recovered.dropped
                ));
            }
        })
        .map(StoreSink::new)
        .map_err(|e| match e.is_bad_input() {
            true => OpError::refused(format!("{}: {e}", path.display())),
            false => OpError::RunFailed(run_failed_text(
                settings,
                &format!("{}: {e}", path.display()),
            )),
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
) -> Result<(RunReport, std::time::Duration), OpError>
where
    S: Simulator,
    K: Sink,
    E: Send,
    B: FnOnce() -> E + Send,
    F: FnOnce(&Path, &StudyInfo, Existing, E) -> Result<K, OpError>,
{
    let plan = &settings.study.plan;
    let observer = &settings.options.observer;
    let pool = crate::run::build_pool(settings.options.jobs).map_err(OpError::io)?;
    if let Some(dir) = settings
        .output
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
    {
        std::fs::create_dir_all(dir)
            .map_err(|e| OpError::io(format!("cannot create {}: {e}", dir.display())))?;
    }
    let started = std::time::Instant::now();
    observer.phase(crate::run::Phase::Preparing {
        bats: plan.bats().len(),
    });
    let (bats, begun) = crate::run::prepare_bats_alongside(sim, plan, &pool, begin);
    swing_law_warnings(plan, &bats.variants, &**observer);
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
    .map_err(|e| OpError::RunFailed(run_failed_text(settings, &e.to_string())))?;
    Ok((report, started.elapsed()))
}

/// A study with a batter whose swing answers to the bat (an exponent n > 0 somewhere): a
/// warning for each bat the swing law is extrapolated to. With n = 0 throughout every bat
/// is swung alike and the law plays no part.
fn swing_law_warnings(
    plan: &crate::study::Plan,
    bats: &[crate::results::BatVariant],
    observer: &dyn Observer,
) {
    let batter = crate::study::paths::get_path(plan.base(), "batter");
    if batter.is_none_or(|b| b.is_null()) || !swing_law_used(plan) {
        return;
    }
    for b in bats {
        let moi6 = b.properties.moment_of_inertia_knob6;
        if let Some(why) = crate::model::spec::swing_law_extrapolated(moi6) {
            let label = crate::study::error::printable(&b.label, false);
            observer.note(&format!("warning: bat {label}: {why}"));
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
    t.push_str(&format!(
        "\nthe points finished so far are kept; once the cause is fixed, finish the run with:\n  {}",
        settings.resume_command()
    ));
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

fn report_text(s: &RunSettings, r: &RunReport, elapsed: std::time::Duration) -> String {
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
        // As this front end was invoked, so that it can be pasted.
        let _ = writeln!(
            t,
            "stopped early; to finish the study run:\n  {}",
            s.resume_command()
        );
    }
    t
}
