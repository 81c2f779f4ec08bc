//! `optimize`: how many design candidates per second this machine evaluates on
//! a 6-variable profile search (the wood barrel of `studies/design_wood.yaml`, cut to a
//! fixed number of candidates), on every core, as `batstudy optimize` runs it; a hollow
//! barrel's search with its shell modes against the same without them; and the wood search
//! made robust (over a sample of 64 billets and ball lots), with the share of a candidate
//! that goes to preparing its bats.

use serde::Serialize;
use std::io::Write;
use std::sync::atomic::AtomicBool;

/// The search's study: six barrel radii of a wood bat, a batter, twelve impact positions.
const STUDY: &str = "name: bench_optimize
model: wave
base:
  bat: {preset: r161}
  ball: {preset: mlb}
  batter: {pitch_speed: 40.2, bat_speed: 31.3, reference_moi: 0.319}
grid:
  impact.z: {range: [0.58, 0.80, 0.02]}
optimize:
  max_evaluations: MAX
  tolerance: 0.0
  profile:
    z: [0.0, 0.02, 0.03, 0.15, 0.35, 0.45, 0.55, 0.62, 0.69, 0.76, 0.84]
    radius: [0.0252, 0.0252, 0.0177, 0.0130, 0.0152,
      {min: 0.012, max: 0.0331, start: 0.018}, {min: 0.012, max: 0.0331, start: 0.0252},
      {min: 0.012, max: 0.0331, start: 0.0295}, {min: 0.012, max: 0.0331, start: 0.0313},
      {min: 0.012, max: 0.0331, start: 0.0318}, {min: 0.012, max: 0.0331, start: 0.0322}]
  objective: {maximize: sweet_spot.exit_speed_lab}
  constraints:
    - {rules: mlb_wood}
    - {quantity: bat.mass, max: 0.869}
";

/// The hollow barrel's search (`studies/design_bbcor.yaml`'s variables, a shorter grid):
/// its candidates with the barrel's breathing modes (`HOOP`: `{from_geometry: true}`) and
/// without (`null`), to price the shell's preparation.
const HOLLOW_STUDY: &str = "name: bench_optimize_hollow
model: wave
base:
  bat: {preset: aluminum, shell: {from: 0.0}}
  ball: {preset: mlb}
  hoop: HOOP
  batter: {pitch_speed: 40.2, bat_speed: 31.3, reference_moi: 0.319}
grid:
  impact.z: {range: [0.58, 0.80, 0.02]}
optimize:
  max_evaluations: MAX
  tolerance: 0.0
  profile:
    z: [0.0, 0.02, 0.03, 0.15, 0.35, 0.45, 0.55, 0.65, 0.75, 0.84]
    radius: [0.0252, 0.0252, 0.0177, 0.0130, 0.0152, 0.0180, 0.0252,
      {min: 0.0240, max: 0.0333, start: 0.0307}, {min: 0.0260, max: 0.0333, start: 0.0318}, 0.0321]
    thickness: [0.002, 0.002, 0.002, 0.002, 0.002, 0.0025,
      {min: 0.0015, max: 0.008, start: 0.003}, {min: 0.0015, max: 0.008, start: 0.003},
      {min: 0.0015, max: 0.008, start: 0.003}, {min: 0.0015, max: 0.008, start: 0.003}]
  objective: {maximize: sweet_spot.exit_speed_lab}
  constraints:
    - {rules: ncaa_bbcor, moi_min: 0.14}
";

/// The robust search: the wood profile over a sample of `POINTS` (64; 8 for `--quick`) billets (density as
/// `studies/design_wood_robust.yaml` draws it) and ball lots, every sampled point a bat of
/// its own.
const ROBUST_SAMPLE: &str = "sample:
  n: POINTS
  seed: 56
  ball_spread: lot
  params:
    bat.material.density: {normal: {mean: 649, sd: 64.9, min: 590, max: 670}}
