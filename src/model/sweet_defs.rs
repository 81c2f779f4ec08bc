//! Sweet-spot definitions of one curve along the impact position, beside the paper's
//! maximum-exit-speed one (`sweet`): the impact position that minimises the vibration felt
//! at the hands (the paper's introduction, first definition), measured two ways —
//! the vibration amplitude at the grip after the ball leaves, and the energy left in bat
//! vibration — and a generic refined extremum finder (also used for the BBCOR maximum).

/// The "least sting" sweet spots of one curve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VibrationSweetSpot {
    /// Impact position minimising the grip vibration amplitude, m (NaN if not defined).
    pub min_vibration_position: f64,
    /// That minimum amplitude, m.
    pub min_vibration_amplitude: f64,
    /// Impact position minimising the energy left in bat vibration, m.
    pub min_vibration_energy_position: f64,
}

/// Both minima of a curve: `grip_amplitude[i]` and `vibration_energy[i]` at increasing
/// `z[i]`. Non-finite samples are skipped. A curve without vibration (all ≤ 0, e.g. the
/// rigid model) has no minimum: NaN.
pub fn vibration_sweet_spot(
    z: &[f64],
    grip_amplitude: &[f64],
    vibration_energy: &[f64],
) -> VibrationSweetSpot {
    let (pa, va) = find_minimum(z, grip_amplitude).unwrap_or((f64::NAN, f64::NAN));
    let (pe, _) = find_minimum(z, vibration_energy).unwrap_or((f64::NAN, f64::NAN));
    VibrationSweetSpot {
        min_vibration_position: pa,
        min_vibration_amplitude: va,
        min_vibration_energy_position: pe,
    }
}

/// Minimum of `v` over increasing `z` (finite samples only), refined by the parabola through
/// the lowest sample and its neighbours; None without a finite sample, when `z` does not
/// increase, or when the curve is identically ≤ 0 (nothing to minimise).
pub fn find_minimum(z: &[f64], v: &[f64]) -> Option<(f64, f64)> {
    if v.iter().filter(|x| x.is_finite()).all(|&x| x <= 0.0) {
        return None;
    }
    let neg: Vec<f64> = v.iter().map(|x| -x).collect();
    find_maximum(z, &neg).map(|(p, m)| (p, -m))
}

/// Maximum of `v` over increasing `z` (finite samples only), refined by the parabola through
/// the best sample and its two neighbours (kept only if its vertex lies between them).
pub fn find_maximum(z: &[f64], v: &[f64]) -> Option<(f64, f64)> {
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
    let (mut position, mut peak) = (z[best], v[best]);
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
            }
        }
    }
    Some((position, peak))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn minimum_of_a_parabola_and_a_kink() {
        let z: Vec<f64> = (0..41).map(|k| 0.5 + 0.01 * k as f64).collect();
        let v: Vec<f64> = z.iter().map(|z| 1.0 + 30.0 * (z - 0.683).powi(2)).collect();
        let (p, m) = find_minimum(&z, &v).unwrap();
        assert!((p - 0.683).abs() < 1e-9 && (m - 1.0).abs() < 1e-9);
        // |z − z0|: the parabola through a kink errs by less than h/8 (h = grid step).
        let v: Vec<f64> = z.iter().map(|z| (z - 0.6775).abs()).collect();
        let (p, _) = find_minimum(&z, &v).unwrap();
        assert!((p - 0.6775).abs() < 0.01 / 8.0, "{p}");
    }

    #[test]
    fn no_vibration_no_minimum() {
        let z = [0.5, 0.6, 0.7];
        assert!(find_minimum(&z, &[0.0, 0.0, 0.0]).is_none());
        let s = vibration_sweet_spot(&z, &[0.0; 3], &[f64::NAN; 3]);
        assert!(s.min_vibration_position.is_nan() && s.min_vibration_energy_position.is_nan());
    }
}
