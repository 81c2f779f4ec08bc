//! Reading a results file back: its records (for resume from a finished file, merge and tests)
//! and a human-readable description (`batstudy inspect`).

use super::dimscale::block;
use super::error::{H5Ctx, StoreError};
use super::header::{JournalHeader, HEADER_ATTR};
use super::layout::{self as l, N_SUMMARY_FLOATS};
use super::modal;
use crate::pointset::PointSet;
use crate::results::PointRecord;
use batstudy_physics::outcome::History;
use hdf5::types::VarLenUnicode;
use std::path::{Path, PathBuf};

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

pub(super) fn str_attr(f: &hdf5::Location, name: &str, path: &Path) -> Result<String, StoreError> {
    let a = f
        .attr(name)
        .map_err(|_| bad(path, format!("root attribute {name} missing")))?;
    let v: VarLenUnicode = a
        .read_scalar()
        .map_err(|_| bad(path, format!("root attribute {name} is not a string")))?;
    text(&v).ok_or_else(|| {
        bad(
            path,
            format!("root attribute {name} is not UTF-8 (damaged)"),
        )
    })
}

/// A string of the file, if it is UTF-8 (HDF5 hands over a damaged one's bytes as they are,
/// and `VarLenUnicode::as_str` would take them for UTF-8 unchecked).
pub(super) fn text(v: &VarLenUnicode) -> Option<String> {
    std::str::from_utf8(v.as_bytes()).ok().map(str::to_string)
}

/// A string of the file to show: a byte that is not UTF-8 shows as U+FFFD.
pub(super) fn shown(v: &VarLenUnicode) -> String {
    String::from_utf8_lossy(v.as_bytes()).into_owned()
}

/// Whether `path` is a batstudy results file of any layout version (an HDF5 file with the
/// root attribute `layout_version`): what `--force` may replace. Files from older versions
/// of batstudy are results files too.
pub fn is_results_file(path: &Path) -> Result<(), StoreError> {
    super::check::regular_file(path)?;
    let f = hdf5::File::open(path).map_err(|e| bad(path, format!("HDF5 cannot open it ({e})")))?;
    f.attr("layout_version")
        .and_then(|a| a.read_scalar::<i64>())
        .map(|_| ())
        .map_err(|_| bad(path, "root attribute layout_version missing"))
}

