//! Histories placed in the final file while the run goes on.
//!
//! The final file holds the history chunks in flat-index order, so that it is the same
//! whatever the thread count. Writing them all at the end put one serial pass over every
//! history (about a quarter of a history study's wall time on 2 cores) after the last point.
//! The placer writes them during the run instead: the runner dispatches points in index
//! order, so records arrive nearly in order; each one at the placer's cursor is written at
//! once, the few that overtake it are held until the gap fills. The finish writes what is
//! left, in the same order, so the file does not depend on how far the placer got.
//!
//! Held records are bounded ([`HELD_BYTES`] by default): past that (a point far slower than the rest
//! holds the cursor) the placer gives up and the finish reads the rest from the journal.

use super::build::HistoryTail;
use crate::pointset::PointSet;
use std::collections::BTreeMap;

/// Default of the most bytes of records held ahead of the cursor (a few hundred history
/// points; `StoreOptions::history_hold`).
pub const HELD_BYTES: usize = 64 << 20;

/// What the placer asks of the session for each record, in flat-index order.
pub trait Place {
    type Error;
    /// Write this point's histories (`framed`: its journal record) into the final file.
    fn place(&mut self, index: usize, framed: &[u8]) -> Result<(), Self::Error>;
}

/// The cursor over the run's flat indices and the records that arrived ahead of it.
#[derive(Debug)]
pub struct HistoryPlacer {
    /// Every point before this one is stored, and its histories written.
    next: usize,
    /// The end of the run's range of points (a shard's, or the study's).
    end: usize,
    held: BTreeMap<usize, Vec<u8>>,
    held_bytes: usize,
    /// Most bytes held before giving up.
    hold: usize,
}

impl HistoryPlacer {
    /// A placer for a run of the points `start..end` into a journal that holds none yet,
    /// holding at most `hold` bytes of records ahead of its cursor.
    pub fn new(start: usize, end: usize, hold: usize) -> Self {
        Self {
            next: start,
            end,
            held: BTreeMap::new(),
            held_bytes: 0,
            hold,
        }
    }

    /// The framed record of point `index`, if it is held ahead of the cursor.
    pub fn held(&self, index: usize) -> Option<&[u8]> {
        self.held.get(&index).map(Vec::as_slice)
    }

    /// Point `index` has just been stored (`done` says which points are), with its framed
    /// record when it has histories. Writes every history the cursor can now pass, in order.
    /// Returns false when the placer gives up (too much held): call [`Self::tail`] then.
    pub fn arrived<P: Place>(
        &mut self,
        index: usize,
        framed: Option<Vec<u8>>,
        done: &PointSet,
        sink: &mut P,
    ) -> Result<bool, P::Error> {
        if let Some(f) = framed {
            if index == self.next {
                sink.place(index, &f)?;
                self.next += 1;
            } else {
                self.held_bytes += f.len();
                self.held.insert(index, f);
            }
        }
        while self.next < self.end && done.contains(self.next) {
            if let Some(f) = self.held.remove(&self.next) {
                self.held_bytes -= f.len();
                sink.place(self.next, &f)?;
            }
            self.next += 1;
        }
        Ok(self.held_bytes <= self.hold)
    }

    /// The histories still to write: those held, when the placer kept up; else every one
    /// from the cursor on, from the journal.
    pub fn tail(self, kept_up: bool) -> HistoryTail {
        if kept_up {
            HistoryTail::Held(self.held)
        } else {
            HistoryTail::Journal { from: self.next }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Records the order in which histories are placed.
    struct Order(Vec<usize>);
    impl Place for Order {
        type Error = ();
        fn place(&mut self, index: usize, _: &[u8]) -> Result<(), ()> {
            self.0.push(index);
            Ok(())
        }
    }

    /// Whatever the arrival order, histories are placed in increasing index order, each
    /// once, and what the cursor could not pass is left in the tail, in order.
    #[test]
    fn places_in_index_order_whatever_the_arrival() {
        let n = 10;
        // 3 has no history; 7 never arrives (an interrupted run)
        let arrival = [1, 0, 2, 5, 3, 4, 9, 6, 8];
        let mut done = PointSet::new(n);
        let mut p = HistoryPlacer::new(0, n, HELD_BYTES);
        let mut out = Order(Vec::new());
        for &i in &arrival {
            done.insert(i);
            let framed = (i != 3).then(|| vec![0u8; 16]);
            assert!(p.arrived(i, framed, &done, &mut out).unwrap());
        }
        assert_eq!(out.0, vec![0, 1, 2, 4, 5, 6]);
        match p.tail(true) {
            HistoryTail::Held(h) => assert_eq!(h.keys().copied().collect::<Vec<_>>(), [8, 9]),
            HistoryTail::Journal { .. } => panic!("kept up"),
        }
    }

    /// A shard's placer starts at its range; one that gives up hands the journal its cursor.
    #[test]
    fn shard_start_and_giving_up() {
        let mut done = PointSet::new(100);
        let mut p = HistoryPlacer::new(40, 60, 1000);
        let mut out = Order(Vec::new());
        done.insert(41);
        assert!(!p
            .arrived(41, Some(vec![0u8; 1001]), &done, &mut out)
            .unwrap());
        assert!(out.0.is_empty());
        match p.tail(false) {
            HistoryTail::Journal { from } => assert_eq!(from, 40),
            HistoryTail::Held(_) => panic!("gave up"),
        }
    }
}
