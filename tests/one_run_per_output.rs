//! Nothing a user does can corrupt a result: a second process on a running
//! output is refused and changes nothing; a SIGKILLed holder blocks nobody; a point that
//! runs out of steps fails alone; a reader that goes away ends a command quietly; a what-if
//! study is recorded as such.
//!
//! The lock is flock(2) on `OUT.h5.lock`: the kernel releases it when its holder dies
//! ("the lock is released ... when all file descriptors referring to it are closed", which
//! process exit does), so these tests kill real processes rather than trust a model of it.

mod common;

use batstudy::store::read_results;
use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::Mutex;
use std::time::{Duration, Instant};

/// One test at a time: a child spawned while another test holds an HDF5 file open would
/// inherit its descriptor (and HDF5's lock on it).
static SERIAL: Mutex<()> = Mutex::new(());

const STUDY: &str = r#"
name: lock_test
base:
  bat: {preset: r161}
  ball: {speed: 40.0}
grid:
  swing.omega: [0, -15, -30, -45, -60]
  bat.material.density: [600, 649, 700]
  impact.z: {range: [0.40, 0.84, 0.002]}
"#;

use common::{batstudy_command as batstudy, batstudy_ok, stored_records as data};

fn lock_of(out: &Path) -> PathBuf {
    PathBuf::from(format!("{}.lock", out.display()))
}

/// Wait until the run has taken its lock (its first act on the output).
fn wait_for_lock(out: &Path) {
    let start = Instant::now();
    while !lock_of(out).exists() {
        assert!(start.elapsed() < Duration::from_secs(30), "no lock file");
        std::thread::sleep(Duration::from_millis(5));
    }
}

fn study_file(dir: &Path, text: &str) -> String {
    let p = dir.join("study.yaml");
    std::fs::write(&p, text).unwrap();
    p.to_str().unwrap().to_string()
}

fn lone_run(dir: &Path, study: &str) -> Vec<String> {
    let reference = dir.join("reference.h5");
    batstudy_ok(&["run", study, "-o", reference.to_str().unwrap(), "-q"]);
    data(&reference)
}

#[test]
fn a_second_run_on_a_running_output_is_refused_and_changes_nothing() {
    let _serial = SERIAL.lock().unwrap_or_else(|p| p.into_inner());
    let dir = tempfile::tempdir().unwrap();
    let study = study_file(dir.path(), STUDY);
    let want = lone_run(dir.path(), &study);

    let out = dir.path().join("out.h5");
    let o = out.to_str().unwrap();
    let first = batstudy(&["run", &study, "-o", o, "-j", "1", "-q"])
        .spawn()
        .unwrap();
    wait_for_lock(&out);
    // The same command, then with --resume and --force: each refused while the first runs.
    for extra in [&[][..], &["--resume"], &["--force"]] {
        let mut args = vec!["run", &study, "-o", o, "-q"];
        args.extend_from_slice(extra);
        let second = batstudy(&args).output().unwrap();
        let err = String::from_utf8_lossy(&second.stderr);
        assert_eq!(second.status.code(), Some(2), "{extra:?}: {err}");
        assert!(err.contains(o), "names the output: {err}");
        assert!(
            err.contains("in use by another batstudy process"),
            "{extra:?}: {err}"
        );
        assert!(
            err.contains(&format!("pid={}", first.id())),
            "names the holder's pid: {err}"
        );
        assert!(err.contains("host=") && err.contains("started="), "{err}");
    }
    let first = first.wait_with_output().unwrap();
    assert!(
        first.status.success(),
        "{}",
        String::from_utf8_lossy(&first.stderr)
    );
    assert_eq!(data(&out), want, "the first run's file equals a lone run's");
    assert!(
        !lock_of(&out).exists(),
        "the lock file is removed at the end"
    );
}

#[test]
fn a_sigkilled_holder_does_not_block_the_next_run() {
    let _serial = SERIAL.lock().unwrap_or_else(|p| p.into_inner());
    let dir = tempfile::tempdir().unwrap();
    let study = study_file(dir.path(), STUDY);
    let want = lone_run(dir.path(), &study);

    let out = dir.path().join("out.h5");
    let o = out.to_str().unwrap();
    let mut holder = batstudy(&["run", &study, "-o", o, "-j", "1", "-q"])
        .spawn()
        .unwrap();
    wait_for_lock(&out);
    // mid-run: its points have begun (the journal is there), most are still to come
    let journal = PathBuf::from(format!("{o}.journal"));
    while !journal.exists() && holder.try_wait().unwrap().is_none() {
        std::thread::sleep(Duration::from_millis(1));
    }
    std::thread::sleep(Duration::from_millis(20));
    holder.kill().unwrap(); // SIGKILL: the lock file stays, the lock does not
    let _ = holder.wait();
    assert!(lock_of(&out).exists(), "a killed run leaves its lock file");
    let next = batstudy(&["run", &study, "-o", o, "-q", "--resume"])
        .output()
        .unwrap();
    assert!(
        next.status.success(),
        "{}",
        String::from_utf8_lossy(&next.stderr)
    );
    assert_eq!(data(&out), want);
}

