//! The physics: one fully specified collision in, one `Outcome` out.
//! No I/O, no threads, no printing.
//!
//! Rooms, each importing only the ones above it:
//! - `spec`, `error`, `protocol`, `outcome`, `plausible`: what a collision is (parameters,
//!   errors, certification constants, results) and the values real bats and balls have;
//!   `xorshift`, the seeded generator for fixed pseudo-random inputs.
//! - `bat/`: the bat — outer profile, cross-sections, the discretised beam, its modes, the
//!   prepared bat, and the motion of a bat state (grip vibration, recoil).
//! - `ball`: the ball's force–compression laws.
//! - `field`: the field's conventions for a swing and a batted ball (bat speed 6 in from the
//!   end, the pitch at the plate, q, squared up).
//! - `collision/`: one collision — what makes it computable (`validate`), the wave model's
//!   integrators (`wave/`), Brody's rigid model, history sampling, and the dispatch.
//! - `measures/`: what is measured over many collisions — sweet spots, least vibration,
//!   centre of percussion, nodes, BBCOR.

pub mod ball;
pub mod bat;
pub mod collision;
pub mod error;
pub mod field;
pub mod flight;
pub mod measures;
pub mod outcome;
pub mod plausible;
pub mod protocol;
pub mod resolved;
pub mod spec;
pub mod units;
pub mod xorshift;

pub use bat::{prepare_bat, PreparedBat};
pub use collision::simulate::{simulate, simulate_target, simulate_with_diagnostics};
pub use collision::target::Target;
pub use collision::validate::validate_spec;
pub use error::ModelError;
