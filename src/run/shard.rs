//! `--shard I/N`: the I-th (1-based) of N disjoint subsets of a study's points.
//!
//! Each shard is one contiguous block of flat indices, cut so that every shard carries about
//! the same *estimated* cost: point `i` goes to shard `⌊N·(C_i + c_i/2)/C⌋ + 1`, where `c_i`
//! is its estimated cost, `C_i` the cost of the points before it and `C` the total. The shard
//! number never decreases along the flat index, so the shards are contiguous blocks that
//! partition the study; each shard's cost differs from `C/N` by less than the costliest point.
//!
//! The estimate ([`estimate_cost`]) is a rough model of run time from the resolved spec:
//! the wave model costs thousands of times more than the rigid one, Verlet more than the
//! modal integrator, finer explicit steps and histories more. It only depends on the
//! parameters of `model`, `numerics` and `hoop` (and on the study's history request), so it
//! is tabulated once per combination of the dims that sweep those parameters, and the split
//! is one streaming pass over the flat indices with O(1) memory: cheap and deterministic
//! (a plain sequential f64 sum) even for millions of points.

use crate::model::outcome::{HistoryField, HistoryRequest};
use crate::model::spec::{CollisionSpec, Integrator, ModelKind};
use crate::study::Plan;
use std::fmt;
use std::ops::Range;
use std::str::FromStr;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// 1-based shard number.
    pub index: usize,
    /// Number of shards.
    pub count: usize,
}

/// Most shards a study may be split into (a bound, so that a huge N is an error, not a panic).
pub const MAX_SHARDS: usize = 1_000_000;

impl FromStr for Shard {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        let (i, n) = s
            .split_once('/')
            .ok_or_else(|| format!("`{s}`: expected I/N, e.g. 1/4"))?;
        let index: usize = i
            .trim()
            .parse()
            .map_err(|_| format!("`{i}` is not a whole number"))?;
        let count: usize = n
            .trim()
            .parse()
            .map_err(|_| format!("`{n}` is not a whole number"))?;
        if count > MAX_SHARDS {
            return Err(format!(
                "`{s}`: at most {MAX_SHARDS} shards (Slurm's largest arrays are smaller)"
            ));
        }
        if count == 0 || index == 0 || index > count {
            return Err(format!(
                "`{s}`: need 1 <= I <= N (shards are numbered from 1)"
            ));
        }
        Ok(Shard { index, count })
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

/// Estimated run time of one collision, in seconds on one core (rough, for balancing shards;
/// only the ratios matter).
pub fn estimate_cost(spec: &CollisionSpec, history: Option<&HistoryRequest>) -> f64 {
    match spec.model {
        ModelKind::Rigid => 2e-6,
        ModelKind::Wave => {
            let mut c = 5e-3;
            if spec.numerics.integrator == Integrator::Verlet {
                // steps at the stability limit of the highest beam mode
                c *= 20.0;
            }
            if let Some(dt) = spec.numerics.dt {
                // the automatic step is about a microsecond
                c *= (1e-6 / dt).clamp(0.05, 1e3);
            }
            if let Some(s) = spec.numerics.segments {
                c *= (s as f64 / 100.0).clamp(0.25, 100.0);
            }
            if spec.hoop.is_some() {
                c *= 1.2;
            }
            if let Some(h) = history {
                let series: usize = h
                    .fields
                    .iter()
                    .map(|f| match f {
                        HistoryField::Displacement => h.z.len().max(1),
                        HistoryField::RigidMotion => 2,
                        HistoryField::Trajectory => 0,
                        _ => 1,
                    })
                    .sum();
                // sampling (the modal sum per z) and storing
                c += 5e-8 * (h.n_samples * series) as f64;
            }
            c
        }
    }
}

/// Most combinations of cost-relevant dims tabulated; beyond, every point costs the same.
const MAX_TABLE: usize = 1 << 16;

/// Per-point estimated costs of a plan, tabulated over the dims that change them.
#[derive(Debug, Clone)]
pub struct CostModel {
    /// (flat-index stride, size, table stride) of each cost-relevant dim.
    dims: Vec<(usize, usize, usize)>,
    table: Vec<f64>,
    n: usize,
}

fn cost_path(p: &str) -> bool {
    ["model", "numerics", "hoop"]
        .iter()
        .any(|k| p == *k || p.starts_with(&format!("{k}.")) || k.starts_with(&format!("{p}.")))
        || p.is_empty()
}

impl CostModel {
    pub fn new(plan: &Plan, history: Option<&HistoryRequest>) -> CostModel {
        let shape = plan.shape();
        let n = plan.n_points();
        let nd = shape.dims.len();
        let mut strides = vec![1usize; nd];
        for k in (0..nd.saturating_sub(1)).rev() {
            strides[k] = strides[k + 1] * shape.dims[k + 1].size;
        }
        let relevant: Vec<usize> = (0..nd)
            .filter(|&k| plan.dims()[k].params.iter().any(|(p, _)| cost_path(p)))
            .collect();
        let combos: usize = relevant.iter().map(|&k| shape.dims[k].size).product();
        if n == 0 || combos > MAX_TABLE {
            return CostModel {
                dims: vec![],
                table: vec![1.0],
                n,
            };
        }
        let mut dims = Vec::new();
        let mut tstride = 1;
        for &k in relevant.iter().rev() {
            dims.push((strides[k], shape.dims[k].size, tstride));
            tstride *= shape.dims[k].size;
        }
        let table = (0..combos)
            .map(|c| {
                // the combination's point with every other dim at 0
                let flat: usize = dims.iter().map(|&(s, m, t)| (c / t % m) * s).sum();
                let mut multi = shape.unravel(flat);
                let first = plan.resolve(&multi);
                let spec = first.or_else(|_| {
                    // that point is invalid: try the others along the first irrelevant dim
                    let free = (0..nd).find(|k| !relevant.contains(k));
                    let mut r = Err(());
                    if let Some(f) = free {
                        for i in 1..shape.dims[f].size {
                            multi[f] = i;
                            if let Ok(s) = plan.resolve(&multi) {
                                r = Ok(s);
                                break;
                            }
                        }
                    }
                    r
                });
                match spec {
                    Ok(s) => estimate_cost(&s, history),
                    // invalid points fail at once
                    Err(_) => 1e-6,
                }
            })
            .collect();
        CostModel { dims, table, n }
    }

