//! What is measured over many collisions of one bat: the sweet spot of an exit-speed curve
//! (`sweet`), the least-vibration definitions and extremum finder (`sweet_defs`), and the
//! bat metrics — centre of percussion, barrel nodes, BBCOR (`metrics`) — and the field's
//! conventions: bat speed 6 in from the end, q, squared up, a bat's best q (`field`).

pub mod field;
pub mod metrics;
pub mod sweet;
pub mod sweet_defs;
