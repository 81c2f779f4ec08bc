//! `optimize`: how many design candidates per second this machine evaluates on
//! a 6-variable profile search (the wood barrel of `studies/design_wood.yaml`, cut to a
//! fixed number of candidates), on every core, as `batstudy optimize` runs it; and a hollow
//! barrel's search with its shell modes against the same without them.

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

/// Run the search (`candidates` of them) on `threads` threads, and the hollow barrel's with
/// and without its shell.
pub fn bench_optimize(candidates: usize, threads: usize) -> Result<OptimizeBench, String> {
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
    let _ = out.flush();
}
