//! BBCOR (NCAA BBCOR protocol on ASTM F2219: bat pivoted 6 in from the knob, at rest, ball
//! fired at it).
//!
//! References: the derivation in crates/physics/src/measures/metrics.rs (angular momentum about the pivot +
//! restitution at the impact point ⇒ BBCOR = e_A (1 + m/M_e) + m/M_e, M_e = I_p/(z − z_p)²,
//! which is exactly the ball's COR e for a rigid bat); docs/physics.md: Nathan's
//! e_A = (e − m/M*)/(1 + m/M*); the stiff-bat limit of the wave model (docs/physics.md: Y × 1000
//! reproduces the rigid-body model, 0.5 % in exit speed in tests/physics_rigid_limit.rs).

mod common;

use batstudy::model::measures::metrics::{bbcor_scan, rigid_pivoted_collision};
use batstudy::model::prepare_bat;
use batstudy::model::protocol::{
    bbcor_from_efficiency, moment_of_inertia_about, BBCOR_BALL_SPEED, KNOB6,
};
use batstudy::model::spec::{BallSpec, NumericsSpec};

/// Independent solution of the pivoted rigid collision: unknowns the ball's final velocity
/// v_f (+ toward the bat) and the bat's angular velocity Ω about the pivot.
///   angular momentum about the pivot:  m r v_f + I_p Ω = m r v_i
///   restitution at the impact point:   −v_f + r Ω = e v_i
/// Cramer's rule; BBCOR straight from its definition (relative separation / approach).
fn pivoted_by_hand(m: f64, v_i: f64, i_p: f64, r: f64, e: f64) -> (f64, f64) {
    let (a11, a12, b1) = (m * r, i_p, m * r * v_i);
    let (a21, a22, b2) = (-1.0, r, e * v_i);
    let det = a11 * a22 - a12 * a21;
    let v_f = (b1 * a22 - a12 * b2) / det;
    let omega = (a11 * b2 - a21 * b1) / det;
    let rebound = -v_f;
    let bbcor = (rebound + omega * r) / v_i;
    (rebound, bbcor)
}

#[test]
fn rigid_pivoted_bat_bbcor_equals_the_ball_cor() {
    let spec = common::base_spec(0.7);
    let bat = prepare_bat(&spec.bat, &spec.numerics).unwrap();
    let p = bat.properties();
    let i_p = moment_of_inertia_about(p.mass, p.z_cm, p.moment_of_inertia, KNOB6);
    assert!((i_p - p.moment_of_inertia_knob6).abs() < 1e-12);
    let m = 0.145;
    for e in [0.45, 0.5, 0.55] {
        for z in [0.55, 0.65, 0.70, 0.78] {
            let r = z - KNOB6;
            let got = rigid_pivoted_collision(m, BBCOR_BALL_SPEED, i_p, r, e);
            let (rebound, bbcor) = pivoted_by_hand(m, BBCOR_BALL_SPEED, i_p, r, e);
            assert!((got.rebound_speed - rebound).abs() < 1e-12 * BBCOR_BALL_SPEED);
            assert!((bbcor - e).abs() < 1e-12, "by hand {bbcor} vs e {e}");
            assert!((got.bbcor - e).abs() < 1e-12, "code {} vs e {e}", got.bbcor);
            // Nathan's closed form of e_A with the pivoted effective mass.
            let ratio = m * r * r / i_p;
            let e_a = (e - ratio) / (1.0 + ratio);
            assert!((got.collision_efficiency - e_a).abs() < 1e-12);
            assert!((bbcor_from_efficiency(e_a, m, i_p / (r * r)) - e).abs() < 1e-12);
        }
    }
}

#[test]
fn stiff_wave_bat_bbcor_tends_to_the_ball_cor() {
    // Y × 1000: no vibration loss, so the wave model's BBCOR along the barrel is e = 0.5
    // within the rigid-limit accuracy (0.5 % in exit speed ⇒ ~0.5 % in BBCOR, since
    // BBCOR = e_A (1 + r) + r and e_A ∝ exit speed).
    let mut spec = common::base_spec(0.7);
    spec.bat.material.youngs_modulus = Some(1.814e10 * 1000.0);
    let numerics = NumericsSpec::default();
    let bat = prepare_bat(&spec.bat, &numerics).unwrap();
    let (z, bb) = bbcor_scan(&bat, &spec.bat, &numerics, &BallSpec::default()).unwrap();
    assert!(z.len() > 40, "{}", z.len());
    for (z, b) in z.iter().zip(&bb) {
        assert!((b - 0.5).abs() < 0.5 * 5e-3, "z {z}: BBCOR {b}");
    }
}

#[test]
fn r161_wave_bbcor_peaks_in_the_barrel() {
    // The flexible R161: BBCOR falls off toward the CM and the tip (vibration losses) and
    // peaks between the nodes of modes 1 and 2 (Nathan 2000: least vibration energy there).
    let spec = common::base_spec(0.7);
    let numerics = NumericsSpec::default();
    let bat = prepare_bat(&spec.bat, &numerics).unwrap();
    let m = batstudy::model::measures::metrics::bat_metrics(&bat, &spec.bat, &numerics).unwrap();
    assert!(
        m.bbcor_max_position > m.node1_barrel - 0.01
            && m.bbcor_max_position < m.node2_barrel + 0.01,
        "{m:?}"
    );
    assert!(m.bbcor[0] < m.bbcor_max - 0.1 && *m.bbcor.last().unwrap() < m.bbcor_max - 0.1);
    // Within a few per cent of e: the losses vanish near the nodes; the local bat
    // deformation can even return a little energy (BBCOR slightly above e).
    assert!((m.bbcor_max - 0.5).abs() < 0.02, "{}", m.bbcor_max);
}
