//! Writing the final HDF5 file from a journal (the only place that writes results to HDF5).
//! The skeleton in two steps ([`begin_skeleton`] while the bats are prepared,
//! [`complete_skeleton`] while the run computes), then [`fill`]. Memory: a bounded window of
//! summary values (see [`fill`]), one history, and the failed points' messages.

use super::chunks;
use super::dimscale::{self as h5u, attr_num, attr_str, attr_vec, describe, Attacher};
use super::error::{H5Ctx, StoreError};
use super::header::{history_vars, JournalHeader, HEADER_ATTR};
use super::journal::{decode_record, encode_record, RecordReader, Scan};
use super::layout::{self as l, VarDef, N_SUMMARY_FLOATS};
use super::options::{RunMeta, Summary};
use crate::model::measures::sweet::find_sweet_spot;
use crate::model::measures::sweet_defs::vibration_sweet_spot;
use crate::model::outcome::BatMetrics;
use crate::model::outcome::{History, HistoryPrecision, HistoryRequest, Outcome};
use crate::pointset::PointSet;
use crate::results::PointRecord;
use crate::results::{CoordValues, Dim, ResultShape, StudyInfo};
use hdf5::types::VarLenUnicode;
use hdf5::{Dataset, Group};
use ndarray::{ArrayD, IxDyn};
use rayon::prelude::*;
use std::borrow::Cow;
use std::collections::BTreeMap;
use std::fs::File;
use std::io::{BufReader, BufWriter, Read, Write};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// Chunk shape of the summary arrays: the whole `impact_z` axis, then growing along the last
/// dims up to [`l::SUMMARY_CHUNK_ELEMS`] elements.
pub fn summary_chunk(dims: &[Dim]) -> Vec<usize> {
    let mut c = vec![1usize; dims.len()];
    let iz = dims.iter().position(|d| d.name == l::IMPACT_Z);
    if let Some(iz) = iz {
        c[iz] = dims[iz].size.max(1);
    }
    for k in (0..dims.len()).rev() {
        if Some(k) == iz {
            continue;
        }
        let rest: usize = c.iter().product();
        c[k] = dims[k]
            .size
            .min((l::SUMMARY_CHUNK_ELEMS / rest).max(1))
            .max(1);
    }
    c
}

/// Coordinate variables of the study dims in one group; returns the scales (one per dim) and
/// the names of auxiliary coordinates (for the `coordinates` attribute).
fn study_dims(
    g: &Group,
    dims: &[Dim],
    att: &Attacher,
    path: &Path,
) -> Result<(Vec<Dataset>, Vec<String>), StoreError> {
    let mut scales = Vec::new();
    let mut aux = Vec::new();
    for d in dims {
        let own = d.coords.iter().find(|c| c.name == d.name);
        let scale = match own {
            Some(c) => {
                let def = VarDef {
                    name: "",
                    units: leak(&c.units),
                    long_name: leak(&c.long_name),
                };
                let ds = coord_values(g, &d.name, &c.values, path)?;
                h5u::set_scale(&ds, &d.name).ctx(path, "make a dimension scale")?;
                describe(&ds, &def).ctx(path, "describe a coordinate")?;
                attr_str(&ds, "parameter_path", &c.path).ctx(path, "describe a coordinate")?;
                ds
            }
            None => {
                let idx: Vec<i64> = (0..d.size as i64).collect();
                let def = VarDef {
                    name: "",
                    units: "1",
                    long_name: leak(&format!("index along {}", d.name)),
                };
                h5u::scale_coord(g, &d.name, &idx, &def).ctx(path, "write an index coordinate")?
            }
        };
        for c in d.coords.iter().filter(|c| c.name != d.name) {
            let ds = coord_values(g, &c.name, &c.values, path)?;
            attr_str(&ds, "units", &c.units).ctx(path, "describe a coordinate")?;
            attr_str(&ds, "long_name", &c.long_name).ctx(path, "describe a coordinate")?;
            attr_str(&ds, "parameter_path", &c.path).ctx(path, "describe a coordinate")?;
            att.add(&ds, &[&scale]);
            aux.push(c.name.clone());
        }
        scales.push(scale);
    }
    Ok((scales, aux))
}

/// Attribute strings must outlive VarDef; coordinate metadata is small and written once.
fn leak(s: &str) -> &'static str {
    Box::leak(s.to_string().into_boxed_str())
}

fn coord_values(
    g: &Group,
    name: &str,
    v: &CoordValues,
    path: &Path,
) -> Result<Dataset, StoreError> {
    match v {
        CoordValues::Numbers(x) => h5u::write_1d(g, name, x),
        CoordValues::Labels(s) => {
            let s: Vec<VarLenUnicode> = s.iter().map(|s| h5u::vlstr(s)).collect();
            h5u::write_1d(g, name, &s)
        }
    }
    .ctx(path, &format!("write coordinate {name}"))
}

fn new_var<T: hdf5::H5Type + Into<hdf5::types::OwnedDynValue>>(
    g: &Group,
    def: &VarDef,
    shape_chunk: (&[usize], &[usize]),
    fill: T,
    links: (&[&Dataset], &[String], &Attacher),
    path: &Path,
) -> Result<Dataset, StoreError> {
    new_var_level(g, def, shape_chunk, fill, links, l::DEFLATE_LEVEL, path)
}

fn new_var_level<T: hdf5::H5Type + Into<hdf5::types::OwnedDynValue>>(
    g: &Group,
    def: &VarDef,
    (shape, chunk): (&[usize], &[usize]),
    fill: T,
    (scales, aux, att): (&[&Dataset], &[String], &Attacher),
    level: u8,
    path: &Path,
) -> Result<Dataset, StoreError> {
    let what = format!("create variable {}/{}", g.name(), def.name);
    let ds = h5u::create_var_level(g, def.name, shape, chunk, fill, level).ctx(path, &what)?;
    describe(&ds, def).ctx(path, &what)?;
    if !aux.is_empty() {
        attr_str(&ds, "coordinates", &aux.join(" ")).ctx(path, &what)?;
    }
    att.add(&ds, scales);
    Ok(ds)
}

