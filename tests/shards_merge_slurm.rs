//! Shards (`run --shard I/N`), `merge` and `slurm`, through the real binary.

use batstudy::run::{CostModel, Shard};
use batstudy::store;
use batstudy::study::{load_str, LoadOptions};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Children inherit the test process's open file descriptors, and with them HDF5's lock on
/// any file a test holds open at that moment: a child of one test then kept another test's
/// `part.h5` locked while that test's `merge` tried to read it ("unable to lock file",
/// seen under load). Tests open HDF5 files only under [`no_spawns`]; children are spawned
/// under [`spawn_guard`].
static FORK: std::sync::RwLock<()> = std::sync::RwLock::new(());

fn spawn_guard() -> std::sync::RwLockReadGuard<'static, ()> {
    FORK.read().unwrap_or_else(|e| e.into_inner())
}

fn no_spawns() -> std::sync::RwLockWriteGuard<'static, ()> {
    FORK.write().unwrap_or_else(|e| e.into_inner())
}

fn file_info(path: &Path) -> store::FileInfo {
    let _g = no_spawns();
    store::file_info(path).unwrap()
}

fn read_results(path: &Path) -> store::ReadBack {
    let _g = no_spawns();
    store::read_results(path).unwrap()
}

fn batstudy(dir: &Path, args: &[&str]) -> Output {
    let child = {
        let _g = spawn_guard();
        Command::new(env!("CARGO_BIN_EXE_batstudy"))
            .args(args)
            .current_dir(dir)
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .expect("run batstudy")
    };
    child.wait_with_output().expect("run batstudy")
}

fn ok(o: &Output) {
    assert!(
        o.status.code() == Some(0) || o.status.code() == Some(1),
        "exit {:?}: {}",
        o.status.code(),
        String::from_utf8_lossy(&o.stderr)
    );
}

/// A small wave study with histories, a cost-relevant axis (`numerics.dt`) and failing
/// points (the coarse step exceeds the integrator's limit).
const STUDY: &str = "name: shardtest
model: wave
base:
  bat: {preset: r161}
  ball: {speed: 40}
  impact: {z: 0.7}
grid:
  numerics.dt: [2.0e-7, 5.0e-4]
  swing.omega: [0, -30]
  impact.z: [0.55, 0.62, 0.7, 0.78]
history: {fields: [force, displacement], interval: 2.0e-5, duration: 1.0e-3, z_step: 0.05}
";

/// Every dataset of every group, as bits (floats by `to_bits`, so NaN payloads count).
fn dump_all(path: &Path) -> Vec<(String, String)> {
    use hdf5::types::{FloatSize, IntSize, TypeDescriptor as T, VarLenUnicode};
    let _g = no_spawns();
    let f = hdf5::File::open(path).unwrap();
    let mut out = Vec::new();
    let mut groups = vec![f.as_group().unwrap()];
    while let Some(g) = groups.pop() {
        for name in g.member_names().unwrap() {
            if let Ok(sub) = g.group(&name) {
                groups.push(sub);
                continue;
            }
            let ds = g.dataset(&name).unwrap();
            let key = format!("{}/{name} {:?}", g.name(), ds.shape());
            let d = ds.dtype().unwrap().to_descriptor().unwrap();
            let text = match d {
                T::Float(FloatSize::U8) => format!(
                    "{:?}",
                    ds.read_raw::<f64>()
                        .unwrap()
                        .iter()
                        .map(|x| x.to_bits())
                        .collect::<Vec<_>>()
                ),
                T::Float(FloatSize::U4) => format!(
                    "{:?}",
                    ds.read_raw::<f32>()
                        .unwrap()
                        .iter()
                        .map(|x| x.to_bits())
                        .collect::<Vec<_>>()
                ),
                T::Integer(IntSize::U1) => format!("{:?}", ds.read_raw::<i8>().unwrap()),
                T::Integer(_) => format!("{:?}", ds.read_raw::<i64>().unwrap()),
                T::Unsigned(_) => format!("{:?}", ds.read_raw::<u64>().unwrap()),
                T::VarLenUnicode => format!("{:?}", ds.read_raw::<VarLenUnicode>().unwrap()),
                other => panic!("{key}: unexpected type {other:?}"),
            };
            out.push((key, text));
        }
    }
    out.sort();
    out
}

