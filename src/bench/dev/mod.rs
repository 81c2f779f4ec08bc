//! The development measurements' helpers, for `benches/` (`cargo bench`) and the tests:
//! nothing here runs in `batstudy bench`.
//!
//! - [`integrator_accuracy`]: the modal integrator and velocity Verlet on the base case
//!   against a converged reference computed on the spot (an accuracy, not a timing:
//!   `tests/bench_quick.rs` asserts it, `benches/integrators.rs` prints it beside the times);
//! - [`write_share`]: what the results store adds to a run's wall time, store runs paired
//!   with null-sink runs of the same plan (`benches/store.rs`).

mod accuracy;
mod write_share;

pub use accuracy::{integrator_accuracy, verlet_spec, IntegratorAccuracy, IntegratorFigures};
pub use write_share::{write_share, WriteShare};
