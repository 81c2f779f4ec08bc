//! Points encoded as journal records on the worker that computed them: the summary, and
//! each stored history variable converted to the stored precision, shuffled and deflated,
//! exactly the chunk the results file will hold (the modal coordinates: one chunk per block
//! of modes, as many as the point's modes need); then the checksum. The writer thread only
//! appends the bytes (serialising, checksumming and compressing histories on the one writer
//! thread would cap a history study at about 2 cores' worth of points).

use super::chunks;
use super::error::StoreError;
use super::header::history_vars;
use super::journal;
use super::layout::{self, HistoryDims};
use super::modal::{coordinate_block_rows, padded_points, ModalExtents};
use crate::results::{PointGroups, PointRecord, StudyInfo};
use batstudy_physics::flight::TRAJECTORY_SAMPLES;
use batstudy_physics::outcome::{History, HistoryPrecision};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// One point, or a group of points sharing history chunks, ready for the journal.
#[derive(Debug, Clone)]
pub struct EncodedRecord {
    /// The points without their histories, in flat-index order (the writer's bookkeeping:
    /// the done set and the summary gathered for the final file).
    pub points: Vec<PointRecord>,
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
            HistoryDims::FlightTime => fits(TRAJECTORY_SAMPLES),
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

/// A history variable's values for one slot of a group chunk: the point's, or the
/// dataset's fill value where the slot has no history (`None`).
type SlotValues<'a> = Option<&'a [f64]>;

impl StoredHistory {
    /// The stored chunks of variable `k` of a group whose places along the study's last dim
    /// hold these histories (`None`: a point without one, or a place past the row's end),
    /// or why one does not fit: one chunk, but a block of modes per chunk for the modal
    /// coordinates, as many as the group's points need.
    fn group_chunks_of(
        &self,
        k: usize,
        places: &[SlotValues],
        precision: HistoryPrecision,
    ) -> Result<Vec<Vec<u8>>, String> {
        let (nt, ext) = (self.n_samples, &self.modal);
        let dims = layout::HISTORY_VARS[k].2;
        let per = match dims {
            HistoryDims::Time => nt,
            HistoryDims::TimeZ => nt * self.nz,
            HistoryDims::FlightTime => TRAJECTORY_SAMPLES,
            HistoryDims::ShapePoint => ext.points,
            HistoryDims::ModeTime => return self.group_coordinates(places),
        };
        for a in places.iter().flatten() {
            match dims {
                HistoryDims::ShapePoint if a.len() > per => {
                    return Err(format!("{} values, at most {per}", a.len()))
                }
                HistoryDims::ShapePoint => {}
                _ if a.len() != per => return Err(format!("{} values, expected {per}", a.len())),
                _ => {}
            }
        }
        let level = self.level;
        Ok(vec![match precision {
            HistoryPrecision::F64 => chunks::filtered_group(places, per, level, |x| x, f64::NAN),
            HistoryPrecision::F32 => {
                chunks::filtered_group(places, per, level, |x| x as f32, f32::NAN)
            }
        }])
    }

    /// The chunks of a group's modal coordinates: one a block of modes, as many as reach
    /// the last mode any of its points stepped; zero (the fill value) where a point has
    /// fewer blocks, or none.
    fn group_coordinates(&self, places: &[SlotValues]) -> Result<Vec<Vec<u8>>, String> {
        let (nt, ext) = (self.n_samples.max(1), &self.modal);
        for a in places.iter().flatten() {
            if a.len() % nt != 0 || a.len() / nt > ext.modes {
                return Err(format!(
                    "{} values, not {nt} samples of at most {} modes",
                    a.len(),
                    ext.modes
                ));
            }
        }
        let rows: Vec<Vec<_>> = places
            .iter()
            .map(|a| a.map_or(Vec::new(), |a| coordinate_block_rows(a, nt, ext.block)))
            .collect();
        let blocks = rows.iter().map(Vec::len).max().unwrap_or(0);
        Ok((0..blocks)
            .map(|b| {
                let block: Vec<_> = places
                    .iter()
                    .zip(&rows)
                    .map(|(a, r)| {
                        let a = (*a)?;
                        Some((a, a.len() / nt, r.get(b)?.clone()))
                    })
                    .collect();
                chunks::filtered_group_coordinates(&block, nt, ext.block, self.level)
            })
            .collect())
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
    groups: PointGroups,
}

impl RecordEncoder {
    /// The encoder of output `path` for this study.
    pub fn new(path: &Path, info: &StudyInfo) -> Self {
        Self::with_groups(path, info, layout::history_groups(info))
    }

