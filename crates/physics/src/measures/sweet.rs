//! The sweet spot as the paper defines it: the impact position of maximum exit speed,
//! refined between grid points, with the sweet-zone width (the z-range within 1 m/s of
//! the maximum).

/// How far below the maximum the sweet zone extends, m/s (the paper's section 2).
pub const SWEET_ZONE_DROP: f64 = 1.0;

/// Sweet spot of one exit-speed curve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SweetSpot {
    /// Impact position of maximum exit speed, m from the knob.
    pub position: f64,
    /// The maximum exit speed, m/s.
    pub exit_speed: f64,
    /// Length of the contiguous z-range around the maximum where the exit speed is within
    /// `SWEET_ZONE_DROP` of it, m. Clipped to the sampled range.
    pub width: f64,
    /// The best sample is the first or the last one: the true maximum may lie outside the
    /// sampled range, and `position` is then only where the range ends.
    pub at_edge: bool,
}

/// How far below its peak BBCOR may fall within a bat's sweet zone: the barrel length the
/// trade compares ("sweet-zone length") is where BBCOR is within 0.01 of the bat's best.
pub const BBCOR_ZONE_DROP: f64 = 0.01;

/// The contiguous range around a curve's maximum where it is within a drop of the maximum.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Zone {
    /// Where the maximum is (parabola-refined), and its value.
    pub position: f64,
    pub peak: f64,
    /// The range's ends, `left ≤ right`, clipped to the sampled range.
    pub left: f64,
    pub right: f64,
    /// The best sample is the first or the last one.
    pub at_edge: bool,
}

/// Find the sweet spot of samples `exit_speed[i]` at increasing positions `z[i]`.
/// Non-finite samples (failed points) are skipped. The maximum is refined by the parabola
/// through the best sample and its two neighbours; the zone edges by linear interpolation.
/// Returns None without a finite sample, or when `z` does not increase or the lengths differ.
pub fn find_sweet_spot(z: &[f64], exit_speed: &[f64]) -> Option<SweetSpot> {
    let zone = find_zone(z, exit_speed, SWEET_ZONE_DROP)?;
    Some(SweetSpot {
        position: zone.position,
        exit_speed: zone.peak,
        width: zone.right - zone.left,
        at_edge: zone.at_edge,
    })
}

/// The zone of samples `v[i]` at increasing `z[i]` within `drop` of their maximum, as
/// [`find_sweet_spot`] finds it.
pub fn find_zone(z: &[f64], v: &[f64], drop: f64) -> Option<Zone> {
    if z.len() != v.len() || z.windows(2).any(|w| w[1] <= w[0]) {
        return None;
    }
    let (z, v): (Vec<f64>, Vec<f64>) = z
        .iter()
        .zip(v)
        .filter(|(a, b)| a.is_finite() && b.is_finite())
        .map(|(a, b)| (*a, *b))
        .unzip();
    let (position, peak, curvature) = refined_maximum(&z, &v)?;
    // The zone grows from the best sample (the refined peak lies next to it).
    let best = (0..v.len()).max_by(|&a, &b| v[a].total_cmp(&v[b]))?;
    let threshold = peak - drop;
    let at_edge = best == 0 || best + 1 == v.len();
    let zone = |left: f64, right: f64| Zone {
        position,
        peak,
        left,
        right,
        at_edge,
    };
    if v[best] < threshold {
        // On a grid coarser than the zone, every sample lies more than the drop below the
        // refined peak: interpolating between samples would put the edges outside-in (a
        // negative width). The zone is then the parabola's own, |z − z*| ≤ √(drop / −c),
        // which lies between the best sample's neighbours.
        let half = curvature.map_or(0.0, |c| (drop / -c).sqrt());
        let left = (position - half).max(z[best.saturating_sub(1)]);
        let right = (position + half).min(z[(best + 1).min(z.len() - 1)]);
        return Some(zone(left, right.max(left)));
    }
    let crossing = |i: usize, j: usize| {
        // Linear interpolation between a sample above the threshold (i) and one below (j).
        z[i] + (threshold - v[i]) * (z[j] - z[i]) / (v[j] - v[i])
    };
    let mut lo = best;
    while lo > 0 && v[lo - 1] >= threshold {
        lo -= 1;
    }
    let left = if lo > 0 { crossing(lo, lo - 1) } else { z[0] };
    let mut hi = best;
    while hi + 1 < v.len() && v[hi + 1] >= threshold {
        hi += 1;
    }
    let right = if hi + 1 < v.len() {
        crossing(hi, hi + 1)
    } else {
        z[v.len() - 1]
    };
    Some(zone(left, right))
}

