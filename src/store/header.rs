//! What identifies the study a journal or a results file belongs to: [`JournalHeader`], at
//! the head of the journal and as the root attribute [`HEADER_ATTR`] of the file. Below the
//! journal, the file's build and the reader, which all three use it.

use super::error::StoreError;
use super::layout::{self, HISTORY_VARS};
use crate::model::outcome::HistoryRequest;
use crate::results::StudyInfo;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// Root attribute holding the store's identification of the study (JSON of [`JournalHeader`]).
pub const HEADER_ATTR: &str = "batstudy_store_header";

/// Indices into [`HISTORY_VARS`] of the variables a request stores.
pub fn history_vars(h: &HistoryRequest) -> Vec<usize> {
    (0..HISTORY_VARS.len())
        .filter(|&k| layout::history_stored(h, k))
        .collect()
}

/// What identifies the study a journal (or a results file) belongs to.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct JournalHeader {
    pub layout_version: u32,
    pub study_name: String,
    pub study_sha256: String,
    /// (name, size) of each result dim.
    pub dims: Vec<(String, usize)>,
    /// Stored history variable names, samples and z count (None: summary only).
    pub history: Option<(Vec<String>, usize, usize)>,
    pub n_bats: usize,
}

impl JournalHeader {
    pub fn of(info: &StudyInfo) -> Self {
        JournalHeader {
            layout_version: layout::LAYOUT_VERSION,
            study_name: info.name.clone(),
            study_sha256: info.study_sha256.clone(),
            dims: info
                .shape
                .dims
                .iter()
                .map(|d| (d.name.clone(), d.size))
                .collect(),
            history: info.history.as_ref().map(|h| {
                (
                    history_vars(h)
                        .iter()
                        .map(|&k| HISTORY_VARS[k].0.name.to_string())
                        .collect(),
                    h.n_samples,
                    h.z.len(),
                )
            }),
            n_bats: info.bats.len(),
        }
    }

    /// Why `self` (found in `file`) does not belong to `want`, if it does not.
    pub fn mismatch(&self, want: &JournalHeader, file: &Path) -> Option<StoreError> {
        let what = if self.layout_version != want.layout_version {
            format!(
                "it was written with layout version {} but this batstudy writes version {}",
                self.layout_version, want.layout_version
            )
        } else if self.study_sha256 != want.study_sha256 {
            format!(
                "it belongs to study '{}' (sha256 {}), not to study '{}' (sha256 {}): the study file changed or is another study",
                self.study_name, short(&self.study_sha256), want.study_name, short(&want.study_sha256)
            )
        } else if self != want {
            format!(
                "its result shape or history request differs (found {:?}, expected {:?})",
                (&self.dims, &self.history, self.n_bats),
                (&want.dims, &want.history, want.n_bats)
            )
        } else {
            return None;
        };
        Some(StoreError::WrongStudy {
            path: file.to_path_buf(),
            what,
        })
    }
}

fn short(s: &str) -> &str {
    &s[..s.len().min(12)]
}
