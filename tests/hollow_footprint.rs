//! A hollow bat's BBCOR rests on no free contact parameter. The ball loads the barrel's
//! breathing modes over its own footprint, which grows from a point as the ball is
//! compressed and shrinks as it unloads (docs/physics.md, "The barrel as a shell"). What is
//! left of a choice is how much of the undeformed bodies' overlap the footprint covers: from
//! Hertz's elastic contact, half of it (a² = R s against 2 R s; Johnson, "Contact Mechanics"
//! §4.2), to a ball flattened over all of it. The aim is that over that range each hollow
//! bat's BBCOR moves by less than a certification measurement's uncertainty, 0.005; it does
//! not yet (about 0.01, docs/physics.md, "The barrel as a shell"). What is held: the
//! footprint's range moves BBCOR by at most half what a fixed patch of 1–3 cm did, and a
//! larger footprint (a heavier piece of wall under the ball) lowers it.
//!
//! Also verification: a footprint of vanishing size is the point load (the mode's shape at
//! the impact point), and the footprint's axes follow √s with the overlap's radii.

use batstudy::model::bat::section::BatGeometry;
use batstudy::model::collision::wave::footprint_axes;
use batstudy::model::measures::metrics::{bbcor_scan_mapped, in_order, BbcorShot};
use batstudy::model::prepare_bat;
use batstudy::model::spec::{BallSpec, BatSpec, HoopSpec, NumericsSpec};

/// The best BBCOR of `bat` under the protocol, its hoop from the shell with `hoop`.
fn best_bbcor(bat: &str, hoop: HoopSpec) -> f64 {
    let bat: BatSpec = serde_json::from_str(bat).unwrap();
    let numerics = NumericsSpec::default();
    let prepared = prepare_bat(&bat, &numerics).unwrap();
    let shot = BbcorShot {
        ball: serde_json::from_str::<BallSpec>(r#"{"preset": "mlb"}"#).unwrap(),
        hoop: Some(hoop),
    };
    let (_, bbcor) = bbcor_scan_mapped(&prepared, &bat, &numerics, &shot, &in_order).unwrap();
    bbcor.into_iter().fold(f64::NEG_INFINITY, f64::max)
}

fn growing(ratio: f64) -> HoopSpec {
    HoopSpec {
        from_geometry: true,
        footprint_ratio: Some(ratio),
        ..HoopSpec::default()
    }
}

fn fixed(radius: f64) -> HoopSpec {
    HoopSpec {
        from_geometry: true,
        patch_radius: Some(radius),
        ..HoopSpec::default()
    }
}

/// The issue's three bats: the two hollow presets and a uniform 2.75-mm 7050 wall on the
/// `alloy_bbcor` geometry (29.7 oz, breathing at about 2.0 kHz).
const BATS: [(&str, &str); 3] = [
    ("alloy_bbcor", r#"{"preset": "alloy_bbcor"}"#),
    ("composite_bbcor", r#"{"preset": "composite_bbcor"}"#),
    (
        "uniform 2.75-mm wall",
        r#"{"preset": "alloy_bbcor", "shell": {"thickness": 0.00275}}"#,
    ),
];

#[test]
fn the_footprint_leaves_less_of_a_knob_than_a_fixed_patch() {
    for (name, bat) in BATS {
        let hertz = best_bbcor(bat, growing(0.5));
        let flattened = best_bbcor(bat, growing(1.0));
        let patches: Vec<f64> = [0.01, 0.02, 0.03]
            .iter()
            .map(|&r| best_bbcor(bat, fixed(r)))
            .collect();
        eprintln!(
            "{name}: BBCOR {hertz:.4} (Hertz's footprint), {flattened:.4} (the whole overlap); \
             fixed patches of 1, 2, 3 cm: {:.4}, {:.4}, {:.4}",
            patches[0], patches[1], patches[2]
        );
        // the footprint's whole range moves BBCOR by at most half what the fixed patch's
        // documented range did (the issue's target, 0.005, is not met: docs/physics.md)
        let footprint = (flattened - hertz).abs();
        let patch = (patches[0] - patches[2]).abs();
        assert!(
            footprint < 0.5 * patch,
            "{name}: {footprint} against {patch}"
        );
        assert!(
            flattened < hertz,
            "{name}: a larger footprint is a heavier wall"
        );
    }
}

#[test]
fn a_footprint_grows_as_the_overlap_of_ball_and_barrel() {
    // overlap of a sphere (R) and a cylinder (ρ) at interference s, to first order in s:
    // along the cylinder's axis a² = 2 R s, around it 2 R′ s with 1/R′ = 1/R + 1/ρ
    let (ball, barrel, s) = (0.0369_f64, 0.033_f64, 0.01_f64);
    let (along, around) = footprint_axes(s, ball, barrel, 1.0);
    assert!((along - (2.0 * ball * s).sqrt()).abs() < 1e-15);
    let across = 1.0 / (1.0 / ball + 1.0 / barrel);
    assert!((around - (2.0 * across * s).sqrt()).abs() < 1e-15);
    let (h_along, h_around) = footprint_axes(s, ball, barrel, 0.5);
    assert!(
        (h_along - (ball * s).sqrt()).abs() < 1e-15,
        "Hertz: a² = R s"
    );
    assert!((h_around / h_along - (across / ball).sqrt()).abs() < 1e-12);
}

#[test]
fn a_vanishing_footprint_is_the_point_load() {
    let bat: BatSpec = serde_json::from_str(r#"{"preset": "alloy_bbcor"}"#).unwrap();
    let prepared = prepare_bat(&bat, &NumericsSpec::default()).unwrap();
    let modes = prepared.shell_modes().unwrap().unwrap();
    let radius = BatGeometry::resolve(&bat).unwrap().outer_radius(0.7);
    for j in 0..modes.modes.len() {
        let point = modes.radial(j, 0.7);
        let tiny = modes.over_footprint(j, 0.7, (1e-7, 1e-7), radius);
        assert!(
            (tiny - point).abs() <= 1e-6 * point.abs().max(1e-12),
            "mode {j}"
        );
    }
}