fn write_block<T: hdf5::H5Type>(
    ds: &Dataset,
    start: &[usize],
    count: &[usize],
    data: Vec<T>,
    path: &Path,
) -> Result<(), StoreError> {
    let arr = ArrayD::from_shape_vec(IxDyn(count), data).expect("block shape");
    if start.is_empty() {
        return ds.write(&arr).ctx(path, "write a scalar");
    }
    ds.write_slice(&arr, h5u::block(start, count))
        .ctx(path, &format!("write a block of {}", ds.name()))
}

/// The chunk grid of the summary arrays: blocks in row-major order, and where a point lies.
struct BlockGrid {
    shape: Vec<usize>,
    chunk: Vec<usize>,
    grid: Vec<usize>,
}

impl BlockGrid {
    fn new(shape: &[usize], chunk: &[usize]) -> Self {
        BlockGrid {
            shape: shape.to_vec(),
            chunk: chunk.to_vec(),
            grid: shape
                .iter()
                .zip(chunk)
                .map(|(&n, &c)| n.div_ceil(c))
                .collect(),
        }
    }

    fn n_points(&self) -> usize {
        self.shape.iter().product()
    }

    fn n_blocks(&self) -> usize {
        if self.shape.contains(&0) {
            0
        } else {
            self.grid.iter().product()
        }
    }

    /// Start and extent of block `b`.
    fn block(&self, b: usize) -> (Vec<usize>, Vec<usize>) {
        let d = self.grid.len();
        let (mut start, mut count) = (vec![0; d], vec![0; d]);
        let mut r = b;
        for k in (0..d).rev() {
            start[k] = r % self.grid[k] * self.chunk[k];
            count[k] = self.chunk[k].min(self.shape[k] - start[k]);
            r /= self.grid[k];
        }
        (start, count)
    }

    fn block_len(&self, b: usize) -> usize {
        self.block(b).1.iter().product()
    }

    /// The block holding flat index `flat`, and its row-major position inside that block.
    fn locate(&self, mut flat: usize) -> (usize, usize) {
        let d = self.shape.len();
        let (mut b, mut pos, mut b_stride, mut p_stride) = (0, 0, 1, 1);
        for k in (0..d).rev() {
            let i = flat % self.shape[k];
            flat /= self.shape[k];
            let (g, r) = (i / self.chunk[k], i % self.chunk[k]);
            let count = self.chunk[k].min(self.shape[k] - g * self.chunk[k]);
            b += g * b_stride;
            pos += r * p_stride;
            b_stride *= self.grid[k];
            p_stride *= count;
        }
        (b, pos)
    }
}

/// Summary values of a run of consecutive blocks, concatenated (block `b0 + q` starts at
/// `offsets[q]`).
struct Window {
    offsets: Vec<usize>,
    floats: Vec<Vec<f64>>,
    recontact: Vec<i8>,
    status: Vec<i8>,
    point_id: Vec<u64>,
    bat_index: Vec<i32>,
}

/// Bytes a window holds per point.
const WINDOW_BYTES_PER_POINT: usize = 8 * N_SUMMARY_FLOATS + 1 + 1 + 8 + 4;

/// Most windows (spill files open at once); a bigger study gets bigger windows.
const MAX_WINDOWS: usize = 256;

/// Runs `[b0, b1)` of whole blocks, in order, each within the memory budget (at least one
/// block each, at most [`MAX_WINDOWS`] runs).
fn plan_windows(blocks: &BlockGrid, memory: usize) -> Vec<(usize, usize)> {
    let n_blocks = blocks.n_blocks();
    let total: usize = (0..n_blocks).map(|b| blocks.block_len(b)).sum();
    let window_points = (memory / WINDOW_BYTES_PER_POINT)
        .max(total.div_ceil(MAX_WINDOWS))
        .max(1);
    let mut windows = Vec::new();
    let mut b0 = 0;
    while b0 < n_blocks {
        let (mut b1, mut m) = (b0, 0);
        while b1 < n_blocks && (b1 == b0 || m + blocks.block_len(b1) <= window_points) {
            m += blocks.block_len(b1);
            b1 += 1;
        }
        windows.push((b0, b1));
        b0 = b1;
    }
    windows
}

/// Where a window's records come from.
enum Source {
    Journal(RecordReader),
    Spill(SpillReader),
}

impl Source {
    fn next(&mut self) -> Result<Option<PointRecord>, StoreError> {
        match self {
            Source::Journal(r) => r.next_summary(),
            Source::Spill(r) => r.next(),
        }
    }
}

/// Path of spill file `k` of the final file `out` (`OUT.h5.partial.spill-K`).
fn spill_path(out: &Path, k: usize) -> PathBuf {
    let mut o = out.as_os_str().to_owned();
    o.push(format!(".spill-{k}"));
    PathBuf::from(o)
}

/// Remove spill files a killed build left next to `out` (best effort).
pub fn remove_stale_spills(out: &Path) {
    let (Some(dir), Some(name)) = (out.parent(), out.file_name()) else {
        return;
    };
    let dir = if dir.as_os_str().is_empty() {
        Path::new(".")
    } else {
        dir
    };
    let prefix = format!("{}.spill-", name.to_string_lossy());
    if let Ok(entries) = std::fs::read_dir(dir) {
        for e in entries.flatten() {
            if e.file_name().to_string_lossy().starts_with(&prefix) {
                let _ = std::fs::remove_file(e.path());
            }
        }
    }
}

/// The journal's summary records split into one file per window by one sequential pass
/// (journal order kept within each file). Removed when dropped.
struct Spill {
    paths: Vec<PathBuf>,
}

