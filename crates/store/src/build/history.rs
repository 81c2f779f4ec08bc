//! `/history`: its (empty) variables, made with the skeleton, and every stored history
//! copied into them in flat-index order: during the run (`store::placer`), the rest at the
//! finish.

use super::shapes::BatShapes;
use super::skeleton::Skeleton;
use super::vars::{new_var_level, study_dims};
use crate::chunks;
use crate::dimscale::{self as h5u, attr_str, Attacher};
use crate::error::{H5Ctx, StoreError};
use crate::header::history_vars;
use crate::journal::{
    decode_points, history_chunks, read_payload, RecordPlace, RecordReader, Scan, REC_PREFIX,
};
use crate::layout::{self as l, HistoryDims};
use crate::modal::ModalExtents;
use crate::pointset::PointSet;
use crate::results::StudyInfo;
use batstudy_physics::outcome::{HistoryPrecision, HistoryRequest};
use hdf5::Dataset;
use std::collections::BTreeMap;
use std::fs::File;
use std::path::Path;

/// The stored history variables: index into [`l::HISTORY_VARS`], dataset, full shape.
pub type HistoryVars = Vec<(usize, Dataset, Vec<usize>)>;

/// The `/history` group and its (empty) variables.
pub(super) fn create_history(
    f: &hdf5::File,
    h: &HistoryRequest,
    info: &StudyInfo,
    att: &Attacher,
    out: &Path,
) -> Result<HistoryVars, StoreError> {
    let dims = &info.shape.dims;
    let g = f
        .create_group(l::GROUP_HISTORY)
        .ctx(out, "create group history")?;
    let (scales, aux) = study_dims(&g, dims, att, out)?;
    let vars = history_vars(h);
    let tails = Tails::create(&g, h, info, vars.iter().any(|&k| l::is_modal(k)), out)?;
    let level = l::history_deflate_level(h);
    let mut created = Vec::new();
    for &k in &vars {
        let (def, _, tail) = &l::HISTORY_VARS[k];
        let mut s: Vec<usize> = dims.iter().map(|d| d.size).collect();
        let mut c = vec![1; s.len()];
        if let Some(last) = c.last_mut() {
            *last = l::history_groups(info).size(); // a group's points share a chunk
        }
        let mut sc: Vec<&Dataset> = scales.iter().collect();
        for (size, chunk, scale) in tails.of(*tail) {
            s.push(size);
            c.push(chunk.max(1));
            sc.extend(scale);
        }
        // an unwritten block of coordinates is a block of modes the point did not step: 0
        let fill = match tail {
            HistoryDims::ModeTime => 0.0,
            _ => f64::NAN,
        };
        let links = (&sc[..], &aux[..], att);
        let (ds, precision) = match l::history_precision(h, k) {
            HistoryPrecision::F64 => (
                new_var_level(&g, def, (&s, &c), fill, links, level, out)?,
                "f64",
            ),
            HistoryPrecision::F32 => (
                new_var_level(&g, def, (&s, &c), fill as f32, links, level, out)?,
                "f32",
            ),
        };
        attr_str(&ds, "precision", precision).ctx(out, "describe history")?;
        created.push((k, ds, s));
    }
    Ok(created)
}

/// The dimension scales of `/history` after the study's, and their sizes: `time`, `z`, and
/// with the displacement's modal form `bat_mode` and `shape_point` (index coordinates).
struct Tails {
    time: (usize, Dataset),
    z: (usize, Dataset),
    modal: Option<(ModalExtents, Dataset, Dataset)>,
}

impl Tails {
    fn create(
        g: &hdf5::Group,
        h: &HistoryRequest,
        info: &StudyInfo,
        modal: bool,
        out: &Path,
    ) -> Result<Tails, StoreError> {
        let t: Vec<f64> = (0..h.n_samples).map(|k| k as f64 * h.interval).collect();
        let time = h5u::scale_coord(g, l::TIME.name, &t, &l::TIME).ctx(out, "write time")?;
        let z = h5u::scale_coord(g, l::HIST_Z.name, &h.z, &l::HIST_Z).ctx(out, "write z")?;
        let modal = match modal {
            true => {
                let ext = ModalExtents::of(info);
                let index = |n: usize| (0..n as i64).collect::<Vec<i64>>();
                let (m, p) = (&l::BAT_MODE_DIM, &l::SHAPE_POINT_DIM);
                let modes =
                    h5u::scale_coord(g, m.name, &index(ext.modes), m).ctx(out, "write bat_mode")?;
                let points = h5u::scale_coord(g, p.name, &index(ext.points), p)
                    .ctx(out, "write shape_point")?;
                Some((ext, modes, points))
            }
            false => None,
        };
        Ok(Tails {
            time: (h.n_samples, time),
            z: (h.z.len(), z),
            modal,
        })
    }

    /// (size, chunk size, dimension scale) of each dim after the study's.
    fn of(&self, dims: HistoryDims) -> Vec<(usize, usize, Option<&Dataset>)> {
        let (nt, time) = (self.time.0, Some(&self.time.1));
        let m = self.modal.as_ref();
        let ext = m.map_or(
            ModalExtents {
                modes: 0,
                block: 1,
                points: 0,
            },
            |m| m.0,
        );
        match dims {
            HistoryDims::Time => vec![(nt, nt, time)],
            HistoryDims::TimeZ => vec![(nt, nt, time), (self.z.0, self.z.0, Some(&self.z.1))],
            HistoryDims::ModeTime => {
                vec![(ext.modes, ext.block, m.map(|m| &m.1)), (nt, nt, time)]
            }
            HistoryDims::ShapePoint => vec![(ext.points, ext.points, m.map(|m| &m.2))],
        }
    }
}

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
