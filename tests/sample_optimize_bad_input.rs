//! Bad `sample` and `optimize` blocks are refused before anything runs or is
//! written: exit status 2, file:line:column, the field, the value and what is allowed.

use std::process::Command;

const BASE: &str = "name: bad\nmodel: rigid\nbase:\n  impact: {z: 0.7}\n";

/// `batstudy CMD` on a study of BASE + `block`: (exit code, stderr, whether an output exists).
fn refused(cmd: &str, block: &str) -> (Option<i32>, String, bool) {
    let dir = tempfile::tempdir().unwrap();
    let study = dir.path().join("bad.yaml");
    std::fs::write(&study, format!("{BASE}{block}")).unwrap();
    let out = dir.path().join("out.h5");
    let mut args = vec![cmd, study.to_str().unwrap()];
    if cmd != "validate" {
        args.extend(["-o", out.to_str().unwrap()]);
    }
    let o = Command::new(env!("CARGO_BIN_EXE_batstudy"))
        .args(args)
        .output()
        .unwrap();
    let left = std::fs::read_dir(dir.path()).unwrap().count() > 1;
    (
        o.status.code(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
        left,
    )
}

fn check(cmd: &str, block: &str, want: &[&str]) {
    let (code, err, left) = refused(cmd, block);
    assert_eq!(code, Some(2), "{block}: {err}");
    assert!(!left, "{block}: something was written");
    for w in want {
        assert!(err.contains(w), "{block}: `{w}` not in\n{err}");
    }
}

#[test]
fn bad_sample_blocks() {
    let s = "sample:\n  n: 8\n  params:\n";
    check(
        "run",
        &format!("{s}    ball.law.cor: {{normal: {{mean: 0.5, sd: -1}}}}\n"),
        &[
            "bad.yaml:8:40",
            "sample.params.ball.law.cor.normal.sd",
            "value: -1",
            "allowed: a standard deviation > 0",
        ],
    );
    check("run", &format!("{s}    ball.law.cor: {{uniform: {{min: 0.4, max: 0.5}}}}\ngrid:\n  ball.law.cor: [0.5]\n"), &[
        "`ball.law.cor` is also set by",
    ]);
    check("run", &format!("{s}    ball.law.cor: {{uniform: {{min: 0.4, max: 0.5}}}}\n  correlation:\n    - {{between: [ball.law.cor, ball.speed], rho: 0.5}}\n"), &[
        "bad.yaml:10:8",
        "value: ball.speed",
        "allowed: two of the paths under `sample.params`",
    ]);
    check(
        "run",
        "sample:\n  n: 100000\n  params:\n    ball.law.cor: {uniform: {min: 0.4, max: 0.5}}\n",
        &["bad.yaml:6:3", "value: 100000", "allowed: 1 to 65536"],
    );
    // the measured spread needs the preset whose balls were measured, and owns its paths
    check(
        "run",
        "sample: {n: 8, ball_spread: ball}\n",
        &[
            "bad.yaml:5:",
            "sample.ball_spread",
            "value: no preset",
            "allowed: `base.ball.preset: mlb`",
        ],
    );
    check(
        "validate",
        "  ball: {preset: mlb, law: {k1: 4.0e7}}\nsample: {n: 8, ball_spread: lot}\n",
        &["`ball.law.k1` is drawn by `sample.ball_spread`"],
    );
    // a draw beyond the plausible ranges is refused like a grid value
    check(
        "run",
        &format!("{s}    ball.law.cor: {{uniform: {{min: 0.05, max: 0.1}}}}\n"),
        &["bad.yaml:8:5", "ball.law.cor"],
    );
}

#[test]
fn bad_optimize_blocks() {
    let o = "optimize:\n  objective: {maximize: exit_speed}\n  variables:\n";
    check(
        "optimize",
        &format!("{o}    impact.z: {{min: 0.8, max: 0.4}}\n"),
        &[
            "bad.yaml:8:5",
            "optimize.variables.impact.z",
            "allowed: min < max",
        ],
    );
    check(
        "optimize",
        &format!("{o}    bat.preset: {{min: 0, max: 1}}\n"),
        &[
            "optimize.variables.bat.preset",
            "allowed: a dotted path of a number",
        ],
    );
    check("optimize", "optimize:\n  objective: {maximize: exit_sped}\n  variables:\n    impact.z: {min: 0.4, max: 0.8}\n", &[
        "bad.yaml:6:15",
        "value: exit_sped",
        "allowed: exit_speed",
    ]);
    check("optimize", &format!("{o}    impact.z: {{min: 0.4, max: 0.8}}\n  constraints:\n    - {{quantity: bat.mass}}\n"), &[
        "optimize.constraints[0]",
        "allowed: `min`, `max` or both",
    ]);
    check(
        "optimize",
        &format!("{o}    impact.z: {{min: 0.4, max: 0.8}}\ngrid:\n  impact.z: [0.6, 0.7]\n"),
        &["`impact.z` is also varied by dimension `impact_z`"],
    );
    // MLB's rules need one piece of solid wood
    check("optimize", &format!("{o}    impact.z: {{min: 0.4, max: 0.8}}\n  constraints:\n    - {{rules: mlb_wood}}\ngrid:\n  bat.preset: [aluminum]\n"), &[
        "`mlb_wood` needs a bat of one piece of solid wood",
        "value: aluminum",
    ]);
    // a profile a lathe can turn: a span the knots' bounds allow to rise, a curvature > 0
    let profile = "optimize:\n  objective: {maximize: exit_speed}\n  profile:\n    z: [0.0, 0.3, 0.6, 0.84]\n\
                   \x20   radius: [0.012, {min: 0.02, max: 0.03}, 0.018, 0.03]\n";
    check(
        "optimize",
        &format!("{profile}    shape: {{rising: [0.1, 0.84]}}\n"),
        &[
            "bad.yaml:10:13",
            "optimize.profile.shape.rising",
            "the radius cannot rise from knot 1 (z = 0.3 m, at least 0.02 m) to knot 2",
            "value: [0.1, 0.84]",
        ],
    );
    check(
        "optimize",
        &format!("{profile}    shape: {{rising: [0.5, 0.9]}}\n"),
        &[
            "bad rising span",
            "value: [0.5, 0.9]",
            "<= 0.84 (the last knot)",
        ],
    );
    check(
        "optimize",
        &format!("{profile}    shape: {{max_curvature: -1}}\n"),
        &[
            "optimize.profile.shape.max_curvature",
            "value: -1",
            "allowed: a curvature > 0",
        ],
    );
    // a probability: one bound, no `over`, 0 < p <= 1; a quantile's fraction likewise
    let c = format!("{o}    impact.z: {{min: 0.4, max: 0.8}}\n  constraints:\n");
    check(
        "optimize",
        &format!("{c}    - {{quantity: exit_speed, min: 20, probability: 1.5}}\n"),
        &[
            "optimize.constraints[0].probability",
            "value: 1.5",
            "allowed: a probability 0 < p <= 1",
        ],
    );
    check(
        "optimize",
        &format!("{c}    - {{quantity: exit_speed, min: 20, max: 40, probability: 0.9}}\n"),
        &["has one bound", "allowed: `min` or `max`, not both"],
    );
    check(
        "optimize",
        &format!("{c}    - {{quantity: exit_speed, min: 20, over: mean, probability: 0.9}}\n"),
        &["has no `over`", "allowed: either `probability` or `over`"],
    );
    check(
        "optimize",
        "optimize:\n  objective: {maximize: exit_speed, over: {quantile: 0}}\n  variables:\n    impact.z: {min: 0.4, max: 0.8}\n",
        &["optimize.objective.over.quantile", "value: 0", "allowed: a fraction 0 < q <= 1"],
    );
    // validate finds the same
    check(
        "validate",
        &format!("{o}    impact.z: {{min: 0.8, max: 0.4}}\n"),
        &["allowed: min < max"],
    );
    // and a study without the block is not a search
    check("optimize", "", &["the study has no `optimize` block"]);
}
