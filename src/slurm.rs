//! `batstudy slurm`: Slurm job scripts for a study split into shards.
//!
//! Three files in one folder: `array.sbatch` (a job array, one task per shard, each running
//! `batstudy run STUDY --shard $SLURM_ARRAY_TASK_ID/N --resume` on its task's cores),
//! `merge.sbatch` (`batstudy merge` of the shard files into the study's results file, after
//! checking that every shard is finished) and `submit.sh` (submits the array tasks whose
//! shard is not finished yet, then the merge with `--dependency=afterany:<array job id>`).
//! `submit.sh` is idempotent: after a time-out, a cancellation or a failed task, running it
//! again submits only the unfinished shards (`batstudy slurm --resubmit DIR` runs it).
//!
//! Safe by construction: every value that comes from the study, the command line
//! or the file system reaches a script once, as the right-hand side of a shell assignment
//! quoted by [`sh_quote`], and is used afterwards only as `"$VAR"`. No value is written
//! inside another quoting context (an `echo "…"`, a comment) or anywhere bash would parse
//! it again. The few values that must go into `#SBATCH` lines (which Slurm does not unquote)
//! are checked by [`sbatch_safe`] or their own format checks before the scripts are written.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Everything the scripts need (paths absolute).
#[derive(Debug, Clone)]
pub struct SlurmJob {
    /// The command that runs batstudy on a compute node, as words (e.g. the binary's path,
    /// or the wheel's `batstudy` command, or `python -m batstudy`).
    pub command: Vec<String>,
    /// The study file.
    pub study: PathBuf,
    /// Study name (job names, shard file names; validated: letters, digits, `_-.`).
    pub name: String,
    /// Number of shards (array tasks).
    pub shards: usize,
    /// `--time` of each array task (Slurm time format), if any.
    pub time: Option<String>,
    /// `--time` of the merge job, if any.
    pub merge_time: Option<String>,
    pub partition: Option<String>,
    pub cpus_per_task: usize,
    /// `--mem` of each task (e.g. `4G`), if any.
    pub mem: Option<String>,
    /// The merged results file.
    pub output: PathBuf,
    /// The folder of the scripts, shard files and logs.
    pub dir: PathBuf,
}

/// Quote one word for bash: the only way a value enters a generated script. Plain words
/// stay as they are; anything else is single-quoted (a `'` inside becomes `'\''`), which
/// bash takes literally: no expansion, substitution or word splitting, newlines included.
pub fn sh_quote(s: &str) -> String {
    if !s.is_empty()
        && s.bytes()
            .all(|b| b.is_ascii_alphanumeric() || b"/._-+=:,@%".contains(&b))
    {
        s.to_string()
    } else {
        format!("'{}'", s.replace('\'', r"'\''"))
    }
}

fn q(p: &Path) -> String {
    sh_quote(&p.display().to_string())
}

/// Is `s` a Slurm time limit (`M`, `M:S`, `H:M:S`, `D-H`, `D-H:M`, `D-H:M:S`, `UNLIMITED`)?
pub fn valid_time(s: &str) -> bool {
    if s.eq_ignore_ascii_case("unlimited") || s.eq_ignore_ascii_case("infinite") {
        return true;
    }
    let num = |x: &str| !x.is_empty() && x.len() <= 6 && x.bytes().all(|b| b.is_ascii_digit());
    let (days, rest) = match s.split_once('-') {
        Some((d, r)) => (Some(d), r),
        None => (None, s),
    };
    if days.is_some_and(|d| !num(d)) {
        return false;
    }
    let parts: Vec<&str> = rest.split(':').collect();
    parts.iter().all(|p| num(p)) && (1..=3).contains(&parts.len())
}

/// Is `s` a Slurm memory size (a number with an optional K/M/G/T suffix)?
pub fn valid_mem(s: &str) -> bool {
    let t = s.trim_end_matches(['K', 'M', 'G', 'T', 'k', 'm', 'g', 't']);
    !t.is_empty() && t.len() + 1 >= s.len() && t.bytes().all(|b| b.is_ascii_digit())
}

/// Is `s` safe in an `#SBATCH` line (Slurm does not unquote these)? Printable ASCII without
/// white space, quotes, `\`, `$`, backticks, `#`, `;` or `%` (a Slurm filename pattern).
pub fn sbatch_safe(s: &str) -> bool {
    !s.is_empty()
        && s.chars()
            .all(|c| c.is_ascii_graphic() && !"'\"\\$`#;%".contains(c))
}

