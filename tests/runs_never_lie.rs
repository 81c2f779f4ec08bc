//! A run never exits 0 with a number it did not compute from what the study says, and every
//! input (study, profile, journal, shard) is held to the same checks whichever door it comes
//! in by. Each test is a way a careless user, a cluster or a damaged file made a run lie,
//! panic or refuse too late; each failed before its fix.

mod common;

use batstudy::optimize::{design_of, search, Evaluator, Stop};
use batstudy::study::{load_str, LoadOptions, Study};
use std::path::Path;
use std::process::Output;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::RwLock;

/// HDF5 opens files without close-on-exec: a child forked while a test holds a file open
/// keeps its lock. Files are opened under [`no_spawns`], children run under [`spawned`].
static FORK: RwLock<()> = RwLock::new(());

fn spawned(args: &[&str], dir: &Path) -> Output {
    let _g = FORK.read().unwrap_or_else(|e| e.into_inner());
    common::batstudy_command(args)
        .current_dir(dir)
        .stdout(std::process::Stdio::piped())
        .output()
        .unwrap()
}

fn no_spawns() -> std::sync::RwLockWriteGuard<'static, ()> {
    FORK.write().unwrap_or_else(|e| e.into_inner())
}

/// `batstudy ARGS` in `dir`: exit code and stderr.
fn batstudy(dir: &Path, args: &[&str]) -> (i32, String) {
    let o = spawned(args, dir);
    (
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

fn write(dir: &Path, name: &str, text: &str) {
    std::fs::write(dir.join(name), text).unwrap();
}

/// Exit status 2 with every `want` in the message, and nothing written beside the study.
fn refused(dir: &Path, args: &[&str], want: &[&str]) {
    let before = std::fs::read_dir(dir).unwrap().count();
    let (code, err) = batstudy(dir, args);
    assert_eq!(code, 2, "{args:?}: {err}");
    for w in want {
        assert!(err.contains(w), "{args:?}: `{w}` not in\n{err}");
    }
    let after = std::fs::read_dir(dir).unwrap().count();
    assert_eq!(before, after, "{args:?} wrote something");
}

fn study(text: &str) -> Study {
    load_str(text, Path::new("s.yaml"), &LoadOptions::default()).unwrap()
}

/// A rigid-bat search of three variables (each candidate a few points).
const SEARCH: &str = "name: s\nmodel: rigid\nbase:\n  impact: {z: 0.6}\n  swing: {omega: -30}\n\
    grid:\n  ball.speed: [30, 40]\noptimize:\n  max_evaluations: 200\n  tolerance: 1.0e-14\n  variables:\n\
    \x20   impact.z: {min: 0.40, max: 0.83}\n    ball.law.cor: {min: 0.4, max: 0.6}\n    swing.cm_speed: {min: 0, max: 10}\n\
    \x20 objective: {maximize: exit_speed}\n";

/// argmin unwraps the costs of its first simplex: a stop (Ctrl-C, a Slurm time limit) or a
/// budget reached there panicked with exit 101 and no resume hint.
#[test]
fn a_search_stopped_inside_its_first_simplex_keeps_what_it_evaluated() {
    let s = study(SEARCH);
    let design = design_of(&s).unwrap().unwrap();
    let ev = Evaluator::new(&s, &design);
    let stop = AtomicBool::new(false);
    let eval = |x: &[f64]| {
        stop.store(true, Ordering::SeqCst);
        ev.evaluate(x)
    };
    let out = search(&design, &eval, &|_| Ok(()), Vec::new(), &stop);
    assert_eq!(out.stopped, Some(Stop::Interrupted));
    assert_eq!(out.candidates.len(), 1);
    let mut small = design.clone();
    small.block.max_evaluations = 2;
    let out = search(
        &small,
        &|x| ev.evaluate(x),
        &|_| Ok(()),
        Vec::new(),
        &AtomicBool::new(false),
    );
    assert_eq!(out.stopped, Some(Stop::Budget));
    assert_eq!(out.candidates.len(), 2);
}

/// A budget below the first simplex is refused when the study is read.
#[test]
fn a_budget_below_the_first_simplex_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    write(
        dir.path(),
        "s.yaml",
        &SEARCH.replace("max_evaluations: 200", "max_evaluations: 3"),
    );
    refused(
        dir.path(),
        &["validate", "s.yaml"],
        &["s.yaml:9:3", "optimize.max_evaluations", "at least 4"],
    );
}

/// Nelder–Mead revisits vertices (shrink steps) and clamps points outside the box onto its
/// boundary: 21 % of a search's budget went on designs already evaluated.
#[test]
fn no_design_is_evaluated_twice() {
    let s = study(SEARCH);
    let design = design_of(&s).unwrap().unwrap();
    let ev = Evaluator::new(&s, &design);
    let calls = AtomicUsize::new(0);
    let eval = |x: &[f64]| {
        calls.fetch_add(1, Ordering::Relaxed);
        ev.evaluate(x)
    };
    let out = search(
        &design,
        &eval,
        &|_| Ok(()),
        Vec::new(),
        &AtomicBool::new(false),
    );
    let n = out.candidates.len();
    assert_eq!(calls.load(Ordering::Relaxed), n);
    let mut designs: Vec<Vec<u64>> = out
        .candidates
        .iter()
        .map(|c| c.x.iter().map(|v| v.to_bits()).collect())
        .collect();
    designs.sort();
    designs.dedup();
    assert_eq!(
        designs.len(),
        n,
        "{n} candidates, {} designs",
        designs.len()
    );
    // the budget went on distinct designs: the search ran to it or converged
    assert!(n > 20, "{n}");
}

/// A normal truncated 9 to 15 sd out drew `inf` (its CDF rounds to 1 there), and every
/// point ran at the preset's density with exit 0.
#[test]
fn a_sample_far_in_a_tail_runs_at_the_values_it_drew() {
    let text = |lo: u32, hi: u32| {
        format!("name: s\nmodel: rigid\nbase:\n  impact: {{z: 0.7}}\nsample:\n  n: 16\n  params:\n    bat.material.density: {{normal: {{mean: 649, sd: 10, min: {lo}, max: {hi}}}}}\n")
    };
    let s = study(&text(740, 800));
    for i in 0..s.plan.n_points() {
        let d = s.plan.point(i).unwrap().spec.bat.material.density.unwrap();
        assert!((740.0..=800.0).contains(&d), "point {i}: density {d}");
    }
    let e = load_str(
        &text(1100, 1200),
        Path::new("s.yaml"),
        &LoadOptions::default(),
    )
    .unwrap_err();
    assert_eq!((e.line, e.column), (Some(8), Some(56)), "{e}");
    assert_eq!(
        e.field.as_deref(),
        Some("sample.params.bat.material.density.normal.min")
    );
}

/// Bounds of ±1e308 made every candidate inf (run at the preset's value) and failed only
/// after the whole search; bounds beyond a parameter's plausible range likewise.
#[test]
fn design_bounds_are_finite_and_plausible() {
    for (bounds, want) in [
        ("{min: -1.0e308, max: 1.0e308}", "finite bounds"),
        ("{min: 300, max: 20000}", "plausible range"),
    ] {
        let text = format!("name: s\nmodel: rigid\nbase:\n  impact: {{z: 0.7}}\noptimize:\n  variables:\n    bat.material.density: {bounds}\n  objective: {{maximize: exit_speed}}\n");
        let s = study(&text);
        let e = design_of(&s).unwrap_err();
        assert_eq!(e.line, Some(7), "{e}");
        assert!(e.to_string().contains(want), "{e}");
    }
}

/// A profile changed between a run and its `--resume` (or between shards and their merge)
/// kept the old profile's numbers with exit 0: the study's digest covers its profiles.
#[test]
fn a_changed_profile_is_a_changed_study() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    write(d, "p.csv", "z,radius\n0,0.012\n0.5,0.016\n0.84,0.033\n");
    write(
        d,
        "s.yaml",
        "name: s\nmodel: rigid\nbase:\n  bat: {profile: {csv: p.csv}}\ngrid:\n  impact.z: [0.6, 0.7]\n  ball.speed: [30, 40]\n",
    );
    for args in [
        &["run", "s.yaml", "-o", "all.h5", "--quiet"][..],
        &["run", "s.yaml", "-o", "a.h5", "--shard", "1/2", "--quiet"],
        &["run", "s.yaml", "-o", "b.h5", "--shard", "2/2", "--quiet"],
    ] {
        assert_eq!(batstudy(d, args).0, 0);
    }
    write(d, "p.csv", "z,radius\n0,0.012\n0.5,0.017\n0.84,0.033\n");
    refused(
        d,
        &["run", "s.yaml", "-o", "all.h5", "--resume", "--quiet"],
        &["a file it names (a profile CSV) changed"],
    );
    refused(
        d,
        &["merge", "-o", "m.h5", "--study", "s.yaml", "a.h5", "b.h5"],
        &["is not the shards' study"],
    );
}

