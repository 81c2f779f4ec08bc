//! Shared helpers for the physics tests.
#![allow(dead_code)]

use batstudy::model::spec::*;

/// The base case: R161, default ball (linear hysteresis, e = 0.5, 40 m/s), free ends.
pub fn base_spec(z: f64) -> CollisionSpec {
    CollisionSpec::base_case(z)
}

pub fn elastic() -> BallLaw {
    BallLaw {
        kind: BallLawKind::Elastic,
        ..BallLaw::default()
    }
}

/// The batstudy binary with `args`, its standard output dropped and its errors kept.
pub fn batstudy_command(args: &[&str]) -> std::process::Command {
    let mut c = std::process::Command::new(env!("CARGO_BIN_EXE_batstudy"));
    c.args(args)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped());
    c
}

/// Run the batstudy binary with `args` to completion and require success (its stderr in
/// the failure message).
pub fn batstudy_ok(args: &[&str]) {
    let out = batstudy_command(args).output().unwrap();
    assert!(
        out.status.success(),
        "batstudy {}: {}",
        args.join(" "),
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Every stored record of a results file, as exact text (Debug of f64 is its shortest
/// round-trip form): two files with equal lists hold the same data.
pub fn stored_records(path: &std::path::Path) -> Vec<String> {
    batstudy::store::read_results(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .records
        .iter()
        .map(|r| format!("{} {} {} {:?}", r.index, r.id, r.bat, r.result))
        .collect()
}
