//! The static shapes of a bat's histories in modal form, kept once computed.
//!
//! A history in modal form stores, per collision, the static response of the modes the
//! integrator does not step (`collision::wave::modal::record::install_modal`). It depends
//! only on the bat, the number of modes stepped and the contact point (node and weight),
//! and costs a pass over nearly all the bat's mode shapes: about 200 KB read, a fortieth of
//! a history point on the bench. A study varies much more than the impact point
//! (a grid of swing speeds at each of its positions), so most of its points ask again for a
//! shape computed before. The memo gives that shape back: the same bits, since it is the
//! same computation on the same inputs, whichever thread or point asked first.

use std::collections::HashMap;
use std::sync::{Arc, Mutex};

/// Most shapes a bat keeps (each one per shape point, about 170 values): enough for every
/// impact point of any grid study, and a bound of a few MB on a study of random points.
const MOST_SHAPES: usize = 4096;

/// What a static shape depends on besides its bat: the modes stepped, and the contact
/// point's node and weight (its bits: the same point, not a nearby one).
pub(crate) type StaticKey = (usize, usize, u64);

/// A bat's static shapes by [`StaticKey`]. Cloning a bat starts an empty memo (what it
/// holds is derived from the bat, and found again when needed).
#[derive(Default)]
pub(crate) struct StaticShapes {
    shapes: Mutex<HashMap<StaticKey, Arc<Vec<f64>>>>,
}

impl StaticShapes {
    /// The shape of `key`: kept, or made by `compute` (and kept while there is room). A
    /// memo poisoned by a panic elsewhere is passed by: the shape is computed.
    pub fn get_or_compute(
        &self,
        key: StaticKey,
        compute: impl FnOnce() -> Vec<f64>,
    ) -> Arc<Vec<f64>> {
        let kept = self.shapes.lock().ok().and_then(|m| m.get(&key).cloned());
        if let Some(shape) = kept {
            return shape;
        }
        let shape = Arc::new(compute());
        if let Ok(mut m) = self.shapes.lock() {
            if m.len() < MOST_SHAPES {
                m.entry(key).or_insert_with(|| Arc::clone(&shape));
            }
        }
        shape
    }

    /// The number of shapes kept.
    pub fn len(&self) -> usize {
        self.shapes.lock().map_or(0, |m| m.len())
    }
}

impl Clone for StaticShapes {
    fn clone(&self) -> Self {
        StaticShapes::default()
    }
}

impl std::fmt::Debug for StaticShapes {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("StaticShapes")
            .field("kept", &self.len())
            .finish()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // A shape is computed once per key and given back as it was; other keys are computed
    // anew; past the bound nothing more is kept, and what is asked is still computed.
    #[test]
    fn shapes_are_computed_once_per_key() {
        let memo = StaticShapes::default();
        let mut calls = 0;
        let a = memo.get_or_compute((21, 40, 0.25f64.to_bits()), || {
            calls += 1;
            vec![1.0, 2.0]
        });
        let b = memo.get_or_compute((21, 40, 0.25f64.to_bits()), || {
            calls += 1;
            vec![9.0]
        });
        assert_eq!((calls, &*a, &*b), (1, &vec![1.0, 2.0], &vec![1.0, 2.0]));
        let c = memo.get_or_compute((21, 40, 0.5f64.to_bits()), || vec![3.0]);
        assert_eq!(*c, vec![3.0]);
        for k in 0..MOST_SHAPES + 10 {
            memo.get_or_compute((0, k, 0), || vec![k as f64]);
        }
        assert_eq!(memo.len(), MOST_SHAPES);
        let past = memo.get_or_compute((0, MOST_SHAPES + 5, 0), || vec![-1.0]);
        assert_eq!(*past, vec![-1.0], "computed, not kept");
        assert_eq!(memo.clone().len(), 0, "a clone starts empty");
    }
}
