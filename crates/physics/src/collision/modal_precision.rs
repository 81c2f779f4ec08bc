//! The modal form's stored precision. With `history.precision: f32`, the grid
//! form keeps y(z, t) to f32 rounding; the modal form keeps its coordinates, bat load and
//! static shape to the precision that gives y(z, t) to the same rounding, and no finer.
//!
//! Every variable is rounded to a power-of-two step, in f64 (its low bits then zero, which
//! shuffle and deflate store in almost nothing), chosen so that the error of the sum
//! y = Σ_j φ_j q_j + s p stays within half an f32 ulp of the history's largest |y|, Y:
//! rounding q_j to a step δ_j moves y at most by Φ_j δ_j / 2 anywhere on the bat (Φ_j: the
//! largest |φ_j| over the shape points; between them y is linear), and the budget is split
//! evenly over the terms (equal shares are what minimise the bits kept, for a sum of
//! logarithms under one linear bound). Y is bounded from below by y at three shape points
//! (the two ends and the largest static response), so the bound holds for the true Y.
//! The grid form's own f32 rounding adds another half ulp: the two forms agree within one
//! f32 ulp of Y, value by value (tested over every bundled history study).
//!
//! A plain f32 coordinate would not do: it keeps 24 bits of each coordinate's own size,
//! too few for the low modes, whose terms cancel (at worst 1.4 ulp of Y, measured), and
//! too many for the high modes and for every value near a zero crossing (13.8 KB against
//! 10.9 KB on the bench's history study).

use crate::outcome::ModalHistory;

/// What the rounding needs to know of a collision's modal basis (in the stored scale).
#[derive(Debug, Clone, Default)]
pub(crate) struct ModalRounding {
    /// Φ_j: the largest |φ_j| over the shape points, per stepped mode.
    shape_max: Vec<f64>,
    /// φ_j at the probe points, probe-major (`[probe][mode]`), and the static shape there.
    probe_shapes: Vec<Vec<f64>>,
    probe_static: Vec<f64>,
}

impl ModalRounding {
    /// The rounding of a modal form whose modes reach at most `shape_max` (one per stepped
    /// mode), whose static shape is `static_shape` (at the shape points) and whose stored
    /// shape of mode j at shape point p is `shape(p, j)`: probes at the two ends and where
    /// the static response is largest.
    pub fn new(
        shape_max: &[f64],
        static_shape: &[f64],
        shape: impl Fn(usize, usize) -> f64,
    ) -> Self {
        let points = static_shape.len();
        let largest_static = (0..points)
            .max_by(|&a, &b| static_shape[a].abs().total_cmp(&static_shape[b].abs()))
            .unwrap_or(0);
        let probes: Vec<usize> = match points {
            0 => Vec::new(),
            _ => vec![0, points - 1, largest_static],
        };
        ModalRounding {
            shape_max: shape_max.to_vec(),
            probe_shapes: probes
                .iter()
                .map(|&p| (0..shape_max.len()).map(|j| shape(p, j)).collect())
                .collect(),
            probe_static: probes.iter().map(|&p| static_shape[p]).collect(),
        }
    }

    /// A lower bound of the history's largest |y|: the largest at the probe points.
    fn largest_displacement(&self, m: &ModalHistory) -> f64 {
        let n = m.modes;
        let probes = match self.probe_shapes.as_slice() {
            [a, b, c] if a.len() == n && b.len() == n && c.len() == n && n > 0 => [a, b, c],
            _ => return self.largest_displacement_by_probe(m),
        };
        let phi = [&probes[0][..n], &probes[1][..n], &probes[2][..n]];
        let zero = vec![0.0; n];
        let mut largest = 0.0_f64;
        // four samples at a time, the three probes' sums of each side by side, every sum in
        // the order of its modes: twelve independent chains where three would wait on each
        // addition, each sum the same as one at a time
        for (g, four) in m.coordinate.chunks(4 * n).enumerate() {
            let row = |r: usize| &four.get(r * n..(r + 1) * n).unwrap_or(&zero)[..n];
            let q = [row(0), row(1), row(2), row(3)];
            let mut y = [[0.0_f64; 3]; 4];
            for j in 0..n {
                let at = [phi[0][j], phi[1][j], phi[2][j]];
                for (yr, qr) in y.iter_mut().zip(&q) {
                    let qj = qr[j];
                    for (yk, a) in yr.iter_mut().zip(at) {
                        *yk += a * qj;
                    }
                }
            }
            for (r, yr) in y.iter().enumerate().take(four.len() / n) {
                let p = m.bat_load.get(4 * g + r).copied().unwrap_or(0.0);
                for (yk, s) in yr.iter().zip(&self.probe_static) {
                    largest = largest.max((yk + s * p).abs());
                }
            }
        }
        largest
    }

