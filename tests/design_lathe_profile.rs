//! Profiles a lathe can turn (`optimize.profile.shape`): the interpolant through a design's
//! knots, and the placement of every candidate's knots.
//!
//! References: the shape-preserving cubic Hermite interpolant of Fritsch & Carlson (1980,
//! SIAM J. Numer. Anal. 17, 238: monotone data give a monotone interpolant) with the knot
//! slopes of Fritsch & Butland (1984, SIAM J. Sci. Stat. Comput. 5, 300), which lie between
//! the neighbouring secants; from that, on a segment of length h, |r''| ≤ (4 |Δδ_left| +
//! 2 |Δδ_right|) / h for the changes of secant Δδ at its ends (the bound derived in
//! `bat::profile_spline`'s documentation).

use batstudy::optimize::design_of;
use batstudy::study::{load_str, LoadOptions};
use batstudy_physics::bat::profile_spline::{
    max_curvature, max_knot_curvature, resample, slopes, value,
};
use std::path::Path;

mod common;
use common::Rng;

/// Random knots: n positions from 0 with gaps in [0.02, 0.12] m, radii rising (or, with
/// `rising` false, free) from 0.012 m.
fn knots(rng: &mut Rng, n: usize, rising: bool) -> (Vec<f64>, Vec<f64>) {
    let (mut z, mut r) = (vec![0.0], vec![0.012]);
    for _ in 1..n {
        z.push(z.last().unwrap() + 0.02 + 0.1 * rng.unit());
        let step = 0.004 * rng.unit() - if rising { 0.0 } else { 0.002 };
        r.push((r.last().unwrap() + step).max(0.005));
    }
    (z, r)
}

/// Fritsch & Carlson: rising knots give an interpolant that rises everywhere, and on every
/// segment it stays between its two knots (no waist or bulge between knots).
#[test]
fn rising_knots_give_a_rising_profile() {
    let mut rng = Rng(0x0BA7_5EED);
    for case in 0..500 {
        let (z, r) = knots(&mut rng, 3 + case % 9, true);
        let sampled = resample(&z, &r, 0.001);
        for w in sampled.windows(2) {
            assert!(w[1][1] >= w[0][1], "case {case}: falls at z = {}", w[1][0]);
        }
        let d = slopes(&z, &r);
        for k in 0..z.len() - 1 {
            for j in 0..=50 {
                let x = z[k] + (z[k + 1] - z[k]) * j as f64 / 50.0;
                let v = value(&z, &r, &d, x);
                assert!(
                    v >= r[k] - 1e-15 && v <= r[k + 1] + 1e-15,
                    "case {case}, segment {k}"
                );
            }
        }
        // every knot is on the sampled profile
        for (zk, rk) in z.iter().zip(&r) {
            assert!(sampled.iter().any(|p| p[0] == *zk && p[1] == *rk));
        }
    }
}

/// Any knots (rising or not): the interpolant's curvature is within the bound set by the
/// changes of secant at each segment's ends, and equals the exact second derivative of a
/// cubic sampled finely (measured by central differences).
#[test]
fn curvature_is_bounded_by_the_knots() {
    let mut rng = Rng(0xC0FF_EE11);
    for case in 0..500 {
        let (z, r) = knots(&mut rng, 4 + case % 8, case % 2 == 0);
        let n = z.len();
        let delta: Vec<f64> = (0..n - 1)
            .map(|k| (r[k + 1] - r[k]) / (z[k + 1] - z[k]))
            .collect();
        let change = |k: usize| match k {
            0 => (delta[1] - delta[0]).abs(),
            k if k >= n - 2 => (delta[n - 2] - delta[n - 3]).abs(),
            k => (delta[k] - delta[k - 1]).abs(),
        };
        let bound = (0..n - 1)
            .map(|k| {
                (4.0 * change(k) + 2.0 * change(k + 1)).max(2.0 * change(k) + 4.0 * change(k + 1))
                    / (z[k + 1] - z[k])
            })
            .fold(0.0, f64::max);
        let measured = max_curvature(&z, &r);
        assert!(
            measured <= bound * (1.0 + 1e-12),
            "case {case}: {measured} > {bound}"
        );
        // measured against finite differences of the interpolant itself
        let d = slopes(&z, &r);
        let mut fd: f64 = 0.0;
        for k in 0..n - 1 {
            let h = (z[k + 1] - z[k]) * 1e-3;
            for j in 1..1000 {
                let x = z[k] + h * j as f64;
                let v = |x: f64| value(&z, &r, &d, x);
                fd = fd.max(((v(x + h) - 2.0 * v(x) + v(x - h)) / (h * h)).abs());
            }
        }
        assert!(
            fd <= measured * 1.01 + 1e-6,
            "case {case}: {fd} > {measured}"
        );
        assert!(
            fd >= measured * 0.98 - 1e-6,
            "case {case}: {fd} < {measured}"
        );
    }
}

