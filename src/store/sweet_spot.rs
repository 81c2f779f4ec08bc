//! The sweet spot of one exit-speed curve over impact position. A pure function.

/// How far below the maximum exit speed the sweet zone extends, m/s.
pub const SWEET_ZONE_DROP: f64 = 1.0;

/// Sweet spot of the curve `exit_speed(z)` (z strictly increasing, both finite, same length):
/// `(position, exit_speed, width)`.
///
/// The maximum is the best sample, refined by the parabola through it and its two neighbours
/// (when it has both and the parabola opens downward). The width is the length of the
/// contiguous z-range around the best sample where `exit_speed >= max - 1 m/s`, with crossings
/// linearly interpolated between samples and clipped to the sampled range.
/// `None` for an empty curve, mismatched lengths or non-finite input.
pub fn sweet_spot(z: &[f64], exit_speed: &[f64]) -> Option<(f64, f64, f64)> {
    let n = z.len();
    if n == 0 || exit_speed.len() != n {
        return None;
    }
    if z.iter().chain(exit_speed).any(|x| !x.is_finite()) {
        return None;
    }
    if z.windows(2).any(|w| w[1] <= w[0]) {
        return None;
    }
    let mut i = 0;
    for k in 1..n {
        if exit_speed[k] > exit_speed[i] {
            i = k;
        }
    }
    let (mut pos, mut vmax) = (z[i], exit_speed[i]);
    if i > 0 && i + 1 < n {
        let (x0, x1, x2) = (z[i - 1], z[i], z[i + 1]);
        let (y0, y1, y2) = (exit_speed[i - 1], exit_speed[i], exit_speed[i + 1]);
        // Divided differences: p(x) = y1 + d01 (x - x1) + a (x - x1)(x - x0)
        let d01 = (y1 - y0) / (x1 - x0);
        let d12 = (y2 - y1) / (x2 - x1);
        let a = (d12 - d01) / (x2 - x0);
        if a < 0.0 {
            // p'(x) = d01 + a (2x - x0 - x1) = 0
            let xv = 0.5 * (x0 + x1) - d01 / (2.0 * a);
            let xv = xv.clamp(x0, x2);
            let yv = y1 + d01 * (xv - x1) + a * (xv - x1) * (xv - x0);
            if yv >= y1 {
                pos = xv;
                vmax = yv;
            }
        }
    }
    let thr = vmax - SWEET_ZONE_DROP;
    if exit_speed[i] < thr {
        return Some((pos, vmax, 0.0));
    }
    let cross = |a: usize, b: usize| {
        // exit_speed[a] >= thr > exit_speed[b]
        let t = (exit_speed[a] - thr) / (exit_speed[a] - exit_speed[b]);
        z[a] + t * (z[b] - z[a])
    };
    let mut lo = i;
    while lo > 0 && exit_speed[lo - 1] >= thr {
        lo -= 1;
    }
    let left = if lo == 0 { z[0] } else { cross(lo, lo - 1) };
    let mut hi = i;
    while hi + 1 < n && exit_speed[hi + 1] >= thr {
        hi += 1;
    }
    let right = if hi + 1 == n {
        z[n - 1]
    } else {
        cross(hi, hi + 1)
    };
    Some((pos, vmax, right - left))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(a: f64, b: f64, n: usize) -> Vec<f64> {
        (0..n)
            .map(|k| a + (b - a) * k as f64 / (n - 1) as f64)
            .collect()
    }

    #[test]
    fn parabola_is_exact() {
        // v = 30 - 400 (z - 0.713)^2 : max 30 at 0.713, v >= 29 for |z - z0| <= 0.05
        let z = grid(0.5, 0.8, 13);
        let v: Vec<f64> = z
            .iter()
            .map(|z| 30.0 - 400.0 * (z - 0.713).powi(2))
            .collect();
        let (p, m, w) = sweet_spot(&z, &v).unwrap();
        assert!((p - 0.713).abs() < 1e-12, "{p}");
        assert!((m - 30.0).abs() < 1e-12, "{m}");
        // linear interpolation of a parabola underestimates the crossing distance slightly
        assert!((w - 0.1).abs() < 5e-3 && w <= 0.1, "{w}");
    }

    #[test]
    fn width_of_a_tent_is_exact() {
        // v = 25 - 10 |z - 0.7| sampled with a node at the peak: width 2 * 0.1
        let z = grid(0.5, 0.9, 41);
        let v: Vec<f64> = z.iter().map(|z| 25.0 - 10.0 * (z - 0.7).abs()).collect();
        let (p, m, w) = sweet_spot(&z, &v).unwrap();
        assert!((p - 0.7).abs() < 1e-9 && (m - 25.0).abs() < 1e-9);
        assert!((w - 0.2).abs() < 1e-9, "{w}");
    }

    #[test]
    fn gaussian_converges() {
        // v = 20 + 5 exp(-((z-0.68)/0.1)^2): max - 1 where exp(..) = 0.8
        let z = grid(0.4, 0.85, 400);
        let v: Vec<f64> = z
            .iter()
            .map(|z| 20.0 + 5.0 * (-((z - 0.68) / 0.1f64).powi(2)).exp())
            .collect();
        let (p, m, w) = sweet_spot(&z, &v).unwrap();
        let exact_w = 2.0 * 0.1 * (-(0.8f64).ln()).sqrt();
        assert!((p - 0.68).abs() < 1e-5, "{p}");
        assert!((m - 25.0).abs() < 1e-6, "{m}");
        assert!((w - exact_w).abs() < 1e-5, "{w} vs {exact_w}");
    }

    #[test]
    fn edges_and_bad_input() {
        let z = [0.1, 0.2, 0.3];
        // monotone: maximum at the last sample, zone clipped at the end
        let (p, m, w) = sweet_spot(&z, &[1.0, 2.0, 3.0]).unwrap();
        assert_eq!((p, m), (0.3, 3.0));
        assert!((w - 0.1).abs() < 1e-12);
        // flat: whole range
        let (_, _, w) = sweet_spot(&z, &[2.0, 2.0, 2.0]).unwrap();
        assert!((w - 0.2).abs() < 1e-12);
        assert_eq!(sweet_spot(&[0.5], &[7.0]), Some((0.5, 7.0, 0.0)));
        assert_eq!(sweet_spot(&[], &[]), None);
        assert_eq!(sweet_spot(&z, &[1.0, f64::NAN, 2.0]), None);
        assert_eq!(sweet_spot(&z, &[1.0, 2.0]), None);
        assert_eq!(sweet_spot(&[0.2, 0.1], &[1.0, 2.0]), None);
    }
}
