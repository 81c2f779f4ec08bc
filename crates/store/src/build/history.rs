//! `/history`: every stored history copied into its variables (`history_vars`) in flat-index order: during the run (`store::placer`), the rest at the
//! finish.

use super::shapes::BatShapes;
use super::skeleton::Skeleton;
use crate::chunks;
use crate::error::{H5Ctx, StoreError};
use crate::journal::{
    decode_points, history_chunks, read_payload, RecordPlace, RecordReader, Scan, REC_PREFIX,
};
use crate::layout as l;
use crate::modal::ModalExtents;
use crate::pointset::PointSet;
use crate::results::StudyInfo;
use hdf5::Dataset;
use std::collections::BTreeMap;
use std::fs::File;
use std::path::Path;

/// The histories still to write when the run finishes (the placer's, `store::placer`).
pub enum HistoryTail {
    /// Every history record at or after the placer's cursor, held in memory: framed journal
    /// records by flat index.
    Held(BTreeMap<usize, Vec<u8>>),
    /// In the journal: every history record at flat index `from` or after (a resumed run's
    /// records, or a placer that gave up holding them).
    Journal { from: usize },
}

/// Write one point's histories: the chunks of its framed journal record (`framed`, made by
/// `store::encode` on the worker), as they are. `store::placer` calls this in flat-index
/// order while the run goes on; [`write_histories`] continues from where it stopped.
/// Returns where in the file each chunk went, in the record's order, where that is known
/// (`chunks::write_chunk_at_end`; the journal's record then names them, `store::by_reference`).
pub fn place_history(
    sk: &mut Skeleton,
    info: &StudyInfo,
    index: usize,
    framed: &[u8],
) -> Result<Vec<Option<u64>>, StoreError> {
    let out = sk.out.clone();
    let mut into = Into {
        created: &sk.history,
        block: ModalExtents::of(info).block,
        shapes: sk.shapes.as_mut(),
        info,
        out: &out,
        offsets: Some((sk.f.id(), Vec::new())),
    };
    into.point(index, &framed[REC_PREFIX..], &out, 0)?;
    Ok(into.offsets.map(|(_, o)| o).unwrap_or_default())
}

/// Where a point's histories go: the variables of [`create_history`], and the bats' mode
/// shapes, written with the first history that steps them.
struct Into<'a> {
    created: &'a [(usize, Dataset, Vec<usize>)],
    /// Modes per chunk of the modal coordinates.
    block: usize,
    shapes: Option<&'a mut BatShapes>,
    info: &'a StudyInfo,
    out: &'a Path,
    /// The file's id and, chunk by chunk, where each went (when asked for).
    offsets: Option<(hdf5_sys::h5i::hid_t, Vec<Option<u64>>)>,
}

impl Into<'_> {
    /// One point's history chunks (`payload`: its journal record's) into the variables.
    /// `source` and `at` name where the record came from, for errors.
    fn point(
        &mut self,
        index: usize,
        payload: &[u8],
        source: &Path,
        at: u64,
    ) -> Result<(), StoreError> {
        let bad = || StoreError::BadJournal {
            path: source.to_path_buf(),
            what: format!(
                "record of point {index} at byte {at} does not hold the study's {} histories",
                self.created.len()
            ),
        };
        let pieces = history_chunks(payload).ok_or_else(bad)?;
        // every variable one chunk, the modal coordinates the rest (their blocks of modes)
        let blocks = (pieces.len() + 1)
            .checked_sub(self.created.len())
            .filter(|&b| b == 1 || self.created.iter().any(|v| v.0 == l::MODAL_COORDINATE))
            .ok_or_else(bad)?;
        let rank = self.info.shape.dims.len();
        // a group's chunk begins at its first place, whichever of its points the record has
        let idx = self
            .info
            .shape
            .unravel(l::history_groups(self.info).start(index));
        let mut pieces = pieces.into_iter();
        // the file's end of allocation as the last chunk left it (nothing else allocates
        // between a point's chunks)
        let mut eoa = None;
        for (k, ds, shape) in self.created {
            let count = if *k == l::MODAL_COORDINATE { blocks } else { 1 };
            let tail = &shape[rank..];
            for (b, bytes) in pieces.by_ref().take(count).enumerate() {
                if tail.iter().product::<usize>() == 0 {
                    if let Some((_, o)) = self.offsets.as_mut() {
                        o.push(None);
                    }
                    continue;
                }
                let mut start = idx.clone();
                start.extend(std::iter::repeat_n(0, tail.len()));
                if *k == l::MODAL_COORDINATE {
                    start[rank] = b * self.block;
                }
                let what = || format!("write a history of {}", ds.name());
                match self.offsets.as_mut() {
                    Some((file, o)) => o.push(
                        chunks::write_chunk_at_end(ds, *file, &start, bytes, &mut eoa)
                            .ctx_with(self.out, what)?,
                    ),
                    None => chunks::write_chunk(ds, &start, bytes).ctx_with(self.out, what)?,
                }
            }
        }
        if let Some(shapes) = self.shapes.as_deref_mut() {
            // each bat a group's points use (a group may span several along the last dim)
            for (rec, _) in decode_points(payload)
                .ok_or_else(bad)?
                .iter()
                .filter(|p| p.1)
            {
                shapes.ensure(self.info, rec.bat as usize, blocks, self.out)?;
            }
        }
        Ok(())
    }
}

/// Write the stored histories not yet in the file (`tail`) into the variables of
/// [`create_history`]: the chunks the workers made (`store::encode`), as they are, in
/// flat-index order after those `store::placer` wrote during the run. Nothing is compressed
/// here, and the file's layout does not depend on the order in which points finished nor on
/// how far the placer got, so a study's file is the same whatever the thread count.
/// Memory: one record, and 32 bytes per point with histories (where its record is).
pub(super) fn write_histories(
    sk: &mut Skeleton,
    info: &StudyInfo,
    journal: &Path,
    scan: &Scan,
    out: &Path,
    tail: HistoryTail,
) -> Result<(), StoreError> {
    let mut into = Into {
        created: &sk.history,
        block: ModalExtents::of(info).block,
        shapes: sk.shapes.as_mut(),
        info,
        out,
        offsets: None,
    };
    let from = match tail {
        HistoryTail::Held(held) => {
            for (index, framed) in held {
                into.point(index, &framed[REC_PREFIX..], journal, 0)?;
            }
            return Ok(());
        }
        HistoryTail::Journal { from } => from,
    };
    // Where each point's first record is (the first record of a point wins, as in the
    // summary): one pass over the summaries, histories skipped over (a small buffer, so
    // that they are not read either).
    let mut written = PointSet::new(info.shape.n_points());
    let mut places: Vec<(usize, RecordPlace)> = Vec::new();
    let mut rr = RecordReader::open_with_buffer(journal, scan, 1 << 12)?;
    while let Some(rec) = rr.next_summary()? {
        if rec.index < written.len() && written.insert(rec.index) && rec.index >= from {
            if let Some(place) = rr.history_place() {
                places.push((rec.index, place));
            }
        }
    }
    drop(rr);
    places.sort_unstable_by_key(|&(index, _)| index);
    let file = File::open(journal).map_err(|e| StoreError::io(journal, "open the journal", e))?;
    let mut payload = Vec::new();
    for (index, place) in places {
        read_payload(&file, journal, place, &mut payload)?;
        into.point(index, &payload, journal, place.at)?;
    }
    Ok(())
}
