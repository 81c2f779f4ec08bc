//! batstudy: baseball bat–ball collisions as parameter studies.
//!
//! Data flow, one direction (see docs/architecture.md):
//! study file → `study` (parse, validate, expand to points) → `model` (simulate one
//! collision) → `results` (finished points) → `store` (HDF5) ← `run` (drives it all).
//! `operations` holds what a user runs (a study to a file, a design search, a merge, a
//! bat's export and card) for every front end: `cli` (the binary) and the Python binding.

pub mod bench;
pub mod cli;
pub mod lab;
/// The physics (crates/physics): one fully specified collision in, one `Outcome` out.
pub use batstudy_physics as model;
pub mod operations;
pub mod optimize;
pub mod profile_export;
pub mod run;
pub mod slurm;
/// The results file (crates/store): HDF5 layout, journal, codecs, reading back and merging;
/// `results`, the plain data the runner hands it; `pointset`, sets of point indices.
pub use batstudy_store as store;
pub use batstudy_store::{pointset, results};
pub mod study;
