//! `batstudy.simulate`'s cost: one collision a call, each a one-point study of its own (what
//! the Python function runs, `run::single`), against the points of a study of the same
//! collisions at 8 swing speeds on one thread. The ratio of a call's time to a point's is the price of calling one
//! collision at a time once the bat is prepared (the target: at most 2).

use super::cases::{load_study, Sizes};
use super::measure::err;
use super::scaling::rate;
use crate::run::{self, single::simulate_first_point};
use serde::Serialize;
use std::path::Path;
use std::time::Instant;

#[derive(Debug, Clone, Serialize)]
pub struct SimulateBench {
    /// Collisions of the calls (the study has 8 swing speeds of each).
    pub points: usize,
    /// Seconds per point of the study on one thread, bat preparation and the store included.
    pub study_seconds_per_point: f64,
    /// Seconds per call once the bat is prepared (the median of `repeats` rounds).
    pub call_seconds: f64,
    /// The first call's seconds: the bat prepared (its modes and BBCOR scan).
    pub first_call_seconds: f64,
    /// A call's time over a study point's.
    pub call_to_point_ratio: f64,
}

const BASE: &str =
    "  bat: {preset: r161}\n  ball: {preset: mlb, speed: 40}\n  swing: {omega: -40}\n";

fn positions(points: usize) -> Vec<f64> {
    (0..points)
        .map(|k| 0.50 + 0.34 * k as f64 / (points - 1) as f64)
        .collect()
}

/// One call per position, each its own one-point study as `batstudy.simulate` writes it.
fn calls(zs: &[f64]) -> Result<f64, String> {
    let t = Instant::now();
    for z in zs {
        let text = format!("name: simulate\nbase:\n{BASE}  impact: {{z: {z}}}\n");
        let study = load_study(&text, "simulate")?;
        simulate_first_point(&study).map_err(err("simulate"))?;
    }
    Ok(t.elapsed().as_secs_f64())
}

pub(super) fn bench_simulate(sz: &Sizes, dir: &Path) -> Result<SimulateBench, String> {
    let points = if sz.repeats > 1 { 35 } else { 8 };
    let zs = positions(points);
    let z_list: Vec<String> = zs.iter().map(|z| z.to_string()).collect();
    // swing speeds besides the calls' -40 rad/s, so that the bat's preparation spreads over
    // many points, as in a real study
    let text = format!(
        "name: bench-simulate\nmodel: wave\nbase:\n{BASE}grid:\n  swing.omega: {{linspace: [-20, -55, 8]}}\n  \
         impact.z: [{}]\n",
        z_list.join(", ")
    );
    let study = load_study(&text, "simulate-study")?;
    let pool = run::build_pool(1).map_err(err("pool"))?;
    let (per_second, _) = rate(&study, "simulate-study", dir, &pool, sz.repeats)?;
    let first = calls(&zs[..1])?;
    let mut rounds: Vec<f64> = (0..sz.repeats.max(1))
        .map(|_| calls(&zs).map(|t| t / points as f64))
        .collect::<Result<_, _>>()?;
    rounds.sort_by(f64::total_cmp);
    let call = rounds[rounds.len() / 2];
    Ok(SimulateBench {
        points,
        study_seconds_per_point: 1.0 / per_second,
        call_seconds: call,
        first_call_seconds: first,
        call_to_point_ratio: call * per_second,
    })
}
