//! One collision of a one-point study, as `batstudy.simulate` asks for it: its bat prepared
//! once and kept (keyed by the bat's parameters and the BBCOR shot), so that a call after the
//! first costs what a study's point does, not a bat's preparation (its modes and its BBCOR
//! scan, most of a first call). `batstudy bench` measures the ratio.

use super::adapters::ModelSimulator;
use super::driver::{build_pool, check_finite_for, prepare_bats, PreparedBats};
use super::traits::Simulator;
use crate::model::field::squared_up;
use crate::model::outcome::{HistoryRequest, Outcome};
use crate::model::Target;
use crate::results::{BatVariant, PointId};
use crate::study::Study;
use std::sync::{Arc, Mutex};

/// Most prepared bats kept (a few MB each at most); the least recently used goes first.
pub const KEPT_BATS: usize = 32;

/// What one call gives: the collision, the history request it recorded, the point's id and
/// its bat.
pub struct Single {
    pub outcome: Outcome,
    pub request: Option<HistoryRequest>,
    pub id: PointId,
    pub bat: BatVariant,
}

type Kept = Vec<(String, Arc<PreparedBats<Target>>)>;

static KEPT: Mutex<Kept> = Mutex::new(Vec::new());

/// The study's bats, from the kept ones when a call has prepared the same bat before (new
/// ones prepared on `pool`, one thread when it is `None`).
pub fn bats_of(
    study: &Study,
    pool: Option<&rayon::ThreadPool>,
) -> Result<Arc<PreparedBats<Target>>, String> {
    let key: String = study
        .plan
        .bats()
        .iter()
        .map(|b| format!("{}|{}\n", b.key, b.shot.json()))
        .collect();
    let mut kept = KEPT.lock().unwrap_or_else(|p| p.into_inner());
    if let Some(i) = kept.iter().position(|(k, _)| *k == key) {
        let entry = kept.remove(i);
        let bats = Arc::clone(&entry.1);
        kept.push(entry);
        return Ok(bats);
    }
    drop(kept);
    let one;
    let pool = match pool {
        Some(p) => p,
        None => {
            one = build_pool(1).map_err(|e| e.to_string())?;
            &one
        }
    };
    let bats = Arc::new(prepare_bats(&ModelSimulator, &study.plan, pool));
    let mut kept = KEPT.lock().unwrap_or_else(|p| p.into_inner());
    if kept.len() >= KEPT_BATS {
        kept.remove(0);
    }
    kept.push((key, Arc::clone(&bats)));
    Ok(bats)
}

/// The first point of `study` simulated, its bat prepared once across calls. A bat that
/// could not be prepared, or a collision that fails or gives a non-finite number, is an error.
pub fn simulate_first_point(study: &Study) -> Result<Single, String> {
    let bats = bats_of(study, None)?;
    let request = study.history_request(bats.max_length());
    let point = study.plan.point(0).map_err(|e| e.message)?;
    let bat = bats.handles[point.bat as usize]
        .as_ref()
        .map_err(|e| e.clone())?;
    let mut outcome = ModelSimulator
        .simulate(bat, &point.spec, request.as_ref())
        .and_then(|o| check_finite_for(&o, point.spec.model).map(|_| o))?;
    // squared up against the bat's own best q, as a study's point is (`driver`)
    let best_q = bats.variants[point.bat as usize].properties.metrics.best_q;
    outcome.batted.squared_up = squared_up(&outcome.batted, outcome.exit_speed_lab, best_q);
    Ok(Single {
        outcome,
        request,
        id: point.id,
        bat: bats.variants[point.bat as usize].clone(),
    })
}
