//! Modal analysis of the lumped beam: the symmetric generalized eigenproblem K φ = ω² M φ,
//! solved as the standard symmetric problem of M^{-1/2} K M^{-1/2} (a band matrix in node
//! order: `band_eigen`), with mass-normalised shapes (φᵀ M φ = 1) and node positions.

use nalgebra::DMatrix;

use crate::bat::band_eigen::symmetric_eigen;

use crate::bat::beam::Beam;
use crate::spec::EndsSpec;

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

/// The standard symmetric problem A = M^{-1/2} K M^{-1/2} of a beam (`inv_sqrt_m`: M^{-1/2}'s
/// diagonal), with a pinned pivot's constraint folded in, and that constraint's unit vector.
fn standard_matrix(
    beam: &Beam,
    inv_sqrt_m: &[f64],
) -> (DMatrix<f64>, Option<nalgebra::DVector<f64>>) {
    let n = beam.dofs();
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
    (a, pin_vector)
}

/// The beam's degrees of freedom in node order (each node's deflection, then, Timoshenko,
/// its rotation), in which its matrices are banded.
fn node_order(beam: &Beam) -> Vec<usize> {
    let (n, nodes) = (beam.dofs(), beam.len());
    if n == 2 * nodes {
        (0..n).map(|p| p / 2 + (p % 2) * nodes).collect()
    } else {
        (0..n).collect()
    }
}

