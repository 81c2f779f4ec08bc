//! The bat: outer profile R(z) (`profile`), resolved cross-sections and material
//! (`section`), the lumped beam (`beam`), its modes (`modal`, solved by `band_eigen`), all of it prepared once per
//! distinct bat (`prepared`), the motion of a bat state (`motion`), and the mode shapes at the
//! bat's shape points for the modal form of its histories (`shapes`) and the static shapes
//! those histories computed, kept per bat (`static_memo`).

pub mod band_eigen;
pub mod beam;
pub mod modal;
pub mod motion;
pub mod prepared;
pub mod profile;
pub mod section;
pub mod shapes;
pub mod static_memo;

pub use prepared::*;
