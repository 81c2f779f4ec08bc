//! The study parser under mutation: thousands of mutated study files go through
//! `study::load_str`, the function behind `batstudy validate` and `run`. Nothing may panic,
//! and every refusal must carry a position (line and column) and a field or a message that
//! says what is wrong. The mutations are seeded, so a failure names a reproducible case.
//!
//! A mutation-based fuzz test in the sense of Zeller et al., "The Fuzzing Book" (chapter
//! "Mutation-Based Fuzzing"): valid seeds, small random edits, an oracle that is the absence
//! of a crash plus the error contract of README ("the message names the file, line and
//! column, the field, the value and what is allowed").

#![allow(clippy::result_large_err)] // StudyError: see src/study/mod.rs

use batstudy::study::{load_str, LoadOptions};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::Path;

mod common;
use common::Rng;

/// Snippets that stress the parser's edges: special floats, huge and negative numbers,
/// wrong types, YAML structure characters, unknown and known keys.
const TOKENS: &[&str] = &[
    ".nan",
    ".inf",
    "-.inf",
    "1e400",
    "-1",
    "0",
    "1e30",
    "1e-30",
    "null",
    "~",
    "true",
    "fast",
    "[]",
    "{}",
    "[1, 2",
    "{a: 1}",
    ": ",
    "- ",
    "\n",
    "\n  ",
    "#",
    "'",
    "\"",
    "&a",
    "*a",
    "!!str",
    "{linspace: [0, 1, 1e12]}",
    "{range: [0, 1, 0]}",
    "{range: [0, 1e9, 1e-9]}",
    "bat.material.density",
    "ball.law.kind",
    "power_law",
    "elastic",
    "aluminum",
    "fixed",
    "hoop",
    "history",
    "only",
    "impact.z",
    "grid",
    "zip",
    "points",
    "9999999999999999999999",
    "0.703",
    "allow_implausible: true",
    "numerics.max_steps",
    "1e20",
    // the history block, names and grids a hostile study may hold
    "fields: [force, force]",
    "fields: [displacement]",
    "z_step: 1.0e-9",
    "interval: 1.0e-12",
    "name: exit_speed",
    "name: \"a/b\"",
    "name: \"\"",
    "name: point_id",
    "{range: [0.84, 0.40, -0.04]}",
    "[0.7, 0.5, 0.6]",
    "csv: /dev/zero",
    "csv: /etc/passwd",
    "\r",
    "\u{2028}",
    "[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[",
    // the `sample` and `optimize` blocks: far tails, huge bounds, tiny budgets, rule sets
    "sample: {n: 8, params: {bat.material.density: {normal: {mean: 649, sd: 10, min: 740, max: 800}}}}",
    "{normal: {mean: 649, sd: 10, min: 1100, max: 1200}}",
    "{lognormal: {mean: 0.5, cov: 0.01, min: 0.9}}",
    "{uniform: {min: 0.4, max: 0.4}}",
    "correlation: [{between: [a, b], rho: 1}]",
    "max_evaluations: 1",
    "max_evaluations: 0",
    "{min: -1.0e308, max: 1.0e308}",
    "{min: 0.5, max: 0.8, start: 0.9}",
    "{rules: ncaa_bbcor}",
    "{rules: ncaa}",
    "{quantity: exit_speed, max: -100}",
    "{maximize: sweet_spot.exit_speed}",
    "objective: {minimize: bat.mass}",
    // the newer blocks: layers, pitch, pareto, cma_es, a robust objective
    "{material: gap, thickness: 1.0e-6}",
    "{material: al6061, thickness: 1.0e-4}",
    "{material: carbon_epoxy, thickness: 0.001, angle: 45}",
    "{material: unobtainium, thickness: 0.001}",
    "break_in: 0.99",
    "thickness_knots: [[0, 0.002], [0.84, 0.006]]",
    "pitch: {speed: 40, descent_angle: 1.6}",
    "horizontal_angle: -3",
    "bat_speed_at: 1.0e-300",
    "pivot: 0.8",
    "pareto: {minimize: approach_speed, points: 1000000}",
    "method: cma_es",
    "seed: 18446744073709551615",
    "tolerance: 1.0e308",
    "over: {quantile: 0}",
    "fields: [trajectory]",
    "duration: 0.05",
];

