//! The certification numbers stored for every collision with a bat at rest: BBCOR, BESR, BPF.
//!
//! References:
//! - NCAA BBCOR protocol (on ASTM F2219): for a *rigid* bat, pivoted or free, the protocol's
//!   BBCOR `e_A (1 + m/M_e) + m/M_e` is exactly the ball's COR e, whatever the bat's inertia
//!   (derivation in `crates/physics/src/measures/metrics.rs`; docs/physics.md, "BBCOR"). A very stiff
//!   wave bat (Y × 1000) is that rigid bat (`tests/physics_rigid_limit.rs`), so its BBCOR
//!   must be e and its BPF (BBCOR over the ball's COR, ASTM F1890) 1.
//! - BESR = e_A + 1/2 (Washington State University Sports Science Laboratory, "Bat
//!   performance measures"; Nathan, SABR Baseball Research Journal 2003).
//! - A rigid wall is a target of infinite effective mass: BBCOR = e_A = the ball's COR.

mod common;

use batstudy::model::spec::{BatPreset, GripKind, GripSpec};
use batstudy::model::{simulate, simulate_target, Target};

#[test]
fn a_stiff_bat_at_rest_has_the_balls_cor_as_its_bbcor_free_or_pivoted() {
    for pinned in [false, true] {
        for z in [0.60, 0.70, 0.78] {
            let mut spec = common::base_spec(z);
            spec.bat.material.youngs_modulus = Some(1.814e10 * 1000.0);
            if pinned {
                spec.bat.grip = Some(GripSpec {
                    z: 0.1524,
                    kind: GripKind::Pinned,
                    ..GripSpec::default()
                });
            }
            let bat = batstudy::model::prepare_bat(&spec.bat, &spec.numerics).unwrap();
            let o = simulate(&spec, &bat, None).unwrap();
            let e = spec.ball.law.cor;
            assert!(
                (o.bbcor - e).abs() < 5e-3,
                "pinned {pinned}, z {z}: BBCOR {}",
                o.bbcor
            );
            assert!(
                (o.bpf - 1.0).abs() < 1e-2,
                "pinned {pinned}, z {z}: BPF {}",
                o.bpf
            );
            assert_eq!(o.besr, o.collision_efficiency + 0.5);
        }
    }
}

#[test]
fn a_wood_bat_gives_back_less_than_a_rigid_one() {
    // Vibration takes energy: the real R161's BBCOR lies below the ball's COR (BPF < 1), the
    // reason the NCAA's 0.50 limit sits just above the best wood bats.
    let spec = common::base_spec(0.70);
    let bat = batstudy::model::prepare_bat(&spec.bat, &spec.numerics).unwrap();
    let o = simulate(&spec, &bat, None).unwrap();
    assert!(
        o.bbcor < spec.ball.law.cor && o.bpf < 1.0,
        "{} {}",
        o.bbcor,
        o.bpf
    );
}

#[test]
fn a_swung_bat_has_no_certification_numbers() {
    let mut spec = common::base_spec(0.70);
    spec.swing.omega = -30.0;
    let bat = batstudy::model::prepare_bat(&spec.bat, &spec.numerics).unwrap();
    let o = simulate(&spec, &bat, None).unwrap();
    assert!(o.bbcor.is_nan() && o.besr.is_nan() && o.bpf.is_nan());
}

#[test]
fn the_wall_has_the_balls_cor_as_its_bbcor() {
    let mut spec = common::base_spec(0.0);
    spec.bat.preset = BatPreset::Wall;
    let target = Target::prepare(&spec.bat, &spec.numerics).unwrap();
    let o = simulate_target(&spec, &target, None).unwrap();
    assert_eq!(o.bbcor, o.collision_efficiency);
    assert!((o.bbcor - 0.5).abs() < 2e-4, "{}", o.bbcor);
    assert!((o.bpf - 1.0).abs() < 4e-4, "{}", o.bpf);
}
