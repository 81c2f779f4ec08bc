//! One window's summary values: the records of a run of consecutive blocks placed at their
//! points (the first record of a point wins), with the counts and the failed points; and
//! [`Gathered`], the one window of a small study filled as the run writes its records.

use super::grid::{plan_windows, summary_chunk, BlockGrid};
use crate::layout::{self as l, N_SUMMARY_FLOATS};
use crate::results::{PointRecord, StudyInfo};

/// Summary values of a run of consecutive blocks, concatenated (block `b0 + q` starts at
/// `offsets[q]`).
pub(super) struct Window {
    pub(super) offsets: Vec<usize>,
    pub(super) floats: Vec<Vec<f64>>,
    pub(super) recontact: Vec<i8>,
    pub(super) status: Vec<i8>,
    pub(super) point_id: Vec<u64>,
    pub(super) bat_index: Vec<i32>,
}

impl Window {
    /// An empty window over blocks `[b0, b1)`.
    pub(super) fn of_blocks(blocks: &BlockGrid, b0: usize, b1: usize) -> Self {
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
    pub(super) fn put(
        &mut self,
        rec: &PointRecord,
        blocks: &BlockGrid,
        b0: usize,
        b1: usize,
        t: &mut Tally,
    ) {
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
pub(super) struct Tally {
    pub(super) n_done: usize,
    pub(super) n_failed: usize,
    pub(super) errors: Vec<(u64, u64, String)>,
}

impl Tally {
    pub(super) fn add(&mut self, other: Tally) {
        self.n_done += other.n_done;
        self.n_failed += other.n_failed;
        self.errors.extend(other.errors);
    }
}

/// The summary of a study that fits one build window, gathered from the records as the run
/// writes them, so that `fill` need not read the journal back (on a small study that read
/// is a fifth of finishing the file). Only for a session that saw every record
/// it stores: a resumed one reads its journal as before.
pub struct Gathered {
    blocks: BlockGrid,
    pub(super) window: Window,
    pub(super) tally: Tally,
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
