//! `--shard I/N`: the I-th (1-based) of N disjoint subsets of a study's points.
//! Points are dealt round-robin by flat index (point k goes to shard k mod N + 1): the
//! subsets are deterministic, differ in size by at most one, and, since neighbouring
//! points cost about the same, balanced in run time.

use std::fmt;
use std::str::FromStr;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// 1-based shard number.
    pub index: usize,
    /// Number of shards.
    pub count: usize,
}

impl Shard {
    /// Does this shard own the point with this flat index?
    pub fn owns(&self, flat: usize) -> bool {
        flat % self.count == self.index - 1
    }
    /// Number of points of an `n`-point study in this shard.
    pub fn size(&self, n: usize) -> usize {
        n / self.count + usize::from(n % self.count >= self.index)
    }
}

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

#[cfg(test)]
mod tests {
    use super::*;

    // issue 8: disjoint, deterministic, balanced subsets
    #[test]
    fn shards_partition() {
        let n = 103;
        let shards: Vec<Shard> = (1..=4).map(|i| format!("{i}/4").parse().unwrap()).collect();
        let mut owners = vec![0; n];
        for s in &shards {
            let c = (0..n).filter(|&k| s.owns(k)).count();
            assert_eq!(c, s.size(n));
            assert!(c == 25 || c == 26);
            for (k, o) in owners.iter_mut().enumerate() {
                if s.owns(k) {
                    *o += 1;
                }
            }
        }
        assert!(owners.iter().all(|&o| o == 1));
        assert!("0/4".parse::<Shard>().is_err());
        assert!("5/4".parse::<Shard>().is_err());
        assert!("x".parse::<Shard>().is_err());
    }
}