";

/// What the search did.
#[derive(Debug, Clone, Serialize)]
pub struct OptimizeBench {
    pub variables: usize,
    pub candidates: usize,
    /// Collisions per candidate (the study's grid).
    pub points_per_candidate: usize,
    pub threads: usize,
    pub seconds: f64,
    pub evaluations_per_second: f64,
    /// A hollow barrel's candidate with the breathing modes over one without them.
    pub shell: ShellCost,
    /// The wood search over a sample of billets and balls.
    pub robust: RobustCost,
}

/// A robust design's candidate: its rate and where its time goes.
#[derive(Debug, Clone, Serialize)]
pub struct RobustCost {
    pub candidates: usize,
    /// Billets and balls sampled.
    pub sample_points: usize,
    /// Collisions per candidate (grid × sample).
    pub points_per_candidate: usize,
    pub seconds: f64,
    pub evaluations_per_second: f64,
    /// Preparing one candidate's distinct bats (their modes), on every core, s.
    pub seconds_preparing_bats: f64,
    /// That over a candidate's whole time.
    pub preparation_share: f64,
}

/// The price of the barrel's shell modes in a design search.
#[derive(Debug, Clone, Serialize)]
pub struct ShellCost {
    pub candidates: usize,
    pub seconds_with_shell: f64,
    pub seconds_without: f64,
    /// Seconds per candidate with the shell over without.
    pub ratio: f64,
}

/// One search of `text` (`MAX` candidates) on `threads` threads: (variables, candidates,
/// points per candidate, seconds).
fn timed_search(
    text: &str,
    name: &str,
    threads: usize,
) -> Result<(usize, usize, usize, f64), String> {
    let study = crate::study::load_str(text, std::path::Path::new(name), &Default::default())
        .map_err(|e| e.to_string())?;
    let design = crate::optimize::design_of(&study)
        .map_err(|e| e.to_string())?
        .ok_or("no optimize block")?;
    let pool = crate::run::build_pool(threads).map_err(|e| e.to_string())?;
    let ev = crate::optimize::Evaluator::new(&study, &design);
    let t0 = std::time::Instant::now();
    let out = pool.install(|| {
        crate::optimize::search(
            &design,
            &|x| ev.evaluate(x),
            &|_| Ok(()),
            Vec::new(),
            &AtomicBool::new(false),
        )
    });
    let seconds = t0.elapsed().as_secs_f64();
    Ok((
        design.variables.len(),
        out.candidates.len(),
        study.plan.n_points(),
        seconds,
    ))
}

/// The hollow search with and without the shell, `candidates` each.
fn shell_cost(candidates: usize, threads: usize) -> Result<ShellCost, String> {
    let text = |hoop: &str| {
        HOLLOW_STUDY
            .replace("MAX", &candidates.to_string())
            .replace("HOOP", hoop)
    };
    let with = timed_search(&text("{from_geometry: true}"), "bench_hollow.yaml", threads)?;
    let without = timed_search(&text("null"), "bench_hollow.yaml", threads)?;
    Ok(ShellCost {
        candidates,
        seconds_with_shell: with.3,
        seconds_without: without.3,
        ratio: (with.3 / with.1 as f64) / (without.3 / without.1 as f64),
    })
}

/// The robust search (`candidates` of them), and the preparation of its start design's bats
/// alone.
fn robust_cost(candidates: usize, sample: usize, threads: usize) -> Result<RobustCost, String> {
    let text = STUDY.replace("MAX", &candidates.to_string())
        + &ROBUST_SAMPLE.replace("POINTS", &sample.to_string());
    let (_, done, points, seconds) = timed_search(&text, "bench_robust.yaml", threads)?;
    let prepare = preparation_seconds(&text, threads)?;
    let per_candidate = seconds / done.max(1) as f64;
    Ok(RobustCost {
        candidates: done,
        sample_points: sample,
        points_per_candidate: points,
        seconds,
        evaluations_per_second: done as f64 / seconds,
        seconds_preparing_bats: prepare,
        preparation_share: prepare / per_candidate,
    })
}