fn mutate(text: &str, rng: &mut Rng) -> String {
    let mut s: Vec<char> = text.chars().collect();
    for _ in 0..1 + rng.below(3) {
        let at = rng.below(s.len() + 1);
        match rng.below(6) {
            0 if !s.is_empty() => {
                let end = (at + 1 + rng.below(8)).min(s.len());
                s.drain(at.min(s.len())..end);
            }
            1 | 2 => {
                let tok = TOKENS[rng.below(TOKENS.len())];
                s.splice(at..at, tok.chars());
            }
            3 => {
                // replace a number-looking run with a token
                let start = (at..s.len()).find(|&i| s[i].is_ascii_digit());
                if let Some(i) = start {
                    let mut j = i;
                    while j < s.len() && (s[j].is_ascii_digit() || ".e-".contains(s[j])) {
                        j += 1;
                    }
                    let tok = TOKENS[rng.below(12)];
                    s.splice(i..j, tok.chars());
                }
            }
            4 => {
                // duplicate a line
                let lines: Vec<String> = s
                    .iter()
                    .collect::<String>()
                    .lines()
                    .map(String::from)
                    .collect();
                if !lines.is_empty() {
                    let k = rng.below(lines.len());
                    let mut out = lines.clone();
                    out.insert(k, lines[k].clone());
                    s = out.join("\n").chars().collect();
                }
            }
            _ => {
                // swap two characters
                if s.len() > 1 {
                    let b = rng.below(s.len());
                    let a = at.min(s.len() - 1);
                    s.swap(a, b);
                }
            }
        }
    }
    s.into_iter().collect()
}

/// Run an accepted study into `out` through the library call behind `batstudy run` (2
/// threads), if it is small enough to be cheap (at most 64 points, estimated under 50 ms of
/// work). The oracle: no panic; a refusal or failure carries its exit code (2 or 3) and a
/// message; a finished run left its file and nothing beside it.
fn run_if_small(study: batstudy::study::Study, out: &Path) -> bool {
    use batstudy::operations::{run_study, RunRequest, RunSettings};
    let plan = &study.plan;
    let history = study.history_request(1.2);
    let cost: f64 = (0..plan.n_points().min(65))
        .filter_map(|i| plan.point(i).ok())
        .map(|p| batstudy::run::estimate_cost(&p.spec, history.as_ref()))
        .sum();
    if plan.n_points() > 64 || cost > 0.05 {
        return false;
    }
    let implausible = study.file.allow_implausible;
    let request = RunRequest {
        output: Some(out.to_path_buf()),
        jobs: Some(2),
        ..RunRequest::default()
    };
    let stop = std::sync::atomic::AtomicBool::new(false);
    let result = RunSettings::new(study, &request)
        .map_err(|e| (2, e.to_string()))
        .and_then(|s| {
            run_study(s, &stop, Default::default()).map_err(|f| (f.exit_code(), f.to_string()))
        });
    match result {
        Ok(done) => {
            let code = batstudy::operations::exit_code_of(done.outcome());
            assert!(code == 0 || code == 1, "exit {code}");
            assert!(out.is_file(), "no output");
            if !implausible {
                physical_outcomes(out);
            }
            for side in [".journal", ".partial", ".lock"] {
                let p = format!("{}{side}", out.display());
                assert!(!Path::new(&p).exists(), "{p} left beside a finished run");
            }
        }
        Err((code, message)) => {
            assert!(code == 2 || code == 3, "exit {code}: {message}");
            assert!(!message.is_empty());
        }
    }
    true
}