    /// [`Self::new`] with points grouped as `groups` says, not as the study's layout does:
    /// for `benches/chunk_groups.rs`, which measures groups of several sizes. Its records
    /// fit only a file whose chunks span the same groups.
    pub fn with_groups(path: &Path, info: &StudyInfo, groups: PointGroups) -> Self {
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
                groups,
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
    /// A study whose points share history chunks ([`Self::groups`]) takes whole groups
    /// ([`Self::encode_group`]): a point encoded alone is refused.
    pub fn encode(&self, rec: PointRecord) -> Result<EncodedRecord, StoreError> {
        let size = self.inner.groups.size();
        if size > 1 {
            return Err(self.reject(format!(
                "point {}: this study stores its histories in chunks of {size} points, \
                 which are encoded a group at a time",
                rec.index
            )));
        }
        self.encode_point(rec)
    }

    /// [`Self::encode`], whatever the study's groups.
    fn encode_point(&self, mut rec: PointRecord) -> Result<EncodedRecord, StoreError> {
        let s = &*self.inner;
        self.check(&rec)?;
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
        // the record's room made once: grown chunk by chunk, a history's 16 KB would be
        // copied about twice over
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
            points: vec![rec],
            framed,
            has_history: stored.is_some(),
        })
    }

    /// A point's index and bat, against the study's.
    pub fn check(&self, rec: &PointRecord) -> Result<(), StoreError> {
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
        Ok(())
    }

    /// How the study's points are grouped in its history chunks.
    pub fn groups(&self) -> PointGroups {
        self.inner.groups
    }

    /// Check points of one group ([`Self::groups`], in increasing flat-index order; the
    /// whole group, or at the finish of a run what it has of it) and encode them as one
    /// record whose history chunks span the group's places along the study's last dim.
    /// The places without a point, or past the end of a row, hold the fill value. With
    /// groups of one point this is [`Self::encode`], byte for byte.
    pub fn encode_group(&self, mut recs: Vec<PointRecord>) -> Result<EncodedRecord, StoreError> {
        let groups = self.inner.groups;
        if recs.len() == 1 && groups.size() == 1 {
            return self.encode_point(recs.pop().expect("one point"));
        }
        let start = recs.first().map_or(0, |r| groups.start(r.index));
        let increasing = recs.windows(2).all(|w| w[1].index > w[0].index);
        let one_group = recs.iter().all(|r| groups.start(r.index) == start);
        if recs.is_empty() || !increasing || !one_group {
            let indices: Vec<usize> = recs.iter().map(|r| r.index).collect();
            return Err(self.reject(format!(
                "points {indices:?} are not of one group of {} in increasing order",
                groups.size()
            )));
        }
        recs.iter().try_for_each(|r| self.check(r))?;
        let st = self.inner.history.as_ref();
        let mut histories: Vec<Option<History>> = vec![None; groups.size()];
        let mut has = Vec::with_capacity(recs.len());
        for r in &mut recs {
            let h = match &mut r.result {
                Ok(o) => o.history.take().filter(|_| st.is_some()),
                Err(_) => None,
            };
            has.push(h.is_some());
            histories[r.index - start] = h;
        }
        let chunks = match st.filter(|_| has.contains(&true)) {
            Some(st) => self.group_chunks(st, &recs, &histories)?,
            None => Vec::new(),
        };
        let chunk_bytes: usize = chunks.iter().map(|c| c.len() + 4).sum();
        let mut framed = Vec::with_capacity(
            journal::REC_PREFIX + recs.len() * (journal::OK_SUMMARY_LEN + 64) + chunk_bytes,
        );
        journal::begin_frame(&mut framed);
        journal::encode_group_summaries(&recs, &has, &mut framed);
        for bytes in &chunks {
            journal::put_history_chunk(bytes, &mut framed);
        }
        journal::end_frame(&mut framed);
        Ok(EncodedRecord {
            points: recs,
            framed,
            has_history: has.contains(&true),
        })
    }

    /// Every stored variable's group chunks, in the file's order (`histories`: one per
    /// place of the group).
    fn group_chunks(
        &self,
        st: &StoredHistory,
        recs: &[PointRecord],
        histories: &[Option<History>],
    ) -> Result<Vec<Vec<u8>>, StoreError> {
        let mut chunks = Vec::new();
        for &(k, precision) in &st.vars {
            let values: Vec<SlotValues> = histories
                .iter()
                .map(|h| h.as_ref().map(|h| layout::history_array(h, k).as_slice()))
                .collect();
            let these = st.group_chunks_of(k, &values, precision).map_err(|e| {
                self.reject(format!(
                    "points {}..={}: history {} has {e}",
                    recs[0].index,
                    recs[recs.len() - 1].index,
                    layout::HISTORY_VARS[k].0.name
                ))
            })?;
            chunks.extend(these);
        }
        Ok(chunks)
    }
}