fn setup() -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let study = dir.path().join("shardtest.yaml");
    std::fs::write(&study, STUDY).unwrap();
    (dir, study)
}

fn run_shards(dir: &Path, study: &str, n: usize) -> Vec<String> {
    (1..=n)
        .map(|i| {
            ok(&batstudy(
                dir,
                &[
                    "run",
                    study,
                    "--shard",
                    &format!("{i}/{n}"),
                    "-j",
                    "2",
                    "-q",
                ],
            ));
            format!("results/shardtest.shard-{i}-of-{n}.h5")
        })
        .collect()
}

// the split is a partition (every point exactly once), deterministic, and balanced
// by estimated cost within the cost of one point.
#[test]
fn split_is_a_balanced_deterministic_partition() {
    let text = "name: t\nbase: {impact: {z: 0.7}}\ngrid:\n  model: [rigid, wave]\n  numerics.integrator: [modal, verlet]\n  impact.z: {range: [0.45, 0.84, 0.01]}\n  swing.omega: [0, -10, -20, -30]\n";
    let s = load_str(text, Path::new("t.yaml"), &LoadOptions::default()).unwrap();
    let hist = s.history_request(0.84);
    let m = CostModel::new(&s.plan, hist.as_ref());
    let n = s.plan.n_points();
    let max = (0..n).map(|i| m.cost(i)).fold(0.0, f64::max);
    let total = m.total();
    for count in [1, 2, 3, 4, 7, 16, 100, n + 3] {
        let mut seen = vec![0u8; n];
        for i in 1..=count {
            let r = batstudy::run::shard_range(&s.plan, hist.as_ref(), Shard { index: i, count });
            assert_eq!(r, m.range(Shard { index: i, count }), "deterministic");
            for k in r.clone() {
                seen[k] += 1;
            }
            let c: f64 = r.map(|k| m.cost(k)).sum();
            assert!(
                (c - total / count as f64).abs() <= max * (1.0 + 1e-9),
                "shard {i}/{count}: cost {c}, mean {}",
                total / count as f64
            );
        }
        assert!(
            seen.iter().all(|&k| k == 1),
            "{count} shards: not a partition"
        );
    }
    // the costly (wave, verlet) quarter is spread over more shards than the cheap rigid half
    let r = m.split(4);
    assert!(r[0].end >= n / 2, "{r:?}");
}

// `run --shard 1/3 … 3/3` then `merge` equals a single-process run bit for bit in
// every dataset; the shard files record study hash, shard and covered block; --resume works
// per shard.
#[test]
fn merged_shards_equal_single_run() {
    merged_shards_equal_single_run_of(STUDY, "/history/modal_coordinate ");
}

/// The same with the displacement on the grid (the study's default is its modal form).
#[test]
fn merged_shards_equal_single_run_grid() {
    let grid = STUDY.replace("z_step: 0.05}", "z_step: 0.05, displacement: grid}");
    merged_shards_equal_single_run_of(&grid, "/history/displacement ");
}

