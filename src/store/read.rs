//! Reading a results file back: its records (for resume from a finished file, merge and tests)
//! and a human-readable description (`batstudy inspect`).

use super::dimscale::block;
use super::error::{H5Ctx, StoreError};
use super::journal::JournalHeader;
use super::layout::{self as l, N_SUMMARY_FLOATS};
use crate::model::outcome::History;
use crate::results::PointRecord;
use hdf5::types::VarLenUnicode;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Root attribute holding the store's identification of the study (JSON of [`JournalHeader`]).
pub const HEADER_ATTR: &str = "batstudy_store_header";

/// A results file read back.
#[derive(Debug, Clone)]
pub struct ReadBack {
    pub path: PathBuf,
    pub study_name: String,
    pub study_sha256: String,
    pub layout_version: u32,
    pub header: JournalHeader,
    /// Present points (status ok or failed), in flat-index order.
    pub records: Vec<PointRecord>,
}

impl ReadBack {
    pub fn header(&self) -> JournalHeader {
        self.header.clone()
    }
}

fn bad(path: &Path, what: impl Into<String>) -> StoreError {
    StoreError::BadFile {
        path: path.to_path_buf(),
        what: what.into(),
    }
}

fn str_attr(f: &hdf5::Location, name: &str, path: &Path) -> Result<String, StoreError> {
    let a = f
        .attr(name)
        .map_err(|_| bad(path, format!("root attribute {name} missing")))?;
    let v: VarLenUnicode = a
        .read_scalar()
        .map_err(|_| bad(path, format!("root attribute {name} is not a string")))?;
    Ok(v.as_str().to_string())
}

fn open_checked(path: &Path) -> Result<(hdf5::File, JournalHeader, u32), StoreError> {
    if !path.exists() {
        return Err(StoreError::io(
            path,
            "open the results file",
            std::io::Error::from(std::io::ErrorKind::NotFound),
        ));
    }
    let f = hdf5::File::open(path).map_err(|e| bad(path, format!("HDF5 cannot open it ({e})")))?;
    let version: i64 = f
        .attr("layout_version")
        .and_then(|a| a.read_scalar())
        .map_err(|_| bad(path, "root attribute layout_version missing"))?;
    let json = str_attr(&f, HEADER_ATTR, path)?;
    let header: JournalHeader = serde_json::from_str(&json).map_err(|e| {
        bad(
            path,
            format!("root attribute {HEADER_ATTR} unreadable: {e}"),
        )
    })?;
    Ok((f, header, version as u32))
}

/// Read every present point of a results file.
pub fn read_results(path: &Path) -> Result<ReadBack, StoreError> {
    let mut records = Vec::new();
    let mut back = for_each_record(path, |r| {
        records.push(r);
        Ok(())
    })?;
    back.records = records;
    Ok(back)
}