#[test]
fn merge_refuses_an_output_in_use() {
    let _serial = SERIAL.lock().unwrap_or_else(|p| p.into_inner());
    let dir = tempfile::tempdir().unwrap();
    let study = study_file(
        dir.path(),
        "name: small\nbase: {}\ngrid:\n  impact.z: [0.5, 0.6, 0.7, 0.8]\n",
    );
    let mut shards = Vec::new();
    for k in 1..=2 {
        let p = dir.path().join(format!("s{k}.h5"));
        let shard = format!("{k}/2");
        batstudy_ok(&[
            "run",
            &study,
            "--shard",
            &shard,
            "-o",
            p.to_str().unwrap(),
            "-q",
        ]);
        shards.push(p.to_str().unwrap().to_string());
    }
    let merged = dir.path().join("merged.h5");
    // Another process holds the output: this test process, through the library.
    let held = batstudy::store::lock::OutputLock::acquire(&merged).unwrap();
    let mut args = vec!["merge", "-o", merged.to_str().unwrap(), "-q"];
    args.extend(shards.iter().map(String::as_str));
    let out = batstudy(&args).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("in use by another batstudy process"), "{err}");
    assert!(!merged.exists(), "nothing written");
    drop(held);
    batstudy_ok(&args);
}

#[test]
fn a_point_that_runs_out_of_steps_fails_alone() {
    let _serial = SERIAL.lock().unwrap_or_else(|p| p.into_inner());
    // The base case takes about 560 modal steps (1.4 ms of contact and 0.5 ms of watching
    // for a re-contact, at 3.4 µs); 300 passes validation (the watch alone needs 147) and
    // runs out at run time. The grid's other point has the default budget.
    let dir = tempfile::tempdir().unwrap();
    let study = study_file(
        dir.path(),
        "name: budget\nbase: {impact: {z: 0.6}}\ngrid:\n  numerics.max_steps: [300, 10000000]\n",
    );
    let out_path = dir.path().join("budget.h5");
    let start = Instant::now();
    let out = batstudy(&["run", &study, "-o", out_path.to_str().unwrap()])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(start.elapsed() < Duration::from_secs(30));
    let records = read_results(&out_path).unwrap().records;
    let failed: Vec<_> = records.iter().filter(|r| r.result.is_err()).collect();
    assert_eq!(failed.len(), 1, "{records:?}");
    let text = failed[0].result.as_ref().unwrap_err();
    assert!(text.contains("numerics.max_steps = 300"), "{text}");
    assert!(text.contains("stopped"), "{text}");
}

#[test]
fn a_reader_that_goes_away_ends_the_command_quietly() {
    let _serial = SERIAL.lock().unwrap_or_else(|p| p.into_inner());
    let mut child = Command::new(env!("CARGO_BIN_EXE_batstudy"))
        .args(["plan", "studies/param_space.yaml", "--list"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut first = String::new();
    BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut first)
        .unwrap(); // `| head -1`: one line, then the pipe closes
    assert!(first.starts_with("study param_space"), "{first}");
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!err.contains("panic"), "{err}");
    assert!(!err.contains("failed printing"), "{err}");
}

#[test]
fn a_what_if_study_runs_and_says_so_in_the_file() {
    let _serial = SERIAL.lock().unwrap_or_else(|p| p.into_inner());
    let dir = tempfile::tempdir().unwrap();
    let text = "name: whatif\nallow_implausible: true\nbase: {bat: {material: {density: 2.0e4}}}\ngrid:\n  impact.z: [0.6]\n";
    let study = study_file(dir.path(), text);
    let out_path = dir.path().join("whatif.h5");
    batstudy_ok(&["run", &study, "-o", out_path.to_str().unwrap(), "-q"]);
    let f = hdf5::File::open(&out_path).unwrap();
    let flag: i64 = f.attr("allow_implausible").unwrap().read_scalar().unwrap();
    assert_eq!(flag, 1);
    drop(f);
    // Without the opt-out the same study is refused.
    let refused = text.replace("allow_implausible: true\n", "");
    let study = study_file(dir.path(), &refused);
    let out = batstudy(&["validate", &study]).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
}

/// A search still running on an output (its journal beside it, its lock held) is reported
/// as busy, not as an interrupted search to `--resume` (which would then fight over it).
#[test]
fn a_busy_search_is_reported_busy() {
    let _serial = SERIAL.lock().unwrap_or_else(|p| p.into_inner());
    let dir = tempfile::tempdir().unwrap();
    let study = study_file(
        dir.path(),
        "name: busy\nmodel: rigid\nbase: {impact: {z: 0.7}}\noptimize:\n  max_evaluations: 5\n  \
         variables: {impact.z: {min: 0.5, max: 0.8}}\n  objective: {maximize: exit_speed}\n",
    );
    let out = dir.path().join("busy.h5");
    let journal = dir.path().join("busy.h5.optimize");
    std::fs::write(&journal, b"{}\n").unwrap();
    let held = batstudy::store::lock::OutputLock::acquire(&out).unwrap();
    let o = batstudy(&["optimize", &study, "-o", out.to_str().unwrap(), "-q"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("in use by another batstudy process"), "{err}");
    assert!(!err.contains("an interrupted search"), "{err}");
    drop(held);
    assert_eq!(
        std::fs::read(&journal).unwrap(),
        b"{}\n",
        "the journal untouched"
    );
}

/// A journal whose header is damaged cannot be resumed; the refusal says how to start over.
#[test]
fn a_damaged_journal_names_the_way_out() {
    let _serial = SERIAL.lock().unwrap_or_else(|p| p.into_inner());
    let dir = tempfile::tempdir().unwrap();
    let study = study_file(
        dir.path(),
        "name: dmg\nmodel: rigid\nbase: {impact: {z: 0.7}}\n",
    );
    let out = dir.path().join("dmg.h5");
    std::fs::write(dir.path().join("dmg.h5.journal"), b"not a journal at all").unwrap();
    let o = batstudy(&["run", &study, "-o", out.to_str().unwrap(), "--resume", "-q"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_ne!(o.status.code(), Some(0), "{err}");
    assert!(
        err.contains("damaged journal") && err.contains("--force"),
        "{err}"
    );
    batstudy_ok(&["run", &study, "-o", out.to_str().unwrap(), "--force", "-q"]);
}
