//! The discretised Euler–Bernoulli beam (docs/physics.md): N segments of length d, one lumped
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

use crate::bat::section::BatGeometry;
use crate::spec::{BeamTheory, EndCondition, EndsSpec, GripKind, GripSpec};

/// One strain measure: Σ coef·u[dof] over up to four taps (dof −1 = a ghost held at zero),
/// with stiffness `weight`; K = Σ weight · r rᵀ (symmetric positive semi-definite).
#[derive(Debug, Clone, Copy, PartialEq)]
struct StrainRow {
    taps: [(isize, f64); 4],
    weight: f64,
}

impl StrainRow {
    fn new(taps: &[(isize, f64)], weight: f64) -> Self {
        let mut t = [(-1isize, 0.0); 4];
        t[..taps.len()].copy_from_slice(taps);
        Self { taps: t, weight }
    }
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
    /// Lumped rotary inertias of the segments, kg·m² (Timoshenko: the rotations ψ_i are
    /// degrees of freedom N..2N; empty for Euler–Bernoulli).
    pub rotary: Vec<f64>,
    /// Pinned pivot: (k, a) of its linear interpolation; (1 − a) y_k + a y_{k+1} = 0.
    pub pin: Option<(usize, f64)>,
    /// Position of the grip (pinned or spring), m.
    pub grip_z: Option<f64>,
    rows: Vec<StrainRow>,
}

impl Beam {
    /// Discretise `geometry` into `segments` segments with the given ends (Euler–Bernoulli,
    /// free bat).
    pub fn new(geometry: &BatGeometry, segments: usize, ends: EndsSpec) -> Self {
        Self::build(geometry, segments, ends, BeamTheory::EulerBernoulli, None)
    }

    /// Discretise with a beam theory and an optional grip.
    ///
    /// Timoshenko: degrees of freedom y_0..y_{N−1}, ψ_0..ψ_{N−1} (ψ = rotation of the
    /// section). Between neighbouring nodes one element with bending strain
    /// (ψ_{i+1} − ψ_i)/d and shear strain γ = (y_{i+1} − y_i)/d − (ψ_i + ψ_{i+1})/2 (one-point
    /// rule: no shear locking), energies ½ (Y I_e/d)(Δψ)² + ½ κ G A_e d γ²; masses m_i and
    /// rotary inertias ρ I_i d lumped at the nodes. Rigid translation and rotation
    /// (y = θ z, ψ = θ) give zero strain exactly. A fixed end adds an element to a ghost
    /// node (y = ψ = 0) one segment beyond the end node.
    pub fn build(
        geometry: &BatGeometry,
        segments: usize,
        ends: EndsSpec,
        theory: BeamTheory,
        grip: Option<&GripSpec>,
    ) -> Self {
        let n = segments;
        let d = geometry.length / n as f64;
        let z: Vec<f64> = (0..n).map(|i| (i as f64 + 0.5) * d).collect();
        let mass: Vec<f64> = (0..n)
            .map(|i| segment_integral(geometry, d, i, &|z| geometry.mass_per_length(z)))
            .collect();
        let mut beam = match theory {
            BeamTheory::EulerBernoulli => {
                // Segment-averaged stiffness: smooth in the profile, exact total bending
                // compliance for a piecewise-constant I.
                let bending: Vec<f64> = (0..n)
                    .map(|i| {
                        let i_avg =
                            segment_integral(geometry, d, i, &|z| geometry.second_moment(z));
                        geometry.youngs_modulus * i_avg / d.powi(4)
                    })
                    .collect();
                Self::from_parts(d, z, mass, &bending, ends)
            }
            BeamTheory::Timoshenko => Self::timoshenko(geometry, d, z, mass, ends),
        };
        if let Some(g) = grip {
            beam.add_grip(g);
        }
        beam
    }

    /// The Timoshenko beam: deflection and rotation per node, a bending and a shear strain
    /// per element (between nodes i and i + 1; ghost elements at fixed ends).
    fn timoshenko(
        geometry: &BatGeometry,
        d: f64,
        z: Vec<f64>,
        mass: Vec<f64>,
        ends: EndsSpec,
    ) -> Self {
        let n = z.len();
        let rotary: Vec<f64> = (0..n)
            .map(|i| segment_integral(geometry, d, i, &|z| geometry.rotary_inertia_per_length(z)))
            .collect();
        let ni = n as isize;
        let mut rows = Vec::new();
        if ends.knob == EndCondition::Fixed {
            rows.extend(timoshenko_element(geometry, d, ni, -1));
        }
        for i in 0..ni - 1 {
            rows.extend(timoshenko_element(geometry, d, ni, i));
        }
        if ends.barrel == EndCondition::Fixed {
            rows.extend(timoshenko_element(geometry, d, ni, ni - 1));
        }
        Self {
            d,
            z,
            mass,
            ends,
            rotary,
            pin: None,
            grip_z: None,
            rows,
        }
    }

