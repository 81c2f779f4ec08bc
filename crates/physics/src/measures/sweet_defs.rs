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
    crate::measures::sweet::find_maximum(z, &neg).map(|(p, m)| (p, -m))
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