    /// [`Self::largest_displacement`] one probe at a time (any number of probes).
    fn largest_displacement_by_probe(&self, m: &ModalHistory) -> f64 {
        let n = m.modes;
        let mut largest = 0.0_f64;
        for (t, q) in m.coordinate.chunks_exact(n.max(1)).enumerate() {
            let p = m.bat_load.get(t).copied().unwrap_or(0.0);
            for (phi, s) in self.probe_shapes.iter().zip(&self.probe_static) {
                let y: f64 = phi.iter().zip(q).map(|(a, b)| a * b).sum::<f64>() + s * p;
                largest = largest.max(y.abs());
            }
        }
        largest
    }

    /// Round `m` in place to the precision that keeps y within half an f32 ulp of its
    /// largest |y| (module docs). A history that does not move is left as it is.
    pub fn round(&self, m: &mut ModalHistory) {
        let y_max = self.largest_displacement(m);
        if !(y_max > 0.0 && y_max.is_finite()) || m.modes != self.shape_max.len() {
            return;
        }
        // a share for each mode, the load, the shape, and the product of the load's and the
        // shape's errors (at most a share: neither error exceeds its value)
        let terms = (m.modes + 3) as f64;
        let share = 0.5 * f32_ulp(y_max) / terms;
        let steps: Vec<Step> = self
            .shape_max
            .iter()
            .map(|&phi| Step::new(step_for(share, phi)))
            .collect();
        for row in m.coordinate.chunks_exact_mut(m.modes.max(1)) {
            for (q, &step) in row.iter_mut().zip(&steps) {
                *q = round_to(*q, step);
            }
        }
        let largest = |v: &[f64]| v.iter().fold(0.0_f64, |a, x| a.max(x.abs()));
        let (s_max, p_max) = (largest(&m.static_shape), largest(&m.bat_load));
        let load_step = Step::new(step_for(share, s_max));
        m.bat_load
            .iter_mut()
            .for_each(|p| *p = round_to(*p, load_step));
        let shape_step = Step::new(step_for(share, p_max));
        m.static_shape
            .iter_mut()
            .for_each(|s| *s = round_to(*s, shape_step));
    }
}

/// The spacing of f32 values at `y` (> 0, normal): 2^(exponent − 23).
fn f32_ulp(y: f64) -> f64 {
    let y = y as f32;
    (f32::from_bits(y.to_bits() + 1) - y) as f64
}

/// The largest power of two δ with δ/2 · `weight` ≤ `share` (no rounding, 0, when the
/// weight is 0: the variable does not reach y): 2·share/weight with its mantissa cleared.
fn step_for(share: f64, weight: f64) -> f64 {
    let bound = 2.0 * share / weight;
    match weight > 0.0 && bound.is_normal() {
        true => f64::from_bits(bound.to_bits() & 0x7FF0_0000_0000_0000),
        false => 0.0,
    }
}

/// Adding and subtracting 1.5 · 2^52 rounds a float of magnitude below 2^51 to an integer
/// (to the nearest, ties to even), in two additions where `f64::round` is a libm call.
const ROUND_TO_INTEGER: f64 = 6_755_399_441_055_744.0;

/// A power-of-two step and its reciprocal, computed once: a division for every value
/// rounded would be most of the rounding's time.
#[derive(Debug, Clone, Copy)]
struct Step {
    size: f64,
    inverse: f64,
}

impl Step {
    fn new(size: f64) -> Self {
        Step {
            size,
            inverse: 1.0 / size, // exact: a power of two (∞ for 0, which keeps x)
        }
    }
}

