//! One collision: whether it can be computed (`validate`), the wave model (`wave/`: time
//! step, contact, hoop, the modal and Verlet integrators), Brody's rigid model (`rigid`),
//! the sampling of time histories (`history`), what the ball hits (`target`: a bat or a
//! rigid wall), and the dispatch between models (`simulate`).

pub(crate) mod history;
pub mod rigid;
pub mod simulate;
pub mod target;
pub mod validate;
pub mod wave;