/// The R161 table written in centimetres is an 84 m, 794-tonne bat; it ran with exit 0.
#[test]
fn a_profile_in_the_wrong_unit_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    write(d, "cm.csv", "z,radius\n0,1.2\n50,1.6\n84,3.3\n");
    write(d, "mm.csv", "z,radius\n0,12\n0.5,16\n0.84,33\n");
    for (csv, field) in [
        ("cm.csv", "bat.profile.length"),
        ("mm.csv", "bat.profile.radius"),
    ] {
        write(
            d,
            "s.yaml",
            &format!("name: s\nmodel: rigid\nbase:\n  bat: {{profile: {{csv: {csv}}}}}\n  impact: {{z: 0.3}}\n"),
        );
        refused(
            d,
            &["validate", "s.yaml"],
            &["s.yaml:4:", field, "plausible"],
        );
    }
}

/// Fields the study sets and no point uses: every point gave the same numbers, exit 0.
#[test]
fn fields_that_change_nothing_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let batter = "  batter: {pitch_speed: 40, bat_speed: 30, reference_moi: 0.3}\n";
    for (body, want) in [
        (format!("base:\n  impact: {{z: 0.7}}\n{batter}grid:\n  ball.speed: [30, 40]\n"), "`ball.speed` is set, but no point"),
        ("base:\n  bat: {preset: wall}\n  impact: {z: 0.7}\ngrid:\n  bat.material.density: [500, 600]\n".into(), "`bat.material` is set, but no point"),
        (format!("base:\n  impact: {{z: 0.7}}\n{batter}  swing: {{omega: -30}}\n"), "s.yaml:5:11: error in `swing.omega`"),
        ("base:\n  impact: {z: 0.7}\n  flight: {pressure: 0}\n".into(), "error in `flight.pressure`"),
    ] {
        write(d, "s.yaml", &format!("name: s\n{body}"));
        refused(d, &["validate", "s.yaml"], &[want]);
    }
}

