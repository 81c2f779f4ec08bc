//! A candidate profile a lathe can turn (`optimize.profile.shape`): its knots' values placed
//! one after another from the knob, each free knot within what its bounds, the rise and the
//! curvature leave it given the knots before it; then the shape-preserving cubic through
//! them, sampled for the bat.
//!
//! The design variable of a free knot is its place in that interval (a fraction in [0, 1]),
//! so the candidates the search asks for are turnable by construction: there is nothing to
//! penalise and no waist to find. Every narrowing of a knot's interval is a necessary
//! condition (a value outside it leaves no way to continue within the bounds), so the map
//! from fractions to profiles reaches every profile that rises and bends no more than
//! allowed: the search loses none. The interval's ends are found with the later knots'
//! bounds on one side at a time; where a fixed knot pins the profile from both sides at
//! once the curvature can, in principle, still be exceeded there (the bundled designs'
//! every candidate keeps it: `tests/design_lathe_profile.rs`).

use batstudy_physics::bat::profile_spline;

/// The spacing at which a shaped profile is sampled for the bat, m (the bat's profile is
/// linear between its knots; 5 mm keeps the chord's sag on a radius of curvature of 1 m
/// at 3 µm).
pub const SAMPLE_STEP: f64 = 0.005;

/// What a profile's knots keep: the radius does not fall between neighbouring knots within
/// `rising` (m from the knob), the parabola through three neighbouring knots has a
/// curvature of at most `max_curvature` (1/m), and neighbouring knots differ by at most
/// `max_slope` per metre between them (a wall's thickness gradient).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Shape {
    pub rising: Option<[f64; 2]>,
    pub max_curvature: Option<f64>,
    pub max_slope: Option<f64>,
}

impl Shape {
    /// The wall's shape: the same curvature and gradient bounds without a rising span (a
    /// wall's thickness need not rise).
    pub fn for_wall(&self) -> Shape {
        Shape {
            rising: None,
            ..*self
        }
    }

    fn rises(&self, z0: f64, z1: f64) -> bool {
        self.rising.is_some_and(|[a, b]| a <= z0 && z1 <= b)
    }
}

/// The knots' values of one candidate. Knot k is `bounds[k]` = (min, max) (equal for a fixed
/// knot); a free knot takes the fraction `t[k]` (clamped to [0, 1]) of the interval left to it
/// by its bounds, the rise over `shape.rising` from the knot before it (and up to any fixed
/// knot after it in that span), and the curvature with the two knots before it. Where a fixed
/// knot leaves the curvature no room, the bounds and the rise win.
pub fn place(z: &[f64], bounds: &[(f64, f64)], t: &[f64], shape: &Shape) -> Vec<f64> {
    let mut r: Vec<f64> = Vec::with_capacity(z.len());
    for (k, tk) in t.iter().enumerate().take(z.len()) {
        let (lo, hi) = interval(z, bounds, &r, k, shape);
        r.push(lo + tk.clamp(0.0, 1.0) * (hi - lo));
    }
    r
}

/// The fractions that [`place`] turns into the knots nearest `target` knot by knot (each
/// knot's value clamped into its interval): `target` itself when it keeps the shape. How a
/// start design written as radii becomes the search's start.
pub fn fractions(z: &[f64], bounds: &[(f64, f64)], target: &[f64], shape: &Shape) -> Vec<f64> {
    let (mut r, mut t): (Vec<f64>, Vec<f64>) = (Vec::new(), Vec::new());
    for (k, want) in target.iter().enumerate().take(z.len()) {
        let (lo, hi) = interval(z, bounds, &r, k, shape);
        let tk = match hi > lo {
            true => ((want - lo) / (hi - lo)).clamp(0.0, 1.0),
            false => 0.0,
        };
        t.push(tk);
        r.push(lo + tk * (hi - lo));
    }
    t
}

