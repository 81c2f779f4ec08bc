//! `batstudy export-profile`: flags → `operations::export_profile`; the CSV on stdout or
//! written whole to `--output`.

use crate::operations;
use crate::profile_export::Units;
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
    match operations::export_profile(&a.file, a.bat.as_deref(), a.units, a.output.as_deref()) {
        Ok(text) => {
            print!("{}", text.unwrap_or_default());
            operations::EXIT_OK
        }
        Err(e) => {
            eprintln!("{e}");
            e.exit_code()
        }
    }
}
