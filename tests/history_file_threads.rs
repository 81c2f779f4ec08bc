//! A history study's file is the same whatever the thread count. The workers
//! compress the history chunks and the finish writes them raw in flat-index order, so the
//! runs with `--jobs 1` and `--jobs 2` give files of the same size whose history chunks sit
//! at the same addresses with the same bytes; HDF5's own shuffle and deflate filters read
//! them back. A journal of the old format is refused on `--resume` with a clear message.
//! Both forms of the displacement: on the grid, and modal (the coordinates in
//! blocks of modes, and `/bat`'s mode shapes written with the first history that steps them).

mod common;

use common::{batstudy_command as batstudy, batstudy_ok, chunk_places, stored_records};
use std::path::Path;

// Some points record histories (`only`), one field per kind (with and without z), f32.
const STUDY: &str = r#"
name: history_threads
model: wave
base:
  bat: {preset: r161}
  ball: {speed: 40.0}
grid:
  swing.omega: [0, -30, -60]
  impact.z: {range: [0.50, 0.80, 0.02]}
history:
  fields: [force, displacement]
  interval: 2.0e-5
  duration: 2.0e-3
  z_step: 0.05
  only: {swing.omega: [0, -60]}
  displacement: grid
"#;

/// The history variables each form stores (one chunk per group of points each, the
/// study's collisions stepping fewer than 32 modes).
const GRID: [&str; 2] = ["force", "displacement"];
const MODAL: [&str; 4] = ["force", "modal_coordinate", "bat_load", "static_shape"];

/// Chunks of each variable: two of the three rows of 16 points record histories, and a
/// chunk holds a group of points along the row (the modal form's groups, one point a
/// chunk on the grid).
fn stored_chunks(text: &str) -> usize {
    let group = match text.contains("displacement: modal") {
        true => batstudy::store::layout::MODAL_HISTORY_GROUP,
        false => 1,
    };
    2 * 16usize.div_ceil(group)
}

fn modal(study: &str) -> String {
    study.replace("displacement: grid", "displacement: modal")
}

/// (chunk offset, file address, stored bytes) of every chunk of a dataset, in HDF5's order.
fn chunks(path: &Path, ds: &hdf5::Dataset) -> Vec<(Vec<u64>, u64, Vec<u8>)> {
    let file = std::fs::read(path).unwrap();
    chunk_places(ds)
        .into_iter()
        .map(|(offset, addr, size)| {
            (
                offset,
                addr,
                file[addr as usize..(addr + size) as usize].to_vec(),
            )
        })
        .collect()
}

#[test]
fn a_history_study_gives_the_same_file_on_one_and_two_threads() {
    same_file_on_one_and_two_threads(STUDY, &GRID);
}

#[test]
fn a_modal_history_study_gives_the_same_file_on_one_and_two_threads() {
    same_file_on_one_and_two_threads(&modal(STUDY), &MODAL);
}

fn same_file_on_one_and_two_threads(text: &str, names: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    let study = dir.path().join("study.yaml");
    std::fs::write(&study, text).unwrap();
    let run = |jobs: &str| {
        let path = dir.path().join(format!("j{jobs}.h5"));
        batstudy_ok(&[
            "run",
            study.to_str().unwrap(),
            "-o",
            path.to_str().unwrap(),
            "-j",
            jobs,
            "-q",
        ]);
        path
    };
    let (one, two) = (run("1"), run("2"));
    assert_eq!(
        std::fs::metadata(&one).unwrap().len(),
        std::fs::metadata(&two).unwrap().len(),
        "file sizes differ"
    );
    assert_eq!(stored_records(&one), stored_records(&two));

    let (f1, f2) = (
        hdf5::File::open(&one).unwrap(),
        hdf5::File::open(&two).unwrap(),
    );
    let (g1, g2) = (f1.group("history").unwrap(), f2.group("history").unwrap());
    for &name in names {
        let (d1, d2) = (g1.dataset(name).unwrap(), g2.dataset(name).unwrap());
        let (c1, c2) = (chunks(&one, &d1), chunks(&two, &d2));
        // two thirds of the points record histories: one chunk a group of them
        assert_eq!(c1.len(), stored_chunks(text), "{name}");
        assert!(c1 == c2, "{name}: chunks differ in place or bytes");
        // HDF5's standard filters (shuffle, deflate) read what the workers compressed
        let filters = d1.filters();
        assert!(filters
            .iter()
            .any(|f| matches!(f, hdf5::filters::Filter::Shuffle)));
        assert!(filters
            .iter()
            .any(|f| matches!(f, hdf5::filters::Filter::Deflate(_))));
        let v: Vec<f64> = d1.read_raw().unwrap();
        let finite = v.iter().filter(|x| x.is_finite() && **x != 0.0).count();
        assert!(
            finite > 0 && finite < v.len(),
            "{name}: {finite} of {}",
            v.len()
        );
        let w: Vec<f64> = d2.read_raw().unwrap();
        assert!(v.iter().zip(&w).all(|(a, b)| a.to_bits() == b.to_bits()));
    }
    if names.contains(&"modal_coordinate") {
        // the bat's mode shapes: one block, written with the first history, in one place
        let (b1, b2) = (f1.group("bat").unwrap(), f2.group("bat").unwrap());
        let (d1, d2) = (
            b1.dataset("mode_shape").unwrap(),
            b2.dataset("mode_shape").unwrap(),
        );
        let (c1, c2) = (chunks(&one, &d1), chunks(&two, &d2));
        assert_eq!(c1.len(), 1);
        assert!(c1 == c2, "mode shapes differ in place or bytes");
    }
}

