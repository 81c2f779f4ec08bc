//! The smallest useful study, an exit-speed curve of 45 impact positions (0.40..0.84 m, base
//! case otherwise), three ways: the collisions on one thread with one prepared bat, the bat's
//! preparation on its own, resolving the study's points (`Plan::point`), and the whole
//! `batstudy run` process (start, study, bat, collisions, the file, exit) beside
//! `batstudy --version` (what starting a process costs).
//!
//!     cargo bench --bench curve

use batstudy::bench::{base_spec, curve_positions, curve_study_text, load_study};
use batstudy::model::spec::CollisionSpec;
use batstudy::model::{prepare_bat, simulate};
use divan::counter::ItemsCount;
use divan::Bencher;
use std::process::{Command, Stdio};

fn main() {
    divan::main();
}

/// 45 collisions, the bat prepared once and shared.
#[divan::bench(sample_count = 300)]
fn curve_45(bencher: Bencher) {
    let base = base_spec(0.70);
    let bat = prepare_bat(&base.bat, &base.numerics).expect("the bat");
    let specs: Vec<CollisionSpec> = curve_positions().into_iter().map(base_spec).collect();
    bencher
        .counter(ItemsCount::new(specs.len()))
        .bench_local(|| {
            specs
                .iter()
                .map(|s| simulate(s, &bat, None).expect("a curve point").exit_speed)
                .fold(0.0, f64::max)
        });
}

/// The R161's discretisation, modal basis and BBCOR scan.
#[divan::bench]
fn prepare(bencher: Bencher) {
    let base = base_spec(0.70);
    bencher.bench_local(|| prepare_bat(&base.bat, &base.numerics).expect("the bat"));
}

/// Resolving one point of a 2 700-point study from its plan (YAML value, checks, id).
#[divan::bench]
fn plan_point(bencher: Bencher) {
    let study = load_study(&curve_study_text("points", 60, ""), "points").expect("study");
    let n = study.plan.n_points();
    let mut i = 0;
    bencher.counter(ItemsCount::new(1usize)).bench_local(|| {
        i = (i + 1) % n;
        study.plan.point(i).is_ok()
    });
}

fn batstudy(args: &[&std::ffi::OsStr]) {
    let status = Command::new(env!("CARGO_BIN_EXE_batstudy"))
        .args(args)
        .stdout(Stdio::null())
        .status()
        .expect("batstudy starts");
    assert!(status.success(), "batstudy {args:?}: {status}");
}

/// `batstudy run` of the 45-point curve into a new file, on every core.
#[divan::bench(sample_count = 25)]
fn curve_process(bencher: Bencher) {
    let dir = tempfile::tempdir().expect("a temporary directory");
    let study = dir.path().join("curve.yaml");
    std::fs::write(&study, curve_study_text("curve", 1, "")).expect("write the study");
    let out = dir.path().join("curve.h5");
    let args = [
        "run".as_ref(),
        study.as_os_str(),
        "-o".as_ref(),
        out.as_os_str(),
        "--force".as_ref(),
        "--quiet".as_ref(),
    ];
    bencher.bench_local(|| batstudy(&args));
}

/// `batstudy --version`: starting and ending the process alone.
#[divan::bench(sample_count = 25)]
fn version_process(bencher: Bencher) {
    bencher.bench_local(|| batstudy(&["--version".as_ref()]));
}
