//! The displacement's modal form in the store: the extents of its dims (the most
//! modes and shape points of the study's bats), a history's coordinates cut into blocks of
//! [`layout::MODE_BLOCK`] modes, and a bat's mode shapes cut the same way for
//! `/bat/mode_shape`. A block is mode-major ([mode][time], [mode][shape point]) and ends in
//! zero rows after the modes it holds.

use super::layout::MODE_BLOCK;
use crate::results::{ShapeSource, StudyInfo};
use std::ops::Range;

/// The modal form's dims: the most modes and shape points of a study's bats, and the modes
/// per chunk.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ModalExtents {
    pub modes: usize,
    pub block: usize,
    pub points: usize,
}

impl ModalExtents {
    /// The extents of a study's bats (zero when none has shapes).
    pub fn of(info: &StudyInfo) -> Self {
        let (modes, points) = info
            .bats
            .iter()
            .filter_map(|b| b.shapes.as_ref())
            .fold((0, 0), |(m, p), s| (m.max(s.modes), p.max(s.z.len())));
        ModalExtents {
            modes,
            block: MODE_BLOCK.min(modes).max(1),
            points,
        }
    }
}

/// Rows up to the last one holding a value other than +0.0 (bit for bit: −0.0 is kept).
fn rows_used(q: &[f64], n_samples: usize) -> usize {
    let modes = q.len() / n_samples.max(1);
    (0..modes)
        .rev()
        .find(|&j| (0..n_samples).any(|t| q[t * modes + j].to_bits() != 0))
        .map_or(0, |j| j + 1)
}

/// The modes of each block of a history's coordinates (row-major [time][modes]): blocks of
/// `block` modes, as many as reach the last mode with a value other than +0.0, each up to
/// that mode (the rest of its rows are zero). A history read back from the file (zeros
/// after its blocks) so gives the same blocks as the run that computed it.
pub fn coordinate_block_rows(q: &[f64], n_samples: usize, block: usize) -> Vec<Range<usize>> {
    let used = rows_used(q, n_samples);
    (0..used.div_ceil(block))
        .map(|b| b * block..((b + 1) * block).min(used))
        .collect()
}

/// A history's coordinates (row-major [time][modes]) as blocks of `block` modes, each
/// mode-major ([mode][time]), zero rows after the last mode: the chunks of
/// [`coordinate_block_rows`] as values.
pub fn coordinate_blocks(q: &[f64], n_samples: usize, block: usize) -> Vec<Vec<f64>> {
    let modes = q.len() / n_samples.max(1);
    coordinate_block_rows(q, n_samples, block)
        .into_iter()
        .map(|rows| mode_major_block(q, modes, n_samples, rows, block))
        .collect()
}

/// Modes `rows` of `q` (row-major [time][`modes`]) mode-major ([mode][time]), then zero
/// rows up to `block` modes: one block's values as its chunk holds them.
pub fn mode_major_block(
    q: &[f64],
    modes: usize,
    n_samples: usize,
    rows: Range<usize>,
    block: usize,
) -> Vec<f64> {
    let mut out: Vec<f64> = rows
        .flat_map(|j| (0..n_samples).map(move |t| q[t * modes + j]))
        .collect();
    out.resize(block * n_samples, 0.0);
    out
}

/// Mode-major blocks (`rows` × `n_samples`, zero rows beyond the data) back to row-major
/// [time][rows] coordinates: the inverse of [`coordinate_blocks`] for the file's reader.
pub fn coordinates_from_mode_major(rows: &[f64], n_samples: usize) -> Vec<f64> {
    let modes = rows.len() / n_samples.max(1);
    let mut q = vec![0.0; rows.len()];
    for j in 0..modes {
        for t in 0..n_samples {
            q[t * modes + j] = rows[j * n_samples + t];
        }
    }
    q
}

/// `values` padded with NaN to `n` (a bat with fewer shape points than the study's most).
pub fn padded_points(values: &[f64], n: usize) -> Vec<f64> {
    let mut v = values.to_vec();
    v.resize(n.max(v.len()), f64::NAN);
    v
}

/// Block `b` of a bat's mode shapes for `/bat/mode_shape`: modes b·block.. (zero rows
/// beyond its modes), each row its shape points padded with NaN.
pub fn shape_block(source: &ShapeSource, b: usize, ext: &ModalExtents) -> Vec<f64> {
    let first = (b * ext.block).min(source.modes);
    let last = ((b + 1) * ext.block).min(source.modes);
    let shapes = (source.shapes)(first..last);
    let own = source.z.len();
    let mut out = vec![0.0; ext.block * ext.points];
    for (r, row) in shapes.chunks_exact(own.max(1)).enumerate() {
        out[r * ext.points..][..ext.points].copy_from_slice(&padded_points(row, ext.points));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    // Blocks reach the last mode that holds a value (−0.0 included), zero rows after it,
    // and read back to the same coordinates.
    #[test]
    fn blocks_reach_the_last_mode_with_a_value() {
        let (t, modes, block) = (3, 5, 2);
        let mut q: Vec<f64> = (0..t * modes).map(|k| k as f64 + 1.0).collect();
        for tt in 0..t {
            q[tt * modes + 4] = 0.0; // mode 4 never moves
        }
        let b = coordinate_blocks(&q, t, block);
        assert_eq!(b.len(), 2, "modes 0..4 in two blocks of two");
        assert_eq!(b[1][..t], [3.0, 8.0, 13.0], "mode 2 over time");
        let rows: Vec<f64> = b.concat();
        let back = coordinates_from_mode_major(&rows, t);
        for tt in 0..t {
            assert_eq!(back[tt * 4..tt * 4 + 4], q[tt * modes..tt * modes + 4]);
        }
        q[modes + 4] = -0.0;
        assert_eq!(coordinate_blocks(&q, t, block).len(), 3, "−0.0 is a value");
        assert!(coordinate_blocks(&[0.0; 6], 3, 2).is_empty());
    }
}
