//! Study files: YAML types (serde + schemars), dotted-path parameter setting, grid
//! expansion (grid, zip, points) into a lazy `Plan`, validation with source positions,
//! point ids. File format: `docs/study-files.md`.

// A bad-input error carries file, position, field, value and allowed text; it is built
// once per failed load, so its size does not matter.
#![allow(clippy::result_large_err)]

pub mod checks;
pub mod error;
pub mod load;
pub mod output;
pub mod paths;
pub mod plan;
pub mod profile;
pub mod source;
pub mod types;
pub mod unused;

pub use error::StudyError;
pub use load::{load, load_str, LoadOptions, Study, DEFAULT_MAX_POINTS};
pub use plan::{point_id, BatChoice, Plan, PlanDim, Point, PointError};
pub use types::{schema_json, AxisValues, HistorySpec, StudyFile, ZipGroup};
