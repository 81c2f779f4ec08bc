//! A profile smooth enough to turn: the shape-preserving piecewise-cubic Hermite
//! interpolant (PCHIP) through a design's knots, and its samples for the bat (whose profile
//! is linear between knots).
//!
//! PCHIP (Fritsch & Carlson 1980, SIAM J. Numer. Anal. 17, 238; the knot slopes of Fritsch
//! & Butland 1984, SIAM J. Sci. Stat. Comput. 5, 300, as in Moler, *Numerical Computing with
//! MATLAB*, ch. 3): the slope at a knot is the weighted harmonic mean of its two secants, or
//! zero where they differ in sign. The interpolant is C¹, monotone wherever the knots are,
//! and has no extremum between knots: a taper whose knots rise rises everywhere, and no waist
//! appears between knots.
//!
//! Curvature: a knot's slope lies between its two secants (a harmonic mean of numbers of one
//! sign lies between them), so on a segment of length h the cubic's r'' = (6δ − 4d₀ − 2d₁)/h
//! is bounded by (4|δ − d₀| + 2|δ − d₁|)/h: by the changes of secant at its ends. Bounding
//! the knots' second divided differences bounds the interpolant's curvature
//! ([`max_curvature`] measures it).

/// The knot slopes dr/dz of the interpolant through (z, r), z strictly increasing.
pub fn slopes(z: &[f64], r: &[f64]) -> Vec<f64> {
    let n = z.len();
    if n < 2 {
        return vec![0.0; n];
    }
    let h: Vec<f64> = z.windows(2).map(|w| w[1] - w[0]).collect();
    let delta: Vec<f64> = (0..n - 1).map(|k| (r[k + 1] - r[k]) / h[k]).collect();
    if n == 2 {
        return vec![delta[0]; 2];
    }
    let mut d = vec![0.0; n];
    for k in 1..n - 1 {
        d[k] = interior_slope(h[k - 1], h[k], delta[k - 1], delta[k]);
    }
    d[0] = end_slope(h[0], h[1], delta[0], delta[1]);
    d[n - 1] = end_slope(h[n - 2], h[n - 3], delta[n - 2], delta[n - 3]);
    d
}

/// Fritsch–Butland: zero at a local extremum of the data, else the weighted harmonic mean
/// of the two secants (weights from the two interval lengths).
fn interior_slope(h0: f64, h1: f64, d0: f64, d1: f64) -> f64 {
    if d0 * d1 <= 0.0 {
        return 0.0;
    }
    let (w1, w2) = (2.0 * h1 + h0, h1 + 2.0 * h0);
    (w1 + w2) / (w1 / d0 + w2 / d1)
}

/// The one-sided three-point slope at an end, kept of the end secant's sign and within
/// three times it (so the end segment stays monotone).
fn end_slope(h0: f64, h1: f64, d0: f64, d1: f64) -> f64 {
    let d = ((2.0 * h0 + h1) * d0 - h0 * d1) / (h0 + h1);
    if d * d0 <= 0.0 {
        0.0
    } else if d0 * d1 < 0.0 && d.abs() > 3.0 * d0.abs() {
        3.0 * d0
    } else {
        d
    }
}

/// The segment holding `x` (the last one for x beyond the last knot).
fn segment(z: &[f64], x: f64) -> usize {
    z.partition_point(|&zk| zk <= x)
        .saturating_sub(1)
        .min(z.len() - 2)
}

/// The cubic's coefficients on segment k: r = r_k + s (d_k + s (c2 + s c3)), s = x − z_k.
fn cubic(z: &[f64], r: &[f64], d: &[f64], k: usize) -> (f64, f64) {
    let h = z[k + 1] - z[k];
    let delta = (r[k + 1] - r[k]) / h;
    let c2 = (3.0 * delta - 2.0 * d[k] - d[k + 1]) / h;
    let c3 = (d[k] - 2.0 * delta + d[k + 1]) / (h * h);
    (c2, c3)
}

