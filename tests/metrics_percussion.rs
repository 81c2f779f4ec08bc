//! Centre of percussion.
//!
//! References: Brody, Am. J. Phys. 54, 640 (1986) and Cross, Am. J. Phys. 66, 772 (1998):
//! for a pivot at z_p, z_cop = z_p + I_p/(M (z_cm − z_p)) (derived in crates/physics/src/measures/metrics.rs).
//! Closed form for a uniform rod of length L pivoted at its end: I_p = M L²/3, z_cm = L/2,
//! so z_cop = 2L/3 (any mechanics text, e.g. Brody 1986 eq. 1).

mod common;

use batstudy::model::measures::metrics::centre_of_percussion;
use batstudy::model::protocol::KNOB6;
use batstudy::model::spec::{BatSpec, MaterialSpec, ModelKind, NumericsSpec, ProfileSpec};
use batstudy::model::{prepare_bat, simulate};

const L: f64 = 0.84;

fn uniform_rod() -> BatSpec {
    BatSpec {
        profile: Some(ProfileSpec::Knots(vec![[0.0, 0.03], [L, 0.03]])),
        material: MaterialSpec {
            density: Some(649.0),
            youngs_modulus: Some(1.814e10),
            ..MaterialSpec::default()
        },
        ..BatSpec::default()
    }
}

#[test]
fn uniform_rod_pivoted_at_its_end_is_two_thirds() {
    // The formula with the rod's closed-form mass properties: exact.
    let m = 1.3;
    let z = centre_of_percussion(m, L / 2.0, m * L * L / 12.0, 0.0);
    assert!((z - 2.0 * L / 3.0).abs() < 1e-14, "{z}");
    // The same from the bat model's integrated mass properties (exact for a cylinder up to
    // the integration's round-off).
    let bat = prepare_bat(&uniform_rod(), &NumericsSpec::default()).unwrap();
    let p = bat.properties();
    let z = centre_of_percussion(p.mass, p.z_cm, p.moment_of_inertia, 0.0);
    assert!((z - 2.0 * L / 3.0).abs() < 1e-9, "{z}");
    // Pivot at 6 in on the rod: z_p + (L²/12 + d²)/d with d = L/2 − z_p (closed form).
    let d = L / 2.0 - KNOB6;
    let want = KNOB6 + (L * L / 12.0 + d * d) / d;
    let z = centre_of_percussion(p.mass, p.z_cm, p.moment_of_inertia, KNOB6);
    assert!((z - want).abs() < 1e-9, "{z} vs {want}");
}

#[test]
fn no_recoil_at_the_grip_for_an_impact_at_the_centre_of_percussion() {
    // Rigid model (Brody) and wave model: the grip point (6 in) does not jolt when the ball
    // hits the centre of percussion of the grip. The wave model's rigid part is exact
    // (momentum and angular momentum are conserved to round-off), so its zero crossing must
    // sit at the rigid centre of percussion up to the lumped-vs-integrated mass properties.
    let mut spec = common::base_spec(0.7);
    let bat = prepare_bat(&spec.bat, &spec.numerics).unwrap();
    let p = bat.properties();
    let z_cop = centre_of_percussion(p.mass, p.z_cm, p.moment_of_inertia, KNOB6);
    for model in [ModelKind::Rigid, ModelKind::Wave] {
        spec.model = model;
        let recoil = |z: f64, spec: &mut batstudy::model::spec::CollisionSpec| {
            spec.impact.z = z;
            simulate(spec, &bat, None).unwrap().grip_recoil_speed
        };
        let (a, b) = (z_cop - 0.01, z_cop + 0.01);
        let (ra, rb) = (recoil(a, &mut spec), recoil(b, &mut spec));
        assert!(ra > 0.0 && rb < 0.0, "{model:?}: {ra} {rb}");
        let zero = a + (b - a) * ra / (ra - rb);
        assert!(
            (zero - z_cop).abs() < 1e-3,
            "{model:?}: zero at {zero}, cop {z_cop}"
        );
        // Away from it the grip jolts by metres per second (40 m/s ball).
        assert!(recoil(0.5, &mut spec).abs() > 1.0);
    }
}