/// Maximum of `v` over increasing `z` (finite samples only), refined by the parabola through
/// the best sample and its two neighbours (kept only if its vertex lies between them).
pub fn find_maximum(z: &[f64], v: &[f64]) -> Option<(f64, f64)> {
    refined_maximum(z, v).map(|(position, peak, _)| (position, peak))
}

/// `find_maximum` with the parabola's curvature c (v ≈ peak + c (z − z*)², c < 0) when the
/// parabola was used.
fn refined_maximum(z: &[f64], v: &[f64]) -> Option<(f64, f64, Option<f64>)> {
    if z.len() != v.len() || z.windows(2).any(|w| w[1] <= w[0]) {
        return None;
    }
    let (z, v): (Vec<f64>, Vec<f64>) = z
        .iter()
        .zip(v)
        .filter(|(a, b)| a.is_finite() && b.is_finite())
        .map(|(a, b)| (*a, *b))
        .unzip();
    let best = (0..v.len()).max_by(|&a, &b| v[a].total_cmp(&v[b]))?;
    let (mut position, mut peak, mut curvature) = (z[best], v[best], None);
    if best > 0 && best + 1 < v.len() {
        let (x, y) = (
            [z[best - 1], z[best], z[best + 1]],
            [v[best - 1], v[best], v[best + 1]],
        );
        let d1 = (y[1] - y[0]) / (x[1] - x[0]);
        let d2 = (y[2] - y[1]) / (x[2] - x[1]);
        let c = (d2 - d1) / (x[2] - x[0]);
        if c < 0.0 && c.is_finite() {
            let xv = 0.5 * (x[0] + x[1]) - d1 / (2.0 * c);
            let yv = y[0] + d1 * (xv - x[0]) + c * (xv - x[0]) * (xv - x[1]);
            if xv > x[0] && xv < x[2] && yv >= peak {
                position = xv;
                peak = yv;
                curvature = Some(c);
            }
        }
    }
    Some((position, peak, curvature))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parabola_peak_and_width_are_exact() {
        // v = 30 − 400 (z − 0.713)²: maximum 30 at 0.713; within 1 m/s for
        // |z − 0.713| ≤ 0.05, so the width is 0.1 m (analytic).
        let z: Vec<f64> = (0..45).map(|k| 0.40 + 0.01 * k as f64).collect();
        let v: Vec<f64> = z
            .iter()
            .map(|z| 30.0 - 400.0 * (z - 0.713).powi(2))
            .collect();
        let s = find_sweet_spot(&z, &v).unwrap();
        assert!((s.position - 0.713).abs() < 1e-9, "{s:?}");
        assert!((s.exit_speed - 30.0).abs() < 1e-9);
        // Linear interpolation of a parabola's crossings errs by O(h²): 1 cm grid.
        assert!((s.width - 0.1).abs() < 2e-3, "{s:?}");
    }

    #[test]
    fn a_grid_coarser_than_the_zone_gives_the_parabolas_width() {
        // v = 30 − 4000 (z − 0.705)² sampled every 10 cm: every sample is more than 1 m/s
        // below the peak (the best, at 0.75, by 8.1 m/s). The parabola through three
        // samples of a parabola is the parabola, so the peak is exact, and so is the zone:
        // |z − 0.705| ≤ √(1/4000), a width of 2/√4000 = 0.0316 m.
        let z = [0.45f64, 0.55, 0.65, 0.75, 0.85];
        let v: Vec<f64> = z
            .iter()
            .map(|z| 30.0 - 4000.0 * (z - 0.705).powi(2))
            .collect();
        let s = find_sweet_spot(&z, &v).unwrap();
        assert!((s.position - 0.705).abs() < 1e-9, "{s:?}");
        assert!((s.exit_speed - 30.0).abs() < 1e-9, "{s:?}");
        assert!((s.width - 2.0 / 4000f64.sqrt()).abs() < 1e-9, "{s:?}");
    }

    #[test]
    fn skips_failed_points_and_clips_at_the_edge() {
        let z = [0.5, 0.6, 0.7, 0.8];
        let v = [20.0, f64::NAN, 24.0, 24.5];
        let s = find_sweet_spot(&z, &v).unwrap();
        assert_eq!(s.position, 0.8);
        // Left edge interpolated between 0.5 (20) and 0.7 (24): 23.5 at 0.675.
        assert!((s.width - (0.8 - 0.675)).abs() < 1e-12);
        assert!(find_sweet_spot(&[0.5], &[f64::NAN]).is_none());
    }
    fn grid(a: f64, b: f64, n: usize) -> Vec<f64> {
        (0..n)
            .map(|k| a + (b - a) * k as f64 / (n - 1) as f64)
            .collect()
    }

    #[test]
    fn width_of_a_tent_is_exact() {
        // v = 25 − 10 |z − 0.7| sampled with a node at the peak: width 2 × 0.1 (analytic).
        let z = grid(0.5, 0.9, 41);
        let v: Vec<f64> = z.iter().map(|z| 25.0 - 10.0 * (z - 0.7).abs()).collect();
        let s = find_sweet_spot(&z, &v).unwrap();
        assert!((s.position - 0.7).abs() < 1e-9 && (s.exit_speed - 25.0).abs() < 1e-9);
        assert!((s.width - 0.2).abs() < 1e-9, "{s:?}");
    }

    #[test]
    fn gaussian_peak_converges() {
        // v = 20 + 5 exp(−((z − 0.68)/0.1)²): the zone ends where exp(…) = 0.8 (analytic).
        let z = grid(0.4, 0.85, 400);
        let v: Vec<f64> = z
            .iter()
            .map(|z| 20.0 + 5.0 * (-((z - 0.68) / 0.1f64).powi(2)).exp())
            .collect();
        let s = find_sweet_spot(&z, &v).unwrap();
        let exact_width = 2.0 * 0.1 * (-(0.8f64).ln()).sqrt();
        assert!((s.position - 0.68).abs() < 1e-5, "{s:?}");
        assert!((s.exit_speed - 25.0).abs() < 1e-6, "{s:?}");
        assert!((s.width - exact_width).abs() < 1e-5, "{s:?}");
    }

    #[test]
    fn monotone_flat_and_bad_input() {
        let z = [0.1, 0.2, 0.3];
        let s = find_sweet_spot(&z, &[1.0, 2.0, 3.0]).unwrap();
        assert_eq!((s.position, s.exit_speed), (0.3, 3.0));
        assert!((s.width - 0.1).abs() < 1e-12);
        let flat = find_sweet_spot(&z, &[2.0, 2.0, 2.0]).unwrap();
        assert!((flat.width - 0.2).abs() < 1e-12);
        assert_eq!(find_sweet_spot(&[], &[]), None);
        assert_eq!(find_sweet_spot(&z, &[1.0, 2.0]), None);
        assert_eq!(find_sweet_spot(&[0.2, 0.1], &[1.0, 2.0]), None);
    }
}