/// The shell lines every script starts with after its `#SBATCH` header: the values as
/// quoted assignments, and `shard_file I` (the path of shard I's file).
fn variables(job: &SlurmJob) -> String {
    let mut s = String::new();
    let words: Vec<String> = job.command.iter().map(|w| sh_quote(w)).collect();
    let _ = writeln!(s, "BATSTUDY=({})", words.join(" "));
    let _ = writeln!(s, "STUDY={}", q(&job.study));
    let _ = writeln!(s, "NAME={}", sh_quote(&job.name));
    let _ = writeln!(s, "SHARDS={}", job.shards);
    let _ = writeln!(s, "OUTPUT={}", q(&job.output));
    let _ = writeln!(s, "DIR={}", q(&job.dir));
    s.push_str("shard_file() { printf '%s/%s.shard-%s-of-%s.h5' \"$DIR\" \"$NAME\" \"$1\" \"$SHARDS\"; }\n");
    s
}

/// Lists the unfinished shards (those without a finished file) in the array `missing`.
const FIND_MISSING: &str = r#"missing=()
for i in $(seq 1 "$SHARDS"); do
  [ -e "$(shard_file "$i")" ] || missing+=("$i")
done
"#;

impl SlurmJob {
    /// The shard file of shard `i` (1-based).
    pub fn shard_file(&self, i: usize) -> PathBuf {
        self.dir
            .join(format!("{}.shard-{i}-of-{}.h5", self.name, self.shards))
    }

    fn logs(&self) -> PathBuf {
        self.dir.join("logs")
    }

    fn header(&self, s: &mut String, job: &str, time: Option<&str>) {
        let _ = writeln!(s, "#!/bin/bash");
        let _ = writeln!(s, "#SBATCH --job-name={job}");
        if let Some(p) = &self.partition {
            let _ = writeln!(s, "#SBATCH --partition={p}");
        }
        if let Some(t) = time {
            let _ = writeln!(s, "#SBATCH --time={t}");
        }
    }

    fn resources(&self, s: &mut String, cpus: usize, log: &str) {
        let _ = writeln!(s, "#SBATCH --nodes=1");
        let _ = writeln!(s, "#SBATCH --ntasks=1");
        let _ = writeln!(s, "#SBATCH --cpus-per-task={cpus}");
        if let Some(m) = &self.mem {
            let _ = writeln!(s, "#SBATCH --mem={m}");
        }
        let _ = writeln!(s, "#SBATCH --output={}/{log}", self.logs().display());
        let _ = writeln!(s, "#SBATCH --chdir={}", self.dir.display());
    }

    /// The job array: one task per shard (`submit.sh` narrows `--array` to the unfinished).
    pub fn array_script(&self) -> String {
        let mut s = String::new();
        self.header(
            &mut s,
            &format!("batstudy-{}", self.name),
            self.time.as_deref(),
        );
        let _ = writeln!(s, "#SBATCH --array=1-{}", self.shards);
        self.resources(&mut s, self.cpus_per_task, "shard-%a.out");
        s.push_str(
            r#"# Generated by `batstudy slurm`: one shard of the study per array task.
# Re-running a task (requeue, or submitting again) continues its shard file with --resume:
# only the points not yet finished are computed. Slurm's SIGTERM (time limit, scancel)
# stops it as Ctrl-C does: the points in flight finish and everything done is kept.
set -euo pipefail
"#,
        );
        s.push_str(&variables(self));
        let _ = write!(
            s,
            r#"I=${{SLURM_ARRAY_TASK_ID:?this script is a Slurm array job: submit it with sbatch}}
JOBS=${{SLURM_CPUS_PER_TASK:-{cpus}}}
OUT=$(shard_file "$I")
printf 'batstudy shard %s/%s of %s on %s with %s threads -> %s\n' "$I" "$SHARDS" "$STUDY" "$(hostname)" "$JOBS" "$OUT"
rc=0
"${{BATSTUDY[@]}}" run "$STUDY" --shard "$I/$SHARDS" --jobs "$JOBS" --resume --quiet -o "$OUT" || rc=$?
if [ "$rc" -eq 1 ]; then
  # some points failed: their error text is in the shard file, as in a single run
  printf 'shard %s/%s: some points failed (recorded in %s)\n' "$I" "$SHARDS" "$OUT"
  exit 0
fi
exit "$rc"
"#,
            cpus = self.cpus_per_task,
        );
        s
    }

    /// The merge job: runs after the array however it ended (`afterany`), refuses an
    /// incomplete set with the command that completes it.
    pub fn merge_script(&self) -> String {
        let mut s = String::new();
        self.header(
            &mut s,
            &format!("batstudy-{}-merge", self.name),
            self.merge_time.as_deref(),
        );
        self.resources(&mut s, 1, "merge.out");
        s.push_str(
            r#"# Generated by `batstudy slurm`: merges the shard files into one results file, identical
# in data to a single-process run. Runs after the array however it ended; refuses (exit 2,
# nothing written) if a shard is unfinished, naming the command that finishes it.
set -euo pipefail
"#,
        );
        s.push_str(&variables(self));
        s.push_str(FIND_MISSING);
        s.push_str(
            r#"if ((${#missing[@]})); then
  {
    printf 'batstudy merge: %s of %s shards are not finished (shards %s); nothing was merged.\n' \
      "${#missing[@]}" "$SHARDS" "${missing[*]}"
    printf 'Submit only those, and the merge again, with:\n  bash %q\n' "$DIR/submit.sh"
    printf 'or: batstudy slurm --resubmit %q\n' "$DIR"
  } >&2
  exit 2
fi
shards=()
for i in $(seq 1 "$SHARDS"); do
  shards+=("$(shard_file "$i")")
done
rc=0
"${BATSTUDY[@]}" merge -o "$OUTPUT" "${shards[@]}" || rc=$?
if [ "$rc" -eq 1 ]; then
  printf 'merged into %s; some points failed (their error text is stored)\n' "$OUTPUT"
  exit 0
fi
exit "$rc"
"#,
        );
        s
    }

