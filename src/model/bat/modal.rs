//! Modal analysis of the lumped beam: the symmetric generalized eigenproblem K φ = ω² M φ,
//! solved as the standard symmetric problem of M^{-1/2} K M^{-1/2} (nalgebra's
//! SymmetricEigen), with mass-normalised shapes (φᵀ M φ = 1) and node positions.

use nalgebra::{DMatrix, SymmetricEigen};

use crate::model::bat::beam::Beam;
use crate::model::spec::EndsSpec;

/// Modes of a beam, lowest first.
#[derive(Debug, Clone, PartialEq)]
pub struct ModalBasis {
    /// Angular frequencies ω_n, rad/s (exactly 0 for rigid-body modes).
    pub omega: Vec<f64>,
    /// Mass-normalised shapes, column n = mode n, row i = node i.
    pub shapes: DMatrix<f64>,
    /// Number of rigid-body (zero-frequency) modes.
    pub n_rigid: usize,
}

impl ModalBasis {
    /// All modes of the beam (one per degree of freedom; with a pinned pivot the last one is
    /// the constraint's and is inert: ω = 0 is never used for it, its shape is zero).
    pub fn of(beam: &Beam) -> Self {
        let n = beam.dofs();
        let nodes = beam.len();
        let dof_mass = beam.dof_mass();
        let inv_sqrt_m: Vec<f64> = dof_mass.iter().map(|m| 1.0 / m.sqrt()).collect();
        let mut a = beam.stiffness_matrix();
        for j in 0..n {
            for i in 0..n {
                a[(i, j)] *= inv_sqrt_m[i] * inv_sqrt_m[j];
            }
        }
        // A pinned pivot cᵀy = 0: with u = M^{-1/2}c/|·| and P = I − uuᵀ, the constrained
        // modes are the eigenvectors of P A P orthogonal to u. Adding σ uuᵀ (σ above the
        // spectrum) makes u an exact eigenvector at the top, so the constrained modes are
        // all the others, exactly.
        let pin_vector = beam.pin.map(|(k, al)| {
            let mut u = nalgebra::DVector::zeros(n);
            u[k] = (1.0 - al) * inv_sqrt_m[k];
            u[k + 1] = al * inv_sqrt_m[k + 1];
            let norm = u.norm();
            u / norm
        });
        if let Some(u) = &pin_vector {
            let bound = (0..n)
                .map(|i| a.row(i).iter().map(|x| x.abs()).sum::<f64>())
                .fold(0.0, f64::max);
            let au = &a * u;
            let uau = u.dot(&au);
            // P A P = A − u (Au)ᵀ − (Au) uᵀ + (uᵀAu) u uᵀ
            let sigma = 4.0 * bound.max(1.0);
            for j in 0..n {
                for i in 0..n {
                    a[(i, j)] += -u[i] * au[j] - au[i] * u[j] + (uau + sigma) * u[i] * u[j];
                }
            }
        }
        let eigen = SymmetricEigen::new(a);
        let mut order: Vec<usize> = (0..n).collect();
        order.sort_by(|&i, &j| eigen.eigenvalues[i].total_cmp(&eigen.eigenvalues[j]));
        // Rigid modes come out as round-off-sized eigenvalues; make them exactly zero so
        // that the integrator treats them as free flight. A free–free beam has two
        // (translation and rotation), a free–free beam held at a grip point one (rotation
        // about the grip); a threshold on λ would misclassify the lowest clamped mode of a
        // fine beam (λ₁/λ_max ~ (βd/2)⁴).
        let free = beam.ends == EndsSpec::default();
        let n_rigid_expected = match (free, beam.grip_z.is_some()) {
            (true, false) => 2,
            (true, true) => 1,
            _ => 0,
        };
        let mut omega = Vec::with_capacity(n);
        let mut shapes = DMatrix::zeros(n, n);
        let mut n_rigid = 0;
        for (col, &k) in order.iter().enumerate() {
            let lambda = eigen.eigenvalues[k];
            if col < n_rigid_expected {
                n_rigid += 1;
                omega.push(0.0);
            } else {
                omega.push(lambda.max(0.0).sqrt());
            }
            if pin_vector.is_some() && col == n - 1 {
                continue; // the constraint's mode: inert, zero shape
            }
            let v = eigen.eigenvectors.column(k);
            // sign convention: positive at the barrel end
            let sign = if v[nodes - 1] < 0.0 { -1.0 } else { 1.0 };
            for i in 0..n {
                shapes[(i, col)] = sign * v[i] * inv_sqrt_m[i];
            }
        }
        if n_rigid > 0 {
            // Replace the solver's rigid modes (exact only to ~ε·λ_max) by the exact
            // translation and rotation (about the CM, or the grip), and M-orthogonalise the
            // flexible shapes against them, so that the modal integrator conserves momentum
            // and angular momentum to round-off (completeness: Σ_n (1ᵀMφ_n) φ_n(z) = 1).
            let mass = &beam.mass;
            let total: f64 = mass.iter().sum();
            let z_cm = mass.iter().zip(&beam.z).map(|(m, z)| m * z).sum::<f64>() / total;
            let centre = beam.grip_z.unwrap_or(z_cm);
            let inertia: f64 = mass
                .iter()
                .zip(&beam.z)
                .map(|(m, z)| m * (z - centre).powi(2))
                .sum::<f64>()
                + beam.total_rotary();
            let rotation_col = n_rigid - 1;
            for i in 0..nodes {
                if n_rigid == 2 {
                    shapes[(i, 0)] = 1.0 / total.sqrt();
                }
                shapes[(i, rotation_col)] = (beam.z[i] - centre) / inertia.sqrt();
            }
            for i in nodes..n {
                if n_rigid == 2 {
                    shapes[(i, 0)] = 0.0;
                }
                shapes[(i, rotation_col)] = 1.0 / inertia.sqrt();
            }
            for col in n_rigid..n {
                for r in 0..n_rigid {
                    let overlap: f64 = (0..n)
                        .map(|i| dof_mass[i] * shapes[(i, r)] * shapes[(i, col)])
                        .sum();
                    for i in 0..n {
                        shapes[(i, col)] -= overlap * shapes[(i, r)];
                    }
                }
            }
        }
        Self {
            omega,
            shapes,
            n_rigid,
        }
    }

    /// Frequencies of the flexible modes, Hz, lowest first.
    pub fn flexible_frequencies(&self) -> Vec<f64> {
        self.omega[self.n_rigid..]
            .iter()
            .map(|w| w / (2.0 * std::f64::consts::PI))
            .collect()
    }

    /// Node positions of flexible mode `k` (0 = the first flexible mode), m: sign changes
    /// of the shape between neighbouring nodes, located by linear interpolation.
    pub fn nodes(&self, beam: &Beam, k: usize) -> Vec<f64> {
        let col = self.shapes.column(self.n_rigid + k);
        let mut nodes = Vec::new();
        for i in 0..beam.len() - 1 {
            let (a, b) = (col[i], col[i + 1]);
            if a == 0.0 {
                nodes.push(beam.z[i]);
            } else if a * b < 0.0 {
                nodes.push(beam.z[i] + (beam.z[i + 1] - beam.z[i]) * a / (a - b));
            }
        }
        nodes
    }
}