/// Accepted, then wrong or failed at the run: a repeated impact position (no sweet spot,
/// exit 0), a dimension named as another's label coordinate (exit 3 after the run), a NUL
/// in the output path (exit 3).
#[test]
fn names_and_values_that_broke_the_run_are_refused_at_validation() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for (body, want) in [
        ("model: rigid\nbase: {}\ngrid:\n  impact.z: [0.6, 0.7, 0.7, 0.8]\n", "s.yaml:5:3: error in `grid.impact.z`: `grid.impact.z` lists a value twice"),
        ("model: rigid\nbase: {impact: {z: 0.7}}\npoints:\n  name: x\n  sets: [{ball.speed: 30}, {ball.speed: 40}]\nzip:\n  - name: x_label\n    ball.mass: [0.14, 0.15]\n", "cannot have a coordinate `x_label`"),
        ("model: rigid\noutput: \"a\\0b.h5\"\nbase: {impact: {z: 0.7}}\n", "holds a NUL byte"),
    ] {
        write(d, "s.yaml", &format!("name: s\n{body}"));
        refused(d, &["run", "s.yaml", "--quiet"], &[want]);
    }
}

/// A byte-order mark is not a second document; escape sequences in a study are printed as
/// text, never sent to the terminal.
#[test]
fn what_editors_and_attackers_put_in_a_study_file_is_read_as_text() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    write(
        d,
        "bom.yaml",
        "\u{feff}name: s\nmodel: rigid\nbase: {impact: {z: 0.7}}\n",
    );
    assert_eq!(batstudy(d, &["validate", "bom.yaml"]).0, 0);
    let esc = "name: s\ndescription: \"\\e[2J\\e]0;owned\\a\\r\"\nmodel: rigid\nbase: {impact: {z: 0.7}}\n\
               zip:\n  - name: case\n    bat.material.density: [600, 700]\n    ball.speed: [30, 40]\n";
    write(d, "esc.yaml", esc);
    let o = spawned(&["plan", "esc.yaml"], d);
    assert!(o.status.success());
    assert!(!o
        .stdout
        .iter()
        .any(|b| *b == 0x1b || *b == b'\r' || *b == 7));
    write(
        d,
        "bad.yaml",
        &esc.replace("ball.speed: [30, 40]", "ball.speed: [\"\\e[31m\", 40]"),
    );
    let o = spawned(&["validate", "bad.yaml"], d);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        !o.stderr.contains(&0x1b),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
}

