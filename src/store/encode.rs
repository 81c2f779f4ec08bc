//! Points encoded as journal records on the worker that computed them: the summary, and
//! each stored history variable converted to the stored precision, shuffled and deflated,
//! exactly the chunk the results file will hold; then the checksum. The writer thread only
//! appends the bytes (issue 22: serialising, checksumming and compressing histories on the
//! one writer thread capped a history study at about 2 cores' worth of points).

use super::chunks;
use super::error::StoreError;
use super::header::history_vars;
use super::journal;
use super::layout;
use crate::model::outcome::HistoryPrecision;
use crate::results::{PointRecord, StudyInfo};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// One point ready for the journal.
#[derive(Debug, Clone)]
pub struct EncodedRecord {
    /// The point without its histories (the writer's bookkeeping: the done set and the
    /// summary gathered for the final file).
    pub summary: PointRecord,
    /// The framed journal record (prefix, payload).
    pub framed: Vec<u8>,
    /// Whether the record holds histories (chunks for the final file's `/history`).
    pub has_history: bool,
}

/// What a study stores of a point's histories.
#[derive(Debug)]
struct StoredHistory {
    /// (index into `layout::HISTORY_VARS`, samples expected), in the file's order.
    vars: Vec<(usize, usize)>,
    precision: HistoryPrecision,
    /// Deflate level (0: no filters).
    level: u8,
}

/// Turns finished points into journal records. Cheap to clone, shared by every worker.
#[derive(Debug, Clone)]
pub struct RecordEncoder {
    inner: Arc<Inner>,
}

#[derive(Debug)]
struct Inner {
    /// The output, for error messages.
    path: PathBuf,
    n_points: usize,
    n_bats: usize,
    history: Option<StoredHistory>,
}

impl RecordEncoder {
    /// The encoder of output `path` for this study.
    pub fn new(path: &Path, info: &StudyInfo) -> Self {
        let history = info.history.as_ref().map(|h| StoredHistory {
            vars: history_vars(h)
                .into_iter()
                .map(|k| {
                    let with_z = layout::HISTORY_VARS[k].2;
                    (k, h.n_samples * if with_z { h.z.len() } else { 1 })
                })
                .collect(),
            precision: h.precision,
            level: layout::history_deflate_level(h),
        });
        RecordEncoder {
            inner: Arc::new(Inner {
                path: path.to_path_buf(),
                n_points: info.shape.n_points(),
                n_bats: info.bats.len(),
                history,
            }),
        }
    }

    fn reject(&self, what: String) -> StoreError {
        StoreError::BadRecord {
            path: self.inner.path.clone(),
            what,
        }
    }

    /// Check a point against the study (index, bat, history sizes) and encode it. Histories
    /// the study does not store are dropped.
    pub fn encode(&self, mut rec: PointRecord) -> Result<EncodedRecord, StoreError> {
        let s = &*self.inner;
        if rec.index >= s.n_points {
            return Err(self.reject(format!(
                "point index {} is outside the study's {} points",
                rec.index, s.n_points
            )));
        }
        if rec.bat as usize >= s.n_bats {
            return Err(self.reject(format!(
                "point {} refers to bat {} but the study has {} bats",
                rec.index, rec.bat, s.n_bats
            )));
        }
        let history = match &mut rec.result {
            Ok(o) => o.history.take(),
            Err(_) => None,
        };
        let stored = history.as_ref().zip(s.history.as_ref());
        let mut framed = Vec::new();
        journal::begin_frame(&mut framed);
        journal::encode_summary(&rec, stored.is_some(), &mut framed);
        if let Some((h, st)) = stored {
            for &(k, want) in &st.vars {
                let a = layout::history_array(h, k);
                if a.len() != want {
                    return Err(self.reject(format!(
                        "point {}: history {} has {} samples, expected {}",
                        rec.index,
                        layout::HISTORY_VARS[k].0.name,
                        a.len(),
                        want
                    )));
                }
                let level = st.level;
                let bytes = match st.precision {
                    HistoryPrecision::F64 => chunks::filtered_whole(a, level),
                    HistoryPrecision::F32 => {
                        let a: Vec<f32> = a.iter().map(|&x| x as f32).collect();
                        chunks::filtered_whole(&a, level)
                    }
                };
                journal::put_history_chunk(&bytes, &mut framed);
            }
        }
        journal::end_frame(&mut framed);
        Ok(EncodedRecord {
            summary: rec,
            framed,
            has_history: stored.is_some(),
        })
    }
}
