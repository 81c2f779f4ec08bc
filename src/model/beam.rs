//! The discretised Euler–Bernoulli beam (PHYSICS.md): N segments of length d, one lumped
//! mass per segment at its centre z_i = (i + ½)d, and the symmetric stiffness
//! K = (Y/d³) Dᵀ diag(I_j) D with D the second difference.
//!
//! Ends. Free: D has rows only at interior nodes (1..N−2); this is the paper's linear
//! ghost extrapolation, and K's null space is exactly rigid translation + rotation.
//! Fixed: two ghost nodes beyond the end held at zero (the paper's y₋₁ = y₀ = 0), which adds
//! the curvature rows centred on the ghost next to the end and on the end node. The clamp then
//! sits between the two ghosts, i.e. d beyond the bat's physical end rather than at it: the
//! clamped–free frequencies converge at first order in d (measured in the tests), free–free
//! at second order.

use nalgebra::DMatrix;

use super::section::BatGeometry;
use super::spec::{EndCondition, EndsSpec};

/// One row of D: the curvature y_{c−1} − 2y_c + y_{c+1} at node `center` (ghost indices
/// outside 0..N are zero), with bending stiffness `weight` = Y I_c / d³.
#[derive(Debug, Clone, Copy, PartialEq)]
struct CurvatureRow {
    center: isize,
    weight: f64,
}

/// The lumped beam.
#[derive(Debug, Clone, PartialEq)]
pub struct Beam {
    /// Segment length, m.
    pub d: f64,
    /// Node (segment centre) positions, m from the knob.
    pub z: Vec<f64>,
    /// Lumped masses, kg (wall + fill of each segment, integrated exactly).
    pub mass: Vec<f64>,
    pub ends: EndsSpec,
    rows: Vec<CurvatureRow>,
}

impl Beam {
    /// Discretise `geometry` into `segments` segments with the given ends.
    pub fn new(geometry: &BatGeometry, segments: usize, ends: EndsSpec) -> Self {
        let n = segments;
        let d = geometry.length / n as f64;
        let z: Vec<f64> = (0..n).map(|i| (i as f64 + 0.5) * d).collect();
        let mass: Vec<f64> = (0..n)
            .map(|i| {
                geometry.integrate(i as f64 * d, (i + 1) as f64 * d, |z| {
                    geometry.mass_per_length(z)
                })
            })
            .collect();
        // Segment-averaged stiffness: smooth in the profile, exact total bending compliance
        // for a piecewise-constant I.
        let bending: Vec<f64> = (0..n)
            .map(|i| {
                geometry.youngs_modulus
                    * geometry.integrate(i as f64 * d, (i + 1) as f64 * d, |z| {
                        geometry.second_moment(z)
                    })
                    / d.powi(4)
            })
            .collect();
        Self::from_parts(d, z, mass, &bending, ends)
    }

    /// A beam from per-segment masses and bending weights Y I_i / d³ (used by `new` and by
    /// tests of uniform beams).
    pub fn from_parts(
        d: f64,
        z: Vec<f64>,
        mass: Vec<f64>,
        bending: &[f64],
        ends: EndsSpec,
    ) -> Self {
        let n = z.len() as isize;
        let mut rows = Vec::new();
        if ends.knob == EndCondition::Fixed {
            rows.push(CurvatureRow {
                center: -1,
                weight: bending[0],
            });
            rows.push(CurvatureRow {
                center: 0,
                weight: bending[0],
            });
        }
        for c in 1..n - 1 {
            rows.push(CurvatureRow {
                center: c,
                weight: bending[c as usize],
            });
        }
        if ends.barrel == EndCondition::Fixed {
            let last = bending[(n - 1) as usize];
            rows.push(CurvatureRow {
                center: n - 1,
                weight: last,
            });
            rows.push(CurvatureRow {
                center: n,
                weight: last,
            });
        }
        Self {
            d,
            z,
            mass,
            ends,
            rows,
        }
    }