    /// Submits the array tasks of the unfinished shards, then the merge after them.
    pub fn submit_script(&self) -> String {
        let mut s = String::from(
            r#"#!/bin/bash
# Generated by `batstudy slurm`: submits the array tasks of every shard that is not finished
# yet (all of them the first time), then the merge job, which runs when they have ended
# (afterany) and refuses an incomplete set. Run it again after a time-out, a cancellation or
# a failed task: it submits only what is left. Extra sbatch options (e.g. --account=X) can
# be given as arguments; they go to both jobs.
set -euo pipefail
"#,
        );
        s.push_str(&variables(self));
        s.push_str(
            r#"if [ -e "$OUTPUT" ]; then
  printf 'results already merged: %s (remove it to merge again)\n' "$OUTPUT"
  exit 0
fi
mkdir -p "$DIR/logs"
"#,
        );
        s.push_str(FIND_MISSING);
        s.push_str(
            r#"dependency=()
array_id=none
if ((${#missing[@]})); then
  list=$(IFS=,; printf '%s' "${missing[*]}")
  array_id=$(sbatch --parsable "$@" --array="$list" "$DIR/array.sbatch")
  array_id=${array_id%%;*}   # --parsable prints "jobid[;cluster]"
  dependency=(--dependency=afterany:"$array_id")
  printf 'submitted array job %s: shards %s of %s\n' "$array_id" "$list" "$SHARDS"
else
  printf 'every shard is finished: submitting the merge only\n'
fi
merge_id=$(sbatch --parsable "$@" "${dependency[@]}" "$DIR/merge.sbatch")
merge_id=${merge_id%%;*}
printf 'ARRAY_JOB_ID=%s\nMERGE_JOB_ID=%s\n' "$array_id" "$merge_id" > "$DIR/jobs.env"
printf 'submitted merge job %s (after the array); results: %s\n' "$merge_id" "$OUTPUT"
"#,
        );
        s
    }

    /// Write the three scripts (and the logs folder) into `dir`; returns their paths.
    pub fn write(&self) -> std::io::Result<Vec<PathBuf>> {
        std::fs::create_dir_all(self.logs())?;
        let mut paths = Vec::new();
        for (name, text) in [
            ("array.sbatch", self.array_script()),
            ("merge.sbatch", self.merge_script()),
            ("submit.sh", self.submit_script()),
        ] {
            let p = self.dir.join(name);
            std::fs::write(&p, text)?;
            #[cfg(unix)]
            {
                use std::os::unix::fs::PermissionsExt;
                std::fs::set_permissions(&p, std::fs::Permissions::from_mode(0o755))?;
            }
            paths.push(p);
        }
        Ok(paths)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // option values that sbatch accepts
    #[test]
    fn time_and_mem_formats() {
        for t in ["10", "00:10:00", "1-00:00:00", "2-12", "5:00", "UNLIMITED"] {
            assert!(valid_time(t), "{t}");
        }
        for t in ["", "1h", "1:2:3:4", "-1", "a-1"] {
            assert!(!valid_time(t), "{t}");
        }
        for m in ["4G", "512M", "1000", "2t"] {
            assert!(valid_mem(m), "{m}");
        }
        for m in ["", "G", "4GB", "four"] {
            assert!(!valid_mem(m), "{m}");
        }
        assert_eq!(sh_quote("/a/b c"), "'/a/b c'");
        assert_eq!(sh_quote("it's"), r"'it'\''s'");
        assert_eq!(sh_quote("/a/b.h5"), "/a/b.h5");
    }

    // what bash reads back from a quoted word is the word, whatever it holds
    #[test]
    fn quoted_words_read_back_literally() {
        for w in [
            "$(touch /tmp/x)",
            "`id`",
            "a\";id;\"b",
            "it's",
            "new\nline",
            "tab\there",
            "*",
            "~",
            "!x",
            "",
            "\\",
        ] {
            let script = format!("printf '%s' {}", sh_quote(w));
            let out = std::process::Command::new("bash")
                .args(["-c", &script])
                .output()
                .unwrap();
            assert_eq!(String::from_utf8_lossy(&out.stdout), w, "{script}");
        }
    }
}
