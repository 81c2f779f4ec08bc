//! The root attributes: those known before the data are read (written with the skeleton),
//! and the counts and `created` (written when the file is filled).

use crate::dimscale::{attr_num, attr_str};
use crate::error::{H5Ctx, StoreError};
use crate::header::{JournalHeader, HEADER_ATTR};
use crate::layout as l;
use crate::options::RunMeta;
use crate::results::StudyInfo;
use std::path::Path;

/// Root attributes known before the data are read (`created`, `n_done`, `n_failed` and
/// `complete` are written by [`final_attrs`]).
pub(super) fn root_attrs(
    f: &hdf5::File,
    info: &StudyInfo,
    meta: &RunMeta,
    out: &Path,
) -> Result<(), StoreError> {
    let s = |k: &str, v: &str| attr_str(f, k, v).ctx(out, "write root attributes");
    s("Conventions", "CF-1.8")?;
    s("title", &format!("batstudy results: {}", info.name))?;
    // CF's provenance: what made the file, how, and what its numbers rest on
    s(
        "source",
        &format!(
            "batstudy {} (commit {})",
            meta.batstudy_version, meta.git_commit
        ),
    )?;
    s(
        "history",
        &format!("{}: {}", meta.created, meta.command_line),
    )?;
    s("references", l::REFERENCES)?;
    s("study_name", &info.name)?;
    s("study_description", &info.description)?;
    s("study_yaml", &info.study_text)?;
    s("study_sha256", &info.study_sha256)?;
    s("study_path", &info.study_path)?;
    s("batstudy_version", &meta.batstudy_version)?;
    s("git_commit", &meta.git_commit)?;
    s("host", &meta.host)?;
    s("command_line", &meta.command_line)?;
    s("shard", meta.shard.as_deref().unwrap_or(""))?;
    let header = JournalHeader::of(info);
    s(
        HEADER_ATTR,
        &serde_json::to_string(&header).expect("header serialises"),
    )?;
    let n = |k: &str, v: i64| attr_num(f, k, v).ctx(out, "write root attributes");
    n("layout_version", l::LAYOUT_VERSION as i64)?;
    n("git_dirty", meta.git_dirty as i64)?;
    n("threads", meta.threads as i64)?;
    n("n_points", info.shape.n_points() as i64)?;
    n("allow_implausible", info.allow_implausible as i64)?;
    if let Some((start, stop)) = meta.shard_range {
        n("shard_start", start as i64)?;
        n("shard_stop", stop as i64)?;
    }
    Ok(())
}

/// The root attributes written when the file is filled: `created`, the counts, and whether
/// every point of the study is present.
pub(super) fn final_attrs(
    f: &hdf5::File,
    created: &str,
    (n_done, n_failed, n_points): (usize, usize, usize),
    out: &Path,
) -> Result<(), StoreError> {
    attr_str(f, "created", created).ctx(out, "write root attributes")?;
    let n = |k: &str, v: i64| attr_num(f, k, v).ctx(out, "write root attributes");
    n("n_done", n_done as i64)?;
    n("n_failed", n_failed as i64)?;
    n("complete", (n_done == n_points) as i64)?;
    Ok(())
}