impl Spill {
    fn split(
        journal: &Path,
        scan: &Scan,
        out: &Path,
        blocks: &BlockGrid,
        windows: &[(usize, usize)],
    ) -> Result<Spill, StoreError> {
        let spill = Spill {
            paths: (0..windows.len()).map(|k| spill_path(out, k)).collect(),
        };
        let mut files = Vec::with_capacity(windows.len());
        for p in &spill.paths {
            let f = File::create(p).map_err(|e| StoreError::io(p, "create a spill file", e))?;
            files.push(BufWriter::with_capacity(1 << 16, f));
        }
        let n_points = blocks.n_points();
        let mut rr = RecordReader::open(journal, scan)?;
        let mut buf = Vec::new();
        while let Some(rec) = rr.next_summary()? {
            if rec.index >= n_points {
                continue;
            }
            let (b, _) = blocks.locate(rec.index);
            let k = windows.partition_point(|&(b0, _)| b0 <= b) - 1;
            buf.clear();
            encode_record(&rec, &mut buf);
            files[k]
                .write_all(&(buf.len() as u32).to_le_bytes())
                .and_then(|_| files[k].write_all(&buf))
                .map_err(|e| StoreError::io(&spill.paths[k], "write a spill file", e))?;
        }
        for (f, p) in files.into_iter().zip(&spill.paths) {
            f.into_inner()
                .map_err(|e| StoreError::io(p, "write a spill file", e.into_error()))?;
        }
        Ok(spill)
    }

    fn reader(&self, k: usize) -> Result<SpillReader, StoreError> {
        let p = &self.paths[k];
        let f = File::open(p).map_err(|e| StoreError::io(p, "open a spill file", e))?;
        Ok(SpillReader {
            r: BufReader::with_capacity(1 << 20, f),
            path: p.clone(),
            buf: Vec::new(),
        })
    }
}

impl Drop for Spill {
    fn drop(&mut self) {
        for p in &self.paths {
            let _ = std::fs::remove_file(p);
        }
    }
}

/// Sequential reading of one spill file.
struct SpillReader {
    r: BufReader<File>,
    path: PathBuf,
    buf: Vec<u8>,
}

impl SpillReader {
    fn next(&mut self) -> Result<Option<PointRecord>, StoreError> {
        let mut len = [0u8; 4];
        match self.r.read_exact(&mut len) {
            Ok(()) => {}
            Err(e) if e.kind() == std::io::ErrorKind::UnexpectedEof => return Ok(None),
            Err(e) => return Err(StoreError::io(&self.path, "read a spill file", e)),
        }
        self.buf.resize(u32::from_le_bytes(len) as usize, 0);
        self.r
            .read_exact(&mut self.buf)
            .map_err(|e| StoreError::io(&self.path, "read a spill file", e))?;
        decode_record(&self.buf, true)
            .map(Some)
            .ok_or_else(|| StoreError::BadRecord {
                path: self.path.clone(),
                what: "undecodable spill record".into(),
            })
    }
}

impl Window {
    /// An empty window over blocks `[b0, b1)`.
    fn of_blocks(blocks: &BlockGrid, b0: usize, b1: usize) -> Self {
        let mut offsets = vec![0];
        for b in b0..b1 {
            offsets.push(offsets[b - b0] + blocks.block_len(b));
        }
        let m = *offsets.last().unwrap_or(&0);
        Window {
            offsets,
            floats: vec![vec![f64::NAN; m]; N_SUMMARY_FLOATS],
            recontact: vec![-1; m],
            status: vec![l::STATUS_NOT_COMPUTED; m],
            point_id: vec![0; m],
            bat_index: vec![-1; m],
        }
    }

    /// Place one record of blocks `[b0, b1)`; others are not this window's. Records come in
    /// journal order, and the first record of a point wins.
    fn put(&mut self, rec: &PointRecord, blocks: &BlockGrid, b0: usize, b1: usize, t: &mut Tally) {
        if rec.index >= blocks.n_points() {
            return;
        }
        let (b, pos) = blocks.locate(rec.index);
        if b < b0 || b >= b1 {
            return;
        }
        let j = self.offsets[b - b0] + pos;
        if self.status[j] != l::STATUS_NOT_COMPUTED {
            return;
        }
        self.point_id[j] = rec.id;
        self.bat_index[j] = rec.bat as i32;
        t.n_done += 1;
        match &rec.result {
            Ok(o) => {
                self.status[j] = l::STATUS_OK;
                self.recontact[j] = o.recontact as i8;
                for (k, x) in l::summary_floats(o).into_iter().enumerate() {
                    self.floats[k][j] = x;
                }
            }
            Err(msg) => {
                self.status[j] = l::STATUS_FAILED;
                t.n_failed += 1;
                t.errors.push((rec.index as u64, rec.id, msg.clone()));
            }
        }
    }
}

/// Counts of the records placed, and the failed points (flat index, id, message).
#[derive(Default)]
struct Tally {
    n_done: usize,
    n_failed: usize,
    errors: Vec<(u64, u64, String)>,
}

impl Tally {
    fn add(&mut self, other: Tally) {
        self.n_done += other.n_done;
        self.n_failed += other.n_failed;
        self.errors.extend(other.errors);
    }
}

/// The summary of a study that fits one build window, gathered from the records as the run
/// writes them, so that [`fill`] need not read the journal back (issue 7: on a small study
/// that read was a fifth of finishing the file). Only for a session that saw every record
/// it stores: a resumed one reads its journal as before.
pub struct Gathered {
    blocks: BlockGrid,
    window: Window,
    tally: Tally,
}

impl Gathered {
    /// `None` when the study needs more than one window of `memory` bytes.
    pub fn new(info: &StudyInfo, memory: usize) -> Option<Gathered> {
        let shape: Vec<usize> = info.shape.dims.iter().map(|d| d.size).collect();
        let blocks = BlockGrid::new(&shape, &summary_chunk(&info.shape.dims));
        if plan_windows(&blocks, memory).len() != 1 {
            return None;
        }
        Some(Gathered {
            window: Window::of_blocks(&blocks, 0, blocks.n_blocks()),
            tally: Tally::default(),
            blocks,
        })
    }

    /// Place a record the session has just stored.
    pub fn put(&mut self, rec: &PointRecord) {
        let n = self.blocks.n_blocks();
        self.window.put(rec, &self.blocks, 0, n, &mut self.tally);
    }
}