/// Seconds to prepare the distinct bats of the study's start design on `threads` threads.
fn preparation_seconds(text: &str, threads: usize) -> Result<f64, String> {
    use rayon::prelude::*;
    let study = crate::study::load_str(
        text,
        std::path::Path::new("bench_robust.yaml"),
        &Default::default(),
    )
    .map_err(|e| e.to_string())?;
    let design = crate::optimize::design_of(&study)
        .map_err(|e| e.to_string())?
        .ok_or("no optimize block")?;
    let base = design.apply(&design.start(), study.plan.base());
    let mut bats = std::collections::BTreeMap::new();
    for flat in 0..study.plan.n_points() {
        let m = study.plan.shape().unravel(flat);
        let spec = study
            .plan
            .resolve_over(&base, &m)
            .map_err(|e| e.to_string())?;
        let key = crate::study::plan::bat_key(&spec.bat, &spec.numerics);
        bats.entry(key).or_insert((spec.bat, spec.numerics));
    }
    let pool = crate::run::build_pool(threads).map_err(|e| e.to_string())?;
    let t0 = std::time::Instant::now();
    let prepared: Result<Vec<_>, _> = pool.install(|| {
        bats.values()
            .collect::<Vec<_>>()
            .par_iter()
            .map(|(bat, numerics)| crate::model::Target::prepare(bat, numerics))
            .collect()
    });
    prepared.map_err(|e| e.to_string())?;
    Ok(t0.elapsed().as_secs_f64())
}

/// Run the search (`candidates` of them) on `threads` threads, and the hollow barrel's with
/// and without its shell, and the robust search over `sample` billets and balls (a tenth as many candidates, at least the 7
/// of its first simplex).
pub fn bench_optimize(
    candidates: usize,
    sample: usize,
    threads: usize,
) -> Result<OptimizeBench, String> {
    let text = STUDY.replace("MAX", &candidates.to_string());
    let (variables, done, points, seconds) = timed_search(&text, "bench_optimize.yaml", threads)?;
    Ok(OptimizeBench {
        variables,
        candidates: done,
        points_per_candidate: points,
        threads,
        seconds,
        evaluations_per_second: done as f64 / seconds,
        shell: shell_cost(candidates, threads)?,
        robust: robust_cost((candidates / 10).max(7), sample, threads)?,
    })
}

/// Print the section.
pub fn print(out: &mut dyn Write, b: &OptimizeBench) {
    let _ = writeln!(
        out,
        "\noptimize: {} candidates of a {}-variable profile search ({} collisions each) on {} threads in {:.2} s: {:.1} evaluations/s",
        b.candidates, b.variables, b.points_per_candidate, b.threads, b.seconds, b.evaluations_per_second
    );
    let c = &b.shell;
    let _ = writeln!(
        out,
        "  a hollow barrel's candidate with its shell modes: {:.2}x one without ({} candidates: {:.2} s with, {:.2} s without)",
        c.ratio, c.candidates, c.seconds_with_shell, c.seconds_without
    );
    let _ = writeln!(
        out,
        "  a hollow barrel's design: {:.1} candidates/s with its shell modes",
        c.candidates as f64 / c.seconds_with_shell
    );
    let r = &b.robust;
    let _ = writeln!(
        out,
        "  a robust wood design over {} billets and balls ({} collisions a candidate): {:.2} candidates/s ({} in {:.2} s); preparing a candidate's bats {:.3} s, {:.0} % of it",
        r.sample_points, r.points_per_candidate, r.evaluations_per_second, r.candidates, r.seconds, r.seconds_preparing_bats, 100.0 * r.preparation_share
    );
    let _ = out.flush();
}
