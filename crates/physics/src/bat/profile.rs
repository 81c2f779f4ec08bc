//! The bat's outer radius R(z): piecewise-linear knots, the embedded R161 table, the
//! handle-thickness variant and the barrel extension.

use crate::error::ModelError;
use crate::spec::HandleSpec;

/// The R161 table (diameter per 1-cm slice), embedded at build time.
const R161_CSV: &str = include_str!("../../../../data/r161_profile.csv");

/// An outer-radius profile: knots (z, R) in m, z from 0 (knob) strictly increasing,
/// linear between knots.
#[derive(Debug, Clone, PartialEq)]
pub struct Profile {
    z: Vec<f64>,
    radius: Vec<f64>,
}

impl Profile {
    /// A profile from user knots `[[z, R], ...]`.
    pub fn from_knots(knots: &[[f64; 2]]) -> Result<Self, ModelError> {
        if knots.len() < 2 {
            return Err(ModelError::Profile(format!(
                "needs at least 2 knots, got {}",
                knots.len()
            )));
        }
        if knots[0][0] != 0.0 {
            return Err(ModelError::Profile(format!(
                "the first knot must be at z = 0 (the knob), got z = {}",
                knots[0][0]
            )));
        }
        for (i, k) in knots.iter().enumerate() {
            if !(k[1] > 0.0 && k[1].is_finite()) {
                return Err(ModelError::Profile(format!(
                    "radius {} m at knot {i} (z = {} m) must be positive",
                    k[1], k[0]
                )));
            }
            if i > 0 && k[0].partial_cmp(&knots[i - 1][0]) != Some(std::cmp::Ordering::Greater) {
                return Err(ModelError::Profile(format!(
                    "knot z values must increase strictly: z = {} m after z = {} m (knot {i})",
                    k[0],
                    knots[i - 1][0]
                )));
            }
        }
        Ok(Self {
            z: knots.iter().map(|k| k[0]).collect(),
            radius: knots.iter().map(|k| k[1]).collect(),
        })
    }

    /// The R161 wood bat: the slice diameters become knots at the slice centres, with the
    /// end slices' radii carried to z = 0 and z = L.
    pub fn r161() -> Self {
        static R161: std::sync::OnceLock<Profile> = std::sync::OnceLock::new();
        R161.get_or_init(Self::parse_r161).clone()
    }

    fn parse_r161() -> Self {
        let mut slices = Vec::new();
        for line in R161_CSV.lines() {
            let line = line.trim();
            if line.is_empty() || line.starts_with('#') || line.starts_with("slice") {
                continue;
            }
            let mut cols = line.split(',');
            let end_cm: f64 = cols
                .next()
                .and_then(|s| s.trim().parse().ok())
                .unwrap_or(f64::NAN);
            let diameter_mm: f64 = cols
                .next()
                .and_then(|s| s.trim().parse().ok())
                .unwrap_or(f64::NAN);
            slices.push((end_cm * 0.01, diameter_mm * 0.5e-3));
        }
        let length = slices.last().map(|s| s.0).unwrap_or(0.0);
        let mut z = vec![0.0];
        let mut radius = vec![slices[0].1];
        for &(end, r) in &slices {
            z.push(end - 0.005);
            radius.push(r);
        }
        z.push(length);
        radius.push(slices.last().map(|s| s.1).unwrap_or(0.0));
        Self { z, radius }
    }

    /// Length of the profile (its last knot), m.
    pub fn length(&self) -> f64 {
        *self.z.last().expect("profile has knots")
    }

    /// Knot positions, m.
    pub fn knots_z(&self) -> &[f64] {
        &self.z
    }

    /// R(z) by linear interpolation; beyond the last knot the end radius continues
    /// (the barrel extension).
    pub fn radius(&self, z: f64) -> f64 {
        let n = self.z.len();
        if z <= self.z[0] {
            return self.radius[0];
        }
        if z >= self.z[n - 1] {
            return self.radius[n - 1];
        }
        let i = self.z.partition_point(|&zk| zk <= z) - 1;
        let t = (z - self.z[i]) / (self.z[i + 1] - self.z[i]);
        self.radius[i] + t * (self.radius[i + 1] - self.radius[i])
    }
}

/// The handle-thickness variant: R(z) × (1 + (scale − 1)·w(z)), w = 1 up to `end`,
/// falling linearly to 0 at `end + blend`.
pub fn handle_factor(handle: &HandleSpec, z: f64) -> f64 {
    let w = if z <= handle.end {
        1.0
    } else if handle.blend > 0.0 && z < handle.end + handle.blend {
        1.0 - (z - handle.end) / handle.blend
    } else {
        0.0
    };
    1.0 + (handle.radius_scale - 1.0) * w
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn r161_table_parses_to_84_cm() {
        let p = Profile::r161();
        assert!((p.length() - 0.84).abs() < 1e-12);
        // first slice: 50.5 mm diameter
        assert!((p.radius(0.0) - 0.02525).abs() < 1e-12);
    }

    #[test]
    fn knots_must_increase() {
        assert!(Profile::from_knots(&[[0.0, 0.01], [0.5, 0.02], [0.4, 0.03]]).is_err());
        assert!(Profile::from_knots(&[[0.0, 0.01], [0.5, 0.02]]).is_ok());
    }

    #[test]
    fn handle_blend_is_continuous() {
        let h = HandleSpec {
            radius_scale: 1.2,
            end: 0.4,
            blend: 0.1,
        };
        assert_eq!(handle_factor(&h, 0.1), 1.2);
        assert!((handle_factor(&h, 0.45) - 1.1).abs() < 1e-12);
        assert_eq!(handle_factor(&h, 0.6), 1.0);
    }
}