/// The sweet-spot variables along `impact_z` for every curve inside one block (`fv` the
/// block's summary floats).
fn block_sweet_spots(fv: &[&[f64]], count: &[usize], iz: usize, z: &[f64]) -> [Vec<f64>; 6] {
    let m: usize = count.iter().product();
    let nz = count[iz];
    let stride: usize = count[iz + 1..].iter().product();
    let outer = m / nz;
    let curve = |slot: usize| -> [f64; 6] {
        let (hi, lo) = (slot / stride, slot % stride);
        let base = hi * nz * stride + lo;
        let along = |k: usize| -> Vec<f64> { (0..nz).map(|q| fv[k][base + q * stride]).collect() };
        let exit = along(0);
        let (zz, vv): (Vec<f64>, Vec<f64>) = z
            .iter()
            .zip(&exit)
            .filter(|(_, v)| v.is_finite())
            .map(|(&z, &v)| (z, v))
            .unzip();
        let s = find_sweet_spot(&zz, &vv);
        let v = vibration_sweet_spot(
            z,
            &along(l::GRIP_VIBRATION_INDEX),
            &along(l::VIBRATION_ENERGY_INDEX),
        );
        [
            s.map_or(f64::NAN, |s| s.position),
            s.map_or(f64::NAN, |s| s.exit_speed),
            s.map_or(f64::NAN, |s| s.width),
            v.min_vibration_position,
            v.min_vibration_amplitude,
            v.min_vibration_energy_position,
        ]
    };
    let rows: Vec<[f64; 6]> = (0..outer).map(curve).collect();
    std::array::from_fn(|k| rows.iter().map(|r| r[k]).collect())
}

fn without<T: Copy>(v: &[T], skip: usize) -> Vec<T> {
    v.iter()
        .enumerate()
        .filter(|&(k, _)| k != skip)
        .map(|(_, &x)| x)
        .collect()
}

/// One block's values for one dataset (borrowed from the window: no copy of the window is
/// made), with the dataset's fill value (which pads an edge chunk).
enum Values<'a> {
    F64(Cow<'a, [f64]>, f64),
    I8(&'a [i8], i8),
    I32(&'a [i32], i32),
    U64(&'a [u64], u64),
}

/// One block's contribution to one dataset (`targets[target]` in [`fill`]).
enum Piece<'a> {
    /// Raw values at `start` with extent `count`, for a dataset of chunk shape `chunk` (empty:
    /// not chunked, e.g. a scalar).
    Block {
        target: usize,
        start: Vec<usize>,
        count: Vec<usize>,
        chunk: Vec<usize>,
        values: Values<'a>,
    },
    /// A whole chunk, filtered (see [`chunks::filtered`]), at its start.
    Chunk(usize, Vec<usize>, Vec<u8>),
}

impl<'a> Piece<'a> {
    fn block(
        target: usize,
        (start, count, chunk): (&[usize], &[usize], &[usize]),
        values: Values<'a>,
    ) -> Piece<'a> {
        Piece::Block {
            target,
            start: start.to_vec(),
            count: count.to_vec(),
            chunk: chunk.to_vec(),
            values,
        }
    }

    /// The chunk's bytes as HDF5 stores them (a block of a dataset that is not chunked stays
    /// as it is). Pure: runs on any thread.
    fn compress(self) -> Piece<'a> {
        let Piece::Block {
            target,
            start,
            count,
            chunk,
            values,
        } = self
        else {
            return self;
        };
        if chunk.is_empty() {
            return Piece::Block {
                target,
                start,
                count,
                chunk,
                values,
            };
        }
        let level = l::DEFLATE_LEVEL;
        let bytes = match &values {
            Values::F64(v, f) => chunks::filtered(v, &count, &chunk, *f, level),
            Values::I8(v, f) => chunks::filtered(v, &count, &chunk, *f, level),
            Values::I32(v, f) => chunks::filtered(v, &count, &chunk, *f, level),
            Values::U64(v, f) => chunks::filtered(v, &count, &chunk, *f, level),
        };
        Piece::Chunk(target, start, bytes)
    }

    fn write(self, targets: &[&Dataset], out: &Path) -> Result<(), StoreError> {
        match self {
            Piece::Chunk(t, start, bytes) => chunks::write_chunk(targets[t], &start, &bytes)
                .ctx(out, &format!("write a chunk of {}", targets[t].name())),
            Piece::Block {
                target,
                start,
                count,
                values,
                ..
            } => {
                let ds = targets[target];
                match values {
                    Values::F64(v, _) => write_block(ds, &start, &count, v.into_owned(), out),
                    Values::I8(v, _) => write_block(ds, &start, &count, v.to_vec(), out),
                    Values::I32(v, _) => write_block(ds, &start, &count, v.to_vec(), out),
                    Values::U64(v, _) => write_block(ds, &start, &count, v.to_vec(), out),
                }
            }
        }
    }
}

/// Compress `pieces` on all cores and write them in their order, each as soon as every
/// piece before it is written: the writes overlap the compression (issue 7: compressing all,
/// then writing all, left one core idle for a third of a small study's finish), and the file
/// is laid out in the same order whatever the threads. Whoever finishes the next piece
/// writes it and the finished ones after it; a thread that finishes a later piece leaves it
/// queued and moves on.
fn compress_and_write(
    pieces: Vec<Piece>,
    targets: &[&Dataset],
    out: &Path,
) -> Result<(), StoreError> {
    struct Queue<'a> {
        next: usize,
        ready: BTreeMap<usize, Piece<'a>>,
        writing: bool,
        error: Option<StoreError>,
    }
    let queue = Mutex::new(Queue {
        next: 0,
        ready: BTreeMap::new(),
        writing: false,
        error: None,
    });
    let lock = || queue.lock().unwrap_or_else(|p| p.into_inner());
    pieces
        .into_par_iter()
        .enumerate()
        .with_max_len(1)
        .for_each(|(i, p)| {
            let p = p.compress();
            let mut q = lock();
            q.ready.insert(i, p);
            if q.writing {
                return;
            }
            q.writing = true;
            loop {
                // the run of pieces that can be written now, taken out under the lock
                let mut run = Vec::new();
                while let Some(p) = {
                    let next = q.next;
                    q.ready.remove(&next)
                } {
                    run.push(p);
                    q.next += 1;
                }
                if run.is_empty() || q.error.is_some() {
                    q.writing = false;
                    return;
                }
                drop(q);
                let written = run.into_iter().try_for_each(|p| p.write(targets, out));
                q = lock();
                if let Err(e) = written {
                    q.error = Some(e);
                }
            }
        });
    let q = queue.into_inner().unwrap_or_else(|p| p.into_inner());
    match q.error {
        Some(e) => Err(e),
        None => {
            debug_assert!(q.ready.is_empty());
            Ok(())
        }
    }
}

