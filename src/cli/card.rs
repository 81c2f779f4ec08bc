//! `batstudy card`: each bat of a results file as the trade states it; `batstudy compare`:
//! the bats in one table (`operations::cards`, rendered by `store::card`).

use crate::operations;
use crate::store::card::{render, render_table};
use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub struct CardArgs {
    /// A results file.
    pub file: PathBuf,
    /// Which bat: its label (as `batstudy inspect` lists them) or its index from 0.
    /// Default: every bat of the file.
    #[arg(long)]
    pub bat: Option<String>,
}

#[derive(Debug, clap::Args)]
pub struct CompareArgs {
    /// Results files: every bat of each, in the order given.
    #[arg(required = true)]
    pub files: Vec<PathBuf>,
}

/// `batstudy compare`: every bat of the files in one table, a row per bat (named by its file
/// too when there are several files).
pub(super) fn cmd_compare(a: &CompareArgs) -> i32 {
    show(operations::cards_of_files(&a.files).map(|c| render_table(&c)))
}

pub(super) fn cmd_card(a: &CardArgs) -> i32 {
    show(operations::cards(&a.file, a.bat.as_deref()).map(|c| render(&c)))
}

fn show(text: Result<String, operations::OpError>) -> i32 {
    match text {
        Ok(t) => {
            print!("{t}");
            operations::EXIT_OK
        }
        Err(e) => {
            eprintln!("{e}");
            e.exit_code()
        }
    }
}
