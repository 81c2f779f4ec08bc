//! The ball's tangential parameters against the ball-on-fixed-cylinder test.
//!
//! Reference: Nathan, Cantakos, Kesman, Mathew & Lukash, "Spin of a batted baseball",
//! Procedia Eng. 34, 182 (2012): baseballs fired at up to 120 mph at a 3-in wood cylinder
//! rigidly fixed to a wall. Read here: the opening (set-up; "for a given angle of incidence
//! the scattered spin is nearly independent of the incident spin"). Second-hand (two public
//! notes that quote the paper): for the 47 impacts without gross slip at 85–120 mph the
//! tangential COR is e_x = 0.30 ± 0.02, flat over the angle, μ = 0.15 from the gross-slip
//! impacts, and the share of the incident spin that survives a fixed cylinder is
//! (0.4 − e_x)/1.4 (its Eq. 3).
//!
//! batstudy's defaults (μ = 0.2, κ = 0.27, docs/physics.md "Oblique impacts") were chosen to
//! bring the calibrated ball's e_x nearest 0.30 at 20° incidence and 46 m/s, with gross slip
//! from between 35° and 40°: those rows are consistency. The flat e_x over 5–35°, the
//! contact's speed independence and the incident-spin independence are predictions of the
//! contact model; the calibrated ball's e_x falling with speed is a stated disagreement (the
//! measured e_x is flat), held here so that a change is noticed.

use batstudy::model::spec::*;
use batstudy::model::{prepare_bat, simulate, PreparedBat};

const CYLINDER_RADIUS: f64 = 0.0381; // 3 in diameter

/// A rigid, immovable 3-in cylinder: a very stiff, very dense bat of constant radius.
fn cylinder() -> (CollisionSpec, PreparedBat) {
    let mut spec = CollisionSpec::base_case(0.42);
    spec.bat.profile = Some(ProfileSpec::Knots(vec![
        [0.0, CYLINDER_RADIUS],
        [0.84, CYLINDER_RADIUS],
    ]));
    spec.bat.material.density = Some(649.0e4);
    spec.bat.material.youngs_modulus = Some(1.814e14);
    spec.ball = BallSpec {
        preset: Some(BallPreset::Mlb),
        law: batstudy::model::ball::preset_law(BallPreset::Mlb),
        ..BallSpec::default()
    };
    let bat = prepare_bat(&spec.bat, &spec.numerics).unwrap();
    (spec, bat)
}

/// (e_x, the ball's spin after) for a ball at `speed` meeting the cylinder `degrees` off
/// normal with incident spin `spin` (rad/s about the cylinder's axis).
fn shot(speed: f64, degrees: f64, spin: f64) -> (f64, f64) {
    shot_with(speed, degrees, spin, |_| {})
}

/// [`shot`] with the collision changed by `edit` (the ball's law, the time step).
fn shot_with(speed: f64, degrees: f64, spin: f64, edit: impl Fn(&mut CollisionSpec)) -> (f64, f64) {
    let (mut spec, bat) = cylinder();
    edit(&mut spec);
    let ball_radius = batstudy::model::collision::oblique::BallContact::of(&spec.ball).radius;
    spec.ball.speed = speed;
    spec.ball.spin = spin;
    spec.impact.offset = -(CYLINDER_RADIUS + ball_radius) * degrees.to_radians().sin();
    let o = simulate(&spec, &bat, None).unwrap();
    (o.tangential_cor, o.ball_exit.spin)
}

#[test]
fn the_calibration_point_20_degrees_off_normal() {
    let (e_x, _) = shot(46.0, 20.0, 0.0);
    assert!((e_x - 0.30).abs() <= 0.02, "e_x {e_x}");
}

/// Verification of the contact's unloading rule. While the patch grips, its stiffness
/// follows the normal compression alone, so the tangential motion is linear in the
/// incident slip: at one normal speed, e_x cannot depend on the angle (Maw, Barber &
/// Fawcett, Wear 38, 101 (1976): the angle enters a gripping elastic contact only through
/// the ratio of tangential to normal force, which sets where microslip begins). With
/// friction too high for any slip, e_x is the same from 2° to 40°. A patch that kept its
/// shear while it shrank failed this, from −0.14 at 2° to +0.05 at 40°.
#[test]
fn a_gripping_ball_s_tangential_cor_does_not_depend_on_the_angle() {
    let normal_speed = 40.0;
    let e_x = |degrees: f64| {
        let speed = normal_speed / degrees.to_radians().cos();
        shot_with(speed, degrees, 0.0, |s| s.ball.law.friction = Some(10.0)).0
    };
    let at_2 = e_x(2.0);
    for degrees in [10.0, 20.0, 30.0, 40.0] {
        let at = e_x(degrees);
        eprintln!("gripping: e_x {at:.4} at {degrees}°, {at_2:.4} at 2°");
        assert!(
            (at - at_2).abs() < 2e-3,
            "{degrees}°: {at} against {at_2} at 2°"
        );
    }
}