/// The bundled wood design's profile block with a shape: the radius rises from the handle's
/// last fixed knot to the end, the knots bend at most 1 /m.
const STUDY: &str = r#"
name: lathe
model: rigid
base:
  bat: {preset: r161}
  impact: {z: 0.7}
optimize:
  max_evaluations: 20
  profile:
    z: [0.0, 0.02, 0.03, 0.15, 0.35, 0.45, 0.55, 0.62, 0.69, 0.76, 0.84]
    radius: [0.0252, 0.0252, 0.0177, 0.0130, 0.0152,
             {min: 0.012, max: 0.0331}, {min: 0.012, max: 0.0331}, {min: 0.012, max: 0.0331},
             {min: 0.012, max: 0.0331}, {min: 0.012, max: 0.0331}, {min: 0.012, max: 0.0331}]
    shape: {rising: [0.35, 0.84], max_curvature: 1.0}
  objective: {maximize: exit_speed}
"#;

/// A point the search may ask for in `n` dimensions: by turns inside the unit cube, on its
/// corners and faces, and beyond it.
fn cube_point(rng: &mut Rng, case: usize, n: usize) -> Vec<f64> {
    (0..n)
        .map(|_| match case % 3 {
            0 => rng.unit(),
            1 => (rng.unit() * 3.0).floor() / 2.0,
            _ => 2.0 * rng.unit() - 0.5,
        })
        .collect()
}

/// Every point of the unit cube the search may ask for is a profile that rises over the
/// span, bends no more than the bound between the knots, and keeps each radius within its
/// bounds and the fixed knots as they are.
#[test]
fn every_candidate_is_turnable() {
    let s = load_str(STUDY, Path::new("lathe.yaml"), &LoadOptions::default()).unwrap();
    let design = design_of(&s).unwrap().unwrap();
    assert_eq!(design.variables.len(), 6);
    let z = [
        0.0, 0.02, 0.03, 0.15, 0.35, 0.45, 0.55, 0.62, 0.69, 0.76, 0.84,
    ];
    let fixed = [0.0252, 0.0252, 0.0177, 0.0130, 0.0152];
    let mut rng = Rng(0x007A_9E12);
    for case in 0..2000 {
        let u = cube_point(&mut rng, case, 6);
        let x = design.from_unit(&u);
        let r: Vec<f64> = fixed.iter().copied().chain(x.iter().copied()).collect();
        for (k, w) in r.windows(2).enumerate().skip(4) {
            assert!(w[1] >= w[0], "case {case}: falls after knot {k}: {r:?}");
        }
        for v in &x {
            assert!((0.012..=0.0331).contains(v), "case {case}: {v}");
        }
        // the knots' curvature from the first free knot on (the fixed knots before it are
        // the R161's handle, which the bound does not reshape)
        let bend = max_knot_curvature(&z[3..], &r[3..]);
        assert!(bend <= 1.0 + 1e-9, "case {case}: {bend} /m: {r:?}");
    }
}

/// The candidate's bat is the interpolant sampled every 5 mm: its radius rises over the span
/// (the waist the unshaped search found cannot occur).
#[test]
fn the_bat_gets_the_turned_profile() {
    let s = load_str(STUDY, Path::new("lathe.yaml"), &LoadOptions::default()).unwrap();
    let design = design_of(&s).unwrap().unwrap();
    let x = design.from_unit(&[0.9, 0.1, 0.9, 0.0, 1.0, 0.2]);
    let base = design.apply(&x, s.plan.base());
    let knots: Vec<[f64; 2]> =
        yaml_serde::from_value(base["bat"]["profile"]["knots"].clone()).unwrap();
    assert!(knots.len() > 160, "{} knots", knots.len());
    assert!(knots.windows(2).all(|w| w[1][0] - w[0][0] <= 0.005 + 1e-12));
    let taper: Vec<f64> = knots
        .iter()
        .filter(|k| k[0] >= 0.35)
        .map(|k| k[1])
        .collect();
    assert!(taper.windows(2).all(|w| w[1] >= w[0]));
}

/// A start written as radii that keep the shape is the search's start as written (the
/// places found for it give it back), and any placed profile is found again from its radii.
#[test]
fn a_start_that_keeps_the_shape_is_kept() {
    let s = load_str(STUDY, Path::new("lathe.yaml"), &LoadOptions::default()).unwrap();
    let design = design_of(&s).unwrap().unwrap();
    // no start given: each knot at the middle of its bounds, a flat barrel from 45 cm on
    for x in design.start() {
        assert!((x - 0.5 * (0.012 + 0.0331)).abs() < 1e-12, "{x}");
    }
    let mut rng = Rng(0x005E_ED0F);
    for case in 0..300 {
        let u: Vec<f64> = (0..6).map(|_| rng.unit()).collect();
        let x = design.from_unit(&u);
        let written = STUDY.replace("{min: 0.012, max: 0.0331}", "R");
        let mut knots = x.iter();
        let mut text = String::new();
        for (k, piece) in written.split('R').enumerate() {
            text.push_str(piece);
            if k < 6 {
                let r = knots.next().unwrap();
                text.push_str(&format!("{{min: 0.012, max: 0.0331, start: {r:e}}}"));
            }
        }
        let s = load_str(&text, Path::new("lathe.yaml"), &LoadOptions::default()).unwrap();
        let again = design_of(&s).unwrap().unwrap().start();
        for (a, b) in again.iter().zip(&x) {
            assert!((a - b).abs() < 1e-12, "case {case}: {again:?} != {x:?}");
        }
    }
}

