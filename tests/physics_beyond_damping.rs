//! Material damping (`bat.material.quality_factor`): modal damping ζ = 1/(2Q).
//!
//! References:
//! - A damped free mode decays as exp(−ζ ω t) = exp(−ω t/(2Q)) in amplitude (any vibration
//!   text, e.g. Thomson, "Theory of vibration with applications", §2.6); ω and the shape are
//!   the bat's, the decay rate is checked against the analytic ω/(2Q).
//! - Energy balance: the dissipated energy is reported (`energy.bat_damping`); the partition
//!   must still sum to the initial energy (docs/physics.md conservation).
//! - Q → ∞ recovers the undamped result.

mod common;

use batstudy::model::outcome::{HistoryField, HistoryPrecision, HistoryRequest};
use batstudy::model::{prepare_bat, simulate, simulate_with_diagnostics};

#[test]
fn damped_partition_sums_to_initial() {
    for (q, omega) in [(30.0, 0.0), (10.0, -40.0)] {
        let mut spec = common::base_spec(0.62);
        spec.swing.omega = omega;
        spec.bat.material.quality_factor = Some(q);
        let bat = prepare_bat(&spec.bat, &spec.numerics).unwrap();
        let (o, d) = simulate_with_diagnostics(&spec, &bat, None).unwrap();
        let e = o.energy;
        assert!(e.bat_damping > 0.01 * e.bat_vibration, "{e:?}");
        let error = d.energy_final / e.initial - 1.0;
        eprintln!(
            "Q {q}: damping {:.4} J of vibration+damping {:.4} J, partition error {error:.1e}",
            e.bat_damping,
            e.bat_damping + e.bat_vibration
        );
        assert!(error.abs() < 1e-4, "Q {q}: partition error {error:e}");
        // momenta are untouched by internal damping (free bat)
        let dp = (d.momentum_final - d.momentum_initial) / (spec.ball.mass * spec.ball.speed);
        assert!(dp.abs() < 1e-12, "Q {q}: Δp {dp:e}");
    }
}

#[test]
fn infinite_q_recovers_the_undamped_result() {
    let spec0 = common::base_spec(0.70);
    let bat0 = prepare_bat(&spec0.bat, &spec0.numerics).unwrap();
    let undamped = simulate(&spec0, &bat0, None).unwrap();
    let mut spec = spec0.clone();
    spec.bat.material.quality_factor = Some(1e9);
    let bat = prepare_bat(&spec.bat, &spec.numerics).unwrap();
    let damped = simulate(&spec, &bat, None).unwrap();
    let rel = damped.exit_speed / undamped.exit_speed - 1.0;
    assert!(rel.abs() < 1e-8, "Q = 1e9: Δv/v {rel:e}");
    assert!(damped.energy.bat_damping < 1e-6 * undamped.energy.bat_vibration);
    assert_eq!(undamped.energy.bat_damping, 0.0);
    // and a finite Q lowers the exit speed only slightly (the ball leaves in ~1.6 ms)
    spec.bat.material.quality_factor = Some(30.0);
    let bat = prepare_bat(&spec.bat, &spec.numerics).unwrap();
    let q30 = simulate(&spec, &bat, None).unwrap();
    eprintln!(
        "exit speed undamped {:.4}, Q=30 {:.4}",
        undamped.exit_speed, q30.exit_speed
    );
}

#[test]
fn free_vibration_decays_at_omega_over_2q() {
    let q_factor = 25.0;
    let mut spec = common::base_spec(0.70);
    spec.bat.material.quality_factor = Some(q_factor);
    let bat = prepare_bat(&spec.bat, &spec.numerics).unwrap();
    let beam = bat.beam();
    let interval = 5e-6;
    let request = HistoryRequest {
        fields: vec![HistoryField::Displacement],
        interval,
        n_samples: 3000,
        z: beam.z.clone(),
        precision: HistoryPrecision::F64,
        compression: Default::default(),
        displacement: batstudy::model::outcome::HistoryDisplacement::Grid,
    };
    let o = simulate(&spec, &bat, Some(&request)).unwrap();
    let h = o.history.unwrap();
    let nodes = beam.z.len();
    let modes = bat.modes();
    let first = modes.n_rigid;
    let omega = modes.omega[first];
    // modal coordinate of the first flexible mode: q = φᵀ M y (rigid motion drops out)
    let q: Vec<f64> = (0..request.n_samples)
        .map(|k| {
            (0..nodes)
                .map(|i| beam.mass[i] * modes.shapes[(i, first)] * h.displacement[k * nodes + i])
                .sum()
        })
        .collect();
    // after the contact (t > 3 ms), compare a peak of |q| with the value one damped period
    // later; higher modes decay faster and are negligible in this projection anyway
    let zeta = 0.5 / q_factor;
    let period = 2.0 * std::f64::consts::PI / (omega * (1.0 - zeta * zeta).sqrt());
    let at = |t: f64| {
        let x = t / interval;
        let k = x.floor() as usize;
        q[k] + (x - k as f64) * (q[k + 1] - q[k])
    };
    let start = 3e-3;
    let k0 = (start / interval) as usize;
    let kpeak = (k0..k0 + (period / interval) as usize)
        .max_by(|&a, &b| q[a].abs().total_cmp(&q[b].abs()))
        .unwrap();
    let t0 = kpeak as f64 * interval;
    let t2 = t0 + period;
    let measured = (at(t0) / at(t2)).ln() / (t2 - t0);
    let expected = omega / (2.0 * q_factor);
    eprintln!("decay rate {measured:.4}/s vs ω/(2Q) = {expected:.4}/s (ω = {omega:.1} rad/s)");
    assert!(
        (measured / expected - 1.0).abs() < 0.01,
        "decay {measured} vs {expected}"
    );
}
