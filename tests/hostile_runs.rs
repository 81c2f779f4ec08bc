//! Runs and merges given what a careless or hostile user, a shared folder or a cluster gives
//! them, through the real binary. Each test fails without the guard it checks.

mod common;

use std::path::{Path, PathBuf};
use std::process::Output;
use std::sync::RwLock;
use std::time::Duration;

/// HDF5 opens files without close-on-exec, with a lock: a child forked while this process
/// holds one open keeps the lock for its life, and a merge in another test then cannot read
/// the file. Files are opened here under [`no_spawns`], children are forked under
/// [`spawn_guard`] (as in tests/shards_merge_slurm.rs).
static FORK: RwLock<()> = RwLock::new(());

fn spawn_guard() -> std::sync::RwLockReadGuard<'static, ()> {
    FORK.read().unwrap_or_else(|e| e.into_inner())
}

fn no_spawns() -> std::sync::RwLockWriteGuard<'static, ()> {
    FORK.write().unwrap_or_else(|e| e.into_inner())
}

fn batstudy_command(args: &[&str]) -> std::process::Command {
    common::batstudy_command(args)
}

fn batstudy_ok(args: &[&str]) {
    let _g = spawn_guard();
    common::batstudy_ok(args)
}

/// Every stored record of a results file (under [`no_spawns`]).
fn stored_records(path: &Path) -> Vec<String> {
    let _g = no_spawns();
    common::stored_records(path)
}

const RIGID: &str = "name: hostile
model: rigid
base: {ball: {speed: 40}}
grid:
  swing.omega: [0, -40]
  impact.z: {range: [0.45, 0.80, 0.05]}
";

fn run(args: &[&str]) -> Output {
    let _g = spawn_guard();
    batstudy_command(args).output().unwrap()
}