    /// Estimated cost of the point with this flat index.
    pub fn cost(&self, flat: usize) -> f64 {
        let c: usize = self.dims.iter().map(|&(s, m, t)| (flat / s % m) * t).sum();
        self.table[c]
    }

    /// Total estimated cost of the study.
    pub fn total(&self) -> f64 {
        (0..self.n).map(|i| self.cost(i)).sum()
    }

    /// Every shard's block of flat indices (`count` ranges that partition `0..n`, in order).
    pub fn split(&self, count: usize) -> Vec<Range<usize>> {
        assert!(count >= 1);
        let total = self.total();
        let mut bounds = vec![0usize; count + 1];
        bounds[count] = self.n;
        let mut before = 0.0;
        let mut next = 1; // the next shard whose start is not yet known
        for i in 0..self.n {
            let c = self.cost(i);
            let s = if total > 0.0 {
                (((before + 0.5 * c) / total * count as f64) as usize).min(count - 1)
            } else {
                i * count / self.n
            };
            // shard s (0-based) starts at i at the latest
            while next <= s {
                bounds[next] = i;
                next += 1;
            }
            before += c;
        }
        while next < count {
            bounds[next] = self.n;
            next += 1;
        }
        (0..count).map(|k| bounds[k]..bounds[k + 1]).collect()
    }