/// Every point a finished run stores as computed is physical: its collision efficiency
/// e_A = (e − r)/(1 + r), with 0 ≤ e ≤ 1 and r = m/M_eff ≥ 0, lies in (−1, 1) (a ball
/// that passes through a bat of no mass gives −1: two 1-µm walls once gave −0.98).
fn physical_outcomes(out: &Path) {
    let back = batstudy::store::read_results(out).expect("a finished run reads back");
    for r in &back.records {
        if let Ok(o) = &r.result {
            let e = o.collision_efficiency;
            assert!(
                !e.is_finite() || (-0.999..1.0).contains(&e),
                "point {}: collision efficiency {e}",
                r.index
            );
        }
    }
}

/// A rigid design search and a sampled study, small enough that most mutants run; and the
/// newer blocks: a layered double wall, an oblique pitch with a batter and its flight, a
/// two-objective (pareto) search, CMA-ES, and a robust search over a sample.
const SMALL_SEEDS: [(&str, &str); 7] = [
    (
        "layers.yaml",
        "name: layers\nbase:\n  impact: {z: 0.7}\n  bat:\n    preset: aluminum\n    shell:\n      layers:\n\
         \x20       - {material: al7050, thickness: 0.0015}\n        - {material: gap, thickness: 0.001}\n\
         \x20       - {material: carbon_epoxy, thickness: 0.0008, angle: 0.5}\n        - {material: glass_epoxy, thickness: 0.0007, angle: 1.5}\n\
         \x20     break_in: 0.1\ngrid:\n  bat.shell.from: [0.0, 0.5]\n",
    ),
    (
        "pitch.yaml",
        "name: pitch\nmodel: rigid\nbase:\n  impact: {z: 0.7, offset: 0.01}\n  ball: {preset: mlb}\n\
         \x20 batter: {bat_speed: 31.3, reference_moi: 0.319, bat_speed_at: 0.7112, pivot: 0.0}\n\
         \x20 pitch: {speed: 40.2, descent_angle: 0.107, horizontal_angle: 0.02}\n\
         \x20 swing: {attack_angle: 0.15, attack_direction: 0.1, tilt: -0.5}\n\
         \x20 flight: {temperature: 294, pressure: 101325, elevation: 1580, humidity: 0.5, wind_speed: 3}\n\
         grid:\n  ball.spin: [0, 200]\n",
    ),
    (
        "pareto.yaml",
        "name: pareto\nmodel: rigid\nbase:\n  impact: {z: 0.6}\n  swing: {omega: -30}\noptimize:\n  max_evaluations: 20\n\
         \x20 variables:\n    impact.z: {min: 0.40, max: 0.83}\n  objective: {maximize: exit_speed}\n\
         \x20 pareto: {minimize: approach_speed, points: 3}\n",
    ),
    (
        "cma_es.yaml",
        "name: cma_es\nmodel: rigid\nbase:\n  impact: {z: 0.6}\n  swing: {omega: -30}\noptimize:\n  method: cma_es\n  seed: 3\n\
         \x20 max_evaluations: 20\n  tolerance: 1.0e-6\n  variables:\n    impact.z: {min: 0.40, max: 0.83}\n\
         \x20 objective: {maximize: exit_speed}\n",
    ),
    (
        "robust.yaml",
        "name: robust\nmodel: rigid\nbase:\n  impact: {z: 0.6}\n  swing: {omega: -30}\nsample:\n  n: 4\n  seed: 5\n  params:\n\
         \x20   ball.law.cor: {uniform: {min: 0.45, max: 0.55}}\noptimize:\n  max_evaluations: 20\n\
         \x20 variables:\n    impact.z: {min: 0.40, max: 0.83}\n  objective: {maximize: exit_speed, over: {quantile: 0.1}}\n",
    ),
    (
        "search.yaml",
        "name: search\nmodel: rigid\nbase:\n  impact: {z: 0.6}\n  swing: {omega: -30}\ngrid:\n  ball.speed: [30, 40]\n\
         optimize:\n  max_evaluations: 20\n  variables:\n    impact.z: {min: 0.40, max: 0.83}\n    ball.law.cor: {min: 0.4, max: 0.6}\n\
         \x20 objective: {maximize: exit_speed}\n  constraints:\n    - {quantity: exit_speed, min: 5}\n",
    ),
    (
        "sample.yaml",
        "name: sample\nmodel: rigid\nbase:\n  impact: {z: 0.7}\nsample:\n  n: 8\n  seed: 3\n  params:\n\
         \x20   bat.material.density: {normal: {mean: 649, sd: 10, min: 600, max: 700}}\n\
         \x20   ball.law.cor: {uniform: {min: 0.45, max: 0.55}}\n  correlation:\n    - {between: [bat.material.density, ball.law.cor], rho: 0.3}\n",
    ),
];

