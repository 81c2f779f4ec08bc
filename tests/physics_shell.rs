//! Verification of the barrel's shell model (`bat::shell`, `bat::laminate`) against closed
//! forms of the same theory and of the ring:
//! - a free–free uniform cylinder's lowest n = 2 mode is Rayleigh's inextensional mode, whose
//!   frequency is the free ring's (Rayleigh, "Theory of Sound" §235; Soedel, "Vibrations of
//!   Shells and Plates", 3rd ed., §5.4): ω² = D n²(n² − 1)² / (ρ h a⁴ (n² + 1));
//! - a simply supported uniform cylinder's modes are u = U cos(mπx/L) cos nθ,
//!   v = V sin(mπx/L) sin nθ, w = W sin(mπx/L) cos nθ exactly (Leissa, NASA SP-288, §2.3),
//!   which turns Love's energies into a 3×3 eigenproblem written out here by hand; the
//!   discretised shell converges to it at the rate of cubic elements;
//! - classical lamination theory's limits: one isotropic ply gives D = Eh³/(12(1 − ν²)), a
//!   ply turned 90° swaps A₁₁ and A₂₂, two walls split by a gap bend as two (Jones 1999,
//!   §4.2).

use batstudy::model::bat::laminate::{Laminate, Layer, Ply, Wall};
use batstudy::model::bat::shell::{mesh, modes_of, ShellEnd, WallAlong};
use nalgebra::{Matrix3, SymmetricEigen};

const E: f64 = 71.7e9;
const NU: f64 = 0.33;
const RHO: f64 = 2830.0;

struct Uniform {
    h: f64,
    a: f64,
}

impl WallAlong for Uniform {
    fn wall(&self, _x: f64) -> Wall {
        Wall::isotropic(E, NU, RHO, self.h, self.a)
    }
}

fn ring_omega(n: f64, h: f64, a: f64) -> f64 {
    let d = E * h.powi(3) / (12.0 * (1.0 - NU * NU));
    (d * n * n * (n * n - 1.0).powi(2) / (RHO * h * a.powi(4) * (n * n + 1.0))).sqrt()
}

/// Love's simply supported cylinder, mode (m, n): the lowest root of the 3×3 problem.
fn supported_omega(m: f64, n: f64, h: f64, a: f64, l: f64) -> f64 {
    let c = E * h / (1.0 - NU * NU);
    let d = E * h.powi(3) / (12.0 * (1.0 - NU * NU));
    let lam = m * std::f64::consts::PI / l;
    // strains per (U, V, W) amplitude: the x-profiles are sin or cos, each squared to L/2
    let rows: [([f64; 3], f64); 6] = [
        ([-lam, 0.0, 0.0], c),                      // ε_x
        ([0.0, n / a, 1.0 / a], c),                 // ε_θ
        ([-n / a, lam, 0.0], 0.5 * (1.0 - NU) * c), // γ
        ([0.0, 0.0, lam * lam], d),                 // κ_x
        ([0.0, n / (a * a), n * n / (a * a)], d),   // κ_θ
        (
            [0.0, 2.0 * lam / a, 2.0 * n * lam / a],
            0.5 * (1.0 - NU) * d,
        ), // τ
    ];
    let mut k = Matrix3::zeros();
    for (b, stiff) in &rows {
        for i in 0..3 {
            for j in 0..3 {
                k[(i, j)] += stiff * b[i] * b[j];
            }
        }
    }
    // the Poisson couplings ε_x ε_θ and κ_x κ_θ
    for (p, q, stiff) in [(0usize, 1usize, NU * c), (3, 4, NU * d)] {
        let (bp, bq) = (rows[p].0, rows[q].0);
        for i in 0..3 {
            for j in 0..3 {
                k[(i, j)] += stiff * (bp[i] * bq[j] + bq[i] * bp[j]);
            }
        }
    }
    let e = SymmetricEigen::new(k / (RHO * h));
    e.eigenvalues
        .iter()
        .copied()
        .fold(f64::INFINITY, f64::min)
        .sqrt()
}

#[test]
fn free_cylinder_lowest_mode_sits_just_below_the_ring() {
    // The uniform inextensional motion (W, V = −W/n, U = 0) is in the element space and its
    // Rayleigh quotient is the ring's ω², so the lowest eigenvalue lies at or below it. The
    // free edges relax the bending (M_x = 0 lets κ_x take up the Poisson coupling), which
    // at most replaces D by D(1 − ν²): a deficit of at most 1 − √(1 − ν²) = 5.6 %; a
    // long tube's is a fraction of a percent.
    let (h, a) = (0.0022, 0.032);
    for n in [2u32, 3] {
        let ring = ring_omega(f64::from(n), h, a);
        for l in [0.3, 1.2] {
            let nodes = mesh(0.0, l, &[], (l / 0.01) as usize);
            let ends = (ShellEnd::Free, ShellEnd::Free);
            let modes = modes_of(n, &nodes, &Uniform { h, a }, ends, 1).unwrap();
            let deficit = 1.0 - modes[0].omega / ring;
            assert!(
                (-1e-12..0.005).contains(&deficit),
                "n = {n}, L = {l}: {deficit:e}"
            );
        }
    }
}

