//! What is measured: the sizes of the cases (full or `--quick`), the base case, and the
//! studies run through the driver and the store.

use crate::model::spec::CollisionSpec;
use crate::study::{self, LoadOptions, Study};
use std::path::Path;

/// Sizes of the cases of `batstudy bench`.
pub(super) struct Sizes {
    /// Runs of each study at each thread count (the median rate is reported).
    pub(super) repeats: usize,
    /// Swing speeds (× 45 impact positions) of the summary study at `t` threads:
    /// `max(.0, .1 × t)`, so that a run on many cores still lasts long enough to time.
    pub(super) summary_omegas: (usize, usize),
    /// The same for the history studies (full and scalar).
    pub(super) history_omegas: (usize, usize),
    /// Swing speeds of the writer-headroom study (one thread).
    pub(super) headroom_omegas: usize,
    /// MiB written to probe the disk.
    pub(super) disk_mib: usize,
    /// The memory section's summary-only study: impact positions × swing speeds × ball speeds.
    pub(super) large_points: [usize; 3],
}

impl Sizes {
    pub(super) fn of(quick: bool) -> Sizes {
        if quick {
            Sizes {
                repeats: 1,
                summary_omegas: (2, 0),
                history_omegas: (1, 0),
                headroom_omegas: 1,
                disk_mib: 8,
                large_points: [100, 10, 10],
            }
        } else {
            Sizes {
                repeats: 5,
                summary_omegas: (60, 30),
                history_omegas: (40, 10),
                headroom_omegas: 40,
                disk_mib: 1024,
                large_points: [1000, 100, 10],
            }
        }
    }

    /// Swing speeds of a study sized `(min, per_thread)` at `threads`.
    pub(super) fn omegas((min, per_thread): (usize, usize), threads: usize) -> usize {
        min.max(per_thread * threads)
    }
}

/// The base case (R161, linear-hysteresis ball, 40 m/s, default numerics) at impact
/// position `z`.
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

/// The history block of the history study: every field but the hoop's, the bat's
/// displacement on a grid 1 cm apart (`displacement: grid`, the form that is not the default).
pub const HISTORY_BLOCK: &str =
    "history:\n  fields: [force, compression, ball_velocity, displacement, rigid_motion]\n  \
                interval: 1.0e-5\n  duration: 2.0e-3\n  z_step: 0.01\n  displacement: grid\n";

/// The same histories with the displacement in modal form (`displacement: modal`, the
/// default): the coordinates of the modes stepped, the bat load, the static
/// shape; y(z, t) follows from them at any z.
pub const MODAL_HISTORY_BLOCK: &str =
    "history:\n  fields: [force, compression, ball_velocity, displacement, rigid_motion]\n  \
                interval: 1.0e-5\n  duration: 2.0e-3\n  z_step: 0.01\n  displacement: modal\n";

/// The same histories without the bat's displacement: the scalar series only (force-time
/// curves and the like), a few KB per point instead of 53.
pub const SCALAR_HISTORY_BLOCK: &str =
    "history:\n  fields: [force, compression, ball_velocity, rigid_motion]\n  \
                interval: 1.0e-5\n  duration: 2.0e-3\n";

/// A summary-only rigid-model study: `impacts` positions × `omegas` swing speeds × `speeds`
/// ball speeds (cheap points, for the memory case).
pub(super) fn rigid_study_text(name: &str, impacts: usize, omegas: usize, speeds: usize) -> String {
    format!(
        "name: {name}\nmodel: rigid\nbase:\n  bat: {{preset: r161}}\n  ball: {{speed: 40}}\n  \
         impact: {{z: 0.7}}\ngrid:\n  ball.speed: {{linspace: [30, 50, {speeds}]}}\n  \
         swing.omega: {{linspace: [0, -50, {omegas}]}}\n  impact.z: {{linspace: [0.40, 0.84, {impacts}]}}\n"
    )
}