/// A prediction: e_x is flat over the angles without gross slip, as measured (0.30 ± 0.02,
/// second-hand; band set before the run: that uncertainty), read as the source states it:
/// a level (the mean over 5–35°) within the band, and flat (its spread within the band's
/// width). Each angle on its own: 0.279 at 5° lies 0.001 below the band's foot with the
/// ball that sees the cylinder's curvature (docs/physics.md, "Oblique impacts").
#[test]
fn the_tangential_cor_is_flat_over_the_angle_until_gross_slip() {
    let e: Vec<f64> = [5.0, 10.0, 15.0, 25.0, 30.0, 35.0]
        .iter()
        .map(|&degrees| shot(46.0, degrees, 0.0).0)
        .collect();
    let mean = e.iter().sum::<f64>() / e.len() as f64;
    let spread =
        e.iter().cloned().fold(f64::MIN, f64::max) - e.iter().cloned().fold(f64::MAX, f64::min);
    eprintln!("e_x over 5–35°: {e:.4?}, mean {mean:.4}, spread {spread:.4}");
    assert!((mean - 0.30).abs() <= 0.02, "mean e_x {mean}");
    assert!(spread <= 0.02, "e_x spreads by {spread}");
}

/// The contact itself has no speed of its own: with a ball whose normal COR does not change
/// with speed (the mlb loading with a fixed COR of 0.5), e_x is the same from 85 to 120 mph,
/// as measured.
#[test]
fn the_tangential_contact_hardly_depends_on_speed() {
    let fixed = |speed: f64, degrees: f64| {
        shot_with(speed, degrees, 0.0, |s| {
            s.ball.law.kind = BallLawKind::PowerLaw;
            s.ball.law.cor = 0.5;
        })
        .0
    };
    for degrees in [10.0, 20.0, 30.0] {
        let (slow, fast) = (fixed(38.0, degrees), fixed(54.0, degrees));
        assert!((slow - fast).abs() < 0.015, "{degrees}°: {slow} vs {fast}");
    }
}

/// A stated disagreement and its cause: the calibrated ball's normal COR on the cylinder falls
/// between 38 and 54 m/s (its ball-alone calibration), and its e_x falls with it, where
/// the measured e_x is flat (±0.02, second-hand). The fall of e_x is the normal COR's within
/// 0.01 at every angle: the cause, held so that a change is noticed.
#[test]
fn the_tangential_cor_falls_with_the_balls_normal_cor() {
    let law = batstudy::model::ball::preset_law(BallPreset::Mlb);
    for degrees in [10.0, 20.0, 30.0] {
        let cos = f64::to_radians(degrees).cos();
        let on = |v: f64| {
            let r = batstudy::model::ball::DEFAULT_BALL_RADIUS;
            batstudy::model::ball::cor_on_target(&law, v * cos, r, Some(CYLINDER_RADIUS))
        };
        let normal = on(38.0) - on(54.0);
        let (slow, _) = shot(38.0, degrees, 0.0);
        let (fast, _) = shot(54.0, degrees, 0.0);
        eprintln!(
            "{degrees}°: e_x {slow:.4} at 38 m/s, {fast:.4} at 54 m/s; normal COR {:.4}, {:.4}",
            on(38.0),
            on(54.0)
        );
        assert!(
            (slow - fast - normal).abs() < 0.01,
            "{degrees}°: e_x falls by {} where the normal COR falls by {normal}",
            slow - fast
        );
    }
}

#[test]
fn the_outgoing_spin_hardly_depends_on_the_incident_spin() {
    // the surviving share of incident spin: (0.4 − e_x)/1.4 = 0.071 ± 0.014 for the measured
    // e_x (second-hand); band set beforehand: below 0.15, "nearly independent"
    for degrees in [10.0, 15.0, 20.0, 25.0, 30.0] {
        let (_, with_back) = shot(46.0, degrees, 200.0);
        let (_, with_top) = shot(46.0, degrees, -200.0);
        let share = (with_back - with_top) / 400.0;
        eprintln!("{degrees}°: share of the incident spin kept {share:.3}");
        assert!(share.abs() < 0.15, "{degrees}°: share {share}");
    }
}

#[test]
fn the_ball_slides_throughout_from_about_40_degrees() {
    // gross slip sets in near 40° (second-hand): a sliding ball keeps its incident spin
    let share = |degrees: f64| {
        let (_, with_back) = shot(46.0, degrees, 200.0);
        let (_, with_top) = shot(46.0, degrees, -200.0);
        (with_back - with_top) / 400.0
    };
    assert!(
        share(30.0).abs() < 0.15 && share(40.0) > 0.5,
        "30°: {}, 40°: {}",
        share(30.0),
        share(40.0)
    );
}

/// The unloading rule acts once per step, at its start; e_x still converges with the step:
/// from 4 µs to 0.25 µs it moves by less than 1e-3, a twentieth of the measurement's
/// uncertainty, in grip (20°) and near gross slip (35°).
#[test]
fn the_tangential_cor_converges_with_the_step() {
    for degrees in [20.0, 35.0] {
        let fine = shot_dt(46.0, degrees, 2.5e-7);
        for dt in [4e-6, 2e-6, 1e-6] {
            let coarse = shot_dt(46.0, degrees, dt);
            assert!(
                (coarse - fine).abs() < 1e-3,
                "{degrees}°, {dt} s: {coarse} against {fine}"
            );
        }
    }
}

/// e_x of [`shot`] without incident spin, with the time step `dt`.
fn shot_dt(speed: f64, degrees: f64, dt: f64) -> f64 {
    shot_with(speed, degrees, 0.0, |s| s.numerics.dt = Some(dt)).0
}
