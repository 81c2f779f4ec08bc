//! Barrel compression (`bat::compression`), verified against closed forms:
//! - a ring pinched by two diametral line loads closes by (π/4 − 2/π) p a³/(E I), 0.1488
//!   p a³/(E I) (Roark's Formulas for Stress and Strain, 7th ed., table 9.2 case 1; Timoshenko,
//!   Strength of Materials I, §83). A free–free uniform tube loaded along its whole length
//!   is that ring in plane strain (E I = D = E h³/(12(1 − ν²)) per unit length), so the
//!   shell's sum over wave numbers must give it;
//! - a homogeneous wall's compliance under any fixed load scales as 1/E exactly (linear
//!   elasticity): twice the modulus, half the deflection;
//! - the mesh and the wave-number series converge (the defaults sit where they have);
//! - the modal expansion of the flexibility (Σ φ²/ω² over every mode) approaches the static
//!   solve from below as modes are added.

use batstudy::model::bat::compression::{
    barrel_compression, pinch_compliance, CompressionTest, PinchResolution, BASEBALL, RESOLUTION,
};
use batstudy::model::bat::laminate::Wall;
use batstudy::model::bat::section::BatGeometry;
use batstudy::model::bat::shell::{ShellEnd, WallAlong};
use batstudy::model::spec::BatSpec;

const E: f64 = 71.7e9;
const NU: f64 = 0.33;
const RHO: f64 = 2830.0;

struct Uniform {
    e: f64,
    h: f64,
    a: f64,
}

impl WallAlong for Uniform {
    fn wall(&self, _x: f64) -> Wall {
        Wall::isotropic(self.e, NU, RHO, self.h, self.a)
    }
}

fn test(from_end: f64, head_length: f64, strip_width: f64) -> CompressionTest {
    CompressionTest {
        from_end,
        deflection: 1e-3,
        head_length,
        strip_width,
    }
}

/// The same theory's ring, in closed form: a wave number's constant fields over a free
/// tube of length l (U = 0 for n ≥ 2; for n = 0 the free ends let the axis stretch, U′ =
/// −A₁₂/A₁₁ · W/a), the membrane's stiffness p and the hoop bending's q in series,
/// summed as the compression sums them (head and anvil, the strip's mean of cos nθ).
fn ring_series(wall: &Wall, l: f64, strip_angle: f64, max_n: u32) -> f64 {
    let a = wall.radius;
    let (p, q) = (wall.a22 / (a * a), wall.d22 / a.powi(4));
    let mut sum = 0.0;
    for n in (0..=max_n).step_by(2) {
        let nf = f64::from(n);
        let per_length = if n == 0 {
            2.0 * std::f64::consts::PI * a * (wall.a22 - wall.a12 * wall.a12 / wall.a11) / (a * a)
        } else {
            std::f64::consts::PI * a * p * q / (p + q) * (nf * nf - 1.0).powi(2)
        };
        let strip = if n == 0 {
            1.0
        } else {
            (nf * strip_angle).sin() / (nf * strip_angle)
        };
        sum += 4.0 * strip * strip / (l * per_length);
    }
    sum
}

#[test]
fn a_tube_pinched_along_its_length_closes_as_a_ring() {
    // long against the edges' anticlastic zones (width about √(a h), where a free end's
    // hoop bending is in plane stress, (1 − ν²) softer), which add about (√(a h)/l) ν²
    for (h, a) in [(0.5e-3, 0.05), (2.5e-3, 0.0333)] {
        let (l, strip) = (10.0, 1e-4);
        let wall = Uniform { e: E, h, a };
        let t = test(0.5 * l, l, strip);
        let c = pinch_compliance(
            (0.0, l),
            &[],
            &wall,
            (ShellEnd::Free, ShellEnd::Free),
            0.5 * l,
            &t,
            RESOLUTION,
        )
        .unwrap();
        let exact = ring_series(
            &wall.wall(0.0),
            l,
            0.5 * strip / a,
            RESOLUTION.max_wave_number,
        );
        let rel = c / exact - 1.0;
        assert!(
            rel.abs() < 2e-4,
            "h/a = {}: {c:e} against the series' {exact:e} ({rel:+.2e})",
            h / a
        );
        // Roark's thin, inextensible ring: the membrane and the axisymmetric squeeze add
        // about (h/a)²/3, the truncated series takes less than 1e-5
        let d = E * h.powi(3) / (12.0 * (1.0 - NU * NU));
        let ring = (std::f64::consts::FRAC_PI_4 - 2.0 / std::f64::consts::PI) * a.powi(3) / (d * l);
        let rel = c / ring - 1.0;
        let band = 0.5 * (h / a).powi(2) + 5e-4;
        assert!(
            rel.abs() < band,
            "h/a = {}: {c:e} against Roark's {ring:e} ({rel:+.2e})",
            h / a
        );
    }
}

