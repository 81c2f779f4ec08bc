//! A window's blocks turned into what the file stores: each block's summary variables and
//! sweet spots as pieces, compressed on all cores and written in a fixed order.

use super::grid::{without, BlockGrid};
use super::sweet::block_sweet_spots;
use super::window::Window;
use crate::chunks;
use crate::dimscale as h5u;
use crate::error::{H5Ctx, StoreError};
use crate::layout::{self as l, N_SUMMARY_FLOATS};
use hdf5::Dataset;
use ndarray::{ArrayD, IxDyn};
use rayon::prelude::*;
use std::borrow::Cow;
use std::collections::BTreeMap;
use std::path::Path;
use std::sync::Mutex;

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

/// One block's values for one dataset (borrowed from the window: no copy of the window is
/// made), with the dataset's fill value (which pads an edge chunk).
pub(super) enum Values<'a> {
    F64(Cow<'a, [f64]>, f64),
    I8(Cow<'a, [i8]>, i8),
    I32(&'a [i32], i32),
    U64(&'a [u64], u64),
}

/// One block's contribution to one dataset (`targets[target]` in `fill`).
pub(super) enum Piece<'a> {
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
/// piece before it is written: the writes overlap the compression (compressing all, then
/// writing all, leaves one core idle for a third of a small study's finish), and the file
/// is laid out in the same order whatever the threads. Whoever finishes the next piece
/// writes it and the finished ones after it; a thread that finishes a later piece leaves it
/// queued and moves on.
pub(super) fn compress_and_write(
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
pub(super) fn block_pieces<'a>(
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
    let recontact = Values::I8(Cow::Borrowed(&w.recontact[r.clone()]), -1);
    let status = Values::I8(Cow::Borrowed(&w.status[r.clone()]), l::STATUS_NOT_COMPUTED);
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
        let (res, at_edge) = block_sweet_spots(&fv, &count, *iz, zc);
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
        let at = (&rs[..], &rcnt[..], &rchunk[..]);
        pieces.push(Piece::block(
            k + 4 + l::N_SWEET_FLOATS,
            at,
            Values::I8(Cow::Owned(at_edge), -1),
        ));
    }
    pieces
}