    /// The hands: a pin, or a spring to the grip point.
    fn add_grip(&mut self, g: &GripSpec) {
        let (k, a) = self.interpolation(g.z);
        self.grip_z = Some(g.z);
        match g.kind {
            GripKind::Pinned => self.pin = Some((k, a)),
            GripKind::Spring => self.rows.push(StrainRow::new(
                &[(k as isize, 1.0 - a), (k as isize + 1, a)],
                g.stiffness.unwrap_or(0.0),
            )),
        }
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
        let curvature = |c: isize, weight: f64| {
            let dof = |i: isize| if (0..n).contains(&i) { i } else { -1 };
            StrainRow::new(
                &[(dof(c - 1), 1.0), (dof(c), -2.0), (dof(c + 1), 1.0)],
                weight,
            )
        };
        let mut rows = Vec::new();
        if ends.knob == EndCondition::Fixed {
            rows.push(curvature(-1, bending[0]));
            rows.push(curvature(0, bending[0]));
        }
        for c in 1..n - 1 {
            rows.push(curvature(c, bending[c as usize]));
        }
        if ends.barrel == EndCondition::Fixed {
            let last = bending[(n - 1) as usize];
            rows.push(curvature(n - 1, last));
            rows.push(curvature(n, last));
        }
        Self {
            d,
            z,
            mass,
            ends,
            rotary: Vec::new(),
            pin: None,
            grip_z: None,
            rows,
        }
    }

    /// Degrees of freedom: N (Euler–Bernoulli) or 2N (Timoshenko: y then ψ).
    pub fn dofs(&self) -> usize {
        self.z.len() + self.rotary.len()
    }

    /// The diagonal mass matrix: masses, then rotary inertias.
    pub fn dof_mass(&self) -> Vec<f64> {
        self.mass.iter().chain(&self.rotary).copied().collect()
    }

    /// Total rotary inertia of the sections (0 for Euler–Bernoulli), kg·m².
    pub fn total_rotary(&self) -> f64 {
        self.rotary.iter().sum()
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

    /// out = K u (u over all degrees of freedom).
    pub fn apply_stiffness(&self, y: &[f64], out: &mut [f64]) {
        out.iter_mut().for_each(|o| *o = 0.0);
        for row in &self.rows {
            let strain: f64 = row
                .taps
                .iter()
                .filter(|t| t.0 >= 0)
                .map(|&(i, c)| c * y[i as usize])
                .sum();
            let stress = row.weight * strain;
            for &(i, c) in row.taps.iter().filter(|t| t.0 >= 0) {
                out[i as usize] += c * stress;
            }
        }
    }

    /// K as a dense matrix (for the eigenproblem).
    pub fn stiffness_matrix(&self) -> DMatrix<f64> {
        let n = self.dofs();
        let mut k = DMatrix::zeros(n, n);
        for row in &self.rows {
            for &(i, ci) in row.taps.iter().filter(|t| t.0 >= 0) {
                for &(j, cj) in row.taps.iter().filter(|t| t.0 >= 0) {
                    k[(i as usize, j as usize)] += row.weight * ci * cj;
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

/// ∫ f over segment i (of length d) of the bat.
fn segment_integral(geometry: &BatGeometry, d: f64, i: usize, f: &dyn Fn(f64) -> f64) -> f64 {
    geometry.integrate(i as f64 * d, (i + 1) as f64 * d, f)
}

/// The Timoshenko element between nodes i and i + 1 of `ni` (i = −1 and ni − 1: ghosts of
/// fixed ends): its bending strain (ψ') and its shear strain (y' − ψ), each with its
/// element-averaged stiffness.
fn timoshenko_element(geometry: &BatGeometry, d: f64, ni: isize, i: isize) -> Vec<StrainRow> {
    let (lo, hi) = ((i as f64 + 0.5) * d, (i as f64 + 1.5) * d);
    let (lo, hi) = (lo.max(0.0), hi.min(geometry.length));
    let span = hi - lo;
    let ei =
        geometry.youngs_modulus * geometry.integrate(lo, hi, |z| geometry.second_moment(z)) / span;
    let ga = geometry.integrate(lo, hi, |z| geometry.shear_stiffness(z)) / span;
    let y = |j: isize| if (0..ni).contains(&j) { j } else { -1 };
    let psi = |j: isize| if (0..ni).contains(&j) { ni + j } else { -1 };
    vec![
        StrainRow::new(&[(psi(i + 1), 1.0), (psi(i), -1.0)], ei / d),
        StrainRow::new(
            &[
                (y(i + 1), 1.0 / d),
                (y(i), -1.0 / d),
                (psi(i), -0.5),
                (psi(i + 1), -0.5),
            ],
            ga * d,
        ),
    ]
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
