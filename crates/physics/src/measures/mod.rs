//! What is measured over many collisions of one bat: the sweet spot of an exit-speed curve
//! (`sweet`), the least-vibration definitions and extremum finder (`sweet_defs`), and the
//! bat metrics — centre of percussion, barrel nodes, BBCOR, the best q in the field's
//! convention (`metrics`).

pub mod metrics;
pub mod sweet;
pub mod sweet_defs;