/// Everything block `b` (the `q`-th of window `w`) writes, uncompressed: its summary variables
/// and, with an `impact_z` dim, the sweet spots of its curves. Pure: runs on any thread.
fn block_pieces<'a>(
    w: &'a Window,
    q: usize,
    blocks: &BlockGrid,
    chunk: &[usize],
    b: usize,
    sweet: Option<&(usize, Vec<Dataset>, Vec<f64>)>,
) -> Vec<Piece<'a>> {
    let (start, count) = blocks.block(b);
    let r = w.offsets[q]..w.offsets[q + 1];
    let fv: Vec<&'a [f64]> = w.floats.iter().map(|v| &v[r.clone()]).collect();
    let at = (&start[..], &count[..], chunk);
    let mut pieces = Vec::with_capacity(N_SUMMARY_FLOATS + 10);
    for (k, v) in fv.iter().enumerate() {
        pieces.push(Piece::block(k, at, Values::F64(Cow::Borrowed(v), f64::NAN)));
    }
    let k = N_SUMMARY_FLOATS;
    let recontact = Values::I8(&w.recontact[r.clone()], -1);
    let status = Values::I8(&w.status[r.clone()], l::STATUS_NOT_COMPUTED);
    let point_id = Values::U64(&w.point_id[r.clone()], 0);
    let bat_index = Values::I32(&w.bat_index[r], -1);
    for (j, v) in [recontact, status, point_id, bat_index]
        .into_iter()
        .enumerate()
    {
        pieces.push(Piece::block(k + j, at, v));
    }
    if let Some((iz, _, z)) = sweet {
        let zc = &z[start[*iz]..start[*iz] + count[*iz]];
        let res = block_sweet_spots(&fv, &count, *iz, zc);
        let (rs, rcnt, rchunk) = (
            without(&start, *iz),
            without(&count, *iz),
            without(chunk, *iz),
        );
        for (j, data) in res.into_iter().enumerate() {
            let at = (&rs[..], &rcnt[..], &rchunk[..]);
            pieces.push(Piece::block(
                k + 4 + j,
                at,
                Values::F64(Cow::Owned(data), f64::NAN),
            ));
        }
    }
    pieces
}

/// The results file with everything that does not depend on the points' results: root
/// attributes, groups, coordinates and dimension scales, every variable (empty), `/bat`. The
/// store creates it in two steps off the critical path, so that finishing a run only fills
/// in the data (issue 7: most of a small study's HDF5 time was this fixed part): the
/// shape's part ([`begin_skeleton`]) while the bats are prepared, the rest
/// ([`complete_skeleton`]) on the writer thread while the workers compute.
pub struct Skeleton {
    f: hdf5::File,
    out: PathBuf,
    /// The shape it was begun for, and whether [`complete_skeleton`] has run.
    shape: ResultShape,
    complete: bool,
    floats: Vec<Dataset>,
    recontact: Dataset,
    status: Dataset,
    point_id: Dataset,
    bat_index: Dataset,
    /// `impact_z`'s position among the dims, the sweet-spot variables and the z values.
    sweet: Option<(usize, Vec<Dataset>, Vec<f64>)>,
    errors: Errors,
    /// Stored history variables: index into [`l::HISTORY_VARS`], dataset, full shape.
    history: Vec<(usize, Dataset, Vec<usize>)>,
}

/// Create `out` with everything but the results (see [`Skeleton`]).
pub fn create_skeleton(
    info: &StudyInfo,
    meta: &RunMeta,
    out: &Path,
) -> Result<Skeleton, StoreError> {
    let mut sk = begin_skeleton(&info.shape, out)?;
    complete_skeleton(&mut sk, info, meta)?;
    Ok(sk)
}