/// Accepted studies run per fuzz pass (each a real run into an HDF5 file; bounded time).
const MAX_RUNS: usize = 150;

/// Accepted design searches run per fuzz pass, and the candidates each may evaluate.
const MAX_SEARCHES: usize = 40;
const SEARCH_BUDGET: usize = 6;

/// What an accepted study stores as coordinates is finite (a drawn or written inf ran at a
/// preset's value with exit 0).
fn coordinates_are_finite(study: &batstudy::study::Study, case: &str) {
    for d in &study.plan.shape().dims {
        for c in &d.coords {
            if let batstudy::results::CoordValues::Numbers(v) = &c.values {
                // NaN marks "not set by this entry" in points/zip coordinates; never ±inf
                assert!(
                    v.iter().all(|x| !x.is_infinite()),
                    "{} holds an infinite value: {case}",
                    c.name
                );
            }
        }
    }
}

/// An accepted study with an `optimize` block: the block checked as `batstudy optimize`
/// checks it (a refusal positioned), and a short search run when its candidates are cheap.
/// The oracle: no panic; every candidate evaluated inside the bounds. Returns whether a
/// search ran.
fn search_if_small(study: &batstudy::study::Study, case: &str) -> bool {
    use batstudy::optimize::{design_of, search, Evaluator};
    let design = match design_of(study) {
        Err(e) => {
            assert!(e.line.is_some(), "no position: {e}\n{case}");
            return false;
        }
        Ok(None) => return false,
        Ok(Some(d)) => d,
    };
    let plan = &study.plan;
    let cost: f64 = (0..plan.n_points().min(65))
        .filter_map(|i| plan.point(i).ok())
        .map(|p| batstudy::run::estimate_cost(&p.spec, None))
        .sum();
    if plan.n_points() > 64 || cost > 0.1 {
        return false;
    }
    let mut short = design.clone();
    short.block.max_evaluations = SEARCH_BUDGET.max(design.variables.len() + 1);
    let ev = Evaluator::new(study, &short);
    let stop = std::sync::atomic::AtomicBool::new(false);
    let out = search(&short, &|x| ev.evaluate(x), &|_| Ok(()), Vec::new(), &stop);
    for c in &out.candidates {
        for (v, x) in short.variables.iter().zip(&c.x) {
            assert!(
                x.is_finite() && *x >= v.min && *x <= v.max,
                "{}: {x}\n{case}",
                v.name
            );
        }
    }
    true
}

/// The seeds are fuzzed in two halves on two threads (each half a fixed mutation sequence
/// of its own); the counts are the two halves' sums.
#[test]
fn mutated_studies_never_panic_and_every_refusal_is_positioned() {
    let counts = std::thread::scope(|s| {
        let halves = [0, 1].map(|half| s.spawn(move || fuzz_half(half)));
        halves.map(|h| h.join().unwrap_or_else(|e| std::panic::resume_unwind(e)))
    });
    let [runs, refused, ran, searched] = [0, 1, 2, 3].map(|k| counts[0][k] + counts[1][k]);
    eprintln!(
        "{runs} mutated studies, {refused} refused, {ran} accepted ones run, {searched} searches"
    );
    assert!(ran >= 20, "only {ran} accepted studies were run");
    assert!(searched >= 10, "only {searched} accepted searches were run");
    assert!(runs >= 1500, "{runs} mutated studies");
    assert!(
        refused * 4 >= runs,
        "the mutations should mostly break studies: {refused}/{runs}"
    );
}