/// Hand every present point of a results file to `each`, in flat-index order, one at a
/// time (memory: the summary arrays and one history). The returned `ReadBack` has no records.
pub fn for_each_record(
    path: &Path,
    mut each: impl FnMut(PointRecord) -> Result<(), StoreError>,
) -> Result<ReadBack, StoreError> {
    let (f, header, layout_version) = open_checked(path)?;
    if layout_version != l::LAYOUT_VERSION {
        return Err(StoreError::WrongStudy {
            path: path.to_path_buf(),
            what: format!(
                "it has layout version {layout_version}, this batstudy reads version {}",
                l::LAYOUT_VERSION
            ),
        });
    }
    let n: usize = header.dims.iter().map(|d| d.1).product();
    let g = f.group(l::GROUP_SUMMARY).ctx(path, "open group summary")?;
    let get = |name: &str| g.dataset(name).ctx(path, &format!("open summary/{name}"));
    let mut floats = Vec::new();
    for def in &l::SUMMARY_FLOATS {
        // Variables added after a file was written read as NaN (layout.md: new variables may
        // be added without a version bump).
        if g.link_exists(def.name) {
            floats.push(get(def.name)?.read_raw::<f64>().ctx(path, def.name)?);
        } else {
            floats.push(vec![f64::NAN; n]);
        }
    }
    let status = get(l::STATUS.name)?.read_raw::<i8>().ctx(path, "status")?;
    let recontact = get(l::RECONTACT.name)?
        .read_raw::<i8>()
        .ctx(path, "recontact")?;
    let ids = get(l::POINT_ID.name)?
        .read_raw::<u64>()
        .ctx(path, "point_id")?;
    let bats = get(l::BAT_INDEX.name)?
        .read_raw::<i32>()
        .ctx(path, "bat_index")?;
    if [status.len(), ids.len(), bats.len(), floats[0].len()]
        .iter()
        .any(|&m| m != n)
    {
        return Err(bad(path, "summary arrays do not match the study's shape"));
    }
    let eg = f.group(l::GROUP_ERRORS).ctx(path, "open group errors")?;
    let eidx = eg
        .dataset(l::ERR_FLAT_INDEX.name)
        .and_then(|d| d.read_raw::<u64>())
        .ctx(path, "errors/flat_index")?;
    let emsg = eg
        .dataset(l::ERR_MESSAGE.name)
        .and_then(|d| d.read_raw::<VarLenUnicode>())
        .ctx(path, "errors/message")?;
    let mut msgs = std::collections::HashMap::new();
    for (i, m) in eidx.iter().zip(emsg) {
        msgs.insert(*i as usize, m.as_str().to_string());
    }
    let hist = match &header.history {
        Some((names, nt, nz)) => {
            let hg = f.group(l::GROUP_HISTORY).ctx(path, "open group history")?;
            let mut v = Vec::new();
            for name in names {
                let k = l::HISTORY_VARS
                    .iter()
                    .position(|h| h.0.name == name)
                    .ok_or_else(|| bad(path, format!("unknown history variable {name}")))?;
                let ds = hg
                    .dataset(name)
                    .ctx(path, &format!("open history/{name}"))?;
                let tail = if l::HISTORY_VARS[k].2 {
                    vec![*nt, *nz]
                } else {
                    vec![*nt]
                };
                v.push((k, ds, tail));
            }
            Some(v)
        }
        None => None,
    };
    let shape = crate::results::ResultShape {
        dims: header
            .dims
            .iter()
            .map(|(name, size)| crate::results::Dim {
                name: name.clone(),
                size: *size,
                coords: vec![],
            })
            .collect(),
    };
    for i in 0..n {
        let result = match status[i] {
            l::STATUS_OK => {
                let mut fv = [0.0; N_SUMMARY_FLOATS];
                for (k, x) in fv.iter_mut().enumerate() {
                    *x = floats[k][i];
                }
                let mut o = l::outcome_from_floats(&fv);
                o.recontact = recontact[i] == 1;
                if let Some(hv) = &hist {
                    let idx = shape.unravel(i);
                    let mut h = History::default();
                    for (k, ds, tail) in hv {
                        let mut start = idx.clone();
                        let mut count = vec![1; idx.len()];
                        for &t in tail {
                            start.push(0);
                            count.push(t);
                        }
                        let a = ds
                            .read_slice::<f64, _, ndarray::IxDyn>(block(&start, &count))
                            .ctx(path, "read a history")?;
                        *l::history_array_mut(&mut h, *k) = a.iter().copied().collect();
                    }
                    o.history = Some(h);
                }
                Ok(o)
            }
            l::STATUS_FAILED => Err(msgs.remove(&i).unwrap_or_default()),
            _ => continue,
        };
        each(PointRecord {
            index: i,
            id: ids[i],
            bat: bats[i].max(0) as u32,
            result,
        })?;
    }
    Ok(ReadBack {
        path: path.to_path_buf(),
        study_name: str_attr(&f, "study_name", path)?,
        study_sha256: str_attr(&f, "study_sha256", path)?,
        layout_version,
        header,
        records: Vec::new(),
    })
}

/// What identifies a results file (root attributes only; cheap): for merge's checks.
#[derive(Debug, Clone)]
pub struct FileInfo {
    pub path: PathBuf,
    pub layout_version: u32,
    pub header: JournalHeader,
    pub study_name: String,
    pub study_sha256: String,
    /// The study file's text, verbatim.
    pub study_yaml: String,
    /// The study path as given to `run`.
    pub study_path: String,
    /// `"I/N"` for a shard, `""` otherwise.
    pub shard: String,
    /// A shard's block of flat indices `[start, stop)` (absent in files of older builds).
    pub shard_range: Option<(usize, usize)>,
}

