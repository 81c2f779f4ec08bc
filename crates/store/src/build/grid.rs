//! The chunk grid of the summary arrays: the chunk shape, the blocks (whole chunks) in
//! row-major order and where a point lies, and the windows of consecutive blocks the final
//! file is built in, each within the build's memory budget.

use crate::layout::{self as l, N_SUMMARY_FLOATS};
use crate::results::Dim;

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

/// The chunk grid of the summary arrays: blocks in row-major order, and where a point lies.
pub(super) struct BlockGrid {
    shape: Vec<usize>,
    chunk: Vec<usize>,
    grid: Vec<usize>,
}

impl BlockGrid {
    pub(super) fn new(shape: &[usize], chunk: &[usize]) -> Self {
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

    pub(super) fn n_points(&self) -> usize {
        self.shape.iter().product()
    }

    pub(super) fn n_blocks(&self) -> usize {
        if self.shape.contains(&0) {
            0
        } else {
            self.grid.iter().product()
        }
    }

    /// Start and extent of block `b`.
    pub(super) fn block(&self, b: usize) -> (Vec<usize>, Vec<usize>) {
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

    pub(super) fn block_len(&self, b: usize) -> usize {
        self.block(b).1.iter().product()
    }

    /// The block holding flat index `flat`, and its row-major position inside that block.
    pub(super) fn locate(&self, mut flat: usize) -> (usize, usize) {
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

/// Bytes a window holds per point.
const WINDOW_BYTES_PER_POINT: usize = 8 * N_SUMMARY_FLOATS + 1 + 1 + 8 + 4;

/// Most windows (spill files open at once); a bigger study gets bigger windows.
const MAX_WINDOWS: usize = 256;

/// Runs `[b0, b1)` of whole blocks, in order, each within the memory budget (at least one
/// block each, at most [`MAX_WINDOWS`] runs).
pub(super) fn plan_windows(blocks: &BlockGrid, memory: usize) -> Vec<(usize, usize)> {
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

/// `v` without its element `skip` (a shape or chunk without the `impact_z` dim).
pub(super) fn without<T: Copy>(v: &[T], skip: usize) -> Vec<T> {
    v.iter()
        .enumerate()
        .filter(|&(k, _)| k != skip)
        .map(|(_, &x)| x)
        .collect()
}