/// Constraint errors named serde's untagged enum instead of the mistake.
#[test]
fn a_bad_constraint_names_its_mistake() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let head = "name: s\nmodel: rigid\nbase: {impact: {z: 0.7}}\noptimize:\n  variables:\n    impact.z: {min: 0.5, max: 0.8}\n  objective: {maximize: exit_speed}\n  constraints:\n";
    for (c, want) in [
        ("    - {rules: ncaa}\n", "unknown variant `ncaa`"),
        (
            "    - {quantity: bbcor, maxi: 0.5}\n",
            "unknown field `maxi`",
        ),
        ("    - {limit: 3}\n", "either `{rules"),
    ] {
        write(d, "s.yaml", &format!("{head}{c}"));
        let (code, err) = batstudy(d, &["validate", "s.yaml"]);
        assert_eq!(code, 2, "{err}");
        assert!(
            err.contains(want) && !err.contains("untagged"),
            "{c}: {err}"
        );
        assert!(err.contains("s.yaml:9:"), "{err}");
    }
}

/// The search's journal: a flipped bit was replayed as a true candidate, a short row
/// crashed the writer with exit 101. A row that does not hold ends the record.
#[test]
fn a_damaged_search_journal_ends_where_it_is_damaged() {
    use batstudy::store::optimize::{journal_path, CandidateRow, OptimizeJournal};
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("o.h5");
    let row = |k: f64| CandidateRow {
        u: vec![0.5, k],
        x: vec![0.6, k],
        objective: 10.0 + k,
        constraints: vec![0.49],
        error: None,
        penalized: -1.0 - k,
    };
    let write_rows = || {
        let _ = std::fs::remove_file(journal_path(&out));
        let mut j = OptimizeJournal::create(&out, "id").unwrap();
        for k in 0..3 {
            j.append(&row(k as f64)).unwrap();
        }
    };
    write_rows();
    let (_, rows) = OptimizeJournal::resume(&out, "id", (2, 1)).unwrap();
    assert_eq!(rows, vec![row(0.0), row(1.0), row(2.0)]);
    // one digit of the second row's objective changed
    write_rows();
    let text = std::fs::read_to_string(journal_path(&out)).unwrap();
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    let bits = 11f64.to_bits().to_string();
    let flipped = bits.replacen('4', "5", 1);
    assert_ne!(bits, flipped);
    lines[2] = lines[2].replace(&bits, &flipped);
    std::fs::write(journal_path(&out), lines.join("\n") + "\n").unwrap();
    let (_, rows) = OptimizeJournal::resume(&out, "id", (2, 1)).unwrap();
    assert_eq!(rows, vec![row(0.0)]);
    // a row of another shape (its checksum intact) ends it too
    write_rows();
    let (_, rows) = OptimizeJournal::resume(&out, "id", (3, 1)).unwrap();
    assert!(rows.is_empty());
}

