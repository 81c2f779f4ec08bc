//! The generated Slurm scripts, run with a stand-in `sbatch` that runs
//! each job at once on this machine: an array task per listed index, then the merge.
//!
//! - Shell metacharacters in every value that reaches a script (the study's path, its
//!   `output`) are data, never code: nothing injected runs, and the merged file lands at the
//!   literal path.
//! - After a task that did not run (a time-out, a cancellation), the merge refuses and names
//!   the command that completes the set; `batstudy slurm --resubmit DIR` submits only the
//!   unfinished shard, and the merge then succeeds.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The stand-in: logs its arguments, runs the script in its `#SBATCH --chdir`, once per
/// array index (`--array=1,3` or `1-3`) or once; tasks listed in STANDIN_SKIP_TASKS do not
/// run (as if cancelled). Job output goes to the log, as Slurm sends it to files.
const SBATCH: &str = r#"#!/bin/bash
echo "sbatch $*" >> "$STANDIN_LOG"
array="" script=""
for a in "$@"; do
  case "$a" in
    --array=*) array=${a#--array=} ;;
    -*) ;;
    *) script=$a ;;
  esac
done
chdir=$(sed -n 's/^#SBATCH --chdir=//p' "$script")
tasks=()
IFS=, read -ra parts <<< "$array"
for p in "${parts[@]}"; do
  if [[ $p == *-* ]]; then tasks+=($(seq "${p%-*}" "${p#*-}")); else tasks+=("$p"); fi
