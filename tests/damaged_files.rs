//! `batstudy inspect` on a file that is not a complete batstudy results file: a damaged one
//! (as a disk or a copy damages it: a block of zeros, a flipped bit, a cut-off end), another
//! program's HDF5 file, or no HDF5 at all. Each ends within seconds with exit status 2 and
//! an error naming the file and what is wrong: never a hang, a crash or a panic.
//!
//! The damage that hung and crashed it is in the global heap collections (`GCOL`), which hold
//! a file's strings and dimension lists and which HDF5 reads without a checksum.

mod common;

use common::batstudy_ok;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Longer than any clean failure takes, by far: the test is on the error and on not hanging.
const LIMIT: Duration = Duration::from_secs(30);

/// HDF5 opens files without close-on-exec, with a lock: the foreign file is written under
/// [`no_spawns`], children run under [`spawn_guard`] (as in tests/inspect_text.rs).
static FORK: std::sync::RwLock<()> = std::sync::RwLock::new(());

fn spawn_guard() -> std::sync::RwLockReadGuard<'static, ()> {
    FORK.read().unwrap_or_else(|e| e.into_inner())
}

fn no_spawns() -> std::sync::RwLockWriteGuard<'static, ()> {
    FORK.write().unwrap_or_else(|e| e.into_inner())
}

/// A small results file with histories and labelled cases (strings and dimension lists in
/// several global heap collections), in a new folder.
fn results_file() -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let study = dir.path().join("s.yaml");
    std::fs::write(
        &study,
        "name: s\nmodel: wave\nbase: {bat: {preset: r161}, ball: {speed: 40}}\n\
         grid:\n  impact.z: [0.6, 0.7]\n\
         points:\n  name: case\n  sets:\n    - {}\n    - {bat.preset: aluminum}\n\
         history: {fields: [force], interval: 1.0e-5, duration: 1.0e-3}\n",
    )
    .unwrap();
    let out = dir.path().join("s.h5");
    let _g = spawn_guard();
    batstudy_ok(&[
        "run",
        study.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "-q",
    ]);
    (dir, out)
}

/// `batstudy inspect FILE` killed after [`LIMIT`]: its exit status (None if killed or
/// crashed) and standard error.
fn inspect(file: &Path) -> (Option<i32>, String) {
    let _g = spawn_guard();
    let mut child = Command::new(env!("CARGO_BIN_EXE_batstudy"))
        .args(["inspect", file.to_str().unwrap()])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > LIMIT {
            child.kill().unwrap();
            child.wait().unwrap();
            return (None, format!("still running after {LIMIT:?}: killed"));
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    let out = child.wait_with_output().unwrap();
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// Inspect `file` and require a clean refusal that names it and says `what`.
fn assert_refused(file: &Path, what: &str, case: &str) {
    let (code, err) = inspect(file);
    assert_eq!(code, Some(2), "{case}: {err}");
    assert!(
        err.contains(&file.display().to_string()) && err.contains(what),
        "{case}: {err}"
    );
    assert!(!err.contains("panicked"), "{case}: {err}");
}

/// Where the file's global heap collections start.
fn collections(bytes: &[u8]) -> Vec<usize> {
    bytes
        .windows(5)
        .enumerate()
        .filter(|(_, w)| w == b"GCOL\x01")
        .map(|(i, _)| i)
        .collect()
}

/// A copy of `good` next to it, as `damage` leaves it.
fn damaged_copy(good: &Path, name: &str, damage: impl FnOnce(&mut Vec<u8>)) -> PathBuf {
    let mut bytes = std::fs::read(good).unwrap();
    damage(&mut bytes);
    let path = good.with_file_name(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

#[test]
fn damaged_global_heap_collections_are_refused_not_hung_on() {
    let (_dir, good) = results_file();
    let bytes = std::fs::read(&good).unwrap();
    let heaps = collections(&bytes);
    assert!(heaps.len() >= 2, "{heaps:?}");
    for (k, &at) in heaps.iter().enumerate() {
        // a block of zeros after the header: an object of length 0, which HDF5 never passes
        let zeroed = damaged_copy(&good, &format!("zeroed{k}.h5"), |b| {
            b[at + 16..at + 80].fill(0)
        });
        assert_refused(
            &zeroed,
            "damaged",
            &format!("zeros in the collection at {at}"),
        );
        // the collection's length, a bit flipped: HDF5 reads on past its end
        let longer = damaged_copy(&good, &format!("longer{k}.h5"), |b| b[at + 9] ^= 0x80);
        assert_refused(
            &longer,
            "damaged",
            &format!("length of the collection at {at}"),
        );
        // its first object's length: HDF5 copies past the collection (a crash)
        let object = damaged_copy(&good, &format!("object{k}.h5"), |b| b[at + 26] ^= 0x80);
        assert_refused(
            &object,
            "damaged",
            &format!("an object in the collection at {at}"),
        );
    }
}

#[test]
fn a_string_that_is_not_utf8_is_refused_not_taken_as_text() {
    let (_dir, good) = results_file();
    let bytes = std::fs::read(&good).unwrap();
    // the study's header (JSON, in a global heap collection): a byte of it made invalid
    let at = bytes
        .windows(9)
        .position(|w| w == b"{\"layout_")
        .expect("the store header in the file");
    let bad = damaged_copy(&good, "utf8.h5", |b| b[at + 3] |= 0x80);
    assert_refused(&bad, "not UTF-8", "a store header that is not UTF-8");
}

#[test]
fn a_truncated_file_is_refused_as_damaged() {
    let (_dir, good) = results_file();
    let len = std::fs::metadata(&good).unwrap().len() as usize;
    for keep in [len / 3, len - 100] {
        let cut = damaged_copy(&good, &format!("cut{keep}.h5"), |b| b.truncate(keep));
        assert_refused(&cut, "truncated", &format!("cut to {keep} bytes"));
    }
}

#[test]
fn another_programs_file_is_not_a_results_file() {
    let dir = tempfile::tempdir().unwrap();
    let foreign = dir.path().join("foreign.h5");
    {
        let _g = no_spawns();
        let f = hdf5::File::create(&foreign).unwrap();
        let d = f.new_dataset::<f64>().shape([3]).create("a").unwrap();
        d.write(&[1.0, 2.0, 3.0]).unwrap();
    }
    assert_refused(
        &foreign,
        "not a batstudy results file: root attribute layout_version missing",
        "an h5py-like file",
    );
    let text = dir.path().join("text.h5");
    std::fs::write(&text, "not HDF5\n").unwrap();
    assert_refused(&text, "not an HDF5 file", "a text file");
}
