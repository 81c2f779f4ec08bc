//! One collision: whether it can be computed (`validate`), the wave model (`wave/`: time
//! step, contact, hoop, the modal and Verlet integrators), Brody's rigid model (`rigid`,
//! and `rigid_model`: head-on, oblique, the wall), an oblique impact's geometry and the
//! rigid oblique collision (`oblique`), the sampling of time histories (`history`), what
//! the ball hits (`target`: a bat or a rigid wall), the batter's swing (`batter`), the
//! swing's and the pitch's geometry (`frame`), the batted ball's launch and flight (`launch`), and the dispatch between models
//! (`simulate`).

pub mod batter;
pub mod frame;
pub(crate) mod history;
pub mod launch;
mod modal_precision;
pub mod oblique;
pub mod rigid;
mod rigid_model;
pub mod simulate;
pub mod target;
pub mod validate;
pub mod wave;