done
if ((${#tasks[@]})); then
  for i in "${tasks[@]}"; do
    [[ ",${STANDIN_SKIP_TASKS:-}," == *",$i,"* ]] && continue
    (cd "$chdir" && SLURM_ARRAY_TASK_ID=$i SLURM_CPUS_PER_TASK=1 bash "$script") >> "$STANDIN_LOG.jobs" 2>&1
  done
else
  (cd "$chdir" && bash "$script") >> "$STANDIN_LOG.jobs" 2>&1
  echo "exit $?" >> "$STANDIN_LOG.jobs"
fi
echo "$RANDOM"
"#;

const STUDY: &str = "name: slurmrun
model: rigid
base:
  ball: {speed: 40}
grid:
  impact.z: [0.55, 0.6, 0.65, 0.7, 0.75, 0.8]
";

struct Cluster {
    _tmp: tempfile::TempDir,
    root: PathBuf,
    bin: PathBuf,
    log: PathBuf,
}

impl Cluster {
    fn new() -> Cluster {
        let tmp = tempfile::tempdir().unwrap();
        let root = tmp.path().canonicalize().unwrap();
        let bin = root.join("bin");
        std::fs::create_dir_all(&bin).unwrap();
        let sbatch = bin.join("sbatch");
        std::fs::write(&sbatch, SBATCH).unwrap();
        use std::os::unix::fs::PermissionsExt;
        std::fs::set_permissions(&sbatch, std::fs::Permissions::from_mode(0o755)).unwrap();
        let log = root.join("sbatch.log");
        Cluster {
            _tmp: tmp,
            root,
            bin,
            log,
        }
    }

    fn command(&self, program: &str, args: &[&str], skip: &str) -> Output {
        let path = format!(
            "{}:{}",
            self.bin.display(),
            std::env::var("PATH").unwrap_or_default()
        );
        Command::new(program)
            .args(args)
            .current_dir(&self.root)
            .env("PATH", path)
            .env("STANDIN_LOG", &self.log)
            .env("STANDIN_SKIP_TASKS", skip)
            .output()
            .unwrap()
    }

    fn batstudy(&self, args: &[&str], skip: &str) -> Output {
        self.command(env!("CARGO_BIN_EXE_batstudy"), args, skip)
    }

    fn jobs_log(&self) -> String {
        std::fs::read_to_string(self.log.with_extension("log.jobs")).unwrap_or_default()
    }
}

fn assert_ok(o: &Output, what: &str) {
    assert!(
        o.status.success(),
        "{what}: exit {:?}\n{}\n{}",
        o.status.code(),
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
}

/// Every file below `root` whose name starts with `INJECTED`.
fn injected(root: &Path) -> Vec<PathBuf> {
    let mut found = Vec::new();
    let mut stack = vec![root.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap().flatten() {
            let p = e.path();
            if e.file_name().to_string_lossy().starts_with("INJECTED") {
                found.push(p.clone());
            }
            if e.file_type().unwrap().is_dir() {
                stack.push(p);
            }
        }
    }
    found
}

// `$(…)`, backticks and `";…;"` in the study's output, and quotes in the study file's
// path, are data: nothing runs them as commands when submit.sh and the array tasks run.
#[test]
fn metacharacters_in_paths_run_nothing() {
    let c = Cluster::new();
    let study_dir = c.root.join("lab's \"x\" $(touch INJECTED_study_dir)");
    std::fs::create_dir_all(&study_dir).unwrap();
    let output =
        "out $(touch INJECTED_dollar) `touch INJECTED_tick` \";touch INJECTED_semi;\" \\\n/r.h5";
    let study = study_dir.join("s`touch INJECTED_file`.yaml");
    std::fs::write(
        &study,
        format!(
            "{STUDY}output: {}\n",
            serde_json::to_string(output).unwrap()
        ),
    )
    .unwrap();
    let study_arg = study.display().to_string();
    let o = c.batstudy(&["slurm", &study_arg, "--shards", "3", "--dir", "jobs"], "");
    assert_ok(&o, "batstudy slurm");
    let o = c.command("bash", &["jobs/submit.sh"], "");
    assert_ok(&o, "submit.sh");
    assert!(c.jobs_log().contains("exit 0"), "{}", c.jobs_log());
    let merged = c.root.join(output);
    assert!(
        merged.is_file(),
        "no merged file at {merged:?}:\n{}",
        c.jobs_log()
    );
    assert_eq!(injected(&c.root), Vec::<PathBuf>::new(), "{}", c.jobs_log());
}

// a task that never ran (time-out, scancel) must not leave the merge pending forever (so
// afterany, not afterok), and `--resubmit` submits only the unfinished shards.
#[test]
fn merge_refuses_an_incomplete_set_and_resubmit_completes_it() {
    let c = Cluster::new();
    std::fs::write(c.root.join("s.yaml"), STUDY).unwrap();
    let o = c.batstudy(
        &[
            "slurm",
            "s.yaml",
            "--shards",
            "3",
            "--dir",
            "jobs",
            "-o",
            "merged.h5",
        ],
        "",
    );
    assert_ok(&o, "batstudy slurm");
    let o = c.command("bash", &["jobs/submit.sh"], "2");
    assert_ok(&o, "submit.sh");
    let log = c.jobs_log();
    assert!(
        log.contains("2 of 3") || log.contains("1 of 3 shards are not finished (shards 2)"),
        "{log}"
    );
    assert!(log.contains("exit 2"), "the merge must refuse: {log}");
    assert!(
        log.contains("--resubmit") && log.contains("submit.sh"),
        "{log}"
    );
    assert!(!c.root.join("merged.h5").exists());

    let o = c.batstudy(&["slurm", "--resubmit", "jobs"], "");
    assert_ok(&o, "batstudy slurm --resubmit");
    let sbatch = std::fs::read_to_string(&c.log).unwrap();
    let arrays: Vec<&str> = sbatch.lines().filter(|l| l.contains("--array=")).collect();
    assert_eq!(arrays.len(), 2, "{sbatch}");
    assert!(arrays[0].contains("--array=1,2,3"), "{sbatch}");
    assert!(
        arrays[1].contains("--array=2 "),
        "only shard 2 again: {sbatch}"
    );
    assert!(c.root.join("merged.h5").is_file(), "{}", c.jobs_log());
    // once merged, submitting again does nothing
    let o = c.command("bash", &["jobs/submit.sh"], "");
    assert_ok(&o, "submit.sh after the merge");
    assert!(String::from_utf8_lossy(&o.stdout).contains("already merged"));
}

// the scripts run the command that started batstudy (the wheel gives its
// own through `Invocation`); the binary's own path otherwise. A missing folder is refused.
#[test]
fn resubmit_needs_a_slurm_folder() {
    let c = Cluster::new();
    let o = c.batstudy(&["slurm", "--resubmit", "nowhere"], "");
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("--resubmit") && err.contains("nowhere"),
        "{err}"
    );
}
