//! Modal validation of the beam model.
//!
//! References: docs/physics.md "Reference numbers and their sources" — the uniform Euler–Bernoulli beam
//! (ω_n = (β_n L)² √(Y I / (ρ A L⁴)), textbook values of β_n L), and Nathan, Am. J. Phys.
//! 68, 979 (2000), Table II (R161 free–free Euler–Bernoulli frequencies and nodes).

use batstudy::model::spec::{
    BatSpec, EndCondition, EndsSpec, MaterialSpec, NumericsSpec, ProfileSpec,
};
use batstudy::model::{prepare_bat, PreparedBat};

const RADIUS: f64 = 0.03;
const LENGTH: f64 = 0.84;
const DENSITY: f64 = 649.0;
const YOUNGS: f64 = 1.814e10;

fn uniform_bat(segments: Option<usize>, ends: EndsSpec) -> PreparedBat {
    let bat = BatSpec {
        profile: Some(ProfileSpec::Knots(vec![[0.0, RADIUS], [LENGTH, RADIUS]])),
        material: MaterialSpec {
            density: Some(DENSITY),
            youngs_modulus: Some(YOUNGS),
            ..MaterialSpec::default()
        },
        ends,
        ..BatSpec::default()
    };
    let numerics = NumericsSpec {
        segments,
        ..NumericsSpec::default()
    };
    prepare_bat(&bat, &numerics).unwrap()
}

/// ω_n / 2π for a uniform beam with the given β_n L.
fn exact_frequency(beta_l: f64) -> f64 {
    let area = std::f64::consts::PI * RADIUS * RADIUS;
    let second_moment = std::f64::consts::PI * RADIUS.powi(4) / 4.0;
    beta_l * beta_l * (YOUNGS * second_moment / (DENSITY * area * LENGTH.powi(4))).sqrt()
        / (2.0 * std::f64::consts::PI)
}

// β_n L to 9 digits (the 5-digit values of docs/physics.md rounded; 4.7300 vs 4.73004 alone is
// a 1.7e-5 frequency error, which would mask the convergence measurement).
const FREE_FREE: [f64; 5] = [
    4.73004074,
    7.85320462,
    10.99560784,
    14.13716549,
    17.27875966,
];
const CLAMPED_FREE: [f64; 3] = [1.87510407, 4.69409113, 7.85475744];

fn free_free_errors(segments: Option<usize>) -> Vec<f64> {
    let bat = uniform_bat(segments, EndsSpec::default());
    let f = bat.properties().mode_frequency.clone();
    FREE_FREE
        .iter()
        .zip(&f)
        .map(|(bl, f)| f / exact_frequency(*bl) - 1.0)
        .collect()
}

#[test]
fn uniform_free_free_modes_within_0p1_percent_at_default_resolution() {
    let errors = free_free_errors(None);
    for (n, e) in errors.iter().enumerate() {
        assert!(e.abs() < 1e-3, "mode {}: relative error {e:e}", n + 1);
    }
}

#[test]
fn uniform_free_free_converges_at_second_order() {
    let coarse = free_free_errors(Some(60));
    let fine = free_free_errors(Some(120));
    for n in 0..5 {
        let ratio = coarse[n] / fine[n];
        assert!(
            (3.6..4.4).contains(&ratio),
            "mode {}: error ratio {ratio} (errors {:e}, {:e})",
            n + 1,
            coarse[n],
            fine[n]
        );
    }
}

#[test]
fn uniform_clamped_free_modes_converge_at_first_order() {
    let ends = EndsSpec {
        knob: EndCondition::Fixed,
        barrel: EndCondition::Free,
    };
    let errors = |n: usize| -> Vec<f64> {
        let bat = uniform_bat(Some(n), ends);
        assert_eq!(bat.modes().n_rigid, 0);
        let f = bat.modes().flexible_frequencies();
        CLAMPED_FREE
            .iter()
            .zip(&f)
            .map(|(bl, f)| f / exact_frequency(*bl) - 1.0)
            .collect()
    };
    let (coarse, fine) = (errors(84), errors(168));
    for n in 0..3 {
        // the clamp sits about one segment beyond the end: errors O(d), halving on refinement
        assert!(fine[n].abs() < 0.02, "mode {}: error {:e}", n + 1, fine[n]);
        let ratio = coarse[n] / fine[n];
        assert!((1.7..2.3).contains(&ratio), "mode {}: ratio {ratio}", n + 1);
    }
}

#[test]
fn r161_matches_nathan_table_ii() {
    let bat = prepare_bat(&BatSpec::default(), &NumericsSpec::default()).unwrap();
    let p = bat.properties();
    // CSV header (solid wood, ρ 649): mass ≈ 0.869 kg, CM ≈ 0.561 m
    assert!((p.mass / 0.869 - 1.0).abs() < 0.01, "mass {}", p.mass);
    assert!((p.z_cm / 0.561 - 1.0).abs() < 0.01, "z_cm {}", p.z_cm);
    // Nathan Table II, Euler–Bernoulli, modes 2–5 (Hz)
    for (k, nathan) in [(1, 612.0), (2, 1334.0), (3, 2220.0), (4, 3304.0)] {
        let f = p.mode_frequency[k];
        assert!(
            (f / nathan - 1.0).abs() < 0.02,
            "mode {}: {f} Hz vs Nathan {nathan}",
            k + 1
        );
    }
    // nodes, cm from the knob (docs/physics.md numbering: mode 1 = first flexible mode)
    let expected: [&[f64]; 3] = [&[17.0, 68.0], &[7.0, 39.0, 72.0], &[5.0, 25.0, 50.0, 74.0]];
    for (k, nodes) in expected.iter().enumerate() {
        let got = &p.mode_nodes[k];
        assert_eq!(got.len(), nodes.len(), "mode {} nodes {got:?}", k + 1);
        for (g, e) in got.iter().zip(nodes.iter()) {
            assert!(
                (g * 100.0 - e).abs() < 1.5,
                "mode {}: node {g} m vs {e} cm",
                k + 1
            );
        }
    }
}