pub(super) fn open_checked(path: &Path) -> Result<(hdf5::File, JournalHeader, u32), StoreError> {
    if !path.exists() {
        return Err(StoreError::io(
            path,
            "open the results file",
            std::io::Error::from(std::io::ErrorKind::NotFound),
        ));
    }
    super::check::check_structure(path)?;
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

/// Points read at once from a file's summary arrays (a slab of about 10 MiB of values), so that
/// reading back a file of any size holds a bounded amount of it.
const READ_SLAB_POINTS: usize = 1 << 16;

/// Hyperslabs `(start, count, first flat index)` that cover a row-major array of `shape` in
/// flat order, each a contiguous flat range of at most `target` (≥ 1) elements.
pub(crate) fn flat_slabs(shape: &[usize], target: usize) -> Vec<(Vec<usize>, Vec<usize>, usize)> {
    let d = shape.len();
    if shape.contains(&0) {
        return Vec::new();
    }
    // smallest k whose trailing block fits the target: dims k.. are read whole
    let k = (0..=d)
        .find(|&k| shape[k..].iter().product::<usize>() <= target.max(1))
        .unwrap_or(d);
    if k == 0 {
        return vec![(vec![0; d], shape.to_vec(), 0)];
    }
    let j = k - 1;
    let inner: usize = shape[k..].iter().product();
    let r = (target / inner).clamp(1, shape[j]);
    let outer: usize = shape[..j].iter().product();
    let mut slabs = Vec::new();
    for o in 0..outer {
        let mut prefix = vec![0; j];
        let mut rem = o;
        for q in (0..j).rev() {
            prefix[q] = rem % shape[q];
            rem /= shape[q];
        }
        for a in (0..shape[j]).step_by(r) {
            let mut start = prefix.clone();
            start.push(a);
            start.extend(std::iter::repeat_n(0, d - k));
            let mut count = vec![1; j];
            count.push(r.min(shape[j] - a));
            count.extend_from_slice(&shape[k..]);
            slabs.push((start, count, (o * shape[j] + a) * inner));
        }
    }
    slabs
}

fn read_slab<T: hdf5::H5Type + Clone>(
    ds: &hdf5::Dataset,
    start: &[usize],
    count: &[usize],
    path: &Path,
) -> Result<Vec<T>, StoreError> {
    let what = format!("read {}", ds.name());
    if start.is_empty() {
        return ds.read_raw::<T>().ctx(path, &what);
    }
    let slab = ds
        .read_slice::<T, _, ndarray::IxDyn>(block(start, count))
        .ctx(path, &what)?;
    // A slab read is a fresh array in row-major order: its buffer is the flat order, taken
    // whole (iterating an n-dimensional array element by element was most of a file's read).
    let n = slab.len();
    if !slab.is_standard_layout() {
        return Ok(slab.iter().cloned().collect());
    }
    match slab.into_raw_vec_and_offset() {
        (data, Some(0) | None) if data.len() == n => Ok(data),
        (data, offset) => {
            let start = offset.unwrap_or(0);
            Ok(data[start..start + n].to_vec())
        }
    }
}

/// Hand every present point of a results file to `each`, in flat-index order, one at a
/// time. Memory: one slab of [`READ_SLAB_POINTS`] points of the summary arrays, one history and
/// the failed points' messages, whatever the file's size.
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
    let shape: Vec<usize> = header.dims.iter().map(|d| d.1).collect();
    let summary = SummaryArrays::open(&f, path, &shape)?;
    let mut messages = error_messages(&f, path)?;
    let histories = history_arrays(&f, path, &header)?;
    let result_shape = crate::results::ResultShape {
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
    for (start, count, flat0) in flat_slabs(&shape, READ_SLAB_POINTS) {
        let slab = summary.read(&start, &count, path)?;
        for j in 0..slab.status.len() {
            let i = flat0 + j;
            let result = match slab.status[j] {
                l::STATUS_OK => {
                    let mut o = slab.outcome(j);
                    if let Some(hv) = &histories {
                        o.history = Some(read_history(hv, &result_shape.unravel(i), path)?);
                    }
                    Ok(o)
                }
                l::STATUS_FAILED => Err(messages.remove(&i).unwrap_or_default()),
                _ => continue,
            };
            each(PointRecord {
                index: i,
                id: slab.ids[j],
                bat: slab.bats[j].max(0) as u32,
                result,
            })?;
        }
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

/// The `/summary` arrays a record is read from. Variables added after a file was written
/// read as NaN (layout.md: new variables may be added without a version bump).
struct SummaryArrays {
    floats: Vec<Option<hdf5::Dataset>>,
    status: hdf5::Dataset,
    recontact: hdf5::Dataset,
    ids: hdf5::Dataset,
    bats: hdf5::Dataset,
}

/// One slab of the summary arrays.
struct SummarySlab {
    floats: Vec<Vec<f64>>,
    status: Vec<i8>,
    recontact: Vec<i8>,
    ids: Vec<u64>,
    bats: Vec<i32>,
}

impl SummaryArrays {
    fn open(f: &hdf5::File, path: &Path, shape: &[usize]) -> Result<Self, StoreError> {
        let g = f.group(l::GROUP_SUMMARY).ctx(path, "open group summary")?;
        let get = |name: &str| g.dataset(name).ctx(path, &format!("open summary/{name}"));
        let mut floats = Vec::new();
        for def in &l::SUMMARY_FLOATS {
            floats.push(match g.link_exists(def.name) {
                true => Some(get(def.name)?),
                false => None,
            });
        }
        let a = SummaryArrays {
            floats,
            status: get(l::STATUS.name)?,
            recontact: get(l::RECONTACT.name)?,
            ids: get(l::POINT_ID.name)?,
            bats: get(l::BAT_INDEX.name)?,
        };
        // every array has the study's shape (a file reshaped since it was written would
        // be read with slabs of the wrong rank: the library's error, not the file's)
        let every = [&a.status, &a.recontact, &a.ids, &a.bats]
            .into_iter()
            .chain(a.floats.iter().flatten());
        if let Some(d) = every.into_iter().find(|d| d.shape() != shape) {
            return Err(bad(
                path,
                format!(
                    "{} has shape {:?}, where the study's dimensions are {shape:?}",
                    d.name(),
                    d.shape()
                ),
            ));
        }
        Ok(a)
    }

    fn read(
        &self,
        start: &[usize],
        count: &[usize],
        path: &Path,
    ) -> Result<SummarySlab, StoreError> {
        let status = read_slab::<i8>(&self.status, start, count, path)?;
        let mut floats = Vec::with_capacity(N_SUMMARY_FLOATS);
        for ds in &self.floats {
            floats.push(match ds {
                Some(ds) => read_slab::<f64>(ds, start, count, path)?,
                None => vec![f64::NAN; status.len()],
            });
        }
        Ok(SummarySlab {
            floats,
            recontact: read_slab::<i8>(&self.recontact, start, count, path)?,
            ids: read_slab::<u64>(&self.ids, start, count, path)?,
            bats: read_slab::<i32>(&self.bats, start, count, path)?,
            status,
        })
    }
}

impl SummarySlab {
    /// The outcome of the slab's point `j` (without histories).
    fn outcome(&self, j: usize) -> batstudy_physics::outcome::Outcome {
        let mut x = [0.0; N_SUMMARY_FLOATS];
        for (k, v) in x.iter_mut().enumerate() {
            *v = self.floats[k][j];
        }
        let mut o = l::outcome_from_floats(&x);
        o.recontact = self.recontact[j] == 1;
        o
    }
}

/// The failed points' messages by flat index (`/errors`).
fn error_messages(
    f: &hdf5::File,
    path: &Path,
) -> Result<std::collections::HashMap<usize, String>, StoreError> {
    let eg = f.group(l::GROUP_ERRORS).ctx(path, "open group errors")?;
    let eidx = eg
        .dataset(l::ERR_FLAT_INDEX.name)
        .and_then(|d| d.read_raw::<u64>())
        .ctx(path, "errors/flat_index")?;
    let emsg = eg
        .dataset(l::ERR_MESSAGE.name)
        .and_then(|d| d.read_raw::<VarLenUnicode>())
        .ctx(path, "errors/message")?;
    Ok(eidx
        .iter()
        .zip(emsg)
        .map(|(i, m)| (*i as usize, shown(&m)))
        .collect())
}

/// A stored history variable: its index in `HISTORY_VARS`, its dataset and the shape of one
/// point's history (time, and z for the displacement).
type HistoryArray = (usize, hdf5::Dataset, Vec<usize>);

/// The `/history` variables the header names, if the file has histories.
fn history_arrays(
    f: &hdf5::File,
    path: &Path,
    header: &JournalHeader,
) -> Result<Option<Vec<HistoryArray>>, StoreError> {
    let Some((names, _, _)) = &header.history else {
        return Ok(None);
    };
    let rank = header.dims.len();
    let study: Vec<usize> = header.dims.iter().map(|d| d.1).collect();
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
        if ds.shape().get(..rank) != Some(&study[..]) {
            return Err(bad(
                path,
                format!(
                    "history/{name} has shape {:?}, where the study's dimensions are {study:?}",
                    ds.shape()
                ),
            ));
        }
        let tail = ds.shape().get(rank..).unwrap_or_default().to_vec();
        v.push((k, ds, tail));
    }
    Ok(Some(v))
}

/// The histories of the point at multi-index `idx`.
fn read_history(
    arrays: &[HistoryArray],
    idx: &[usize],
    path: &Path,
) -> Result<History, StoreError> {
    let mut h = History::default();
    for (k, ds, tail) in arrays {
        let mut start = idx.to_vec();
        let mut count = vec![1; idx.len()];
        for &t in tail {
            start.push(0);
            count.push(t);
        }
        let values = read_slab::<f64>(ds, &start, &count, path)?;
        *l::history_array_mut(&mut h, *k) = match *k == l::MODAL_COORDINATE {
            // stored mode-major (bat_mode, time): back to the model's [time][mode]
            true => {
                let nt = tail.last().copied().unwrap_or(1);
                h.modal.modes = tail.first().copied().unwrap_or(0);
                modal::coordinates_from_mode_major(&values, nt)
            }
            false => values,
        };
    }
    Ok(h)
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

/// The points present in a results file (status ok or failed). Memory: one bit per point
/// and one slab of `status`.
pub fn present_points(path: &Path) -> Result<PointSet, StoreError> {
    let mut present = None;
    for_each_present_slab(path, |n, slab| {
        let set = present.get_or_insert_with(|| PointSet::new(n));
        for &(i, _) in slab {
            set.insert(i);
        }
        Ok(())
    })?;
    Ok(present.unwrap_or_else(|| PointSet::new(0)))
}

/// The (flat index, point id) of every stored point (ok or failed) of a results file, a
/// slab at a time in flat order, with the study's number of points. A file without its
/// `status` or `point_id` arrays, or with arrays of another shape, is not a results file
/// (exit status 2 for a merge: bad input, not a failure of the run).
pub fn for_each_present_slab(
    path: &Path,
    mut visit: impl FnMut(usize, &[(usize, u64)]) -> Result<(), StoreError>,
) -> Result<(), StoreError> {
    let (f, header, _) = open_checked(path)?;
    let shape: Vec<usize> = header.dims.iter().map(|d| d.1).collect();
    let n: usize = shape.iter().product();
    let summary = f
        .group(l::GROUP_SUMMARY)
        .map_err(|_| bad(path, "it has no group summary"))?;
    let array = |name: &str| {
        summary
            .dataset(name)
            .ok()
            .filter(|d| d.size() == n)
            .ok_or_else(|| {
                bad(
                    path,
                    format!("summary/{name} is missing or not of the study's shape"),
                )
            })
    };
    let (status, ids) = (array(l::STATUS.name)?, array(l::POINT_ID.name)?);
    let mut slab = Vec::new();
    for (start, count, flat0) in flat_slabs(&shape, READ_SLAB_POINTS) {
        let st = read_slab::<i8>(&status, &start, &count, path)?;
        let id = read_slab::<u64>(&ids, &start, &count, path)?;
        slab.clear();
        slab.extend(
            st.iter()
                .zip(&id)
                .enumerate()
                .filter(|(_, (&s, _))| s == l::STATUS_OK || s == l::STATUS_FAILED)
                .map(|(j, (_, &id))| (flat0 + j, id)),
        );
        visit(n, &slab)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::flat_slabs;

    // The slabs must tile the array exactly once, in flat order, each within the target:
    // guards the resume-from-file and merge reads, which rely on both.
    #[test]
    fn flat_slabs_tile_the_array_in_order() {
        for (shape, target) in [
            (vec![3usize, 5, 7], 10usize),
            (vec![3, 5, 7], 1000),
            (vec![2, 1000], 64),
            (vec![10], 3),
            (vec![4, 3], 1),
            (vec![2, 0, 3], 5),
        ] {
            let n: usize = shape.iter().product();
            let mut next = 0;
            for (start, count, flat0) in flat_slabs(&shape, target) {
                assert_eq!(flat0, next, "{shape:?} {target}");
                let m: usize = count.iter().product();
                assert!(m <= target, "{shape:?} {target}");
                // the slab's first element is at flat0
                let f = start.iter().zip(&shape).fold(0, |a, (&s, &d)| a * d + s);
                assert_eq!(f, flat0);
                next += m;
            }
            assert_eq!(next, n, "{shape:?} {target}");
        }
    }
}