#[test]
fn compliance_scales_as_one_over_the_modulus() {
    let t = test(0.15, 0.0254, 1e-3);
    let ends = (ShellEnd::Free, ShellEnd::Supported);
    let c = |e: f64| {
        let wall = Uniform {
            e,
            h: 2.5e-3,
            a: 0.0318,
        };
        pinch_compliance((0.0, 0.6), &[], &wall, ends, 0.45, &t, RESOLUTION).unwrap()
    };
    let ratio = c(E) / c(2.0 * E);
    assert!((ratio - 2.0).abs() < 1e-9, "ratio {ratio}");
}

/// The presets' barrels: the hollow presets and a uniform 7050 wall on their geometry.
fn geometry(bat: &str) -> BatGeometry {
    BatGeometry::resolve(&serde_json::from_str::<BatSpec>(bat).unwrap()).unwrap()
}

#[test]
fn the_default_resolution_is_converged_to_a_thousandth() {
    let finer = PinchResolution {
        elements: 2 * RESOLUTION.elements,
        max_wave_number: 2 * RESOLUTION.max_wave_number,
    };
    for bat in [
        r#"{"preset": "alloy_bbcor"}"#,
        r#"{"preset": "composite_bbcor"}"#,
    ] {
        let g = geometry(bat);
        let (at, fine) = (
            barrel_compression(&g, &BASEBALL, RESOLUTION).unwrap(),
            barrel_compression(&g, &BASEBALL, finer).unwrap(),
        );
        assert!(
            (at / fine - 1.0).abs() < 1e-3,
            "{bat}: {at} N against {fine} N"
        );
    }
}

/// Two more checks of the same linear theory: a static deflection is the sum over all the
/// modes of φ² / ω² (the modal expansion of the flexibility), so the wave number 2 modes
/// the collisions keep give less than the static solve, and more of them come closer.
#[test]
fn the_modes_flexibility_approaches_the_static_one_from_below() {
    use batstudy::model::bat::barrel::{barrel_wall, hollow_part};
    use batstudy::model::bat::shell::{mesh, modes_of, static_radial};
    let g = geometry(r#"{"preset": "alloy_bbcor", "shell": {"thickness": 0.00275}}"#);
    let (start, ends) = hollow_part(&g).unwrap();
    let (centre, half) = (g.length - 0.1524, 0.0127);
    let nodes = mesh(start, g.length, &[centre - half, centre + half], 120);
    let wall = barrel_wall(&g);
    let exact = static_radial(2, &nodes, &wall, ends, centre, half).unwrap();
    let modal = |count: usize| -> f64 {
        let shapes = batstudy::model::bat::shell::ShellModes {
            nodes: nodes.clone(),
            modes: modes_of(2, &nodes, &wall, ends, count).unwrap(),
            factors: Vec::new(),
            static_nodes: Vec::new(),
            held: Vec::new(),
        };
        (0..shapes.modes.len())
            .map(|j| {
                let phi = mean_over(&shapes, j, centre, half);
                phi * phi / shapes.modes[j].omega.powi(2)
            })
            .sum()
    };
    let (few, many) = (modal(4), modal(24));
    assert!(
        few < many && many < exact * (1.0 + 1e-9),
        "{few:e} < {many:e} < {exact:e}"
    );
    assert!(many > 0.9 * exact, "24 modes give {many:e} of {exact:e}");
}

/// Mode j's W averaged over [centre − half, centre + half] (Simpson's rule, fine).
fn mean_over(s: &batstudy::model::bat::shell::ShellModes, j: usize, centre: f64, half: f64) -> f64 {
    let k = 200;
    let h = 2.0 * half / k as f64;
    let mut sum = 0.0;
    for i in 0..=k {
        let w = if i == 0 || i == k {
            1.0
        } else if i % 2 == 1 {
            4.0
        } else {
            2.0
        };
        sum += w * s.radial(j, centre - half + i as f64 * h);
    }
    sum * h / 3.0 / (2.0 * half)
}

/// A thicker wall is stiffer (between the ring's h³ and a plate's local h²), and a solid
/// bat has no compression.
#[test]
fn thicker_walls_squeeze_harder_and_solid_bats_not_at_all() {
    let force = |t: f64| {
        let bat = format!(r#"{{"preset": "alloy_bbcor", "shell": {{"thickness": {t}}}}}"#);
        barrel_compression(&geometry(&bat), &BASEBALL, RESOLUTION).unwrap()
    };
    let (thin, mid, thick) = (force(0.0015), force(0.002), force(0.00275));
    assert!(thin < mid && mid < thick, "{thin} {mid} {thick}");
    // near the ring's h³ (the wall's hoop bending), less at a local load: between h² and h³
    let exponent = (thick / thin).ln() / (0.00275f64 / 0.0015).ln();
    assert!((2.0..3.2).contains(&exponent), "force ∝ h^{exponent}");
    let solid = geometry(r#"{"preset": "r161"}"#);
    assert!(barrel_compression(&solid, &BASEBALL, RESOLUTION)
        .unwrap()
        .is_nan());
}
