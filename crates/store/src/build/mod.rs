//! Writing the final HDF5 file from a journal (the only place that writes results to HDF5).
//! The skeleton in two steps ([`begin_skeleton`] while the bats are prepared,
//! [`complete_skeleton`] while the run computes), then [`fill`]. Memory: a bounded window of
//! summary values (see [`fill`]), one history, and the failed points' messages.
//!
//! Files, from the bottom up:
//! - `grid`: the summary arrays' chunk shape, their blocks and the build's windows;
//! - `window`: one window's summary values and counts, and [`Gathered`] (a one-window
//!   study's summary gathered while the run writes);
//! - `spill`: where a window's records come from (the journal, or one spill file each);
//! - `sweet`: the sweet spots of a block's curves;
//! - `pieces`: blocks → pieces, compressed on all cores and written in order;
//! - `vars`: coordinates, dimension scales and empty variables of a group;
//! - `attrs` (root attributes), `errors` (`/errors`), `shapes` (`/bat`'s mode shapes for
//!   the displacement's modal form, written as histories need them), `history`
//!   (`/history`), `bat` (`/bat`): one part of the file each;
//! - `skeleton`: the file with everything but the results;
//! - `fill`: the results written into the skeleton, window by window.

mod attrs;
mod bat;
mod errors;
mod fill;
mod grid;
mod history;
mod history_vars;
mod pieces;
mod shapes;
mod skeleton;
mod spill;
mod sweet;
mod uncertainty;
mod vars;
mod window;

pub use fill::{fill, FromRun};
pub use grid::summary_chunk;
pub use history::{place_history, HistoryTail};
pub use skeleton::{begin_skeleton, complete_skeleton, create_skeleton, Skeleton};
pub use spill::remove_stale_spills;
pub use uncertainty::{statistics, GROUP_UNCERTAINTY, QUANTILES, UNCERTAINTY_NAMES};
pub use window::Gathered;
