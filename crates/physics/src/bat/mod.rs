//! The bat: outer profile R(z) (`profile`), resolved cross-sections and material
//! (`section`), the lumped beam (`beam`), its modes (`modal`, solved by `band_eigen`), all of it prepared once per
//! distinct bat (`prepared`), the motion of a bat state (`motion`), and the mode shapes at the
//! bat's shape points for the modal form of its histories (`shapes`) and the static shapes
//! those histories computed, kept per bat (`static_memo`); a hollow part's wall as a shell of
//! layers (`laminate`, `shell`) and its breathing modes (`barrel`).

pub mod band_eigen;
pub mod barrel;
pub mod beam;
pub mod compression;
pub mod export;
pub mod hollow_presets;
pub mod laminate;
pub mod modal;
pub mod motion;
pub mod prepared;
pub mod profile;
pub mod profile_spline;
pub mod section;
pub mod shapes;
pub mod shell;
pub mod static_memo;
pub mod subspace;
pub mod wall_stress;

pub use prepared::*;

/// Whether an impact at `z` (m from the knob) is on a bat of `length` (m): 0 ≤ z ≤ length,
/// give or take a picometre a metre, so that an end reached by floating-point arithmetic
/// (0.50 + 34 × 0.01 = 0.8400000000000001) counts as the end. The beam's interpolation
/// extrapolates past its last node to the end, so such a z computes as the end does.
pub fn on_bat(z: f64, length: f64) -> bool {
    let slack = 1e-12 * length;
    z >= -slack && z <= length + slack
}