/// The part of the skeleton that depends on the study's shape alone: `/summary`,
/// `/sweet_spot` and `/errors`, with their coordinates and empty variables. It can be made
/// before the bats are prepared (issue 7: while a one-bat study prepares its bat, a core is
/// idle); [`complete_skeleton`] adds the rest.
pub fn begin_skeleton(study_shape: &ResultShape, out: &Path) -> Result<Skeleton, StoreError> {
    let f = hdf5::File::create(out).ctx(out, "create the results file")?;

    let dims = &study_shape.dims;
    let shape: Vec<usize> = dims.iter().map(|d| d.size).collect();
    let chunk = summary_chunk(dims);

    // ---- /summary (and /sweet_spot, computed from the same blocks)
    let att = Attacher::default();
    let g = f
        .create_group(l::GROUP_SUMMARY)
        .ctx(out, "create group summary")?;
    let (scales, aux) = study_dims(&g, dims, &att, out)?;
    let sref: Vec<&Dataset> = scales.iter().collect();
    let links = (&sref[..], &aux[..], &att);
    let mut floats = Vec::new();
    for def in &l::SUMMARY_FLOATS {
        floats.push(new_var(&g, def, (&shape, &chunk), f64::NAN, links, out)?);
    }
    let recontact = new_var(&g, &l::RECONTACT, (&shape, &chunk), -1i8, links, out)?;
    let status = new_var(
        &g,
        &l::STATUS,
        (&shape, &chunk),
        l::STATUS_NOT_COMPUTED,
        links,
        out,
    )?;
    attr_vec(&status, "flag_values", &[-1i8, 0, 1]).ctx(out, "describe status")?;
    attr_str(&status, "flag_meanings", "not_computed ok failed").ctx(out, "describe status")?;
    let point_id = new_var(&g, &l::POINT_ID, (&shape, &chunk), 0u64, links, out)?;
    let bat_index = new_var(&g, &l::BAT_INDEX, (&shape, &chunk), -1i32, links, out)?;

    let iz = dims.iter().position(|d| d.name == l::IMPACT_Z);
    let sweet = match iz {
        Some(iz) => {
            let sg = f
                .create_group(l::GROUP_SWEET_SPOT)
                .ctx(out, "create group sweet_spot")?;
            let rest: Vec<Dim> = dims
                .iter()
                .enumerate()
                .filter(|&(k, _)| k != iz)
                .map(|(_, d)| d.clone())
                .collect();
            let (ss, saux) = study_dims(&sg, &rest, &att, out)?;
            let ssref: Vec<&Dataset> = ss.iter().collect();
            let rshape: Vec<usize> = rest.iter().map(|d| d.size).collect();
            let rchunk = without(&chunk, iz);
            let mut vars = Vec::new();
            for def in [
                &l::SWEET_POSITION,
                &l::SWEET_EXIT_SPEED,
                &l::SWEET_WIDTH,
                &l::SWEET_MIN_VIBRATION_POSITION,
                &l::SWEET_MIN_VIBRATION_AMPLITUDE,
                &l::SWEET_MIN_VIBRATION_ENERGY_POSITION,
            ] {
                let links = (&ssref[..], &saux[..], &att);
                vars.push(new_var(&sg, def, (&rshape, &rchunk), f64::NAN, links, out)?);
            }
            let z = match dims[iz]
                .coords
                .iter()
                .find(|c| c.name == l::IMPACT_Z)
                .map(|c| &c.values)
            {
                Some(CoordValues::Numbers(z)) => z.clone(),
                _ => {
                    return Err(StoreError::BadRecord {
                        path: out.to_path_buf(),
                        what: "dim impact_z has no numeric coordinate impact_z".into(),
                    })
                }
            };
            Some((iz, vars, z))
        }
        None => None,
    };

    let errors = create_errors(&f, &att, out)?;
    att.write().ctx(out, "attach the dimension scales")?;
    Ok(Skeleton {
        f,
        out: out.to_path_buf(),
        shape: study_shape.clone(),
        complete: false,
        floats,
        recontact,
        status,
        point_id,
        bat_index,
        sweet,
        errors,
        history: Vec::new(),
    })
}

/// `/errors`: the failed points, one row each, along a growable dim.
struct Errors {
    index: Dataset,
    flat_index: Dataset,
    point_id: Dataset,
    message: Dataset,
}

/// `/errors` with no rows: most runs have no failed points, and then finishing the file
/// writes nothing here.
fn create_errors(f: &hdf5::File, att: &Attacher, out: &Path) -> Result<Errors, StoreError> {
    let g = f
        .create_group(l::GROUP_ERRORS)
        .ctx(out, "create group errors")?;
    let e = |r: hdf5::Result<Dataset>| r.ctx(out, "create the errors");
    let edef = VarDef {
        name: l::ERR_DIM,
        units: "1",
        long_name: "failed point number",
    };
    let index = e(h5u::create_growable::<i64>(&g, l::ERR_DIM))?;
    h5u::set_scale(&index, l::ERR_DIM).ctx(out, "create the errors")?;
    describe(&index, &edef).ctx(out, "create the errors")?;
    let column = |def: &VarDef, ds: hdf5::Result<Dataset>| -> Result<Dataset, StoreError> {
        let ds = e(ds)?;
        describe(&ds, def).ctx(out, "create the errors")?;
        att.add(&ds, &[&index]);
        Ok(ds)
    };
    let flat_index = column(
        &l::ERR_FLAT_INDEX,
        h5u::create_growable::<u64>(&g, l::ERR_FLAT_INDEX.name),
    )?;
    let point_id = column(
        &l::ERR_POINT_ID,
        h5u::create_growable::<u64>(&g, l::ERR_POINT_ID.name),
    )?;
    let message = column(
        &l::ERR_MESSAGE,
        h5u::create_growable::<VarLenUnicode>(&g, l::ERR_MESSAGE.name),
    )?;
    Ok(Errors {
        index,
        flat_index,
        point_id,
        message,
    })
}

/// Add what depends on the bats and the run to a begun skeleton: the root attributes,
/// `/history` and `/bat`; then hand the metadata to the OS.
pub fn complete_skeleton(
    sk: &mut Skeleton,
    info: &StudyInfo,
    meta: &RunMeta,
) -> Result<(), StoreError> {
    let out = sk.out.as_path();
    if sk.complete {
        return Ok(());
    }
    if !sk.shape.identical(&info.shape) {
        return Err(StoreError::BegunMismatch {
            path: out.to_path_buf(),
            what: "it was begun for another study shape".into(),
        });
    }
    let f = &sk.f;
    root_attrs(f, info, meta, out)?;
    let att = Attacher::default();
    if let Some(h) = &info.history {
        sk.history = create_history(f, h, info, &att, out)?;
    }
    write_bats(f, info, &att, out)?;
    att.write().ctx(out, "attach the dimension scales")?;
    // hand the metadata to the OS now, not on the critical path at the end
    f.flush().ctx(out, "flush the results file")?;
    sk.complete = true;
    Ok(())
}

