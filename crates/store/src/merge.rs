//! Merging shard files into one results file, after checking, before anything is written,
//! that the shards are of one study and hold every point exactly once.

use super::error::StoreError;
use super::header::JournalHeader;
use super::layout;
use super::options::{StoreOptions, Summary};
use super::read;
use super::session::open;
use crate::pointset::PointSet;
use crate::results::StudyInfo;
use std::path::{Path, PathBuf};

/// Merge shard files (each the same layout with a subset of the points) into one complete
/// results file `out`, identical in data to a single-process run. Refuses, before writing
/// anything, shards of another study or layout version, points present twice, and missing
/// points. Memory: one flag per point and one record at a time (shards are streamed).
pub fn merge(
    out: &Path,
    info: &StudyInfo,
    shards: &[PathBuf],
    opts: &StoreOptions,
    point_id: &PointIdOf<'_>,
) -> Result<Summary, StoreError> {
    merge_check(out, info, shards, point_id)?;
    let mut s = open(
        out,
        info,
        &StoreOptions {
            resume: false,
            ..opts.clone()
        },
    )?;
    let copied = shards
        .iter()
        .try_for_each(|p| read::for_each_record(p, |r| s.write(r)).map(drop));
    let merged = match copied {
        Ok(()) => s.finish(),
        Err(e) => {
            drop(s);
            Err(e)
        }
    };
    // A merge has nothing to resume (its shards are its record): what a failed one wrote
    // would only make the retry refuse the output as an interrupted run.
    if merged.is_err() {
        discard(out);
    }
    merged
}

/// Remove what a failed merge into `out` left: its journal and the file it was building.
fn discard(out: &Path) {
    use super::paths::{journal_path, partial_path};
    let _ = super::paths::remove_if_exists(&journal_path(out));
    let _ = super::paths::remove_if_exists(&partial_path(out));
}

/// The id a point of the study at this flat index has (the study's own, recomputed).
pub type PointIdOf<'a> = dyn Fn(usize) -> u64 + Sync + 'a;

/// The checks of [`merge`], without writing anything: every shard of this study and layout
/// version, every point present exactly once and with its own point id (a shard whose ids
/// were altered is refused, not merged).
pub fn merge_check(
    out: &Path,
    info: &StudyInfo,
    shards: &[PathBuf],
    point_id: &PointIdOf<'_>,
) -> Result<(), StoreError> {
    let want = JournalHeader::of(info);
    let n = info.shape.n_points();
    // one bit per point; the earlier owner of a duplicate is looked up only then
    let mut seen = PointSet::new(n);
    let mut declared = Vec::new();
    for (k, p) in shards.iter().enumerate() {
        let fi = read::file_info(p)?;
        if fi.layout_version != layout::LAYOUT_VERSION {
            return Err(StoreError::CannotMerge {
                path: p.clone(),
                what: format!(
                    "it has layout version {}, this batstudy writes version {}",
                    fi.layout_version,
                    layout::LAYOUT_VERSION
                ),
            });
        }
        if let Some(StoreError::WrongStudy { path, what }) = fi.header.mismatch(&want, p) {
            return Err(StoreError::CannotMerge { path, what });
        }
        if out.exists() && same_file(out, p) {
            return Err(StoreError::CannotMerge {
                path: p.clone(),
                what: "it is also the merge's output file".into(),
            });
        }
        let present = present_with_their_ids(p, point_id)?;
        if let Some(i) = present.iter().find(|&i| seen.contains(i)) {
            let mut other = None;
            for q in &shards[..k] {
                if read::present_points(q)?.contains(i) {
                    other = Some(q);
                    break;
                }
            }
            return Err(StoreError::CannotMerge {
                path: p.clone(),
                what: format!(
                    "point at flat index {i} is also in {}: points present twice (each shard may be given once)",
                    other.map_or_else(|| p.display().to_string(), |q| q.display().to_string())
                ),
            });
        }
        for i in present.iter() {
            seen.insert(i);
        }
        declared.push((fi.shard, fi.shard_range));
    }
    match missing_points(out, shards, &declared, &seen, n) {
        Some((path, what)) => Err(StoreError::CannotMerge { path, what }),
        None => Ok(()),
    }
}

/// Where the points missing from the shards belong, naming the incomplete shard and the
/// command that finishes it (or a missing shard file), if any are missing.
fn missing_points(
    out: &Path,
    shards: &[PathBuf],
    declared: &[(String, Option<(usize, usize)>)],
    seen: &PointSet,
    n: usize,
) -> Option<(PathBuf, String)> {
    let n_missing = n - seen.count();
    let shown: Vec<usize> = seen.missing().take(8).collect();
    let &first = shown.first()?;
    let list = format!("{shown:?}{}", if n_missing > 8 { ", ..." } else { "" });
    let owner_of = declared
        .iter()
        .position(|(_, r)| r.is_some_and(|(a, b)| a <= first && first < b));
    Some(match owner_of {
        Some(k) => {
            let (a, b) = declared[k].1.unwrap_or_default();
            let lack = (a..b.min(n)).filter(|&i| !seen.contains(i)).count();
            (
                shards[k].clone(),
                format!(
                    "shard {} is incomplete: it lacks {lack} of its {} points (flat indices {list}); the shards lack {} of the study's {n} points in all. Finish it with `batstudy run STUDY --shard {} --resume -o {}`",
                    declared[k].0,
                    b - a,
                    n_missing,
                    declared[k].0,
                    shards[k].display()
                ),
            )
        }
        None => (
            out.to_path_buf(),
            format!(
                "the shards lack {n_missing} of the study's {n} points (flat indices {list}): a shard file is missing from the list"
            ),
        ),
    })
}

/// The stored points of shard `p`, each checked to have the id the study gives its flat
/// index (on all cores: recomputing an id resolves the point and hashes it), in one pass
/// over the shard's status and ids.
fn present_with_their_ids(p: &Path, point_id: &PointIdOf<'_>) -> Result<PointSet, StoreError> {
    use rayon::prelude::*;
    let mut present = None;
    read::for_each_present_slab(p, |n, slab| {
        if let Some(&(i, id)) = slab.par_iter().find_first(|&&(i, id)| point_id(i) != id) {
            return Err(StoreError::CannotMerge {
                path: p.to_path_buf(),
                what: format!(
                    "the point at flat index {i} has point_id {id}, but the study's point there has {}: the file was altered or is of another study",
                    point_id(i)
                ),
            });
        }
        let set = present.get_or_insert_with(|| PointSet::new(n));
        for &(i, _) in slab {
            set.insert(i);
        }
        Ok(())
    })?;
    Ok(present.unwrap_or_else(|| PointSet::new(0)))
}

fn same_file(a: &Path, b: &Path) -> bool {
    match (a.canonicalize(), b.canonicalize()) {
        (Ok(x), Ok(y)) => x == y,
        _ => false,
    }
}
