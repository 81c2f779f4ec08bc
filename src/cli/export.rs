//! `batstudy export-profile`: a bat of a results file as a profile CSV
//! (`profile_export`), written whole or not at all.

use super::{EXIT_BAD_INPUT, EXIT_OK, EXIT_RUN_FAILED};
use crate::profile_export::{profile_csv, Units};
use crate::study::error::printable;
use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub struct ExportArgs {
    /// A results file.
    pub file: PathBuf,
    /// Which bat: its label (as `batstudy inspect` lists them) or its index from 0.
    /// Required when the file holds more than one bat.
    #[arg(long)]
    pub bat: Option<String>,
    /// Units of the CSV's columns.
    #[arg(long, value_enum, default_value = "m")]
    pub units: Units,
    /// Where to write the CSV (default: standard output). Written whole or not at all.
    #[arg(short, long)]
    pub output: Option<PathBuf>,
}

pub(super) fn cmd_export(a: &ExportArgs) -> i32 {
    if let Some(path) = &a.output {
        if let Err(e) = super::common::side_output_ok(path, "--output", &[&a.file]) {
            eprintln!("{e}");
            return EXIT_BAD_INPUT;
        }
    }
    let text = match profile_csv(&a.file, a.bat.as_deref(), a.units) {
        Ok(t) => t,
        Err(e) => {
            eprintln!("error: {e}");
            return EXIT_BAD_INPUT;
        }
    };
    match &a.output {
        None => {
            print!("{text}");
            EXIT_OK
        }
        Some(path) => match crate::store::journal::write_whole(path, text.as_bytes()) {
            Ok(()) => EXIT_OK,
            Err(e) => {
                eprintln!(
                    "error: cannot write {}: {e}",
                    printable(&path.display().to_string(), false)
                );
                EXIT_RUN_FAILED
            }
        },
    }
}
