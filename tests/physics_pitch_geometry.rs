//! A pitch off the bat's path: the geometry of a real swing against references independent
//! of the code.
//!
//! - Isotropy of a rigid bat across its axis: a rigid bat has the same effective mass in
//!   every direction across its axis (Cross & Nathan, Am. J. Phys. 74, 896 (2006), §II), so
//!   a ball meeting it at a relative velocity turned by δ about the bat's axis, with the
//!   offset measured across that velocity, must leave with the same spin, the same speed
//!   relative to the bat's impact point, and that velocity turned by the same δ.
//! - The "on plane" swing is the special case δ = ψ, η = −α of the pitch block.
//! - Energy: an off-plane collision's energy balance closes, the ball's motion across the
//!   plane before contact counted.

use batstudy::model::outcome::Outcome;
mod common;

use batstudy::model::spec::*;
use batstudy::model::{prepare_bat, simulate, simulate_with_diagnostics, PreparedBat};

fn batter() -> BatterSpec {
    BatterSpec {
        pitch_speed: None,
        bat_speed: 31.3,
        bat_speed_at: 0.7112,
        reference_moi: 0.319,
        exponent: 0.27,
        pivot: 0.0,
    }
}

fn spec(model: ModelKind, offset: f64, pitch: PitchSpec) -> CollisionSpec {
    let mut s = CollisionSpec::base_case(0.70);
    s.model = model;
    s.ball = BallSpec {
        preset: Some(BallPreset::Mlb),
        law: batstudy::model::ball::preset_law(BallPreset::Mlb),
        ..BallSpec::default()
    };
    s.batter = Some(batter());
    s.pitch = Some(pitch);
    s.impact.offset = offset;
    s
}

fn falling(speed: f64, descent: f64) -> PitchSpec {
    PitchSpec {
        speed,
        descent_angle: descent,
        horizontal_angle: 0.0,
    }
}

/// The bat's impact point's speed toward the pitcher (lab), the ball's velocity relative
/// to it in the collision's plane (ŷ, x̂) after, and its spin.
fn relative_exit(o: &Outcome, s: &CollisionSpec, bat: &PreparedBat) -> ((f64, f64), f64) {
    let swung = batstudy::model::collision::batter::swung(s, bat).unwrap();
    let bat_point = swung.swing.omega * (s.impact.z - bat.properties().z_cm);
    let e = &o.ball_exit;
    ((e.along - bat_point, e.across), e.spin)
}

#[test]
fn a_rigid_bat_answers_a_turned_approach_with_the_turned_answer() {
    let bat = prepare_bat(&CollisionSpec::base_case(0.7).bat, &NumericsSpec::default()).unwrap();
    let (speed, descent, offset) = (38.0, 0.15, -0.012);
    let off_plane = spec(ModelKind::Rigid, offset, falling(speed, descent));
    // the same bat swung by the same batter: its impact point's lab speed toward the pitcher
    let swung = batstudy::model::collision::batter::swung(&off_plane, &bat).unwrap();
    let k = swung.swing.cm_speed - swung.swing.omega * (0.70 - bat.properties().z_cm);
    // the relative velocity (ŷ, x̂) of the falling pitch against a level swing
    let (vy, vx) = (speed * descent.cos() + k, -speed * descent.sin());
    let turn = vx.atan2(vy);
    // on plane at the same relative speed: the pitch speed that gives |v| along ŷ
    let on_plane = spec(ModelKind::Rigid, offset, falling(vy.hypot(vx) - k, 0.0));
    let a = simulate(&off_plane, &bat, None).unwrap();
    let b = simulate(&on_plane, &bat, None).unwrap();
    let ((ay, ax), a_spin) = relative_exit(&a, &off_plane, &bat);
    let ((by, bx), b_spin) = relative_exit(&b, &on_plane, &bat);
    let (s, c) = turn.sin_cos();
    let (ty, tx) = (by * c - bx * s, by * s + bx * c);
    let scale = vy.hypot(vx);
    assert!(
        (ay - ty).abs() < 1e-9 * scale && (ax - tx).abs() < 1e-9 * scale,
        "({ay}, {ax}) vs ({ty}, {tx})"
    );
    assert!(
        (a_spin - b_spin).abs() < 1e-9 * b_spin.abs(),
        "spin {a_spin} vs {b_spin}"
    );
    assert!(
        turn.abs() > 0.05,
        "the test turns the approach by {turn} rad"
    );
}

#[test]
fn the_on_plane_swing_is_the_pitch_blocks_special_case() {
    let bat = prepare_bat(&CollisionSpec::base_case(0.7).bat, &NumericsSpec::default()).unwrap();
    let (attack, direction, tilt) = (0.2, -0.1, -0.4);
    for offset in [0.0, -0.015] {
        let mut block = spec(
            ModelKind::Wave,
            offset,
            PitchSpec {
                speed: 40.2,
                descent_angle: attack,
                horizontal_angle: -direction,
            },
        );
        block.swing.attack_angle = attack;
        block.swing.attack_direction = direction;
        block.swing.tilt = tilt;
        block.flight = Some(FlightSpec::default());
        let mut plane = block.clone();
        plane.pitch = None;
        plane.batter.as_mut().unwrap().pitch_speed = Some(40.2);
        let (a, b) = (
            simulate(&block, &bat, None).unwrap(),
            simulate(&plane, &bat, None).unwrap(),
        );
        let pairs = [
            (a.exit_speed_lab, b.exit_speed_lab),
            (a.batted.launch_angle, b.batted.launch_angle),
            (a.batted.spray_angle, b.batted.spray_angle),
            (a.batted.backspin, b.batted.backspin),
            (a.batted.carry, b.batted.carry),
        ];
        for (x, y) in pairs {
            assert!(
                (x - y).abs() <= 1e-9 * y.abs().max(1.0),
                "offset {offset}: {x} vs {y}"
            );
        }
    }
}

#[test]
fn an_off_plane_collisions_energy_balance_closes() {
    let bat = prepare_bat(&CollisionSpec::base_case(0.7).bat, &NumericsSpec::default()).unwrap();
    for (offset, descent, horizontal) in [(0.0, 0.12, 0.0), (-0.02, 0.12, 0.05), (0.01, -0.05, 0.0)]
    {
        let mut s = spec(
            ModelKind::Wave,
            offset,
            PitchSpec {
                speed: 40.0,
                descent_angle: descent,
                horizontal_angle: horizontal,
            },
        );
        s.swing.attack_angle = 0.17;
        let (o, d) = simulate_with_diagnostics(&s, &bat, None).unwrap();
        common::assert_energy_closes(&o, &d, 2e-4, &format!("offset {offset}"));
    }
}

#[test]
fn a_pitch_without_a_batter_or_with_two_speeds_is_refused() {
    let mut s = spec(ModelKind::Wave, 0.0, falling(40.0, 0.1));
    s.batter.as_mut().unwrap().pitch_speed = Some(40.0);
    let e = batstudy::model::collision::validate::validate_spec(&s)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("batter.pitch_speed") && e.contains("pitch block"),
        "{e}"
    );
    s.batter = None;
    let e = batstudy::model::collision::validate::validate_spec(&s)
        .unwrap_err()
        .to_string();
    assert!(e.contains("pitch block without a batter"), "{e}");
    let mut s = spec(ModelKind::Wave, 0.0, falling(40.0, 0.1));
    s.pitch = None;
    let e = batstudy::model::collision::validate::validate_spec(&s)
        .unwrap_err()
        .to_string();
    assert!(e.contains("batter.pitch_speed"), "{e}");
}
