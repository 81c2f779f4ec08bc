//! The memory a point's time histories take, bounded before anything runs (unbounded, a
//! request too big for memory would pass validation, then abort `run` and kill a Python
//! kernel).

use super::checks::bat_length;
use super::error::StudyError;
use super::locate::Ctx;
use super::plan::Plan;
use super::source::keys;
use super::types::{StudyFile, MAX_AXIS_VALUES};
use crate::model::outcome::HistoryField;

/// Largest history a point may record, in bytes as computed (f64): samples × (series +
/// displacement positions) × 8. 256 MiB is about 2 000 times the bundled history studies'
/// and leaves a many-core run's workers (one history each) within a node's memory.
pub const MAX_HISTORY_BYTES_PER_POINT: u64 = 256 << 20;

/// Series a field records per sample (the rigid motion is a translation and a rotation;
/// the trajectory has a time axis of its own, [`trajectory_values`]).
fn series(field: HistoryField) -> u64 {
    match field {
        HistoryField::RigidMotion => 2,
        HistoryField::Displacement | HistoryField::Trajectory => 0,
        _ => 1,
    }
}

/// Values the trajectory adds to a history: x, y, z on the flight's time axis.
pub fn trajectory_values(fields: &[HistoryField]) -> f64 {
    match fields.contains(&HistoryField::Trajectory) {
        true => 3.0 * crate::model::flight::TRAJECTORY_SAMPLES as f64,
        false => 0.0,
    }
}

/// The number of displacement positions for the longest bat, and the bytes one history
/// takes; refuses a `z_step` that gives more positions than a grid may have and a history
/// over [`MAX_HISTORY_BYTES_PER_POINT`].
pub(super) fn check_history_size(
    cx: &Ctx,
    file: &StudyFile,
    plan: &Plan,
) -> Result<(), StudyError> {
    let Some(h) = file.history.as_ref().filter(|h| !h.fields.is_empty()) else {
        return Ok(());
    };
    // a bat that cannot be resolved (NaN) fails its points later; f64::max skips it here
    let longest = plan
        .bats()
        .iter()
        .map(|b| bat_length(&b.bat))
        .fold(0.0, f64::max);
    let positions = if h.fields.contains(&HistoryField::Displacement) {
        (longest / h.z_step + 1e-9).floor() + 1.0
    } else {
        0.0
    };
    if positions > MAX_AXIS_VALUES as f64 {
        return Err(cx
            .err(&keys(&["history", "z_step"]), "history.z_step gives too many positions")
            .field("history.z_step")
            .value(h.z_step.to_string())
            .allowed(format!(
                "a step that gives at most {MAX_AXIS_VALUES} positions along the longest bat ({longest} m)"
            )));
    }
    let per_sample = h.fields.iter().map(|&f| series(f)).sum::<u64>() as f64 + positions;
    let bytes = (h.n_samples() as f64 * per_sample + trajectory_values(&h.fields)) * 8.0;
    if bytes > MAX_HISTORY_BYTES_PER_POINT as f64 {
        return Err(cx
            .err(&keys(&["history"]), "the history of one point is too big")
            .field("history")
            .value(format!(
                "{} samples × {per_sample} values × 8 bytes = {:.0} MiB per point",
                h.n_samples(),
                bytes / (1u64 << 20) as f64
            ))
            .allowed(format!(
                "at most {} MiB per point: fewer samples (duration / interval), a coarser z_step, or fewer fields",
                MAX_HISTORY_BYTES_PER_POINT >> 20
            )));
    }
    Ok(())
}
