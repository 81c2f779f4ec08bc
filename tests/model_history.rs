//! Histories: one common time axis from first contact, NaN beyond the bat, every field sized.

mod common;

use batstudy::model::outcome::{HistoryField, HistoryRequest};
use batstudy::model::spec::{HoopSpec, Integrator};
use batstudy::model::{prepare_bat, simulate};

#[test]
fn every_requested_field_is_sampled_on_the_common_axis() {
    for integrator in [Integrator::Modal, Integrator::Verlet] {
        let mut spec = common::base_spec(0.7);
        spec.numerics.integrator = integrator;
        spec.hoop = Some(HoopSpec {
            frequency: Some(1500.0),
            mass: Some(0.02),
            ..HoopSpec::default()
        });
        let bat = prepare_bat(&spec.bat, &spec.numerics).unwrap();
        let request = HistoryRequest {
            fields: vec![
                HistoryField::Force,
                HistoryField::Compression,
                HistoryField::BallVelocity,
                HistoryField::Displacement,
                HistoryField::RigidMotion,
                HistoryField::HoopDisplacement,
            ],
            interval: 1e-5,
            n_samples: 300,
            z: vec![0.1, 0.7, 0.9],
            precision: Default::default(),
            compression: Default::default(),
            displacement: batstudy::model::outcome::HistoryDisplacement::Grid,
        };
        let o = simulate(&spec, &bat, Some(&request)).unwrap();
        let h = o.history.unwrap();
        for (name, v) in [
            ("force", &h.force),
            ("compression", &h.compression),
            ("ball_velocity", &h.ball_velocity),
            ("rigid_translation", &h.rigid_translation),
            ("rigid_rotation", &h.rigid_rotation),
            ("hoop_displacement", &h.hoop_displacement),
        ] {
            assert_eq!(v.len(), 300, "{name}");
        }
        assert_eq!(h.displacement.len(), 900);
        // t = 0 is first contact: no force yet, the ball at its initial speed
        assert_eq!(h.force[0], 0.0);
        assert_eq!(h.ball_velocity[0], spec.ball.speed);
        // z = 0.9 m is beyond the 0.84 m bat
        assert!(h.displacement.iter().skip(2).step_by(3).all(|y| y.is_nan()));
        assert!(h.displacement.iter().step_by(3).all(|y| y.is_finite()));
        // the peak force is seen in the sampled force within sampling resolution
        let sampled_peak = h.force.iter().fold(0.0f64, |a, f| a.max(*f));
        assert!((sampled_peak / o.peak_force - 1.0).abs() < 0.01);
        // after separation the ball flies back at the exit speed
        assert!((h.ball_velocity[299] + o.exit_speed).abs() < 1e-9 * o.exit_speed.abs().max(1.0));
    }
}
