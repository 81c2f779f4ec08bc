//! `batstudy validate`: check study files; one line per file, the counts it expands to.

#![allow(clippy::result_large_err)] // StudyError: see study/mod.rs

use super::common::check_output_of;
use super::{EXIT_BAD_INPUT, EXIT_OK};
use crate::operations::OutputNamed;
use crate::study;
use crate::study::output::Existing;
use crate::study::LoadOptions;
use std::path::PathBuf;

pub(super) fn cmd_validate(files: &[PathBuf], max_points: usize) -> i32 {
    let mut code = EXIT_OK;
    for f in files {
        let res = study::load(f, &LoadOptions { max_points }).and_then(|s| {
            let out = s.output_path(None);
            check_output_of(&s, &out, OutputNamed::ByStudy, Existing::Resume)?;
            crate::optimize::design_of(&s)?;
            Ok(s)
        });
        match res {
            Ok(s) => println!(
                "ok: {}: {} points, {} dimensions, {} bats{}",
                crate::study::error::printable(&f.display().to_string(), false),
                s.plan.n_points(),
                s.plan.dims().len(),
                s.plan.bats().len(),
                match s.plan.history_count() {
                    Some(h) => format!(", {h} histories"),
                    None => String::new(),
                }
            ),
            Err(e) => {
                eprintln!("{e}");
                code = EXIT_BAD_INPUT;
            }
        }
    }
    code
}
