//! `batstudy card`: each bat of a results file as the trade states it; `batstudy compare`:
//! the bats in one table (`store::card`).

use super::{EXIT_BAD_INPUT, EXIT_OK};
use crate::store::card::{bat_cards, render, render_table};
use crate::store::inspect::pick_bat;
use crate::study::error::printable;
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
    /// A results file.
    pub file: PathBuf,
}

/// `batstudy compare`: every bat of the file in one table, a row per bat.
pub(super) fn cmd_compare(a: &CompareArgs) -> i32 {
    match bat_cards(&a.file) {
        Ok(cards) => {
            print!("{}", render_table(&cards));
            EXIT_OK
        }
        Err(e) => {
            eprintln!("error: {e}");
            EXIT_BAD_INPUT
        }
    }
}

pub(super) fn cmd_card(a: &CardArgs) -> i32 {
    let shown = printable(&a.file.display().to_string(), false).to_string();
    let mut cards = match bat_cards(&a.file) {
        Ok(c) => c,
        Err(e) => {
            eprintln!("error: {e}");
            return EXIT_BAD_INPUT;
        }
    };
    if let Some(want) = a.bat.as_deref() {
        let labels: Vec<String> = cards.iter().map(|c| c.label.clone()).collect();
        match pick_bat(&labels, Some(want)) {
            Ok(k) => cards = vec![cards.swap_remove(k)],
            Err(allowed) => {
                eprintln!("error: {shown}: --bat: {allowed}");
                return EXIT_BAD_INPUT;
            }
        }
    }
    print!("{}", render(&cards));
    EXIT_OK
}
