//! `batstudy optimize`: search a study's design space within its rules.
//!
//! - `design`: the `optimize` block checked (located errors) and made usable: variables,
//!   how a design becomes a candidate's base parameters, objective, limits;
//! - `quantity`: the quantities an objective or limit names, and aggregation over the grid;
//! - `rules`: the rule sets built in (NCAA/NFHS BBCOR, MLB wood) and the protocol's BBCOR;
//! - `evaluate`: one candidate on the study's grid, prepared bats shared;
//! - `search`: argmin's Nelder–Mead with an exact penalty, resumable by replay.
//!
//! The record of the search (a journal while it runs, `/optimize` in the results file) is
//! the store's (`store::optimize`); the operation that runs a search is `operations::optimize`.

pub mod at_design;
pub mod cmaes;
pub mod design;
pub mod evaluate;
pub mod pareto;
mod profile_design;
pub mod profile_shape;
pub mod quantity;
pub mod rules;
pub mod search;
mod variable;

pub use design::{checked, design_of, Design, Variable};
pub use evaluate::{Evaluation, Evaluator};
pub use search::{search, Candidate, Stop};
