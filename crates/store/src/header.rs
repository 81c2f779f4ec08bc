//! What identifies the study a journal or a results file belongs to: [`JournalHeader`], at
//! the head of the journal and as the root attribute [`HEADER_ATTR`] of the file. Below the
//! journal, the file's build and the reader, which all three use it.

use super::error::StoreError;
use super::layout::{self, HISTORY_VARS};
use crate::results::StudyInfo;
use batstudy_physics::outcome::HistoryRequest;
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
    /// Points whose histories share a chunk along the last dim
    /// (`layout::history_groups`): a journal's records hold whole groups of this size. 1,
    /// and not written, where each point has its own (every journal and file before groups).
    #[serde(default = "one", skip_serializing_if = "is_one")]
    pub history_group: usize,
}

fn one() -> usize {
    1
}

fn is_one(n: &usize) -> bool {
    *n == 1
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
            history_group: layout::history_groups(info).size(),
        }
    }

    /// `self` with the history group of `found`: a finished file's points are read back
    /// whatever its chunks, and encoded again in this study's groups (a resume from it).
    pub fn with_group_of(&self, found: &JournalHeader) -> JournalHeader {
        JournalHeader {
            history_group: found.history_group,
            ..self.clone()
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
                "it belongs to study '{}' (sha256 {}), not to study '{}' (sha256 {}): the study file or a file it names (a profile CSV) changed, or it is another study; --force starts over",
                self.study_name, short(&self.study_sha256), want.study_name, short(&want.study_sha256)
            )
        } else if self.history_group != want.history_group {
            format!(
                "its histories are stored in chunks of {} points along the last dim, this \
                 batstudy stores them in chunks of {}: run again with --force to start over",
                self.history_group, want.history_group
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
