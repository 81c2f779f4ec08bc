//! Spec validation: errors name the field by dotted path and the allowed range.

mod common;

use batstudy::model::spec::{HoopSpec, Integrator, ProfileSpec, ShellSpec};
use batstudy::model::{prepare_bat, simulate, validate_spec, ModelError, PreparedBat};

fn message(spec: &batstudy::model::spec::CollisionSpec) -> String {
    validate_spec(spec).unwrap_err().to_string()
}

#[test]
fn prepared_bat_is_shareable_across_threads() {
    fn assert_send_sync<T: Send + Sync>() {}
    assert_send_sync::<PreparedBat>();
}

#[test]
fn bad_values_name_their_field_and_range() {
    let mut s = common::base_spec(0.7);
    s.ball.law.cor = 1.2;
    let m = message(&s);
    assert!(m.contains("ball.law.cor") && m.contains("(0, 1]"), "{m}");

    let mut s = common::base_spec(0.9);
    s.impact.z = 0.9;
    let m = message(&s);
    assert!(m.contains("impact.z") && m.contains("0.84"), "{m}");

    let mut s = common::base_spec(0.7);
    s.hoop = Some(HoopSpec {
        frequency: Some(2e5),
        mass: Some(0.01),
        ..HoopSpec::default()
    });
    assert!(message(&s).contains("hoop.frequency"));

    let mut s = common::base_spec(0.7);
    s.bat.shell = Some(ShellSpec {
        thickness: Some(0.04),
        from: Some(0.6),
        ..Default::default()
    });
    let m = message(&s);
    assert!(
        m.contains("shell thickness 0.04 m exceeds the outer radius"),
        "{m}"
    );

    let mut s = common::base_spec(0.7);
    s.bat.profile = Some(ProfileSpec::Csv("bat.csv".into()));
    assert!(matches!(
        validate_spec(&s),
        Err(ModelError::UnresolvedCsvProfile(_))
    ));

    let mut s = common::base_spec(0.7);
    s.bat.length = Some(0.5);
    assert!(matches!(
        validate_spec(&s),
        Err(ModelError::BatShorterThanProfile { .. })
    ));
}

#[test]
fn a_step_above_the_stability_limit_is_an_error() {
    for (integrator, dt) in [(Integrator::Verlet, 1e-6), (Integrator::Modal, 1e-3)] {
        let mut s = common::base_spec(0.7);
        s.numerics.integrator = integrator;
        s.numerics.dt = Some(dt);
        let bat = prepare_bat(&s.bat, &s.numerics).unwrap();
        let err = simulate(&s, &bat, None).unwrap_err();
        assert!(matches!(err, ModelError::TimeStepTooLarge { .. }), "{err}");
        assert!(err.to_string().contains("numerics.dt"), "{err}");
    }
}

#[test]
fn presets_and_variants_prepare() {
    use batstudy::model::spec::{BatPreset, BatSpec, NumericsSpec};
    let wood = prepare_bat(&BatSpec::default(), &NumericsSpec::default())
        .unwrap()
        .properties()
        .clone();
    for preset in [BatPreset::Aluminum, BatPreset::Corked] {
        let bat = BatSpec {
            preset,
            ..BatSpec::default()
        };
        let p = prepare_bat(&bat, &NumericsSpec::default())
            .unwrap()
            .properties()
            .clone();
        assert!(p.mass > 0.3 && p.mass < wood.mass, "{preset:?}: {}", p.mass);
        assert!(p.inner_radius.iter().any(|r| *r > 0.0));
    }
    // 110 cm bat: barrel extended at its end radius
    let long = BatSpec {
        length: Some(1.10),
        ..BatSpec::default()
    };
    let p = prepare_bat(&long, &NumericsSpec::default())
        .unwrap()
        .properties()
        .clone();
    assert!((p.length - 1.10).abs() < 1e-12 && p.mass > wood.mass);
    // thicker handle: heavier
    let mut thick = BatSpec::default();
    thick.handle.radius_scale = 1.2;
    let p = prepare_bat(&thick, &NumericsSpec::default())
        .unwrap()
        .properties()
        .clone();
    assert!(p.mass > wood.mass);
}