/// Against an independent implementation: SciPy 1.17.1's `PchipInterpolator` (the same
/// Fritsch–Butland slopes and end conditions) on the waisted profile an unshaped search once
/// found, its knot slopes and values between knots as SciPy printed them.
#[test]
fn agrees_with_scipy_pchip() {
    let z = [
        0.0, 0.02, 0.03, 0.15, 0.35, 0.45, 0.55, 0.62, 0.69, 0.76, 0.84,
    ];
    let r = [
        0.0252, 0.0252, 0.0177, 0.0130, 0.0152, 0.0150, 0.0252, 0.0331, 0.0277, 0.0325, 0.0329,
    ];
    let scipy_slopes = [
        0.0,
        0.0,
        -0.09980036297640657,
        0.0,
        0.0,
        0.0,
        0.10747371724462579,
        0.0,
        0.0,
        0.009502859656841127,
        0.0,
    ];
    let scipy_values = [
        (0.01, 0.0252),
        (0.025, 0.021574750453720506),
        (0.1, 0.013555088181420984),
        (0.3, 0.01485625),
        (0.4, 0.015099999999999999),
        (0.5, 0.018756578534442174),
        (0.6, 0.03197248747563404),
        (0.65, 0.030974635568513112),
        (0.7, 0.027954253058146143),
        (0.8, 0.03279502859656842),
    ];
    let d = slopes(&z, &r);
    for (k, (a, b)) in d.iter().zip(scipy_slopes).enumerate() {
        assert!((a - b).abs() < 1e-14, "slope at knot {k}: {a} against {b}");
    }
    for (x, want) in scipy_values {
        let got = value(&z, &r, &d, x);
        assert!((got - want).abs() < 1e-15, "at {x}: {got} against {want}");
    }
}

/// A hollow barrel's wall with a gradient bound (`shape.max_wall_slope`): four free wall
/// knots between fixed ones.
const WALL_STUDY: &str = r#"
name: wall
model: rigid
base:
  bat: {preset: aluminum, shell: {from: 0.0}}
  impact: {z: 0.7}
optimize:
  max_evaluations: 20
  profile:
    z: [0.0, 0.02, 0.03, 0.15, 0.35, 0.45, 0.55, 0.65, 0.75, 0.84]
    radius: [0.0252, 0.0252, 0.0177, 0.0130, 0.0152, 0.0180, 0.0252, 0.0307, 0.0318, 0.0321]
    thickness: [0.002, 0.002, 0.002, 0.002, 0.002, 0.0025,
                {min: 0.0015, max: 0.008}, {min: 0.0015, max: 0.008},
                {min: 0.0015, max: 0.008}, {min: 0.0015, max: 0.008}]
    shape: {max_wall_slope: 0.02}
  objective: {maximize: exit_speed}
"#;

/// Every candidate's wall keeps the gradient between neighbouring knots (2 mm per 10 cm)
/// and its knots' bounds, from the fixed 2.5 mm at 45 cm on; and a bound the fixed knots
/// themselves break is refused where the study sets it.
#[test]
fn every_candidate_wall_keeps_its_gradient() {
    let s = load_str(WALL_STUDY, Path::new("wall.yaml"), &LoadOptions::default()).unwrap();
    let design = design_of(&s).unwrap().unwrap();
    assert_eq!(design.variables.len(), 4);
    let z = [0.45, 0.55, 0.65, 0.75, 0.84];
    let mut rng = Rng(0x0057_EE11);
    for case in 0..2000 {
        let u = cube_point(&mut rng, case, 4);
        let x = design.from_unit(&u);
        let t: Vec<f64> = std::iter::once(0.0025).chain(x.iter().copied()).collect();
        for k in 1..t.len() {
            let slope = (t[k] - t[k - 1]).abs() / (z[k] - z[k - 1]);
            assert!(
                slope <= 0.02 * (1.0 + 1e-9),
                "case {case}: {slope} after knot {k}: {t:?}"
            );
        }
        for v in &x {
            assert!((0.0015..=0.008).contains(v), "case {case}: {v}");
        }
    }
    // 0.001 cannot pass from the fixed 2.0 mm at 35 cm to 2.5 mm at 45 cm
    let tight = WALL_STUDY.replace("max_wall_slope: 0.02", "max_wall_slope: 0.001");
    let err = match load_str(&tight, Path::new("wall.yaml"), &LoadOptions::default()) {
        Ok(s) => design_of(&s).unwrap_err().to_string(),
        Err(e) => e.to_string(),
    };
    assert!(
        err.contains("max_wall_slope") && err.contains("within the gradient"),
        "{err}"
    );
}