/// Fill a skeleton with the journal's records, write the counts and `created`, and close
/// the file. Memory: `memory` bytes of summary values at most (a study larger than that is
/// built window by window, its journal first split into one spill file per window), one
/// history, the failed points' messages; nothing else grows with the study.
pub fn fill(
    sk: Skeleton,
    journal: &Path,
    scan: &Scan,
    info: &StudyInfo,
    created: &str,
    memory: usize,
    mut gathered: Option<Gathered>,
) -> Result<Summary, StoreError> {
    let out = sk.out.as_path();
    let n_points = info.shape.n_points();
    let shape: Vec<usize> = info.shape.dims.iter().map(|d| d.size).collect();
    let chunk = summary_chunk(&info.shape.dims);
    let mut tally = Tally::default();
    let blocks = BlockGrid::new(&shape, &chunk);
    let windows = plan_windows(&blocks, memory);
    // the datasets a block writes to, in the order of [`block_pieces`]
    let mut targets: Vec<&Dataset> = sk.floats.iter().collect();
    targets.extend([&sk.recontact, &sk.status, &sk.point_id, &sk.bat_index]);
    if let Some((_, vars, _)) = &sk.sweet {
        targets.extend(vars.iter());
    }
    // One window: read the journal directly. Several: route the records to one spill file
    // per window in a single pass, so that the journal is read once, not once per window.
    let spill = if windows.len() > 1 {
        Some(Spill::split(journal, scan, out, &blocks, &windows)?)
    } else {
        None
    };
    for (k, &(b0, b1)) in windows.iter().enumerate() {
        let w = match gathered.take() {
            // one window, gathered while the run wrote its journal: nothing to read back
            Some(g) if windows.len() == 1 => {
                tally.add(g.tally);
                g.window
            }
            _ => {
                let mut w = Window::of_blocks(&blocks, b0, b1);
                let mut source = match &spill {
                    Some(sp) => Source::Spill(sp.reader(k)?),
                    None => Source::Journal(RecordReader::open(journal, scan)?),
                };
                while let Some(rec) = source.next()? {
                    w.put(&rec, &blocks, b0, b1, &mut tally);
                }
                w
            }
        };
        // a small study is one block: parallel over (block, variable), not blocks alone
        let pieces: Vec<Piece> = (b0..b1)
            .into_par_iter()
            .flat_map_iter(|b| block_pieces(&w, b - b0, &blocks, &chunk, b, sk.sweet.as_ref()))
            .collect();
        compress_and_write(pieces, &targets, out)?;
    }
    drop(spill);

    let Tally {
        n_done,
        n_failed,
        mut errors,
    } = tally;
    // ---- /errors: made empty with the skeleton; grown only when points failed
    if !errors.is_empty() {
        errors.sort_by_key(|e| e.0);
        let e = &sk.errors;
        let n = errors.len();
        let grow = |ds: &Dataset| ds.resize(n).ctx(out, "write errors");
        let eidx: Vec<i64> = (0..n as i64).collect();
        let flat: Vec<u64> = errors.iter().map(|e| e.0).collect();
        let ids: Vec<u64> = errors.iter().map(|e| e.1).collect();
        let msgs: Vec<VarLenUnicode> = errors.iter().map(|e| h5u::vlstr(&e.2)).collect();
        for ds in [&e.index, &e.flat_index, &e.point_id, &e.message] {
            grow(ds)?;
        }
        let w = |r: hdf5::Result<()>| r.ctx(out, "write errors");
        w(h5u::write_small(&e.index, &eidx))?;
        w(h5u::write_small(&e.flat_index, &flat))?;
        w(h5u::write_small(&e.point_id, &ids))?;
        w(h5u::write_small(&e.message, &msgs))?;
    }
    drop(errors);

    // ---- /history
    if let Some(h) = &info.history {
        write_histories(&sk.history, h, info, journal, scan, out)?;
    }

    let f = &sk.f;
    attr_str(f, "created", created).ctx(out, "write root attributes")?;
    let n = |k: &str, v: i64| attr_num(f, k, v).ctx(out, "write root attributes");
    n("n_done", n_done as i64)?;
    n("n_failed", n_failed as i64)?;
    n("complete", (n_done == n_points) as i64)?;
    f.flush().ctx(out, "flush the results file")?;
    drop(sk);
    Ok(Summary {
        n_points,
        n_done,
        n_failed,
    })
}

