//! One design variable of a search, and how the `optimize` block's checks name a place in
//! it (an error located at its line, a variable's bounds checked).

use crate::study::optimize_block::Bounds;
use crate::study::source::{keys, Seg, SourceMap};
use crate::study::{Study, StudyError};

/// One design variable.
#[derive(Debug, Clone, PartialEq)]
pub struct Variable {
    /// Its label: the dotted path, or `bat.profile.radius[k]` for knot k's radius.
    pub name: String,
    pub min: f64,
    pub max: f64,
    pub start: f64,
    pub units: String,
    /// The knot it is the radius (or, `wall`, the wall thickness) of.
    pub(super) knot: Option<usize>,
    pub(super) wall: bool,
}

/// A located error in the `optimize` block.
pub(super) fn located(study: &Study, at: &[Seg], message: String) -> StudyError {
    let pos = SourceMap::build(&study.text).nearest(at);
    StudyError::new(&study.path, message).at(pos)
}

pub(super) fn at(parts: &[&str]) -> Vec<Seg> {
    let mut v = keys(&["optimize"]);
    v.extend(keys(parts));
    v
}

/// A variable's start: as written, or the middle of its bounds; what is wrong otherwise.
pub(super) fn bounds_ok(b: &Bounds) -> Result<f64, &'static str> {
    let start = b.start.unwrap_or(0.5 * (b.min + b.max));
    match () {
        // a span that overflows (bounds of ±1e308) scales every candidate to inf or NaN
        _ if !(b.max - b.min).is_finite() => Err("finite bounds whose difference is finite"),
        _ if b.min.partial_cmp(&b.max) != Some(std::cmp::Ordering::Less) => Err("min < max"),
        _ if !(b.min..=b.max).contains(&start) => Err("min <= start <= max"),
        _ => Ok(start),
    }
}
