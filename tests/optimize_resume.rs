//! A design search killed (`kill -9`) part way resumes with `--resume` and gives
//! the same record of the search and the same results as an uninterrupted one: every
//! evaluated candidate is synced to `OUT.h5.optimize` before the search goes on, and the
//! deterministic search replays them.

mod common;

use common::{batstudy_command, batstudy_ok, stored_records};
use std::path::Path;
use std::time::{Duration, Instant};

const STUDY: &str = "name: resume_search
model: wave
base:
  bat: {preset: r161}
  swing: {omega: -30}
grid:
  impact.z: {range: [0.60, 0.78, 0.03]}
optimize:
  max_evaluations: 80
  tolerance: 0.0
  variables:
    bat.material.density: {min: 550, max: 750, start: 600}
    bat.handle.radius_scale: {min: 0.8, max: 1.3}
  objective: {maximize: sweet_spot.exit_speed}
  constraints:
    - {quantity: bat.mass, max: 0.95}
";

fn journal_lines(out: &Path) -> usize {
    let j = batstudy::store::optimize::journal_path(out);
    std::fs::read_to_string(j).map_or(0, |t| t.lines().count())
}

/// Every variable of `/optimize`, as exact text.
fn search_record(path: &Path) -> Vec<String> {
    let f = hdf5::File::open(path).unwrap();
    let g = f.group("optimize").unwrap();
    let mut names = g.member_names().unwrap();
    names.sort();
    let mut out = Vec::new();
    for n in names
        .iter()
        .filter(|n| !["variable", "constraint", "message"].contains(&n.as_str()))
    {
        let d = g.dataset(n).unwrap();
        let v: Vec<String> = match d.dtype().unwrap().size() {
            1 => d
                .read_raw::<i8>()
                .unwrap()
                .iter()
                .map(|x| x.to_string())
                .collect(),
            _ => d
                .read_raw::<f64>()
                .unwrap()
                .iter()
                .map(|x| format!("{:?}", x.to_bits()))
                .collect(),
        };
        out.push(format!("{n}: {}", v.join(" ")));
    }
    let best: f64 = g.attr("best_objective").unwrap().read_scalar().unwrap();
    out.push(format!("best {:?}", best.to_bits()));
    out
}

#[test]
fn a_killed_search_resumes_to_the_same_record() {
    killed_and_resumed(STUDY, 13);
}

/// A two-objective search (three searches sharing what they evaluated) killed in its second
/// search resumes to the same record, its front included.
#[test]
fn a_killed_pareto_search_resumes_to_the_same_record() {
    let text = STUDY.replace("max_evaluations: 80", "max_evaluations: 30")
        + "  pareto: {minimize: bat.moment_of_inertia_knob6, points: 3}\n";
    assert!(text.contains("max_evaluations: 30"));
    killed_and_resumed(&text, 40);
}

/// A robust search (over a sample of billets: eight densities, with the mass a probability)
/// killed part way resumes to the same record.
#[test]
fn a_killed_robust_search_resumes_to_the_same_record() {
    let text = STUDY
        .replace("    bat.material.density: {min: 550, max: 750, start: 600}\n", "")
        .replace(
            "    - {quantity: bat.mass, max: 0.95}",
            "    - {quantity: bat.mass, max: 0.95, probability: 0.75}",
        )
        .replace("max_evaluations: 80", "max_evaluations: 16")
        + "sample:\n  n: 8\n  seed: 4\n  params:\n    bat.material.density: {normal: {mean: 649, sd: 40}}\n";
    assert!(text.contains("probability: 0.75") && !text.contains("start: 600"));
    killed_and_resumed(&text, 6);
}

/// `text` searched whole, and killed once `lines` candidates are in its journal then
/// resumed: the same `/optimize` and the same results.
fn killed_and_resumed(text: &str, lines: usize) {
    let dir = tempfile::tempdir().unwrap();
    let study = dir.path().join("s.yaml");
    std::fs::write(&study, text).unwrap();
    let (full, cut) = (dir.path().join("full.h5"), dir.path().join("cut.h5"));
    let s = study.to_str().unwrap();
    batstudy_ok(&[
        "optimize",
        s,
        "-o",
        full.to_str().unwrap(),
        "-j",
        "2",
        "--quiet",
    ]);
    let total = search_record(&full).len();
    assert!(total > 5);

    // kill -9 once a dozen candidates are in the journal
    let mut child = batstudy_command(&[
        "optimize",
        s,
        "-o",
        cut.to_str().unwrap(),
        "-j",
        "1",
        "--quiet",
    ])
    .spawn()
    .unwrap();
    let t0 = Instant::now();
    while journal_lines(&cut) < lines && t0.elapsed() < Duration::from_secs(120) {
        std::thread::sleep(Duration::from_millis(5));
    }
    child.kill().unwrap();
    let _ = child.wait();
    let kept = journal_lines(&cut);
    assert!(
        kept >= lines && !cut.exists(),
        "killed too late: {kept} lines, finished {}",
        cut.exists()
    );
    // without --resume the interrupted search is not overwritten
    let refused = batstudy_command(&["optimize", s, "-o", cut.to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(refused.status.code(), Some(2));

    batstudy_ok(&[
        "optimize",
        s,
        "-o",
        cut.to_str().unwrap(),
        "--resume",
        "-j",
        "2",
        "--quiet",
    ]);
    assert!(!batstudy::store::optimize::journal_path(&cut).exists());
    assert_eq!(search_record(&full), search_record(&cut));
    assert_eq!(stored_records(&full), stored_records(&cut));
}
