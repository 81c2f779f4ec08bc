//! `/history`: its (empty) variables, made with the skeleton, and every stored history
//! written into them in one pass over the journal.

use super::vars::{new_var_level, study_dims};
use crate::model::outcome::{History, HistoryPrecision, HistoryRequest, Outcome};
use crate::pointset::PointSet;
use crate::results::StudyInfo;
use crate::store::chunks;
use crate::store::dimscale::{self as h5u, attr_str, Attacher};
use crate::store::error::{H5Ctx, StoreError};
use crate::store::header::history_vars;
use crate::store::journal::{RecordReader, Scan};
use crate::store::layout as l;
use hdf5::Dataset;
use rayon::prelude::*;
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
    const HL: u8 = l::HISTORY_DEFLATE_LEVEL;
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
                new_var_level(&g, def, (&s, &c), f64::NAN, (&sc, &aux, att), HL, out)?
            }
            HistoryPrecision::F32 => {
                new_var_level(&g, def, (&s, &c), f32::NAN, (&sc, &aux, att), HL, out)?
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

/// Write every stored history into the variables of [`create_history`].
pub(super) fn write_histories(
    created: &[(usize, Dataset, Vec<usize>)],
    h: &HistoryRequest,
    info: &StudyInfo,
    journal: &Path,
    scan: &Scan,
    out: &Path,
) -> Result<(), StoreError> {
    let rank = info.shape.dims.len();
    // One sequential pass. Every history is one whole chunk: batches of histories are
    // shuffled and deflated on all cores and written whole, in journal order (issue 7: this
    // was most of a history study's time). The first record of a point wins, as in the
    // summary.
    const BATCH: usize = 64;
    let mut written = PointSet::new(info.shape.n_points());
    let mut rr = RecordReader::open(journal, scan)?;
    let mut batch: Vec<(usize, History)> = Vec::with_capacity(BATCH);
    loop {
        let rec = rr.next_summary()?;
        let end = rec.is_none();
        if let Some(rec) = rec {
            if rec.index < written.len() && written.insert(rec.index) && rec.result.is_ok() {
                if let Ok(Outcome {
                    history: Some(hist),
                    ..
                }) = rr.whole()?.result
                {
                    batch.push((rec.index, hist));
                }
            }
        }
        if batch.len() == BATCH || (end && !batch.is_empty()) {
            let pieces: Vec<(usize, Vec<usize>, Vec<u8>)> = batch
                .par_iter()
                .flat_map_iter(|(index, hist)| {
                    let idx = info.shape.unravel(*index);
                    created
                        .iter()
                        .enumerate()
                        .filter_map(move |(c, (k, _, shape))| {
                            let a = l::history_array(hist, *k);
                            let tail = &shape[rank..];
                            if a.is_empty() || a.len() != tail.iter().product::<usize>() {
                                return None;
                            }
                            let mut start = idx.clone();
                            start.extend(std::iter::repeat_n(0, tail.len()));
                            let mut chunk = vec![1; rank];
                            chunk.extend_from_slice(tail);
                            let level = l::HISTORY_DEFLATE_LEVEL;
                            let bytes = match h.precision {
                                HistoryPrecision::F64 => {
                                    chunks::filtered(a, &chunk, &chunk, f64::NAN, level)
                                }
                                HistoryPrecision::F32 => {
                                    let a: Vec<f32> = a.iter().map(|&x| x as f32).collect();
                                    chunks::filtered(&a, &chunk, &chunk, f32::NAN, level)
                                }
                            };
                            Some((c, start, bytes))
                        })
                        .collect::<Vec<_>>()
                })
                .collect();
            for (c, start, bytes) in pieces {
                let ds = &created[c].1;
                chunks::write_chunk(ds, &start, &bytes)
                    .ctx(out, &format!("write a history of {}", ds.name()))?;
            }
            batch.clear();
        }
        if end {
            return Ok(());
        }
    }
}