impl ModalBasis {
    /// All modes of the beam (one per degree of freedom; with a pinned pivot the last one is
    /// the constraint's and is inert: ω = 0 is never used for it, its shape is zero).
    pub fn of(beam: &Beam) -> Self {
        let n = beam.dofs();
        let nodes = beam.len();
        let dof_mass = beam.dof_mass();
        let inv_sqrt_m: Vec<f64> = dof_mass.iter().map(|m| 1.0 / m.sqrt()).collect();
        let (a, pin_vector) = standard_matrix(beam, &inv_sqrt_m);
        let eigen = symmetric_eigen(a, &node_order(beam));
        // Rigid modes come out as round-off-sized eigenvalues; make them exactly zero so
        // that the integrator treats them as free flight. A free–free beam has two
        // (translation and rotation), a free–free beam held at a grip point one (rotation
        // about the grip); a threshold on λ would misclassify the lowest clamped mode of a
        // fine beam (λ₁/λ_max ~ (βd/2)⁴).
        let free = beam.ends == EndsSpec::default();
        let n_rigid = match (free, beam.grip_z.is_some()) {
            (true, false) => 2,
            (true, true) => 1,
            _ => 0,
        }
        .min(eigen.values.len());
        let omega: Vec<f64> = eigen
            .values
            .iter()
            .enumerate()
            .map(|(col, &lambda)| {
                if col < n_rigid {
                    0.0
                } else {
                    lambda.max(0.0).sqrt()
                }
            })
            .collect();
        let mut shapes = DMatrix::zeros(n, n);
        for col in 0..eigen.values.len() {
            if pin_vector.is_some() && col == n - 1 {
                continue; // the constraint's mode: inert, zero shape
            }
            let v = eigen.vectors.column(col);
            // sign convention: positive at the barrel end
            let sign = if v[nodes - 1] < 0.0 { -1.0 } else { 1.0 };
            for i in 0..n {
                shapes[(i, col)] = sign * v[i] * inv_sqrt_m[i];
            }
        }
        if n_rigid > 0 {
            exact_rigid_modes(beam, &dof_mass, &mut shapes, n_rigid);
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

/// Replace the solver's rigid modes (exact only to ~ε·λ_max) by the exact translation and
/// rotation (about the CM, or the grip), and M-orthogonalise the flexible shapes against
/// them, so that the modal integrator conserves momentum and angular momentum to round-off
/// (completeness: Σ_n (1ᵀMφ_n) φ_n(z) = 1).
fn exact_rigid_modes(beam: &Beam, dof_mass: &[f64], shapes: &mut DMatrix<f64>, n_rigid: usize) {
    let (n, nodes) = (beam.dofs(), beam.len());
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bat::band_eigen::{bandwidth, dense, MAX_BAND};
    use crate::bat::section::BatGeometry;
    use crate::spec::{BatPreset, BatSpec, BeamTheory, EndCondition, EndsSpec, GripKind, GripSpec};

    // The band solver against nalgebra's dense one (Householder tridiagonalisation and QR
    // with accumulated vectors: an independent algorithm) on the beams the program builds:
    // the three presets, fixed ends, a pinned and a spring grip, Timoshenko, a fine beam.
    // Eigenvalues agree to 10⁻¹² ‖A‖, the residual ‖Av − λv‖ of every pair is round-off, the
    // vectors are orthonormal to 10⁻¹⁰, and each vector whose eigenvalue is apart from its
    // neighbours agrees with the dense one to 10⁻⁸ (eigenvector error ~ ε‖A‖ / gap).
    #[test]
    fn band_and_dense_solvers_agree_on_every_kind_of_beam() {
        let grip = |kind, stiffness| GripSpec {
            z: 0.1524,
            kind,
            stiffness,
            ..GripSpec::default()
        };
        let fixed = EndsSpec {
            knob: EndCondition::Fixed,
            barrel: EndCondition::Free,
        };
        let preset = |preset| BatSpec {
            preset,
            ..BatSpec::default()
        };
        let (free, eb) = (EndsSpec::default(), BeamTheory::EulerBernoulli);
        type Case = (
            &'static str,
            BatSpec,
            usize,
            EndsSpec,
            BeamTheory,
            Option<GripSpec>,
        );
        let cases: Vec<Case> = vec![
            ("r161", BatSpec::default(), 169, free, eb, None),
            ("aluminum", preset(BatPreset::Aluminum), 169, free, eb, None),
            ("corked", preset(BatPreset::Corked), 169, free, eb, None),
            ("knob fixed", BatSpec::default(), 169, fixed, eb, None),
            (
                "pinned grip",
                BatSpec::default(),
                169,
                free,
                eb,
                Some(grip(GripKind::Pinned, None)),
            ),
            (
                "spring grip",
                BatSpec::default(),
                169,
                free,
                eb,
                Some(grip(GripKind::Spring, Some(2e5))),
            ),
            (
                "timoshenko",
                BatSpec::default(),
                120,
                free,
                BeamTheory::Timoshenko,
                None,
            ),
            ("fine", BatSpec::default(), 400, free, eb, None),
        ];
        for (name, spec, segments, ends, theory, grip) in cases {
            let geometry = BatGeometry::resolve(&spec).unwrap();
            let beam = Beam::build(&geometry, segments, ends, theory, grip.as_ref());
            band_solver_agrees_with_dense(name, &beam);
        }
    }

    /// The band solver's eigenpairs against nalgebra's dense solver on `beam`'s standard
    /// matrix: values to 1e-12 of the norm, residuals, orthogonality, and the vectors of
    /// well-separated values.
    fn band_solver_agrees_with_dense(name: &str, beam: &Beam) {
        let inv_sqrt_m: Vec<f64> = beam.dof_mass().iter().map(|m| 1.0 / m.sqrt()).collect();
        let (a, _) = standard_matrix(beam, &inv_sqrt_m);
        let order = node_order(beam);
        assert!(bandwidth(&a, &order) <= MAX_BAND, "{name}: not banded");
        let n = a.nrows();
        let norm = a.abs().row_sum().max();
        let band = symmetric_eigen(a.clone(), &order);
        let reference = dense(a.clone());
        let v = &band.vectors;
        let orthogonality = (v.transpose() * v - DMatrix::identity(n, n)).abs().max();
        assert!(
            orthogonality < 1e-10,
            "{name}: VᵀV − I reaches {orthogonality:e}"
        );
        for k in 0..n {
            let (got, want) = (band.values[k], reference.values[k]);
            assert!(
                (got - want).abs() <= 1e-12 * norm,
                "{name}, value {k}: {got} vs {want}"
            );
            let col = v.column(k);
            let residual = (&a * col - col * got).abs().max();
            assert!(
                residual <= 1e-12 * norm,
                "{name}, pair {k}: residual {residual:e}"
            );
            let gap = [k.checked_sub(1), Some(k + 1).filter(|&j| j < n)]
                .into_iter()
                .flatten()
                .map(|j| (reference.values[j] - want).abs())
                .fold(f64::INFINITY, f64::min);
            if gap > 1e-6 * norm {
                let r = reference.vectors.column(k);
                let sign = col.dot(&r).signum();
                let diff = (col - r * sign).abs().max();
                assert!(diff < 1e-8, "{name}, vector {k}: differs by {diff:e}");
            }
        }
    }
}