#[test]
fn a_journal_of_the_old_format_is_refused_on_resume() {
    let dir = tempfile::tempdir().unwrap();
    let study = dir.path().join("study.yaml");
    std::fs::write(&study, STUDY).unwrap();
    let out = dir.path().join("o.h5");
    let journal = dir.path().join("o.h5.journal");
    // the first bytes of a format-1 journal (its header would follow)
    std::fs::write(&journal, b"BATSJRN1\x02\x00\x00\x00{}").unwrap();
    let args = [
        "run",
        study.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "-q",
    ];
    let r = batstudy(&[&args[..], &["--resume"]].concat())
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&r.stderr);
    assert_eq!(r.status.code(), Some(2), "{err}");
    assert!(
        err.contains("older batstudy") && err.contains("--force"),
        "{err}"
    );
    assert!(journal.exists(), "the old journal must be left alone");
    // --force starts over
    let r = batstudy(&[&args[..], &["--force"]].concat())
        .output()
        .unwrap();
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    assert!(!journal.exists());
}

/// `history.compression: none` stores the same histories without filters: every variable of
/// `/history` has no filter, the data read back equal the deflated study's bit for bit, and
/// the file holds the raw chunk sizes (samples × z × 4 bytes for f32 displacement; a block
/// of 32 modes × samples × 8 bytes for the modal coordinates).
#[test]
fn uncompressed_histories_hold_the_same_data() {
    uncompressed_same_data(STUDY, &GRID);
    uncompressed_same_data(&modal(STUDY), &MODAL);
}

fn uncompressed_same_data(text: &str, names: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    let run = |name: &str, text: &str| {
        let study = dir.path().join(format!("{name}.yaml"));
        std::fs::write(&study, text).unwrap();
        let path = dir.path().join(format!("{name}.h5"));
        batstudy_ok(&[
            "run",
            study.to_str().unwrap(),
            "-o",
            path.to_str().unwrap(),
            "-q",
        ]);
        path
    };
    let deflated = run("deflated", text);
    let raw = run(
        "raw",
        &text.replace("  z_step: 0.05\n", "  z_step: 0.05\n  compression: none\n"),
    );
    let (f1, f2) = (
        hdf5::File::open(&deflated).unwrap(),
        hdf5::File::open(&raw).unwrap(),
    );
    let (g1, g2) = (f1.group("history").unwrap(), f2.group("history").unwrap());
    for &name in names {
        let (d1, d2) = (g1.dataset(name).unwrap(), g2.dataset(name).unwrap());
        assert!(!d1.filters().is_empty(), "{name}: deflated by default");
        assert!(d2.filters().is_empty(), "{name}: no filters");
        let (v, w): (Vec<f64>, Vec<f64>) = (d1.read_raw().unwrap(), d2.read_raw().unwrap());
        assert_eq!(v.len(), w.len());
        assert!(
            v.iter().zip(&w).all(|(a, b)| a.to_bits() == b.to_bits()),
            "{name}"
        );
        // each stored chunk is the raw values: its elements × their size
        let per_chunk = d2.chunk().unwrap().iter().product::<usize>() * d2.dtype().unwrap().size();
        let c = chunks(&raw, &d2);
        assert_eq!(c.len(), stored_chunks(text), "{name}");
        assert!(
            c.iter().all(|(_, _, bytes)| bytes.len() == per_chunk),
            "{name}"
        );
    }
    assert_eq!(stored_records(&deflated), stored_records(&raw));
}
