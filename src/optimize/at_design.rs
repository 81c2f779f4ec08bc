//! The study at one design: its base with the design applied, without the `optimize` block
//! and `output`, loaded and checked as a plain study (what `batstudy optimize` runs at the
//! best design, and what `validate` checks at the start design).

#![allow(clippy::result_large_err)] // StudyError: see study/mod.rs

use super::Design;
use crate::study::source::{keys, SourceMap};
use crate::study::{self, LoadOptions, Study, StudyError};

/// The study as a plain study at design `x` (the results file's `study_yaml`). An error
/// is placed at the study file's `optimize` block, with the refused field, value and what
/// is allowed: the text it was found in is made here, not written by the user.
pub fn study_at(
    study: &Study,
    design: &Design,
    x: &[f64],
    max_points: usize,
) -> Result<Study, StudyError> {
    let mut root: yaml_serde::Value = yaml_serde::from_str(&study.text)
        .map_err(|e| StudyError::new(&study.path, e.to_string()))?;
    if let Some(m) = root.as_mapping_mut() {
        let base = m
            .get("base")
            .cloned()
            .filter(|b| b.is_mapping())
            .unwrap_or_else(|| yaml_serde::Value::Mapping(Default::default()));
        m.insert("base".into(), design.apply(x, &base));
        m.remove("optimize");
        m.remove("output");
    }
    let body =
        yaml_serde::to_string(&root).map_err(|e| StudyError::new(&study.path, e.to_string()))?;
    let text = format!(
        "# `{}` at the best design `batstudy optimize` found\n{body}",
        study.file.name
    );
    study::load_str(&text, &study.path, &LoadOptions { max_points }).map_err(|e| {
        let pos = SourceMap::build(&study.text).nearest(&keys(&["optimize", "variables"]));
        StudyError {
            line: None,
            column: None,
            message: format!(
                "the study at a design of its `optimize` block: {}",
                e.message
            ),
            ..e
        }
        .at(pos)
    })
}
