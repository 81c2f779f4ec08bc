//! `batstudy inspect`: sweet spots named by their coordinates and labels, not by
//! an index; the bats' properties; a maximum at the edge of the sampled range flagged.

mod common;

use common::batstudy_ok;
use std::process::Command;

/// HDF5 opens files without close-on-exec, with a lock: a child forked while a test holds
/// one open would keep it locked. The file is edited under [`no_spawns`], children run under
/// [`spawn_guard`] (as in tests/shards_merge_slurm.rs).
static FORK: std::sync::RwLock<()> = std::sync::RwLock::new(());

fn spawn_guard() -> std::sync::RwLockReadGuard<'static, ()> {
    FORK.read().unwrap_or_else(|e| e.into_inner())
}

fn no_spawns() -> std::sync::RwLockWriteGuard<'static, ()> {
    FORK.write().unwrap_or_else(|e| e.into_inner())
}

/// Run `study` (YAML text) into a results file in a new folder; returns both.
fn results_of(study: &str) -> (tempfile::TempDir, std::path::PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("s.yaml");
    std::fs::write(&path, study).unwrap();
    let out = dir.path().join("s.h5");
    let _g = spawn_guard();
    batstudy_ok(&[
        "run",
        path.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "-q",
    ]);
    (dir, out)
}

/// `batstudy inspect FILE`'s standard output (it must succeed).
fn inspect(out: &std::path::Path) -> String {
    let _g = spawn_guard();
    let o = Command::new(env!("CARGO_BIN_EXE_batstudy"))
        .args(["inspect", out.to_str().unwrap()])
        .output()
        .unwrap();
    let text = String::from_utf8(o.stdout).unwrap();
    assert!(o.status.success(), "{text}");
    text
}

#[test]
fn inspect_names_sweet_spots_by_coordinates_and_lists_the_bats() {
    // The R161 base case's sweet spot lies near 0.65 m on the still bat and moves toward the
    // barrel with the swing (the paper's Fig. 6: about 0.71 m at -60 rad/s); a range that
    // starts at 0.66 m cuts off the still bat's at its edge.
    let (_dir, out) = results_of(
        "name: s\nmodel: wave\nbase: {bat: {preset: r161}, ball: {speed: 40}}\n\
         grid:\n  impact.z: {range: [0.66, 0.80, 0.02]}\n\
         points:\n  name: case\n  sets:\n    - {}\n    - {swing.omega: -60}\n",
    );
    let text = inspect(&out);
    let line = |prefix: &str| {
        text.lines()
            .find(|l| l.starts_with(prefix))
            .unwrap_or_else(|| panic!("no line {prefix}: {text}"))
            .to_string()
    };
    let still = line("sweet spot at case=0 (base): z = 0.6600 m");
    assert!(
        still.ends_with("(at the edge of the sampled impact_z)"),
        "{text}"
    );
    let swung = line("sweet spot at case=1 (swing.omega=-60): z = 0.7");
    assert!(!swung.contains("edge"), "{text}");
    assert!(!text.contains("sweet spot [0]"), "{text}");
    assert!(
        text.contains("bats: 1") && text.contains("r161: mass 0.8"),
        "{text}"
    );
}

// `inspect` never prints terminal escape sequences from the file's strings raw
#[test]
fn inspect_prints_no_terminal_control_sequences() {
    let (_dir, out) = results_of(
        "name: s\nmodel: rigid\nbase: {ball: {speed: 40}}\ngrid:\n  impact.z: [0.6, 0.7]\n",
    );
    {
        let _g = no_spawns();
        let f = hdf5::File::open_rw(&out).unwrap();
        let name: hdf5::types::VarLenUnicode =
            "s\u{1b}]0;pwned\u{7}\u{1b}[2J\r\u{202e}x".parse().unwrap();
        f.attr("study_name").unwrap().write_scalar(&name).unwrap();
    }
    let text = inspect(&out);
    assert!(
        !text.contains('\u{1b}') && !text.contains('\r') && !text.contains('\u{202e}'),
        "{text:?}"
    );
    assert!(text.contains("\\u{1b}]0;pwned"), "{text}");
}