/// Shards of `study` merged equal its single run in every dataset, `stored` among them.
fn merged_shards_equal_single_run_of(study: &str, stored: &str) {
    let (d, path) = setup();
    std::fs::write(&path, study).unwrap();
    let dir = d.path();
    ok(&batstudy(
        dir,
        &["run", "shardtest.yaml", "-o", "single.h5", "-j", "2", "-q"],
    ));
    let shards = run_shards(dir, "shardtest.yaml", 3);
    let mut covered = 0;
    for (k, s) in shards.iter().enumerate() {
        let fi = file_info(&dir.join(s));
        assert_eq!(fi.shard, format!("{}/3", k + 1));
        let single = file_info(&dir.join("single.h5"));
        assert_eq!(fi.study_sha256, single.study_sha256);
        let (a, b) = fi.shard_range.unwrap();
        assert_eq!(a, covered);
        covered = b;
        let present = store::present_points(&dir.join(s)).unwrap();
        assert_eq!(
            present.iter().collect::<Vec<_>>(),
            (a..b).collect::<Vec<_>>()
        );
    }
    assert_eq!(covered, 16);
    // resume of a finished shard computes nothing and keeps its data
    let before = dump_all(&dir.join(&shards[1]));
    let o = batstudy(
        dir,
        &[
            "run",
            "shardtest.yaml",
            "--shard",
            "2/3",
            "--resume",
            "-j",
            "2",
        ],
    );
    ok(&o);
    assert!(
        String::from_utf8_lossy(&o.stderr).contains("0 ok, 0 failed"),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert_eq!(before, dump_all(&dir.join(&shards[1])));

    let mut args = vec!["merge", "-o", "merged.h5"];
    args.extend(shards.iter().map(String::as_str));
    let o = batstudy(dir, &args);
    assert_eq!(
        o.status.code(),
        Some(1),
        "some points fail in this study: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    let a = dump_all(&dir.join("single.h5"));
    let b = dump_all(&dir.join("merged.h5"));
    assert!(a.len() > 30, "{} datasets", a.len());
    assert!(
        a.iter().any(|(k, _)| k.starts_with(stored)),
        "{stored} stored"
    );
    assert_eq!(a, b);
    // and through the store's reader
    let ra = read_results(&dir.join("single.h5"));
    let rb = read_results(&dir.join("merged.h5"));
    assert_eq!(format!("{:?}", ra.records), format!("{:?}", rb.records));
    assert_eq!(ra.records.len(), 16);
    assert!(ra.records.iter().any(|r| r.result.is_err()));
}

fn assert_refused(dir: &Path, args: &[&str], want: &str) {
    let o = batstudy(dir, args);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains(want), "expected `{want}` in: {err}");
    assert!(!dir.join("bad.h5").exists(), "nothing written");
    assert!(!store::journal_path(&dir.join("bad.h5")).exists());
}

// merge refuses, with exit 2 and nothing written, shards of different studies,
// missing points and points present twice.
#[test]
fn merge_refuses_bad_shard_sets() {
    let (d, _) = setup();
    let dir = d.path();
    let s = run_shards(dir, "shardtest.yaml", 3);
    // a missing shard
    let (a, b) = file_info(&dir.join(&s[1])).shard_range.unwrap();
    assert_refused(
        dir,
        &["merge", "-o", "bad.h5", &s[0], &s[2]],
        &format!("lack {} of the study's 16 points", b - a),
    );
    // the same shard twice
    assert_refused(
        dir,
        &["merge", "-o", "bad.h5", &s[0], &s[1], &s[1], &s[2]],
        "present twice",
    );
    // another study (same name, one more value)
    std::fs::write(
        dir.join("other.yaml"),
        STUDY.replace("[0, -30]", "[0, -30, -40]"),
    )
    .unwrap();
    ok(&batstudy(
        dir,
        &[
            "run",
            "other.yaml",
            "--shard",
            "1/1",
            "-o",
            "other.h5",
            "-q",
        ],
    ));
    assert_refused(
        dir,
        &["merge", "-o", "bad.h5", &s[0], &s[1], "other.h5"],
        "different studies",
    );
    // an incomplete shard names itself and how to finish it
    std::fs::copy(dir.join(&s[1]), dir.join("part.h5")).unwrap();
    let keep = dir.join("part.h5");
    {
        let _no_spawns = no_spawns();
        let f = hdf5::File::open_rw(&keep).unwrap();
        let st = f.dataset("summary/status").unwrap();
        let mut v = st.read_raw::<i8>().unwrap();
        let first = v.iter().position(|&x| x >= 0).unwrap();
        v[first] = -1;
        st.write_raw(&v).unwrap();
    }
    assert_refused(
        dir,
        &["merge", "-o", "bad.h5", &s[0], "part.h5", &s[2]],
        "--shard 2/3 --resume",
    );
    // an existing output is not replaced without --force
    std::fs::write(dir.join("exists.h5"), b"x").unwrap();
    let o = batstudy(dir, &["merge", "-o", "exists.h5", &s[0], &s[1], &s[2]]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(std::fs::read(dir.join("exists.h5")).unwrap(), b"x");
}

// `batstudy slurm` writes an sbatch array (one task per shard), a merge job and a
// submit script that chains them, with absolute paths; all pass `bash -n`.
#[test]
fn slurm_scripts() {
    let (d, _) = setup();
    let dir = d.path();
    let o = batstudy(
        dir,
        &[
            "slurm",
            "shardtest.yaml",
            "--shards",
            "5",
            "--time",
            "01:30:00",
            "--partition",
            "short",
            "--cpus-per-task",
            "8",
            "--mem",
            "4G",
            "-o",
            "out/merged.h5",
            "--dir",
            "jobs",
        ],
    );
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let jobs = dir.canonicalize().unwrap().join("jobs");
    let read = |n: &str| std::fs::read_to_string(jobs.join(n)).unwrap();
    let (array, merge, submit) = (
        read("array.sbatch"),
        read("merge.sbatch"),
        read("submit.sh"),
    );
    let bin = Path::new(env!("CARGO_BIN_EXE_batstudy"))
        .canonicalize()
        .unwrap();
    let study = dir.canonicalize().unwrap().join("shardtest.yaml");
    for want in [
        "#SBATCH --array=1-5",
        "#SBATCH --cpus-per-task=8",
        "#SBATCH --time=01:30:00",
        "#SBATCH --partition=short",
        "#SBATCH --mem=4G",
        "SHARDS=5",
        "--jobs \"$JOBS\"",
        "--resume",
        "SLURM_ARRAY_TASK_ID",
        "SLURM_CPUS_PER_TASK",
    ] {
        assert!(array.contains(want), "array.sbatch lacks {want}:\n{array}");
    }
    // every value reaches the scripts once, as a quoted assignment
    assert!(
        array.contains(&format!("BATSTUDY=({})", bin.display())),
        "{array}"
    );
    assert!(array.contains(&format!("STUDY={}", study.display())));
    assert!(array.contains(&format!("DIR={}", jobs.display())));
    assert!(array.contains("\"${BATSTUDY[@]}\" run \"$STUDY\" --shard \"$I/$SHARDS\""));
    assert!(
        merge.contains("\"${BATSTUDY[@]}\" merge -o \"$OUTPUT\""),
        "{merge}"
    );
    let out = dir.canonicalize().unwrap().join("out/merged.h5");
    assert!(merge.contains(&format!("OUTPUT={}", out.display())));
    assert!(merge.contains("seq 1 \"$SHARDS\""));
    assert!(submit.contains("sbatch --parsable"));
    // the merge runs however the array ended, and checks the set itself
    assert!(
        submit.contains("--dependency=afterany:\"$array_id\""),
        "{submit}"
    );
    for n in ["array.sbatch", "merge.sbatch", "submit.sh"] {
        let _g = spawn_guard();
        let st = Command::new("bash")
            .arg("-n")
            .arg(jobs.join(n))
            .status()
            .unwrap();
        assert!(st.success(), "bash -n {n}");
    }
    assert!(jobs.join("logs").is_dir());
    // bad flags: exit 2 naming the flag and value
    for (flag, value) in [
        ("--shards", "0"),
        ("--time", "1h"),
        ("--mem", "lots"),
        ("--cpus-per-task", "0"),
    ] {
        let mut args = vec!["slurm", "shardtest.yaml", "--shards", "2"];
        if flag == "--shards" {
            args[3] = value;
        } else {
            args.extend([flag, value]);
        }
        let o = batstudy(dir, &args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{flag}: {err}");
        assert!(err.contains(flag) && err.contains(value), "{err}");
    }
}
