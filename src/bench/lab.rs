//! The bat lab's latency: from an edit to its answer (the server's computation of the
//! curve and the card, `lab::answer::evaluate`, on every core), for a solid and a hollow
//! bat. Each edit moves one knot of the barrel by 0.1 mm, so that every edit is a new bat
//! (its modes, BBCOR scan and best q found again), as a drag on the page is. The page's
//! drawing and the loopback's round trip add a few milliseconds, not measured here.

use crate::lab::{answer, session};
use serde::Serialize;
use serde_json::Value;
use std::time::Instant;

#[derive(Debug, Clone, Serialize)]
pub struct LabBench {
    /// Threads the evaluation used.
    pub threads: usize,
    /// Impact positions a session sweeps (the default session's).
    pub positions: usize,
    /// Edits timed per bat.
    pub edits: usize,
    /// Median seconds from an edit to its answer: the R161 wood bat.
    pub solid_seconds: f64,
    /// The same for `alloy_bbcor` (its breathing modes found for each edit).
    pub hollow_seconds: f64,
}

/// Median seconds of `edits` answers, each after moving the knot 10 cm from the barrel's
/// end by another 0.1 mm.
fn median_edit(mut s: Value, edits: usize, pool: &rayon::ThreadPool) -> Result<f64, String> {
    let mut times = Vec::with_capacity(edits);
    for k in 0..edits {
        let knots = s["base"]["bat"]["profile"]["knots"]
            .as_array_mut()
            .ok_or("the session's profile has no knots")?;
        let i = knots.len().saturating_sub(11);
        let r = knots[i][1].as_f64().ok_or("a knot without a radius")?;
        knots[i][1] = Value::from(r + if k % 2 == 0 { 1e-4 } else { -1e-4 } * (k + 1) as f64);
        let t = Instant::now();
        let a = answer::evaluate(&s, pool);
        times.push(t.elapsed().as_secs_f64());
        if let Some(e) = a.get("error") {
            return Err(format!("lab bench: {e}"));
        }
    }
    times.sort_by(f64::total_cmp);
    Ok(times[times.len() / 2])
}

pub(super) fn bench_lab(quick: bool, cores: usize) -> Result<LabBench, String> {
    let pool = crate::run::build_pool(cores).map_err(|e| e.to_string())?;
    let edits = if quick { 3 } else { 15 };
    let solid = session::default_session()?;
    let positions = answer::evaluate(&solid, &pool)["points"]
        .as_array()
        .map_or(0, Vec::len);
    let mut hollow = solid.clone();
    hollow["base"]["bat"] = serde_json::json!({"preset": "alloy_bbcor"});
    let hollow = session::with_knots(hollow)?;
    Ok(LabBench {
        threads: cores,
        positions,
        edits,
        solid_seconds: median_edit(solid, edits, &pool)?,
        hollow_seconds: median_edit(hollow, edits, &pool)?,
    })
}

pub(super) fn print(out: &mut dyn std::io::Write, b: &LabBench) {
    let _ = writeln!(
        out,
        "\n== the bat lab: an edit to its answer ({} positions and the bat's card, {} threads, median of {} edits)\n\
         solid (R161) {:.0} ms, hollow (alloy_bbcor, its breathing modes) {:.0} ms",
        b.positions,
        b.threads,
        b.edits,
        b.solid_seconds * 1e3,
        b.hollow_seconds * 1e3
    );
}