/// A search that ends with no feasible candidate said "converged" and exited 0; a file
/// left at `OUT.h5.optimum.h5` was found only after the whole search; `batstudy slurm` on a
/// search ran its base design.
#[test]
fn searches_say_when_they_have_no_answer_and_refuse_early() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let s = "name: s\nmodel: rigid\nbase: {impact: {z: 0.7}}\noptimize:\n  max_evaluations: 12\n  variables:\n    impact.z: {min: 0.5, max: 0.8}\n  objective: {maximize: exit_speed}\n";
    write(d, "s.yaml", s);
    write(
        d,
        "none.yaml",
        &format!("{s}  constraints:\n    - {{quantity: exit_speed, max: -100}}\n"),
    );
    let (code, err) = batstudy(d, &["optimize", "none.yaml", "-o", "none.h5", "--quiet"]);
    assert_eq!(code, 1, "{err}");
    assert!(
        err.contains("no candidate of the search met its constraints"),
        "{err}"
    );
    write(d, "o.h5.optimum.h5", "not a results file");
    refused(
        d,
        &["optimize", "s.yaml", "-o", "o.h5", "--quiet"],
        &["o.h5.optimum.h5"],
    );
    refused(
        d,
        &["slurm", "s.yaml", "--shards", "2"],
        &[
            "s.yaml:4:1",
            "cannot split into shards",
            "batstudy optimize",
        ],
    );
}

/// A shard whose summary array was reshaped: the merge failed with exit 3 and left a
/// journal that refused the retry.
#[test]
fn a_merge_of_a_reshaped_shard_is_refused_and_leaves_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    write(
        d,
        "s.yaml",
        "name: s\nmodel: rigid\nbase: {}\ngrid:\n  impact.z: [0.5, 0.6, 0.7, 0.8]\n  ball.speed: [30, 40]\n",
    );
    for sh in ["1/2", "2/2"] {
        let out = format!("{}.h5", &sh[..1]);
        assert_eq!(
            batstudy(d, &["run", "s.yaml", "--shard", sh, "-o", &out, "--quiet"]).0,
            0
        );
    }
    {
        let _g = no_spawns();
        let f = hdf5::File::open_rw(d.join("2.h5")).unwrap();
        let g = f.group("summary").unwrap();
        let v: Vec<f64> = g.dataset("exit_speed").unwrap().read_raw().unwrap();
        g.unlink("exit_speed").unwrap();
        g.new_dataset_builder()
            .with_data(&v)
            .create("exit_speed")
            .unwrap();
    }
    for _ in 0..2 {
        refused(
            d,
            &["merge", "-o", "m.h5", "1.h5", "2.h5"],
            &["/summary/exit_speed has shape [8]", "[4, 2]"],
        );
    }
}

/// A full disk: the message said neither "no space" nor how to finish the run. Needs a
/// small file system (a tmpfs mounted here, as root); skipped where none can be mounted.
#[test]
fn a_full_disk_is_named_with_the_command_that_finishes_the_run() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let small = d.join("small");
    std::fs::create_dir(&small).unwrap();
    let mounted = std::process::Command::new("mount")
        .args(["-t", "tmpfs", "-o", "size=256k", "tmpfs"])
        .arg(&small)
        .output()
        .is_ok_and(|o| o.status.success());
    if !mounted {
        eprintln!("skipped: no tmpfs could be mounted here");
        return;
    }
    write(
        d,
        "s.yaml",
        "name: s\nbase: {}\ngrid:\n  impact.z: {linspace: [0.5, 0.8, 40]}\n  ball.speed: {linspace: [20, 40, 40]}\nhistory: {fields: [force], duration: 2.0e-3, interval: 1.0e-6}\n",
    );
    let (code, err) = batstudy(d, &["run", "s.yaml", "-o", "small/s.h5", "--quiet"]);
    let _ = std::process::Command::new("umount").arg(&small).status();
    assert_eq!(code, 3, "{err}");
    assert!(err.contains("no space left on the device"), "{err}");
    assert!(err.contains("run s.yaml --resume -o small/s.h5"), "{err}");
}