#[test]
fn supported_cylinder_converges_to_the_closed_form_at_fourth_order() {
    let (h, a, l) = (0.0022, 0.032, 0.30);
    for n in [2u32, 3, 4] {
        let exact = supported_omega(1.0, f64::from(n), h, a, l);
        let err = |elements: usize| {
            let nodes = mesh(0.0, l, &[], elements);
            let ends = (ShellEnd::Supported, ShellEnd::Supported);
            let m = modes_of(n, &nodes, &Uniform { h, a }, ends, 1).unwrap();
            (m[0].omega / exact - 1.0).abs()
        };
        let (e8, e16, e32) = (err(8), err(16), err(32));
        let order = (e8 / e16).log2();
        assert!(e32 < 1e-6, "n = {n}: error {e32:e} at 32 elements");
        assert!(
            order > 3.5,
            "n = {n}: observed order {order:.2} ({e8:e}, {e16:e})"
        );
    }
}

#[test]
fn lamination_limits() {
    let (h, t) = (0.002, 0.5 * 0.002);
    let metal = Ply::isotropic(E, NU, RHO);
    let one = Laminate {
        layers: vec![Layer {
            ply: Some(metal),
            thickness: h,
            angle: 0.0,
        }],
    }
    .wall(1.0, 0.03);
    let d = E * h.powi(3) / (12.0 * (1.0 - NU * NU));
    assert!((one.d11 / d - 1.0).abs() < 1e-12 && (one.d12 / (NU * d) - 1.0).abs() < 1e-12);
    assert!((one.a66 / (E * h / (2.0 * (1.0 + NU))) - 1.0).abs() < 1e-12);
    let ply = Ply {
        e1: 181e9,
        e2: 10.3e9,
        g12: 7.17e9,
        nu12: 0.28,
        density: 1600.0,
        matrix: true,
        loss: [0.0; 3],
        strength: batstudy::model::bat::laminate::Strength::Unknown,
    };
    let at = |angle: f64| {
        Laminate {
            layers: vec![Layer {
                ply: Some(ply),
                thickness: h,
                angle,
            }],
        }
        .wall(1.0, 0.03)
    };
    let (axial, hoop) = (at(0.0), at(std::f64::consts::FRAC_PI_2));
    assert!(
        (axial.a11 / hoop.a22 - 1.0).abs() < 1e-12 && (axial.a22 / hoop.a11 - 1.0).abs() < 1e-12
    );
    // two walls of h/2 split by a gap: membrane as one wall of h, bending a quarter of it
    let split = Laminate {
        layers: vec![
            Layer {
                ply: Some(metal),
                thickness: t,
                angle: 0.0,
            },
            Layer {
                ply: None,
                thickness: 0.001,
                angle: 0.0,
            },
            Layer {
                ply: Some(metal),
                thickness: t,
                angle: 0.0,
            },
        ],
    }
    .wall(1.0, 0.03);
    assert!((split.a11 / one.a11 - 1.0).abs() < 1e-12);
    assert!((split.d22 / (0.25 * one.d22) - 1.0).abs() < 1e-12);
    assert!((split.mass_per_area / (RHO * h) - 1.0).abs() < 1e-12);
}

#[test]
fn subspace_iteration_agrees_with_the_dense_solver() {
    // the same matrices through nalgebra's dense symmetric solver (Cholesky of M on the
    // free dofs, then L⁻¹ K L⁻ᵀ)
    use batstudy::model::bat::shell::held_matrices;
    let nodes = mesh(0.0, 0.3, &[], 12);
    let ends = (ShellEnd::Clamped, ShellEnd::Supported);
    let walls = Uniform {
        h: 0.0022,
        a: 0.032,
    };
    let (k, m) = held_matrices(2, &nodes, &walls, ends);
    let free: Vec<usize> = (0..m.n).filter(|&i| m.get(i, i) > 0.0).collect();
    let pick = |a: &nalgebra::DMatrix<f64>| {
        nalgebra::DMatrix::from_fn(free.len(), free.len(), |i, j| a[(free[i], free[j])])
    };
    let (kd, md) = (pick(&k.to_dense()), pick(&m.to_dense()));
    let l = md.cholesky().unwrap().l();
    let li = l.try_inverse().unwrap();
    let a = &li * kd * li.transpose();
    let mut dense: Vec<f64> = SymmetricEigen::new((&a + a.transpose()) * 0.5)
        .eigenvalues
        .iter()
        .copied()
        .collect();
    dense.sort_by(f64::total_cmp);
    let modes = modes_of(2, &nodes, &walls, ends, 4).unwrap();
    for (j, mode) in modes.iter().enumerate() {
        let rel = mode.omega.powi(2) / dense[j] - 1.0;
        assert!(rel.abs() < 1e-10, "mode {j}: {rel:e}");
    }
}
