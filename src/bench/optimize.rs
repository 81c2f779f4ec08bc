//! `optimize`: how many design candidates per second this machine evaluates on
//! a 6-variable profile search (the wood barrel of `studies/design_wood.yaml`, cut to a
//! fixed number of candidates), on every core, as `batstudy optimize` runs it.

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
}

/// Run the search (`candidates` of them) on `threads` threads.
pub fn bench_optimize(candidates: usize, threads: usize) -> Result<OptimizeBench, String> {
    let text = STUDY.replace("MAX", &candidates.to_string());
    let study = crate::study::load_str(
        &text,
        std::path::Path::new("bench_optimize.yaml"),
        &Default::default(),
    )
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
    Ok(OptimizeBench {
        variables: design.variables.len(),
        candidates: out.candidates.len(),
        points_per_candidate: study.plan.n_points(),
        threads,
        seconds,
        evaluations_per_second: out.candidates.len() as f64 / seconds,
    })
}

/// Print the section.
pub fn print(out: &mut dyn Write, b: &OptimizeBench) {
    let _ = writeln!(
        out,
        "\noptimize: {} candidates of a {}-variable profile search ({} collisions each) on {} threads in {:.2} s: {:.1} evaluations/s",
        b.candidates, b.variables, b.points_per_candidate, b.threads, b.seconds, b.evaluations_per_second
    );
    let _ = out.flush();
}
