//! Study files: YAML types (serde + schemars), dotted-path parameter setting, grid
//! expansion (grid, zip, points) into a lazy `Plan`, validation with source positions,
//! point ids. File format: `docs/study-files.md`.

// A bad-input error carries file, position, field, value and allowed text; it is built
// once per failed load, so its size does not matter.
#![allow(clippy::result_large_err)]

pub mod checks;
pub mod coords;
pub mod error;
mod expand;
mod history_only;
pub mod history_size;
pub mod load;
mod locate;
pub mod optimize_block;
pub mod output;
pub mod paths;
pub mod plan;
pub mod profile;
mod quantities;
pub mod sample;
mod sample_dim;
pub mod source;
mod syntax;
pub mod types;
pub mod unused;

pub use error::StudyError;
pub use expand::{LoadOptions, DEFAULT_MAX_POINTS, FULL_CHECK_LIMIT, MAX_BATS};
pub use history_size::MAX_HISTORY_BYTES_PER_POINT;
pub use load::{load, load_str, Study};
pub use plan::{point_id, BatChoice, Plan, PlanDim, Point, PointError};
pub use types::{schema_json, AxisValues, HistorySpec, StudyFile, ZipGroup};
