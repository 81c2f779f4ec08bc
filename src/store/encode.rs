//! Points encoded as journal records on the worker that computed them: the summary, and
//! each stored history variable converted to the stored precision, shuffled and deflated,
//! exactly the chunk the results file will hold (the modal coordinates: one chunk per block
//! of modes, as many as the point's modes need); then the checksum. The writer thread only
//! appends the bytes (issue 22: serialising, checksumming and compressing histories on the
//! one writer thread capped a history study at about 2 cores' worth of points).

use super::chunks;
use super::error::StoreError;
use super::header::history_vars;
use super::journal;
use super::layout::{self, HistoryDims};
use super::modal::{coordinate_block_rows, padded_points, ModalExtents};
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
    /// (index into `layout::HISTORY_VARS`, its precision), in the file's order.
    vars: Vec<(usize, HistoryPrecision)>,
    n_samples: usize,
    nz: usize,
    modal: ModalExtents,
    /// Deflate level (0: no filters).
    level: u8,
}

/// One chunk's stored bytes: the values in `precision`, shuffled and deflated at `level`
/// (the modal coordinates, mostly runs of zeros, have an encoder of their own:
/// `chunks::filtered_coordinates`).
fn chunk(values: &[f64], precision: HistoryPrecision, level: u8) -> Vec<u8> {
    match precision {
        HistoryPrecision::F64 => chunks::filtered_whole(values, level),
        HistoryPrecision::F32 => {
            let a: Vec<f32> = values.iter().map(|&x| x as f32).collect();
            chunks::filtered_whole(&a, level)
        }
    }
}

impl StoredHistory {
    /// The stored chunks of variable `k` of this point (`a`: its values, `precision`: its
    /// stored precision), or why they do not fit: one chunk, but a block of modes per chunk
    /// for the modal coordinates.
    fn chunks_of(
        &self,
        k: usize,
        a: &[f64],
        precision: HistoryPrecision,
    ) -> Result<Vec<Vec<u8>>, String> {
        let (nt, ext, level) = (self.n_samples, &self.modal, self.level);
        let fits = |want: usize| match a.len() == want {
            true => Ok(vec![chunk(a, precision, level)]),
            false => Err(format!("{} values, expected {want}", a.len())),
        };
        match layout::HISTORY_VARS[k].2 {
            HistoryDims::Time => fits(nt),
            HistoryDims::TimeZ => fits(nt * self.nz),
            HistoryDims::ShapePoint if a.len() <= ext.points => {
                Ok(vec![chunk(&padded_points(a, ext.points), precision, level)])
            }
            HistoryDims::ModeTime
                if a.len() % nt.max(1) == 0 && a.len() / nt.max(1) <= ext.modes =>
            {
                let modes = a.len() / nt.max(1);
                Ok(coordinate_block_rows(a, nt, ext.block)
                    .into_iter()
                    .map(|rows| chunks::filtered_coordinates(a, modes, nt, rows, ext.block, level))
                    .collect())
            }
            HistoryDims::ShapePoint => Err(format!("{} values, at most {}", a.len(), ext.points)),
            HistoryDims::ModeTime => Err(format!(
                "{} values, not {nt} samples of at most {} modes",
                a.len(),
                ext.modes
            )),
        }
    }
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
                .map(|k| (k, layout::history_precision(h, k)))
                .collect(),
            n_samples: h.n_samples,
            nz: h.z.len(),
            modal: ModalExtents::of(info),
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
        let mut chunks = Vec::new();
        if let Some((h, st)) = stored {
            for &(k, precision) in &st.vars {
                let these = st.chunks_of(k, layout::history_array(h, k), precision);
                chunks.extend(these.map_err(|e| {
                    self.reject(format!(
                        "point {}: history {} has {e}",
                        rec.index,
                        layout::HISTORY_VARS[k].0.name
                    ))
                })?);
            }
        }
        // the record's room made once: grown chunk by chunk, a history's 16 KB were copied
        // about twice over (issue 37)
        let chunk_bytes: usize = chunks.iter().map(|c| c.len() + 4).sum();
        let mut framed =
            Vec::with_capacity(journal::REC_PREFIX + journal::OK_SUMMARY_LEN + chunk_bytes);
        journal::begin_frame(&mut framed);
        journal::encode_summary(&rec, stored.is_some(), &mut framed);
        for bytes in &chunks {
            journal::put_history_chunk(bytes, &mut framed);
        }
        journal::end_frame(&mut framed);
        Ok(EncodedRecord {
            summary: rec,
            framed,
            has_history: stored.is_some(),
        })
    }
}
