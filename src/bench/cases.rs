//! What is measured: the sizes of the cases (full or `--quick`), the base case of issue 7, and
//! the studies run through the driver.

use crate::model::spec::CollisionSpec;
use crate::study::{self, LoadOptions, Study};
use std::path::Path;

/// Sizes of the cases.
pub(super) struct Sizes {
    pub(super) repeats: usize,
    pub(super) min_time: f64,
    pub(super) curve_repeats: usize,
    pub(super) parallel_omegas: usize,
    pub(super) parallel_repeats: usize,
    pub(super) summary_omegas: usize,
    pub(super) history_omegas: usize,
    pub(super) plan_points: [usize; 3],
    pub(super) store_points: [usize; 3],
    /// Store + null-sink pairs of the summary case. On a shared 2-core machine a 0.3 s run
    /// varies by ±10 %; the median of 121 pairs pins the overhead to about ±1 %.
    pub(super) write_repeats: usize,
}

impl Sizes {
    pub(super) fn of(quick: bool) -> Sizes {
        if quick {
            Sizes {
                repeats: 3,
                min_time: 0.005,
                curve_repeats: 3,
                parallel_omegas: 2,
                parallel_repeats: 1,
                summary_omegas: 2,
                history_omegas: 1,
                plan_points: [100, 10, 10],
                store_points: [100, 10, 10],
                write_repeats: 1,
            }
        } else {
            Sizes {
                repeats: 7,
                min_time: 0.25,
                curve_repeats: 9,
                parallel_omegas: 60,
                parallel_repeats: 3,
                summary_omegas: 60,
                history_omegas: 40,
                plan_points: [1000, 100, 100],
                store_points: [1000, 100, 10],
                write_repeats: 121,
            }
        }
    }
}

/// The base case of issue 7 at impact position `z`.
pub fn base_spec(z: f64) -> CollisionSpec {
    CollisionSpec::base_case(z)
}

/// The 45 impact positions 0.40, 0.41, …, 0.84 m.
pub fn curve_positions() -> Vec<f64> {
    (0..45).map(|k| (40 + k) as f64 / 100.0).collect()
}

/// A wave-model study: the 45-point curve × `omegas` swing speeds, optional history block.
pub fn curve_study_text(name: &str, omegas: usize, history: &str) -> String {
    let omega = if omegas <= 1 {
        "[0]".to_string()
    } else {
        format!("{{linspace: [0, -50, {omegas}]}}")
    };
    format!(
        "name: {name}\nmodel: wave\nbase:\n  bat: {{preset: r161}}\n  ball: {{speed: 40}}\n  \
         impact: {{z: 0.7}}\ngrid:\n  swing.omega: {omega}\n  impact.z: {{range: [0.40, 0.84, 0.01]}}\n{history}"
    )
}

/// Load a study from its text (as `NAME.yaml`).
pub fn load_study(text: &str, name: &str) -> Result<Study, String> {
    study::load_str(
        text,
        Path::new(&format!("{name}.yaml")),
        &LoadOptions::default(),
    )
    .map_err(|e| format!("bench study {name}: {e}"))
}

/// The history block of the history study: every field but the hoop's, 1 cm apart.
pub(super) const HISTORY_BLOCK: &str =
    "history:\n  fields: [force, compression, ball_velocity, displacement, rigid_motion]\n  \
                interval: 1.0e-5\n  duration: 2.0e-3\n  z_step: 0.01\n";

/// The same histories without the bat's displacement: the scalar series only (force-time
/// curves and the like), a few KB per point instead of 53.
pub(super) const SCALAR_HISTORY_BLOCK: &str =
    "history:\n  fields: [force, compression, ball_velocity, rigid_motion]\n  \
                interval: 1.0e-5\n  duration: 2.0e-3\n";

/// A summary-only rigid-model study: `impacts` positions × `omegas` swing speeds × `speeds`
/// ball speeds (cheap points, for the memory cases).
pub(super) fn rigid_study_text(name: &str, impacts: usize, omegas: usize, speeds: usize) -> String {
    format!(
        "name: {name}\nmodel: rigid\nbase:\n  bat: {{preset: r161}}\n  ball: {{speed: 40}}\n  \
         impact: {{z: 0.7}}\ngrid:\n  ball.speed: {{linspace: [30, 50, {speeds}]}}\n  \
         swing.omega: {{linspace: [0, -50, {omegas}]}}\n  impact.z: {{linspace: [0.40, 0.84, {impacts}]}}\n"
    )
}
