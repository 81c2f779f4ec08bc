//! Points handed over one at a time gathered into their groups (`results::PointGroups`):
//! a group's histories share chunks, so it is encoded once all of its points are there.
//! The merge of shards and the tests hand the session points one by one
//! (`Session::write`); a resume from a finished file reads them back in flat-index order.

use crate::results::{PointGroups, PointRecord};
use std::collections::BTreeMap;

/// The groups begun and not yet whole, by their first place.
#[derive(Debug)]
pub struct GroupGatherer {
    groups: PointGroups,
    open: BTreeMap<usize, Vec<PointRecord>>,
}

impl GroupGatherer {
    pub fn new(groups: PointGroups) -> Self {
        GroupGatherer {
            groups,
            open: BTreeMap::new(),
        }
    }

    /// Add a point (one already added is ignored); its group's points, in flat-index
    /// order, once the group is whole.
    pub fn add(&mut self, rec: PointRecord) -> Option<Vec<PointRecord>> {
        let (start, end) = (self.groups.start(rec.index), self.groups.end(rec.index));
        let members = self.open.entry(start).or_default();
        if let Err(at) = members.binary_search_by_key(&rec.index, |m| m.index) {
            members.insert(at, rec);
        }
        match members.len() == end - start {
            true => self.open.remove(&start),
            false => None,
        }
    }

    /// Forget the groups that begin before point `index`'s own (points read in flat-index
    /// order: those can no longer be whole). Returns how many points they held.
    pub fn drop_before(&mut self, index: usize) -> usize {
        let keep = self.open.split_off(&self.groups.start(index));
        let dropped = std::mem::replace(&mut self.open, keep);
        dropped.values().map(Vec::len).sum()
    }

    /// The groups that are not whole, each its points in flat-index order.
    pub fn into_rest(self) -> impl Iterator<Item = Vec<PointRecord>> {
        self.open.into_values()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(index: usize) -> PointRecord {
        PointRecord {
            index,
            id: index as u64,
            bat: 0,
            result: Err(String::new()),
        }
    }

    fn indices(v: &[PointRecord]) -> Vec<usize> {
        v.iter().map(|p| p.index).collect()
    }

    /// A group comes out when its last point arrives, whatever the order, in flat-index
    /// order; a row's short last group is whole with fewer points; what never completes
    /// is left, or dropped once points after it arrive.
    #[test]
    fn groups_come_out_whole_and_in_order() {
        let mut g = GroupGatherer::new(PointGroups::new(3, 5));
        assert!(g.add(point(2)).is_none());
        assert!(g.add(point(0)).is_none());
        assert!(g.add(point(0)).is_none(), "a point twice counts once");
        assert_eq!(indices(&g.add(point(1)).unwrap()), [0, 1, 2]);
        assert!(g.add(point(3)).is_none());
        assert_eq!(
            indices(&g.add(point(4)).unwrap()),
            [3, 4],
            "a row's last group"
        );
        assert!(g.add(point(6)).is_none());
        assert!(g.add(point(12)).is_none());
        assert_eq!(g.drop_before(11), 1, "group 5..8 can no longer be whole");
        let rest: Vec<Vec<usize>> = g.into_rest().map(|v| indices(&v)).collect();
        assert_eq!(rest, [vec![12]]);
    }
}