/// `x` to the nearest multiple of `step` (a power of two; 0 keeps x): exact in f64, the
/// product by the reciprocal and by the step only move the exponent. +0.0 for zero (a −0.0
/// would count as a value when the store trims zero modes). A value already coarser than
/// the step (|x| ≥ 2^51 steps) is kept as it is.
#[inline(always)]
fn round_to(x: f64, step: Step) -> f64 {
    let y = x * step.inverse;
    let rounded = ((y + ROUND_TO_INTEGER) - ROUND_TO_INTEGER) * step.size;
    // a step is 0 or a normal power of two (`step_for`); for 0 the reciprocal is ∞ and y is
    // ±∞ or NaN, which fail the test: one comparison, a select the loops vectorise
    match y.abs() < 2_251_799_813_685_248.0 {
        true => rounded,
        false => x,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // Rounding to a power of two is exact and within half a step; the steps meet the share.
    #[test]
    fn rounding_is_within_half_a_step() {
        let step = 2f64.powi(-30);
        for x in [1.234_567_890_123e-3, -7.7e-9, 3.0e-10, -1.0e-12, 0.0] {
            let r = round_to(x, Step::new(step));
            assert!((r - x).abs() <= step / 2.0, "{x}");
            assert_eq!((r / step).fract(), 0.0, "{x}: a multiple of the step");
            assert!(r.to_bits() != (-0.0_f64).to_bits(), "{x}: no −0.0");
        }
        for (share, w) in [(1e-12, 3.0), (2.5e-9, 0.7), (1e-3, 1e-9)] {
            let d = step_for(share, w);
            assert!(
                d / 2.0 * w <= share && d * w > share,
                "{share} {w}: the largest"
            );
        }
        assert_eq!(f32_ulp(1.0), 2f64.powi(-23));
        assert_eq!(f32_ulp(1.5e-3), 2f64.powi(-10 - 23));
    }

    // The bound, on a made-up basis: three modes whose terms cancel, a static term; the
    // rounded sum stays within half an f32 ulp of the largest |y| at every shape point.
    #[test]
    fn rounded_sum_within_half_an_ulp_of_the_largest() {
        let points = 9;
        let shape = |j: usize| -> Vec<f64> {
            (0..points)
                .map(|i| ((j + 1) as f64 * 0.37 * i as f64).cos() * (1.0 + j as f64))
                .collect()
        };
        let static_shape: Vec<f64> = (0..points).map(|i| 1e-8 * (i as f64 - 3.0)).collect();
        let (modes, samples) = (3, 50);
        let mut m = ModalHistory {
            modes,
            coordinate: (0..modes * samples)
                .map(|k| {
                    1e-3 * ((k * 7919 % 1000) as f64 / 1000.0 - 0.5)
                        * 0.3f64.powi((k % modes) as i32)
                })
                .collect(),
            bat_load: (0..samples)
                .map(|t| 4e3 * (t as f64 * 0.2).sin().max(0.0))
                .collect(),
            static_shape: static_shape.clone(),
        };
        let y = |m: &ModalHistory| -> Vec<f64> {
            let mut out = Vec::new();
            for t in 0..samples {
                for i in 0..points {
                    let q = &m.coordinate[t * modes..][..modes];
                    let s: f64 = (0..modes).map(|j| shape(j)[i] * q[j]).sum();
                    out.push(s + m.static_shape[i] * m.bat_load[t]);
                }
            }
            out
        };
        let exact = y(&m);
        let shape_max: Vec<f64> = (0..modes)
            .map(|j| shape(j).iter().fold(0.0_f64, |m, x| m.max(x.abs())))
            .collect();
        let r = ModalRounding::new(&shape_max, &static_shape, |p, j| shape(j)[p]);
        r.round(&mut m);
        let largest = exact.iter().fold(0.0_f64, |a, x| a.max(x.abs()));
        let worst = exact
            .iter()
            .zip(y(&m))
            .fold(0.0_f64, |a, (e, r)| a.max((e - r).abs()));
        assert!(
            worst <= 0.5 * f32_ulp(largest),
            "{worst} vs {}",
            f32_ulp(largest)
        );
        assert!(worst > 0.0, "the values were rounded");
    }
}
