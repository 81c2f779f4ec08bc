//! The batted ball's cost: the same undercut study (oblique impacts, a swinging bat in the
//! lab) run with and without its `flight` block, through the driver and the real store on the
//! most threads; the flight's share is their time ratio (the target: at most 2).

use super::cases::{load_study, Sizes};
use super::measure::err;
use super::scaling::rate;
use crate::run;
use serde::Serialize;
use std::path::Path;

#[derive(Debug, Clone, Serialize)]
pub struct Batted {
    /// Points of each study.
    pub points: usize,
    /// Points/s of the undercut study without and with its flight, on `threads` threads.
    pub threads: usize,
    pub without_flight_points_per_second: f64,
    pub with_flight_points_per_second: f64,
    /// Time per point with the flight over time per point without it.
    pub flight_time_ratio: f64,
}

/// The undercut study: the 45-point curve × `omegas` swing speeds, the calibrated ball met
/// 1.5 cm below its centre on a 10° swing plane, the bat's CM at 25 m/s, optionally flown.
fn undercut_study_text(omegas: usize, flight: bool) -> String {
    let flight = if flight { "  flight: {}\n" } else { "" };
    format!(
        "name: bench-batted\nmodel: wave\nbase:\n  bat: {{preset: r161}}\n  ball: {{preset: mlb, speed: 65}}\n  \
         swing: {{cm_speed: 25, attack_angle: 0.1745}}\n  impact: {{z: 0.7, offset: -0.015}}\n{flight}\
         grid:\n  swing.omega: {{linspace: [-20, -50, {omegas}]}}\n  impact.z: {{range: [0.40, 0.84, 0.01]}}\n"
    )
}

/// Both studies on `threads` threads, `repeats` times each (the median rates).
pub(super) fn bench_batted(sz: &Sizes, threads: usize, dir: &Path) -> Result<Batted, String> {
    let omegas = Sizes::omegas(sz.summary_omegas, threads).max(2);
    let without = load_study(&undercut_study_text(omegas, false), "batted")?;
    let with = load_study(&undercut_study_text(omegas, true), "batted-flight")?;
    let pool = run::build_pool(threads).map_err(err("pool"))?;
    let (a, _) = rate(&without, "batted", dir, &pool, sz.repeats)?;
    let (b, _) = rate(&with, "batted-flight", dir, &pool, sz.repeats)?;
    Ok(Batted {
        points: without.plan.n_points(),
        threads,
        without_flight_points_per_second: a,
        with_flight_points_per_second: b,
        flight_time_ratio: a / b,
    })
}