    /// The block of flat indices of one shard.
    pub fn range(&self, shard: Shard) -> Range<usize> {
        self.split(shard.count)
            .swap_remove(shard.index.clamp(1, shard.count) - 1)
    }
}

/// The block of flat indices of `shard` in `plan` (see the module docs), its ends moved
/// back to the start of their group where points share history chunks
/// (`store::layout::history_groups_of`): a chunk is never split between two shards' files.
pub fn shard_range(plan: &Plan, history: Option<&HistoryRequest>, shard: Shard) -> Range<usize> {
    let groups = crate::store::layout::history_groups_of(history, plan.shape());
    let r = CostModel::new(plan, history).range(shard);
    let start = |i: usize| match i < plan.n_points() {
        true => groups.start(i),
        false => i,
    };
    start(r.start)..start(r.end)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::study::{load_str, LoadOptions};
    use std::path::Path;

    fn plan(text: &str) -> Plan {
        load_str(text, Path::new("t.yaml"), &LoadOptions::default())
            .unwrap()
            .plan
    }

    // where the histories of a group of points share a chunk (the modal form),
    // every shard begins and ends on a group's start, so no chunk is split between shards,
    // and the shards still partition the study
    #[test]
    fn shards_end_on_group_boundaries() {
        let text = "name: t\nbase: {impact: {z: 0.7}}\ngrid:\n  swing.omega: [0, -10, -20, -30]\n  impact.z: {range: [0.5, 0.8, 0.01]}\nhistory: {fields: [force, displacement], interval: 1.0e-5, duration: 2.0e-3, z_step: 0.01, displacement: modal}\n";
        let study = load_str(text, Path::new("t.yaml"), &LoadOptions::default()).unwrap();
        let request = study.history_request(0.84).expect("histories");
        let groups = crate::store::layout::history_groups_of(Some(&request), study.plan.shape());
        assert_eq!(groups.size(), crate::store::layout::MODAL_HISTORY_GROUP);
        let n = study.plan.n_points();
        for count in [2, 3, 5, 7] {
            let ranges: Vec<Range<usize>> = (1..=count)
                .map(|index| shard_range(&study.plan, Some(&request), Shard { index, count }))
                .collect();
            assert_eq!((ranges[0].start, ranges[count - 1].end), (0, n));
            for (a, b) in ranges.iter().zip(&ranges[1..]) {
                assert_eq!(a.end, b.start, "{count} shards");
                assert_eq!(groups.start(b.start), b.start, "{count} shards: {b:?}");
            }
        }
    }

    // disjoint, deterministic, balanced by estimated cost
    #[test]
    fn shards_partition_by_cost() {
        let p = plan(
            "name: t\nbase: {impact: {z: 0.7}}\ngrid:\n  model: [rigid, wave]\n  impact.z: {range: [0.5, 0.8, 0.01]}\n  swing.omega: [0, -10, -20]\n",
        );
        let m = CostModel::new(&p, None);
        let n = p.n_points();
        for count in 1..=7 {
            let r = m.split(count);
            assert_eq!(r.len(), count);
            assert_eq!(r[0].start, 0);
            assert_eq!(r[count - 1].end, n);
            for w in r.windows(2) {
                assert_eq!(w[0].end, w[1].start);
            }
            let total = m.total();
            let max = (0..n).map(|i| m.cost(i)).fold(0.0, f64::max);
            for rg in &r {
                let c: f64 = rg.clone().map(|i| m.cost(i)).sum();
                assert!(
                    (c - total / count as f64).abs() <= max,
                    "{count}: {c} vs {total}"
                );
            }
            assert_eq!(r, m.split(count));
        }
        // the rigid half is nearly free: with 2 shards, shard 1 takes all rigid points and
        // half the wave points
        let r = m.split(2);
        assert!(r[0].end > n * 7 / 10, "{r:?}");
        assert!("0/4".parse::<Shard>().is_err());
        assert!("5/4".parse::<Shard>().is_err());
        assert!("x".parse::<Shard>().is_err());
    }

    #[test]
    fn more_shards_than_points() {
        let p = plan("name: t\nbase: {impact: {z: 0.7}}\ngrid:\n  impact.z: [0.6, 0.7]\n");
        let r = CostModel::new(&p, None).split(5);
        let sizes: Vec<usize> = r.iter().map(|r| r.len()).collect();
        assert_eq!(sizes.iter().sum::<usize>(), 2);
        assert_eq!(r.last().unwrap().end, 2);
    }
}