/// The interpolant at `x` (z[0] ≤ x ≤ z[n−1]), with the knot slopes `d` of [`slopes`].
pub fn value(z: &[f64], r: &[f64], d: &[f64], x: f64) -> f64 {
    let k = segment(z, x);
    let (c2, c3) = cubic(z, r, d, k);
    let s = x - z[k];
    r[k] + s * (d[k] + s * (c2 + s * c3))
}

/// The interpolant sampled at every knot and between them at a spacing of at most `step`
/// (m): knots `[z, r]` for a profile that is linear between them.
pub fn resample(z: &[f64], r: &[f64], step: f64) -> Vec<[f64; 2]> {
    let d = slopes(z, r);
    let mut out = Vec::new();
    for k in 0..z.len().saturating_sub(1) {
        let pieces = ((z[k + 1] - z[k]) / step).ceil().max(1.0) as usize;
        for j in 0..pieces {
            let x = z[k] + (z[k + 1] - z[k]) * j as f64 / pieces as f64;
            out.push([x, value(z, r, &d, x)]);
        }
    }
    if let (Some(&zl), Some(&rl)) = (z.last(), r.last()) {
        out.push([zl, rl]);
    }
    out
}

/// The largest |r''| of the interpolant, 1/m (a cubic's second derivative is linear, so its
/// largest magnitude on a segment is at one of the segment's ends).
pub fn max_curvature(z: &[f64], r: &[f64]) -> f64 {
    let d = slopes(z, r);
    (0..z.len().saturating_sub(1))
        .map(|k| {
            let (c2, c3) = cubic(z, r, &d, k);
            let h = z[k + 1] - z[k];
            (2.0 * c2).abs().max((2.0 * c2 + 6.0 * c3 * h).abs())
        })
        .fold(0.0, f64::max)
}

/// The largest second divided difference of the knots, |2 (δ_k − δ_{k−1}) / (h_{k−1} + h_k)|,
/// 1/m: the curvature of the parabola through three neighbouring knots.
pub fn max_knot_curvature(z: &[f64], r: &[f64]) -> f64 {
    (1..z.len().saturating_sub(1))
        .map(|k| {
            let (h0, h1) = (z[k] - z[k - 1], z[k + 1] - z[k]);
            let (d0, d1) = ((r[k] - r[k - 1]) / h0, (r[k + 1] - r[k]) / h1);
            (2.0 * (d1 - d0) / (h0 + h1)).abs()
        })
        .fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Data on a straight line: PCHIP reproduces it exactly (every slope is the line's), and
    /// its curvature is zero.
    #[test]
    fn a_line_is_reproduced() {
        let z = [0.0, 0.1, 0.25, 0.3, 0.6];
        let r: Vec<f64> = z.iter().map(|&x| 0.01 + 0.05 * x).collect();
        for d in slopes(&z, &r) {
            assert!((d - 0.05).abs() < 1e-15);
        }
        let d = slopes(&z, &r);
        for x in [0.0, 0.05, 0.2, 0.31, 0.6] {
            assert!((value(&z, &r, &d, x) - (0.01 + 0.05 * x)).abs() < 1e-15);
        }
        assert!(max_curvature(&z, &r) < 1e-12);
    }

    /// The knots are interpolated, and a flat stretch stays flat (zero slopes at both of its
    /// ends: no overshoot into a waist or a bulge).
    #[test]
    fn knots_held_and_flats_stay_flat() {
        let z = [0.0, 0.1, 0.2, 0.3, 0.4];
        let r = [0.012, 0.012, 0.02, 0.03, 0.03];
        let d = slopes(&z, &r);
        for k in 0..z.len() {
            assert_eq!(value(&z, &r, &d, z[k]), r[k]);
        }
        for j in 0..=100 {
            let x = 0.1 * j as f64 / 100.0;
            assert!((value(&z, &r, &d, x) - 0.012).abs() < 1e-15);
            let x = 0.3 + 0.1 * j as f64 / 100.0;
            assert!((value(&z, &r, &d, x) - 0.03).abs() < 1e-15);
        }
    }
}