/// Read a results file's identification (root attributes), whatever its layout version.
pub fn file_info(path: &Path) -> Result<FileInfo, StoreError> {
    let (f, header, layout_version) = open_checked(path)?;
    let num = |name: &str| f.attr(name).and_then(|a| a.read_scalar::<i64>()).ok();
    let shard_range = match (num("shard_start"), num("shard_stop")) {
        (Some(a), Some(b)) if 0 <= a && a <= b => Some((a as usize, b as usize)),
        _ => None,
    };
    Ok(FileInfo {
        path: path.to_path_buf(),
        layout_version,
        study_name: str_attr(&f, "study_name", path)?,
        study_sha256: str_attr(&f, "study_sha256", path)?,
        study_yaml: str_attr(&f, "study_yaml", path)?,
        study_path: str_attr(&f, "study_path", path)?,
        shard: str_attr(&f, "shard", path).unwrap_or_default(),
        shard_range,
        header,
    })
}

/// Flat indices of the points present in a results file (status ok or failed), in order.
pub fn present_points(path: &Path) -> Result<Vec<usize>, StoreError> {
    let (f, header, _) = open_checked(path)?;
    let n: usize = header.dims.iter().map(|d| d.1).product();
    let status = f
        .group(l::GROUP_SUMMARY)
        .and_then(|g| g.dataset(l::STATUS.name))
        .and_then(|d| d.read_raw::<i8>())
        .ctx(path, "read summary/status")?;
    if status.len() != n {
        return Err(bad(path, "summary arrays do not match the study's shape"));
    }
    Ok((0..n)
        .filter(|&i| status[i] == l::STATUS_OK || status[i] == l::STATUS_FAILED)
        .collect())
}

/// A human-readable description of a results file: study, layout version, dims, counts by
/// status, sweet spots.
pub fn inspect(path: &Path) -> Result<String, StoreError> {
    let (f, header, version) = open_checked(path)?;
    let mut s = String::new();
    let name = str_attr(&f, "study_name", path)?;
    let _ = writeln!(
        s,
        "{}: batstudy results, layout version {version}",
        path.display()
    );
    let _ = writeln!(
        s,
        "study: {name} (sha256 {})",
        str_attr(&f, "study_sha256", path)?
    );
    if let Ok(c) = str_attr(&f, "created", path) {
        let _ = writeln!(s, "created: {c}");
    }
    let dims: Vec<String> = header
        .dims
        .iter()
        .map(|(n, k)| format!("{n}={k}"))
        .collect();
    let n: usize = header.dims.iter().map(|d| d.1).product();
    let _ = writeln!(s, "dims: {} ({n} points)", dims.join(" × "));
    let g = f.group(l::GROUP_SUMMARY).ctx(path, "open group summary")?;
    let status = g
        .dataset(l::STATUS.name)
        .and_then(|d| d.read_raw::<i8>())
        .ctx(path, "read summary/status")?;
    let count = |v: i8| status.iter().filter(|&&x| x == v).count();
    let _ = writeln!(
        s,
        "points: {} ok, {} failed, {} not computed",
        count(l::STATUS_OK),
        count(l::STATUS_FAILED),
        count(l::STATUS_NOT_COMPUTED)
    );
    if let Some((names, nt, nz)) = &header.history {
        let _ = writeln!(
            s,
            "history: {} ({nt} samples, {nz} z positions)",
            names.join(", ")
        );
    }
    if let Ok(sg) = f.group(l::GROUP_SWEET_SPOT) {
        let rd = |v: &str| {
            sg.dataset(v)
                .and_then(|d| d.read_raw::<f64>())
                .ctx(path, "read sweet_spot")
        };
        let (p, e, w) = (rd("position")?, rd("exit_speed")?, rd("width")?);
        let fin: Vec<usize> = (0..p.len()).filter(|&i| p[i].is_finite()).collect();
        if fin.is_empty() {
            let _ = writeln!(s, "sweet spot: none computed");
        } else if fin.len() <= 10 {
            for i in fin {
                let _ = writeln!(
                    s,
                    "sweet spot [{i}]: z = {:.4} m, exit speed {:.3} m/s, width {:.4} m",
                    p[i], e[i], w[i]
                );
            }
        } else {
            let mm = |v: &[f64]| {
                let it = fin.iter().map(|&i| v[i]);
                (
                    it.clone().fold(f64::INFINITY, f64::min),
                    it.fold(f64::NEG_INFINITY, f64::max),
                )
            };
            let ((p0, p1), (e0, e1), (w0, w1)) = (mm(&p), mm(&e), mm(&w));
            let _ = writeln!(
                s,
                "sweet spots ({} curves): z {p0:.4}..{p1:.4} m, exit speed {e0:.3}..{e1:.3} m/s, width {w0:.4}..{w1:.4} m",
                fin.len()
            );
        }
    }
    Ok(s)
}
