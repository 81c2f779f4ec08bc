//! `batstudy slurm`: the job array, merge job and submit scripts for a Slurm cluster.

#![allow(clippy::result_large_err)] // StudyError: see study/mod.rs

use super::common::load_or_report;
use super::common::{MAX_JOBS, MAX_SHARDS};
use super::{Invocation, EXIT_BAD_INPUT, EXIT_OK, EXIT_RUN_FAILED};
use crate::study::output::check_output;
use crate::study::output::Existing;
use crate::study::StudyError;
use crate::study::DEFAULT_MAX_POINTS;
use clap::Args;
use std::path::Path;
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct SlurmArgs {
    /// The study file (YAML).
    #[arg(required_unless_present = "resubmit")]
    pub study: Option<PathBuf>,
    /// Number of shards (array tasks).
    #[arg(long, required_unless_present = "resubmit")]
    pub shards: Option<usize>,
    /// Submit again, from a folder `batstudy slurm` wrote, the array tasks of the shards that
    /// are not finished (a time-out, a cancellation, a failed task), then the merge: runs
    /// DIR/submit.sh. Further arguments go to sbatch (e.g. --account=X).
    #[arg(long, value_name = "DIR", conflicts_with_all = ["study", "shards"])]
    pub resubmit: Option<PathBuf>,
    /// With --resubmit: extra sbatch options, after `--`.
    #[arg(last = true)]
    pub sbatch_args: Vec<String>,
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

/// `batstudy slurm --resubmit DIR`: run DIR/submit.sh, which submits what is unfinished.
fn resubmit(dir: &Path, sbatch_args: &[String]) -> i32 {
    let script = dir.join("submit.sh");
    if !script.is_file() {
        eprintln!(
            "{}",
            StudyError::new(dir, "no submit.sh in this folder")
                .field("--resubmit")
                .value(dir.display().to_string())
                .allowed("a folder written by `batstudy slurm` (its --dir)")
        );
        return EXIT_BAD_INPUT;
    }
    match std::process::Command::new("bash")
        .arg(&script)
        .args(sbatch_args)
        .status()
    {
        Ok(st) if st.success() => EXIT_OK,
        Ok(st) => {
            eprintln!("error: {} failed ({st})", script.display());
            EXIT_RUN_FAILED
        }
        Err(e) => {
            eprintln!("error: cannot run bash {}: {e}", script.display());
            EXIT_RUN_FAILED
        }
    }
}

/// The words that run batstudy on a compute node: the caller's (the Python wheel's
/// command), else this executable.
fn batstudy_command(invocation: &Invocation) -> Result<Vec<String>, String> {
    if let Some(c) = invocation.command.as_ref().filter(|c| !c.is_empty()) {
        return Ok(c.clone());
    }
    std::env::current_exe()
        .and_then(|p| p.canonicalize())
        .map(|p| vec![p.display().to_string()])
        .map_err(|e| format!("cannot find the batstudy binary's path: {e}"))
}

/// `batstudy slurm`: write the job array, merge job and submit scripts (or, with
/// `--resubmit`, submit what is unfinished).
pub(super) fn cmd_slurm(a: &SlurmArgs, invocation: &Invocation) -> i32 {
    if let Some(dir) = &a.resubmit {
        return resubmit(dir, &a.sbatch_args);
    }
    let (Some(study_file), Some(shards)) = (a.study.as_deref(), a.shards) else {
        unreachable!("clap requires STUDY and --shards without --resubmit")
    };
    let study = match load_or_report(study_file, a.max_points) {
        Ok(s) => s,
        Err(code) => return code,
    };
    if let Err(e) = refuse_search(&study) {
        eprintln!("{e}");
        return EXIT_BAD_INPUT;
    }
    let job = check_flags(a, study_file, shards)
        .map_err(JobError::Flag)
        .and_then(|()| job_of(a, invocation, &study, shards));
    let job = match job {
        Ok(j) => j,
        Err(JobError::Run(m)) => {
            eprintln!("error: {m}");
            return EXIT_RUN_FAILED;
        }
        Err(JobError::Flag(e)) => {
            eprintln!("{e}");
            return EXIT_BAD_INPUT;
        }
    };
    warn_about(&job, study.plan.n_points());
    write_job(&job)
}

/// Why the scripts cannot be written: a bad flag (exit 2) or the machine (exit 3).
enum JobError {
    Flag(StudyError),
    Run(String),
}

fn bad_flag(study_file: &Path, name: &str, value: String, allowed: &str) -> StudyError {
    StudyError::new(study_file, format!("bad {name}"))
        .field(name)
        .value(value)
        .allowed(allowed)
}

/// The flags that go into the scripts, each in the form Slurm takes.
fn check_flags(a: &SlurmArgs, study_file: &Path, shards: usize) -> Result<(), StudyError> {
    let bad =
        |name: &str, value: String, allowed: &str| Err(bad_flag(study_file, name, value, allowed));
    if !a.sbatch_args.is_empty() {
        let allowed = "sbatch options only with --resubmit (give them to submit.sh otherwise)";
        return bad("-- ARGS", a.sbatch_args.join(" "), allowed);
    }
    if !(1..=MAX_SHARDS).contains(&shards) {
        return bad(
            "--shards",
            shards.to_string(),
            &format!("a number of shards from 1 to {MAX_SHARDS}"),
        );
    }
    if !(1..=MAX_JOBS).contains(&a.cpus_per_task) {
        return bad(
            "--cpus-per-task",
            a.cpus_per_task.to_string(),
            &format!("a number of cores from 1 to {MAX_JOBS}"),
        );
    }
    for (name, v) in [("--time", &a.time), ("--merge-time", &a.merge_time)] {
        if let Some(t) = v.as_ref().filter(|t| !crate::slurm::valid_time(t)) {
            return bad(
                name,
                t.clone(),
                "a Slurm time limit: MM, HH:MM:SS, D-HH or D-HH:MM:SS",
            );
        }
    }
    if let Some(m) = a.mem.as_ref().filter(|m| !crate::slurm::valid_mem(m)) {
        return bad("--mem", m.clone(), "a size such as 4G or 500M");
    }
    if let Some(p) = a
        .partition
        .as_ref()
        .filter(|p| !crate::slurm::sbatch_safe(p))
    {
        return bad("--partition", p.clone(), "a partition name");
    }
    Ok(())
}

/// The job: the command, the study, the folder and the output as absolute paths, checked.
fn job_of(
    a: &SlurmArgs,
    invocation: &Invocation,
    study: &crate::study::Study,
    shards: usize,
) -> Result<crate::slurm::SlurmJob, JobError> {
    let study_file = study.path.as_path();
    let flag = |name: &str, value: String, allowed: &str| {
        JobError::Flag(bad_flag(study_file, name, value, allowed))
    };
    let command = batstudy_command(invocation).map_err(JobError::Run)?;
    let study_path = study_file
        .canonicalize()
        .map_err(|e| flag("STUDY", format!("{} ({e})", study_file.display()), "a file"))?;
    let name = study.file.name.clone();
    let dir = absolute(
        &a.dir
            .clone()
            .unwrap_or_else(|| PathBuf::from("slurm").join(&name)),
    );
    if !crate::slurm::sbatch_safe(&dir.display().to_string()) {
        return Err(flag(
            "--dir",
            dir.display().to_string(),
            "a folder path of printable ASCII without spaces, quotes, `\\`, `$`, backticks, `#`, `;` or `%` (it goes into #SBATCH lines)",
        ));
    }
    let output = absolute(&study.output_path(a.output.as_deref()));
    if let Err((msg, allowed)) = check_output(&output, Existing::Refuse) {
        if !output.exists() {
            return Err(flag("--output", output.display().to_string(), &allowed));
        }
        eprintln!("warning: {msg}: the merge job will refuse to replace it; remove it or choose another -o before submitting");
    }
    Ok(crate::slurm::SlurmJob {
        command,
        study: study_path,
        name,
        shards,
        merge_time: a.merge_time.clone().or_else(|| a.time.clone()),
        time: a.time.clone(),
        partition: a.partition.clone(),
        cpus_per_task: a.cpus_per_task,
        mem: a.mem.clone(),
        output,
        dir,
    })
}

fn warn_about(job: &crate::slurm::SlurmJob, n: usize) {
    if job.shards > n {
        eprintln!(
            "warning: {} shards for {n} points: {} shards will be empty",
            job.shards,
            job.shards - n
        );
    }
}

/// Write the scripts and say how to submit them.
fn write_job(job: &crate::slurm::SlurmJob) -> i32 {
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

/// A design search is one sequence of candidates, each run over the study's grid: shards
/// of its grid would run the base design alone, which is not what the study asks.
fn refuse_search(study: &crate::study::Study) -> Result<(), crate::study::StudyError> {
    if study.file.optimize.is_none() {
        return Ok(());
    }
    let mut e = crate::study::StudyError::new(
        &study.path,
        "a study with an `optimize` block is a design search, which `batstudy slurm` cannot split into shards",
    )
    .field("optimize")
    .allowed("`batstudy optimize STUDY --resume -o OUT` in one job (its candidates run on all the job's cores; --resume continues it after a time limit)");
    if let Some(p) = study.position_of("optimize") {
        e = e.at(Some(p));
    }
    Err(e)
}