/// Fuzz every other seed file, starting at `half` (0 or 1), and the small seeds, with a
/// generator of its own: the counts of studies mutated, refused, run and searched.
fn fuzz_half(half: usize) -> [usize; 4] {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut seeds = Vec::new();
    for dir in ["studies", "tests/bad_studies"] {
        for e in std::fs::read_dir(root.join(dir)).unwrap() {
            let p = e.unwrap().path();
            if p.extension().is_some_and(|x| x == "yaml") {
                seeds.push((p.clone(), std::fs::read_to_string(&p).unwrap()));
            }
        }
    }
    seeds.sort();
    let mut seeds: Vec<_> = seeds.into_iter().skip(half).step_by(2).collect();
    // small seeds whose mutants are cheap to search and to sample (in both halves)
    for (name, text) in SMALL_SEEDS {
        seeds.push((Path::new(name).to_path_buf(), text.to_string()));
    }
    // Large seeds are checked point by point at load time; keep the run short by using
    // each seed a number of times inversely related to its size.
    let opts = LoadOptions {
        max_points: 200_000,
    };
    // BATSTUDY_FUZZ_SEED and BATSTUDY_FUZZ_ROUNDS explore further by hand; CI runs the
    // fixed seed once (about 4 500 studies on two threads, about 13 s).
    let env = |k: &str| std::env::var(k).ok().and_then(|v| v.parse::<u64>().ok());
    let mut rng = Rng(env("BATSTUDY_FUZZ_SEED").unwrap_or(0x5EED_BA75) ^ half as u64);
    let rounds = env("BATSTUDY_FUZZ_ROUNDS").unwrap_or(1) as usize;
    let (mut runs, mut refused, mut ran, mut searched) = (0usize, 0usize, 0usize, 0usize);
    let out_dir = tempfile::tempdir().unwrap();
    for (path, text) in &seeds {
        let tries = rounds * if text.len() > 1500 { 40 } else { 80 };
        for k in 0..tries {
            let mutated = mutate(text, &mut rng);
            let result = catch_unwind(AssertUnwindSafe(|| load_str(&mutated, path, &opts)));
            let case = format!("{} mutation #{k}:\n{mutated}", path.display());
            let Ok(result) = result else {
                panic!("load_str panicked on {case}");
            };
            runs += 1;
            match result {
                Err(e) => {
                    refused += 1;
                    assert!(
                        e.line.is_some() && e.column.is_some(),
                        "no position: {e}\n{case}"
                    );
                    assert!(!e.message.is_empty(), "no message: {e}\n{case}");
                }
                Ok(study) if study.file.optimize.is_some() => {
                    coordinates_are_finite(&study, &case);
                    if searched < MAX_SEARCHES {
                        let run = catch_unwind(AssertUnwindSafe(|| search_if_small(&study, &case)));
                        match run {
                            Ok(true) => searched += 1,
                            Ok(false) => {}
                            Err(_) => panic!("the search panicked on {case}"),
                        }
                    }
                }
                // what validate accepts, run (accepted studies once failed after
                // computing everything, or wrote broken files)
                Ok(study) if ran < MAX_RUNS => {
                    coordinates_are_finite(&study, &case);
                    let out = out_dir.path().join(format!("run{runs}.h5"));
                    let run = catch_unwind(AssertUnwindSafe(|| run_if_small(study, &out)));
                    match run {
                        Ok(true) => ran += 1,
                        Ok(false) => {}
                        Err(_) => panic!("run panicked on {case}"),
                    }
                }
                Ok(_) => {}
            }
        }
    }
    [runs, refused, ran, searched]
}

/// The seeds themselves are valid studies (a seed refused as written fuzzes nothing of its
/// block).
#[test]
fn every_small_seed_is_accepted() {
    for (name, text) in SMALL_SEEDS {
        let loaded = load_str(text, Path::new(name), &LoadOptions::default());
        let study = loaded.unwrap_or_else(|e| panic!("{name}: {e}\n{text}"));
        batstudy::optimize::design_of(&study).unwrap_or_else(|e| panic!("{name}: {e}"));
    }
}