/// Knot k's interval given the knots before it: its bounds (a point for a fixed knot),
/// narrowed by the rise, the curvature and what the later knots need.
fn interval(z: &[f64], bounds: &[(f64, f64)], r: &[f64], k: usize, shape: &Shape) -> (f64, f64) {
    let (min, max) = bounds[k];
    if min == max {
        return (min, max);
    }
    let (lo, hi) = rise_interval(z, bounds, r, k, shape);
    let (lo, hi) = match curvature_interval(z, r, k, shape) {
        Some((c, d)) if c.max(lo) <= d.min(hi) => (c.max(lo), d.min(hi)),
        Some((_, d)) if d < lo => (lo, lo),
        Some((c, _)) if c > hi => (hi, hi),
        _ => (lo, hi),
    };
    let (lo, hi) = viable_interval(z, bounds, r, k, (lo, hi), shape);
    slope_interval(z, bounds, r, k, (lo, hi), shape)
}

/// Knot k's interval narrowed by the gradient bound: within `max_slope` × the spacing of the
/// knot before it, and close enough to every later knot's bounds to reach them at that
/// slope. Where a fixed knot leaves it no room, the bounds win.
fn slope_interval(
    z: &[f64],
    bounds: &[(f64, f64)],
    r: &[f64],
    k: usize,
    (lo, hi): (f64, f64),
    shape: &Shape,
) -> (f64, f64) {
    let Some(g) = shape.max_slope else {
        return (lo, hi);
    };
    let (mut a, mut b) = (f64::NEG_INFINITY, f64::INFINITY);
    if k > 0 {
        let reach = g * (z[k] - z[k - 1]);
        (a, b) = (r[k - 1] - reach, r[k - 1] + reach);
    }
    for j in k + 1..z.len() {
        let reach = g * (z[j] - z[k]);
        (a, b) = (a.max(bounds[j].0 - reach), b.min(bounds[j].1 + reach));
    }
    match (a.max(lo), b.min(hi)) {
        (c, d) if c <= d => (c, d),
        _ if b < lo => (lo, lo),
        _ if a > hi => (hi, hi),
        _ => (lo, hi),
    }
}

/// Whether fixed knots and bounds leave a gradient-bounded list possible: the first pair
/// (k, j) whose bounds lie further apart than `max_slope` × their spacing otherwise.
pub fn check_slope(z: &[f64], bounds: &[(f64, f64)], max_slope: f64) -> Result<(), (usize, usize)> {
    for k in 0..z.len() {
        for j in k + 1..z.len() {
            let reach = max_slope * (z[j] - z[k]);
            if bounds[k].0 - bounds[j].1 > reach * (1.0 + 1e-12)
                || bounds[j].0 - bounds[k].1 > reach * (1.0 + 1e-12)
            {
                return Err((k, j));
            }
        }
    }
    Ok(())
}

/// Knot k's bounds narrowed by the rise: at least the knot before it, at most every later
/// knot's upper bound, within the rising span (so the knots after it can still rise; with
/// [`check_rise`]'s bounds the interval is never empty).
fn rise_interval(
    z: &[f64],
    bounds: &[(f64, f64)],
    r: &[f64],
    k: usize,
    shape: &Shape,
) -> (f64, f64) {
    let (mut lo, mut hi) = bounds[k];
    if k > 0 && shape.rises(z[k - 1], z[k]) {
        lo = lo.max(r[k - 1]);
    }
    for j in k + 1..z.len() {
        if !shape.rises(z[k], z[j]) {
            break;
        }
        hi = hi.min(bounds[j].1);
    }
    (lo, hi.max(lo))
}

/// Whether knots' bounds allow a rise over the span: no knot's lower bound above a later
/// knot's upper bound within it. The first such pair (k, j) otherwise.
pub fn check_rise(z: &[f64], bounds: &[(f64, f64)], shape: &Shape) -> Result<(), (usize, usize)> {
    for k in 0..z.len() {
        for j in k + 1..z.len() {
            if !shape.rises(z[k], z[j]) {
                break;
            }
            if bounds[k].0 > bounds[j].1 {
                return Err((k, j));
            }
        }
    }
    Ok(())
}

/// The values of knot k that keep the parabola through knots k − 2, k − 1, k within the
/// curvature bound: 2 |δ₁ − δ₀| / (h₀ + h₁) ≤ κ, δ the secants.
fn curvature_interval(z: &[f64], r: &[f64], k: usize, shape: &Shape) -> Option<(f64, f64)> {
    let kappa = shape.max_curvature?;
    if k < 2 {
        return None;
    }
    let (h0, h1) = (z[k - 1] - z[k - 2], z[k] - z[k - 1]);
    let s0 = (r[k - 1] - r[k - 2]) / h0;
    let band = 0.5 * kappa * (h0 + h1);
    Some((r[k - 1] + h1 * (s0 - band), r[k - 1] + h1 * (s0 + band)))
}