/// Root attributes known before the data are read (`created`, `n_done`, `n_failed` and
/// `complete` are written by [`fill`]).
fn root_attrs(
    f: &hdf5::File,
    info: &StudyInfo,
    meta: &RunMeta,
    out: &Path,
) -> Result<(), StoreError> {
    let s = |k: &str, v: &str| attr_str(f, k, v).ctx(out, "write root attributes");
    s("Conventions", "CF-1.8")?;
    s("title", &format!("batstudy results: {}", info.name))?;
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

/// The `/history` group and its (empty) variables.
fn create_history(
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
fn write_histories(
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

fn padded<T: Clone>(rows: &[Vec<T>], fill: T) -> (Vec<T>, usize) {
    let w = rows.iter().map(|r| r.len()).max().unwrap_or(0);
    let mut v = Vec::with_capacity(rows.len() * w);
    for r in rows {
        v.extend_from_slice(r);
        v.extend(std::iter::repeat_n(fill.clone(), w - r.len()));
    }
    (v, w)
}

fn write_bats(
    f: &hdf5::File,
    info: &StudyInfo,
    att: &Attacher,
    out: &Path,
) -> Result<(), StoreError> {
    let g = f.create_group(l::GROUP_BAT).ctx(out, "create group bat")?;
    let e = |what: &str| format!("write bat {what}");
    let labels: Vec<VarLenUnicode> = info.bats.iter().map(|b| h5u::vlstr(&b.label)).collect();
    let bat = h5u::scale_coord(&g, l::BAT_DIM.name, &labels, &l::BAT_DIM).ctx(out, &e("labels"))?;
    let p: Vec<_> = info.bats.iter().map(|b| &b.properties).collect();
    let n_modes = p.iter().map(|p| p.mode_frequency.len()).max().unwrap_or(0);
    let modes: Vec<i64> = (1..=n_modes as i64).collect();
    let mode =
        h5u::scale_coord(&g, l::MODE_DIM.name, &modes, &l::MODE_DIM).ctx(out, &e("modes"))?;
    let nodes_rows: Vec<Vec<f64>> = p
        .iter()
        .flat_map(|p| (0..n_modes).map(move |m| p.mode_nodes.get(m).cloned().unwrap_or_default()))
        .collect();
    let (nodes, n_nodes) = padded(&nodes_rows, f64::NAN);
    let node_idx: Vec<i64> = (0..n_nodes as i64).collect();
    let node =
        h5u::scale_coord(&g, l::NODE_DIM.name, &node_idx, &l::NODE_DIM).ctx(out, &e("nodes"))?;
    let (pz, n_prof) = padded(&p.iter().map(|p| p.z.clone()).collect::<Vec<_>>(), f64::NAN);
    let prof_idx: Vec<i64> = (0..n_prof as i64).collect();
    let prof = h5u::scale_coord(&g, l::PROFILE_DIM.name, &prof_idx, &l::PROFILE_DIM)
        .ctx(out, &e("profile"))?;
    let nb = info.bats.len();
    let var = |def: &VarDef,
               shape: Vec<usize>,
               data: Vec<f64>,
               sc: &[&Dataset]|
     -> Result<(), StoreError> {
        let ds = g
            .new_dataset::<f64>()
            .shape(shape.clone())
            .create(def.name)
            .ctx(out, &e(def.name))?;
        h5u::write_small(&ds, &data).ctx(out, &e(def.name))?;
        describe(&ds, def).ctx(out, &e(def.name))?;
        att.add(&ds, sc);
        Ok(())
    };
    var(
        &l::BAT_MASS,
        vec![nb],
        p.iter().map(|p| p.mass).collect(),
        &[&bat],
    )?;
    var(
        &l::BAT_Z_CM,
        vec![nb],
        p.iter().map(|p| p.z_cm).collect(),
        &[&bat],
    )?;
    var(
        &l::BAT_MOI,
        vec![nb],
        p.iter().map(|p| p.moment_of_inertia).collect(),
        &[&bat],
    )?;
    var(
        &l::BAT_MOI6,
        vec![nb],
        p.iter().map(|p| p.moment_of_inertia_knob6).collect(),
        &[&bat],
    )?;
    var(
        &l::BAT_LENGTH,
        vec![nb],
        p.iter().map(|p| p.length).collect(),
        &[&bat],
    )?;
    let (mf, _) = padded(
        &p.iter()
            .map(|p| p.mode_frequency.clone())
            .collect::<Vec<_>>(),
        f64::NAN,
    );
    let mf = if n_modes == 0 { vec![] } else { mf };
    // rows shorter than n_modes are padded by `padded` only up to the longest row: same here
    var(&l::BAT_MODE_FREQ, vec![nb, n_modes], mf, &[&bat, &mode])?;
    var(
        &l::BAT_MODE_NODES,
        vec![nb, n_modes, n_nodes],
        nodes,
        &[&bat, &mode, &node],
    )?;
    var(&l::BAT_PROFILE_Z, vec![nb, n_prof], pz, &[&bat, &prof])?;
    let (ro, _) = padded(
        &p.iter()
            .map(|p| pad_to(&p.outer_radius, n_prof))
            .collect::<Vec<_>>(),
        f64::NAN,
    );
    let (ri, _) = padded(
        &p.iter()
            .map(|p| pad_to(&p.inner_radius, n_prof))
            .collect::<Vec<_>>(),
        f64::NAN,
    );
    var(
        &l::BAT_OUTER,
        vec![nb, n_prof],
        if n_prof == 0 { vec![] } else { ro },
        &[&bat, &prof],
    )?;
    var(
        &l::BAT_INNER,
        vec![nb, n_prof],
        if n_prof == 0 { vec![] } else { ri },
        &[&bat, &prof],
    )?;
    type Getter = fn(&BatMetrics) -> f64;
    let per_bat: [(&VarDef, Getter); 7] = [
        (&l::BAT_PIVOT, |m| m.pivot),
        (&l::BAT_COP, |m| m.centre_of_percussion),
        (&l::BAT_NODE1, |m| m.node1_barrel),
        (&l::BAT_NODE2, |m| m.node2_barrel),
        (&l::BAT_BBCOR_SPEED, |m| m.bbcor_ball_speed),
        (&l::BAT_BBCOR_MAX, |m| m.bbcor_max),
        (&l::BAT_BBCOR_MAX_POS, |m| m.bbcor_max_position),
    ];
    for (def, get) in per_bat {
        var(
            def,
            vec![nb],
            p.iter().map(|p| get(&p.metrics)).collect(),
            &[&bat],
        )?;
    }
    let (bz, n_bb) = padded(
        &p.iter()
            .map(|p| p.metrics.bbcor_z.clone())
            .collect::<Vec<_>>(),
        f64::NAN,
    );
    let (bb, _) = padded(
        &p.iter()
            .map(|p| pad_to(&p.metrics.bbcor, p.metrics.bbcor_z.len()))
            .collect::<Vec<_>>(),
        f64::NAN,
    );
    let bb_idx: Vec<i64> = (0..n_bb as i64).collect();
    let bb_dim =
        h5u::scale_coord(&g, l::BBCOR_DIM.name, &bb_idx, &l::BBCOR_DIM).ctx(out, &e("bbcor"))?;
    var(&l::BAT_BBCOR_Z, vec![nb, n_bb], bz, &[&bat, &bb_dim])?;
    var(&l::BAT_BBCOR, vec![nb, n_bb], bb, &[&bat, &bb_dim])?;
    let spec: Vec<VarLenUnicode> = info.bats.iter().map(|b| h5u::vlstr(&b.spec_json)).collect();
    let ds = h5u::write_1d(&g, l::BAT_SPEC.name, &spec).ctx(out, &e("spec"))?;
    describe(&ds, &l::BAT_SPEC).ctx(out, &e("spec"))?;
    att.add(&ds, &[&bat]);
    Ok(())
}

fn pad_to(v: &[f64], n: usize) -> Vec<f64> {
    let mut v = v.to_vec();
    v.truncate(n);
    v.resize(n, f64::NAN);
    v
}