    /// Number of nodes (= segments).
    pub fn len(&self) -> usize {
        self.z.len()
    }

    pub fn is_empty(&self) -> bool {
        self.z.is_empty()
    }

    /// Total mass, kg.
    pub fn total_mass(&self) -> f64 {
        self.mass.iter().sum()
    }

    /// Centre of mass of the lumped masses, m.
    pub fn center_of_mass(&self) -> f64 {
        self.mass
            .iter()
            .zip(&self.z)
            .map(|(m, z)| m * z)
            .sum::<f64>()
            / self.total_mass()
    }

    /// out = K y.
    pub fn apply_stiffness(&self, y: &[f64], out: &mut [f64]) {
        let n = y.len() as isize;
        out.iter_mut().for_each(|o| *o = 0.0);
        let at = |i: isize| {
            if (0..n).contains(&i) {
                y[i as usize]
            } else {
                0.0
            }
        };
        for row in &self.rows {
            let c = row.center;
            let moment = row.weight * (at(c - 1) - 2.0 * at(c) + at(c + 1));
            for (offset, coef) in [(-1isize, 1.0), (0, -2.0), (1, 1.0)] {
                let i = c + offset;
                if (0..n).contains(&i) {
                    out[i as usize] += coef * moment;
                }
            }
        }
    }

    /// K as a dense matrix (for the eigenproblem).
    pub fn stiffness_matrix(&self) -> DMatrix<f64> {
        let n = self.len();
        let mut k = DMatrix::zeros(n, n);
        for row in &self.rows {
            let taps: Vec<(usize, f64)> = [(-1isize, 1.0), (0, -2.0), (1, 1.0)]
                .iter()
                .filter_map(|&(o, c)| {
                    let i = row.center + o;
                    (0..n as isize).contains(&i).then_some((i as usize, c))
                })
                .collect();
            for &(i, ci) in &taps {
                for &(j, cj) in &taps {
                    k[(i, j)] += row.weight * ci * cj;
                }
            }
        }
        k
    }

    /// Linear interpolation of the contact point: (k, a) with z ≈ (1 − a) z_k + a z_{k+1}.
    /// Outside the first/last half-segment the end node's pair is extrapolated linearly
    /// (consistent with the free end's straight continuation).
    pub fn interpolation(&self, z: f64) -> (usize, f64) {
        let n = self.len();
        let s = z / self.d - 0.5;
        let k = (s.floor().max(0.0) as usize).min(n - 2);
        (k, s - k as f64)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn uniform(n: usize, ends: EndsSpec) -> Beam {
        let d = 1.0 / n as f64;
        Beam::from_parts(
            d,
            (0..n).map(|i| (i as f64 + 0.5) * d).collect(),
            vec![d; n],
            &vec![1.0; n],
            ends,
        )
    }

    #[test]
    fn free_free_null_space_is_rigid_motion() {
        let b = uniform(20, EndsSpec::default());
        let mut out = vec![0.0; 20];
        let line: Vec<f64> = b.z.iter().map(|z| 0.3 + 2.0 * z).collect();
        b.apply_stiffness(&line, &mut out);
        assert!(out.iter().all(|o| o.abs() < 1e-12));
    }

    #[test]
    fn dense_and_applied_stiffness_agree() {
        let ends = EndsSpec {
            knob: EndCondition::Fixed,
            barrel: EndCondition::Free,
        };
        let b = uniform(12, ends);
        let y: Vec<f64> = (0..12).map(|i| ((i * 7 % 5) as f64).sin()).collect();
        let mut out = vec![0.0; 12];
        b.apply_stiffness(&y, &mut out);
        let k = b.stiffness_matrix();
        let ky = &k * nalgebra::DVector::from_vec(y);
        for i in 0..12 {
            assert!((ky[i] - out[i]).abs() < 1e-12);
        }
        assert!((&k - k.transpose()).amax() < 1e-12);
    }
}