/// Knot k's interval narrowed to values from which the knots after it can still keep their
/// bounds under the curvature bound: the lowest path on from it (the slope turned down as
/// fast as the bound allows, and not below zero where the radius rises) must stay under
/// every later upper bound, and the highest (turned up as fast) must reach every later lower
/// bound. Either path is monotone in knot k's value, so each end is found by bisection.
fn viable_interval(
    z: &[f64],
    bounds: &[(f64, f64)],
    r: &[f64],
    k: usize,
    (lo, hi): (f64, f64),
    shape: &Shape,
) -> (f64, f64) {
    let Some(kappa) = shape.max_curvature else {
        return (lo, hi);
    };
    if k == 0 || k + 1 == z.len() {
        return (lo, hi);
    }
    // the path on from (r[k-1], x) with the slope turned by `turn` (−1 down, +1 up) at
    // every knot: whether it keeps the later knots' bounds on that side
    let keeps = |x: f64, turn: f64| {
        let (mut prev, mut here) = (r[k - 1], x);
        for j in k + 1..z.len() {
            let (h0, h1) = (z[j - 1] - z[j - 2], z[j] - z[j - 1]);
            let mut slope = (here - prev) / h0 + turn * 0.5 * kappa * (h0 + h1);
            if turn < 0.0 && shape.rises(z[j - 1], z[j]) {
                slope = slope.max(0.0);
            }
            (prev, here) = (here, here + h1 * slope);
            let (min, max) = bounds[j];
            if (turn < 0.0 && here > max) || (turn > 0.0 && here < min) {
                return false;
            }
        }
        true
    };
    let hi = match keeps(hi, -1.0) {
        true => hi,
        false => bisect(lo, hi, |x| keeps(x, -1.0)),
    };
    let lo = match keeps(lo, 1.0) {
        true => lo,
        false => lowest(lo, hi, |x| keeps(x, 1.0)),
    };
    (lo.min(hi), hi)
}

/// The largest x in [lo, hi] with `ok(x)`, for `ok` true up to some point and false beyond
/// (lo itself when none).
fn bisect(lo: f64, hi: f64, ok: impl Fn(f64) -> bool) -> f64 {
    let (mut a, mut b) = (lo, hi);
    for _ in 0..60 {
        let m = 0.5 * (a + b);
        (a, b) = if ok(m) { (m, b) } else { (a, m) };
    }
    a
}

/// The smallest x in [lo, hi] with `ok(x)`, for `ok` false up to some point and true
/// beyond (hi itself when none).
fn lowest(lo: f64, hi: f64, ok: impl Fn(f64) -> bool) -> f64 {
    let (mut a, mut b) = (lo, hi);
    for _ in 0..60 {
        let m = 0.5 * (a + b);
        (a, b) = if ok(m) { (a, m) } else { (m, b) };
    }
    b
}

/// The bat's knots `[z, value]` of a shaped profile: the shape-preserving cubic through the
/// placed knots, sampled every [`SAMPLE_STEP`].
pub fn turned(z: &[f64], values: &[f64]) -> Vec<[f64; 2]> {
    profile_spline::resample(z, values, SAMPLE_STEP)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fixed knot above the rising span's free knots caps them; below, the free knots
    /// start from it.
    #[test]
    fn fixed_knots_bound_the_rise() {
        let z = [0.0, 0.1, 0.2, 0.3];
        let bounds = [(0.01, 0.01), (0.005, 0.04), (0.005, 0.04), (0.03, 0.03)];
        let shape = Shape {
            rising: Some([0.0, 0.3]),
            max_curvature: None,
            max_slope: None,
        };
        let r = place(&z, &bounds, &[0.0, 1.0, 1.0, 0.0], &shape);
        assert_eq!(r, vec![0.01, 0.03, 0.03, 0.03]);
        let r = place(&z, &bounds, &[0.0, 0.0, 0.0, 0.0], &shape);
        assert_eq!(r, vec![0.01, 0.01, 0.01, 0.03]);
    }
}
