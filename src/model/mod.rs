//! The physics: one fully specified collision in, one `Outcome` out.
//! No I/O, no threads, no printing.
//!
//! Modules, one idea each: `profile` (outer radius R(z)), `section` (resolved geometry and
//! cross-sections), `beam` (lumped Euler–Bernoulli beam), `modal` (eigenmodes), `bat`
//! (`PreparedBat`), `ball` (force laws), `wave` (time integration), `history` (sampling),
//! `validate` (spec checks), `plausible` (the values real bats and balls have), `simulate` (dispatch), `rigid` (Brody's model), `sweet`
//! (sweet-spot finder), `sweet_defs` (least-vibration sweet spots, extremum finder),
//! `metrics` (centre of percussion, barrel nodes, BBCOR, grip vibration), `error`.

pub mod ball;
pub mod bat;
pub mod beam;
pub mod error;
mod history;
pub mod metrics;
pub mod modal;
pub mod outcome;
pub mod plausible;
pub mod profile;
pub mod rigid;
pub mod section;
pub mod simulate;
pub mod spec;
pub mod sweet;
pub mod sweet_defs;
pub mod validate;
pub mod wave;

pub use bat::{prepare_bat, PreparedBat};
pub use error::ModelError;
pub use simulate::{simulate, simulate_with_diagnostics};
pub use validate::validate_spec;