fn code(o: &Output) -> Option<i32> {
    o.status.code()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

struct Dir {
    _tmp: tempfile::TempDir,
    path: PathBuf,
}

impl Dir {
    fn with_study(text: &str) -> Dir {
        let tmp = tempfile::tempdir().unwrap();
        let path = tmp.path().to_path_buf();
        std::fs::write(path.join("s.yaml"), text).unwrap();
        Dir { _tmp: tmp, path }
    }
    fn p(&self, name: &str) -> String {
        self.path.join(name).display().to_string()
    }
}

// item 3: a symlink planted at OUT.h5.partial (a shared results folder) was followed and
// its target overwritten
#[test]
fn a_symlink_at_the_partial_file_is_replaced_not_followed() {
    let d = Dir::with_study(RIGID);
    let victim = d.path.join("victim.txt");
    std::fs::write(&victim, "precious").unwrap();
    std::os::unix::fs::symlink(&victim, d.path.join("out.h5.partial")).unwrap();
    batstudy_ok(&["run", &d.p("s.yaml"), "-o", &d.p("out.h5"), "-q"]);
    assert_eq!(std::fs::read_to_string(&victim).unwrap(), "precious");
    assert!(d.path.join("out.h5").is_file());
}

fn sweet_positions(path: &Path) -> Vec<f64> {
    let _g = no_spawns();
    let f = hdf5::File::open(path).unwrap();
    f.dataset("sweet_spot/position")
        .unwrap()
        .read_raw()
        .unwrap()
}

// item 7: a descending impact.z grid (the documented negative-step range) ran with exit 0
// and no sweet spot at all
#[test]
fn a_descending_impact_grid_has_the_ascending_grids_sweet_spots() {
    let up = Dir::with_study(RIGID);
    let down = Dir::with_study(&RIGID.replace("[0.45, 0.80, 0.05]", "[0.80, 0.45, -0.05]"));
    batstudy_ok(&["run", &up.p("s.yaml"), "-o", &up.p("o.h5"), "-q"]);
    batstudy_ok(&["run", &down.p("s.yaml"), "-o", &down.p("o.h5"), "-q"]);
    let (a, b) = (
        sweet_positions(&up.path.join("o.h5")),
        sweet_positions(&down.path.join("o.h5")),
    );
    assert!(a.iter().all(|x| x.is_finite()), "{a:?}");
    assert_eq!(a, b);
}

/// `batstudy run` whose files may grow to `max_bytes` at most (RLIMIT_FSIZE: a write past it
/// fails with EFBIG, as on a full disk; SIGXFSZ ignored so that the write returns an error).
fn run_with_file_limit(args: &[&str], max_bytes: u64) -> Output {
    use std::os::unix::process::CommandExt;
    let mut c = batstudy_command(args);
    // SAFETY: only async-signal-safe calls between fork and exec
    unsafe {
        c.pre_exec(move || {
            libc::signal(libc::SIGXFSZ, libc::SIG_IGN);
            let lim = libc::rlimit {
                rlim_cur: max_bytes,
                rlim_max: max_bytes,
            };
            match libc::setrlimit(libc::RLIMIT_FSIZE, &lim) {
                0 => Ok(()),
                _ => Err(std::io::Error::last_os_error()),
            }
        });
    }
    let _g = spawn_guard();
    c.output().unwrap()
}

// item 10: a disk full at the start gave exit 2 (bad input) and a 0-byte journal that
// --resume then refused; only --force got out. Whichever write the full disk stops (the
// journal's header, the file's skeleton, a record, the final flush), the run fails with
// exit 3 and `--resume` then completes it.
#[test]
fn a_full_disk_is_exit_3_and_resume_completes_the_run() {
    for max_bytes in [100, 128, 160, 192, 256, 1024] {
        let d = Dir::with_study(RIGID);
        let out = d.p("out.h5");
        let o = run_with_file_limit(&["run", &d.p("s.yaml"), "-o", &out, "-q"], max_bytes);
        assert_eq!(code(&o), Some(3), "limit {max_bytes}: {}", stderr(&o));
        let journal = PathBuf::from(format!("{out}.journal"));
        if let Ok(m) = std::fs::metadata(&journal) {
            assert!(m.len() > 0, "limit {max_bytes}: an empty journal was left");
        }
        let o = run(&["run", &d.p("s.yaml"), "-o", &out, "-q", "--resume"]);
        assert_eq!(code(&o), Some(0), "limit {max_bytes}: {}", stderr(&o));
    }
}

// item 10: a refused --resume (damaged journal header) deleted OUT.h5.partial, although
// exit 2 promises nothing was written
#[test]
fn a_refused_resume_touches_nothing() {
    let d = Dir::with_study(RIGID);
    let out = d.p("out.h5");
    std::fs::write(format!("{out}.journal"), b"not a journal at all").unwrap();
    std::fs::write(format!("{out}.partial"), b"the killed run's partial file").unwrap();
    let o = run(&["run", &d.p("s.yaml"), "-o", &out, "-q", "--resume"]);
    assert_eq!(code(&o), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("journal"), "{}", stderr(&o));
    assert_eq!(
        std::fs::read(format!("{out}.partial")).unwrap(),
        b"the killed run's partial file"
    );
    assert_eq!(
        std::fs::read(format!("{out}.journal")).unwrap(),
        b"not a journal at all"
    );
}

// item 12: --force replaced any file, batstudy's or not
#[test]
fn force_replaces_only_batstudy_results() {
    let d = Dir::with_study(RIGID);
    let out = d.p("thesis.h5");
    std::fs::write(&out, b"two years of work").unwrap();
    let o = run(&["run", &d.p("s.yaml"), "-o", &out, "-q", "--force"]);
    assert_eq!(code(&o), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("--force replaces only"),
        "{}",
        stderr(&o)
    );
    assert_eq!(std::fs::read(&out).unwrap(), b"two years of work");
    // a results file is replaced
    let res = d.p("res.h5");
    batstudy_ok(&["run", &d.p("s.yaml"), "-o", &res, "-q"]);
    batstudy_ok(&["run", &d.p("s.yaml"), "-o", &res, "-q", "--force"]);
}

fn two_shards(d: &Dir) -> [String; 2] {
    let s = [d.p("a.h5"), d.p("b.h5")];
    for (k, p) in s.iter().enumerate() {
        let shard = format!("{}/2", k + 1);
        batstudy_ok(&["run", &d.p("s.yaml"), "--shard", &shard, "-o", p, "-q"]);
    }
    s
}

// item 11: a shard whose point ids were altered merged with exit 0; one without its
// point_id array gave exit 3 and left a journal
#[test]
fn merge_refuses_altered_and_incomplete_shards_and_writes_nothing() {
    let d = Dir::with_study(RIGID);
    let [a, b] = two_shards(&d);
    {
        let _g = no_spawns();
        let f = hdf5::File::open_rw(&b).unwrap();
        let ds = f.dataset("summary/point_id").unwrap();
        let mut ids: ndarray::ArrayD<u64> = ds.read_dyn().unwrap();
        let last = ids.iter_mut().filter(|id| **id != 0).last().unwrap();
        *last ^= 1;
        ds.write(&ids).unwrap();
    }
    let merged = d.p("m.h5");
    let o = run(&["merge", "-o", &merged, &a, &b]);
    assert_eq!(code(&o), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("point_id"), "{}", stderr(&o));
    // the study text a shard stores must be the one its sha256 names
    let a2 = d.p("a2.h5");
    std::fs::copy(&a, &a2).unwrap();
    {
        let _g = no_spawns();
        let f = hdf5::File::open_rw(&a2).unwrap();
        let text: hdf5::types::VarLenUnicode =
            RIGID.replace("speed: 40", "speed: 41").parse().unwrap();
        f.attr("study_yaml").unwrap().write_scalar(&text).unwrap();
    }
    let o = run(&["merge", "-o", &merged, &a2, &b]);
    assert_eq!(code(&o), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("sha256"), "{}", stderr(&o));
    {
        let _g = no_spawns();
        let f = hdf5::File::open_rw(&b).unwrap();
        f.group("summary").unwrap().unlink("point_id").unwrap();
    }
    let o = run(&["merge", "-o", &merged, &a, &b]);
    assert_eq!(code(&o), Some(2), "{}", stderr(&o));
    for leftover in ["", ".journal", ".partial"] {
        assert!(
            !Path::new(&format!("{merged}{leftover}")).exists(),
            "{leftover}"
        );
    }
}

// item 12: `--shard` with a huge N panicked or aborted; `-j 100000` spawned threads until
// resources ran out
#[test]
fn huge_shard_counts_and_thread_counts_are_refused() {
    let d = Dir::with_study(RIGID);
    for args in [
        vec!["--shard", "1/18446744073709551615"],
        vec!["--shard", "1/100000000"],
        vec!["-j", "100000"],
    ] {
        let mut all = vec!["run", "s.yaml", "-q"];
        all.extend(args.iter().copied());
        let o = batstudy_command(&all)
            .current_dir(&d.path)
            .output()
            .unwrap();
        assert_eq!(code(&o), Some(2), "{args:?}: {}", stderr(&o));
        assert!(!d.path.join("results").exists(), "{args:?} wrote output");
    }
    let o = run(&["slurm", &d.p("s.yaml"), "--shards", "100000000"]);
    assert_eq!(code(&o), Some(2), "{}", stderr(&o));
}

// Slurm's SIGTERM (time limit, scancel, pre-emption) makes the graceful stop: it acts as the
// first Ctrl-C: the points in flight finish, everything done is kept, exit 130, and
// --resume completes the same data as an uninterrupted run
#[test]
fn sigterm_stops_as_the_first_ctrl_c_and_the_run_resumes() {
    let study = "name: term
model: wave
base: {bat: {preset: r161}, ball: {speed: 40}}
grid:
  swing.omega: [0, -20, -40, -60]
  impact.z: {range: [0.40, 0.84, 0.002]}
";
    let d = Dir::with_study(study);
    let (s, out, reference) = (d.p("s.yaml"), d.p("out.h5"), d.p("ref.h5"));
    batstudy_ok(&["run", &s, "-o", &reference, "-q", "-j", "2"]);
    let child = {
        let _g = spawn_guard();
        batstudy_command(&["run", &s, "-o", &out, "-q", "-j", "1"])
            .spawn()
            .unwrap()
    };
    let journal = format!("{out}.journal");
    while !Path::new(&journal).exists() {
        std::thread::sleep(Duration::from_millis(1));
    }
    std::thread::sleep(Duration::from_millis(20));
    // SAFETY: a signal to our own child
    assert_eq!(unsafe { libc::kill(child.id() as i32, libc::SIGTERM) }, 0);
    let o = child.wait_with_output().unwrap();
    assert_eq!(code(&o), Some(130), "{}", stderr(&o));
    batstudy_ok(&["run", &s, "-o", &out, "-q", "--resume"]);
    assert_eq!(
        stored_records(Path::new(&out)),
        stored_records(Path::new(&reference))
    );
}
