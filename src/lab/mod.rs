//! The bat lab: a local web page where a bat is shaped and hit live (`batstudy lab`). The
//! page edits a session (`session`), the server (`server`) evaluates it with the library
//! every front end uses (`answer`: the run's own point function), and saves it as a study
//! and a profile (`save`).

pub mod answer;
pub mod balls;
pub mod save;
pub mod server;
pub mod session;
pub mod species;

pub use server::{Lab, LabSettings};
