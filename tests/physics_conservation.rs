//! Conservation laws of the wave model.
//!
//! Reference: docs/physics.md "Reference numbers and their sources" — with an elastic ball the total energy
//! is conserved to the integrator's accuracy, and linear and angular momentum of bat + ball
//! exactly (free ends), since K's null space is rigid translation + rotation and the contact
//! force is applied by linear interpolation (its moment about the CM is exact).

mod common;

use batstudy::model::spec::{HoopSpec, Integrator};
use batstudy::model::{prepare_bat, simulate_with_diagnostics};

fn check(omega: f64, hoop: Option<HoopSpec>, integrator: Integrator, dt: Option<f64>) {
    let mut spec = common::base_spec(0.66);
    spec.ball.law = common::elastic();
    spec.swing.omega = omega;
    spec.hoop = hoop.clone();
    spec.numerics.integrator = integrator;
    spec.numerics.dt = dt;
    let bat = prepare_bat(&spec.bat, &spec.numerics).unwrap();
    let (o, d) = simulate_with_diagnostics(&spec, &bat, None).unwrap();
    let label = format!("omega {omega}, hoop {hoop:?}, {integrator:?}");
    let energy_error = d.energy_final / o.energy.initial - 1.0;
    assert!(
        energy_error.abs() < 1e-6,
        "{label}: energy error {energy_error:e}"
    );
    assert_eq!(o.energy.ball_loss, 0.0);
    let p_scale = spec.ball.mass * spec.ball.speed;
    let dp = (d.momentum_final - d.momentum_initial) / p_scale;
    assert!(dp.abs() < 1e-12, "{label}: momentum error {dp:e}");
    let dl = (d.angular_momentum_final - d.angular_momentum_initial) / (p_scale * 0.5);
    assert!(dl.abs() < 1e-12, "{label}: angular momentum error {dl:e}");
    assert!(o.exit_speed > 0.0 && o.contact_time > 0.0);
}

const FINE_DT: f64 = 5e-7;

fn hoop() -> Option<HoopSpec> {
    Some(HoopSpec {
        frequency: Some(1500.0),
        mass: Some(0.02),
        ..HoopSpec::default()
    })
}

#[test]
fn elastic_ball_conserves_energy_and_momenta_modal() {
    // modal energy error is O(dt²) (≈1e-5 at the default step): use a finer step here
    for omega in [0.0, -40.0] {
        check(omega, None, Integrator::Modal, Some(FINE_DT));
        check(omega, hoop(), Integrator::Modal, Some(FINE_DT));
    }
}

#[test]
fn elastic_ball_conserves_energy_and_momenta_verlet() {
    for omega in [0.0, -40.0] {
        check(omega, None, Integrator::Verlet, None);
        check(omega, hoop(), Integrator::Verlet, None);
    }
}

#[test]
fn lossy_ball_energy_partition_sums_to_initial() {
    // the partition must account for every joule (loss computed from the hysteresis loop)
    for omega in [0.0, -40.0] {
        let mut spec = common::base_spec(0.7);
        spec.swing.omega = omega;
        spec.hoop = hoop();
        let bat = prepare_bat(&spec.bat, &spec.numerics).unwrap();
        let (o, d) = simulate_with_diagnostics(&spec, &bat, None).unwrap();
        let e = o.energy;
        assert!(e.ball_loss > 0.0 && e.bat_vibration > 0.0 && e.hoop > 0.0);
        let error = d.energy_final / e.initial - 1.0;
        assert!(
            error.abs() < 1e-4,
            "omega {omega}: partition error {error:e}"
        );
    }
}
