//! `/history`: its (empty) variables, made with the skeleton, and every stored history
//! copied into them in flat-index order: during the run (`store::placer`), the rest at the
//! finish.

use super::skeleton::Skeleton;
use super::vars::{new_var_level, study_dims};
use crate::model::outcome::{HistoryPrecision, HistoryRequest};
use crate::pointset::PointSet;
use crate::results::StudyInfo;
use crate::store::chunks;
use crate::store::dimscale::{self as h5u, attr_str, Attacher};
use crate::store::error::{H5Ctx, StoreError};
use crate::store::header::history_vars;
use crate::store::journal::{
    history_chunks, read_payload, RecordPlace, RecordReader, Scan, REC_PREFIX,
};
use crate::store::layout as l;
use hdf5::Dataset;
use std::collections::BTreeMap;
use std::fs::File;
use std::path::Path;

/// The `/history` group and its (empty) variables.
pub(super) fn create_history(
    f: &hdf5::File,
    h: &HistoryRequest,
    info: &StudyInfo,
    att: &Attacher,
    out: &Path,
) -> Result<Vec<(usize, Dataset, Vec<usize>)>, StoreError> {
    let dims = &info.shape.dims;
    let g = f
        .create_group(l::GROUP_HISTORY)
        .ctx(out, "create group history")?;
    let (scales, aux) = study_dims(&g, dims, att, out)?;
    let t: Vec<f64> = (0..h.n_samples).map(|k| k as f64 * h.interval).collect();
    let tscale = h5u::scale_coord(&g, l::TIME.name, &t, &l::TIME).ctx(out, "write time")?;
    let zscale = h5u::scale_coord(&g, l::HIST_Z.name, &h.z, &l::HIST_Z).ctx(out, "write z")?;
    let shape: Vec<usize> = dims.iter().map(|d| d.size).collect();
    let vars = history_vars(h);
    let level = l::history_deflate_level(h);
    let mut created: Vec<(usize, Dataset, Vec<usize>)> = Vec::new();
    for &k in &vars {
        let (def, _, with_z) = &l::HISTORY_VARS[k];
        let mut s = shape.clone();
        let mut c = vec![1; shape.len()];
        let mut sc: Vec<&Dataset> = scales.iter().collect();
        s.push(h.n_samples);
        c.push(h.n_samples.max(1));
        sc.push(&tscale);
        if *with_z {
            s.push(h.z.len());
            c.push(h.z.len().max(1));
            sc.push(&zscale);
        }
        let ds = match h.precision {
            HistoryPrecision::F64 => {
                new_var_level(&g, def, (&s, &c), f64::NAN, (&sc, &aux, att), level, out)?
            }
            HistoryPrecision::F32 => {
                new_var_level(&g, def, (&s, &c), f32::NAN, (&sc, &aux, att), level, out)?
            }
        };
        attr_str(
            &ds,
            "precision",
            match h.precision {
                HistoryPrecision::F64 => "f64",
                HistoryPrecision::F32 => "f32",
            },
        )
        .ctx(out, "describe history")?;
        created.push((k, ds, s));
    }
    Ok(created)
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
pub fn place_history(
    sk: &Skeleton,
    info: &StudyInfo,
    index: usize,
    framed: &[u8],
) -> Result<(), StoreError> {
    write_point(
        &sk.history,
        info,
        index,
        &framed[REC_PREFIX..],
        &sk.out,
        &sk.out,
        0,
    )
}

/// One point's history chunks (`payload`: its journal record's) into the variables of
/// [`create_history`]. `source` and `at` name where the record came from, for errors.
fn write_point(
    created: &[(usize, Dataset, Vec<usize>)],
    info: &StudyInfo,
    index: usize,
    payload: &[u8],
    source: &Path,
    out: &Path,
    at: u64,
) -> Result<(), StoreError> {
    let rank = info.shape.dims.len();
    let pieces = history_chunks(payload, created.len()).ok_or_else(|| StoreError::BadJournal {
        path: source.to_path_buf(),
        what: format!(
            "record of point {index} at byte {at} does not hold the study's {} histories",
            created.len()
        ),
    })?;
    let mut start = info.shape.unravel(index);
    for ((_, ds, shape), bytes) in created.iter().zip(pieces) {
        let tail = &shape[rank..];
        if tail.iter().product::<usize>() == 0 {
            continue;
        }
        start.truncate(rank);
        start.extend(std::iter::repeat_n(0, tail.len()));
        chunks::write_chunk(ds, &start, bytes)
            .ctx(out, &format!("write a history of {}", ds.name()))?;
    }
    Ok(())
}

/// Write the stored histories not yet in the file (`tail`) into the variables of
/// [`create_history`]: the chunks the workers made (`store::encode`), as they are, in
/// flat-index order after those `store::placer` wrote during the run. Nothing is compressed
/// here, and the file's layout does not depend on the order in which points finished nor on
/// how far the placer got, so a study's file is the same whatever the thread count (issue 22).
/// Memory: one record, and 32 bytes per point with histories (where its record is).
pub(super) fn write_histories(
    created: &[(usize, Dataset, Vec<usize>)],
    info: &StudyInfo,
    journal: &Path,
    scan: &Scan,
    out: &Path,
    tail: HistoryTail,
) -> Result<(), StoreError> {
    let from = match tail {
        HistoryTail::Held(held) => {
            for (index, framed) in held {
                write_point(created, info, index, &framed[REC_PREFIX..], journal, out, 0)?;
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
        write_point(created, info, index, &payload, journal, out, place.at)?;
    }
    Ok(())
}
