//! The physics: one fully specified collision in, one `Outcome` out.
//! No I/O, no threads, no printing.

pub mod outcome;
pub mod rigid;
pub mod spec;
pub mod sweet;
