//! Brody's rigid-body model (the paper's section 2; docs/physics.md "The rigid-body model (Brody)").

use batstudy::model::collision::rigid::rigid_collision;

// The seed paper's bat (docs/physics.md): M 0.831 kg, I_cm 0.039 kg·m², CM 0.593 m; ball 0.145 kg.
const BAT_MASS: f64 = 0.831;
const BAT_INERTIA: f64 = 0.039;
const Z_CM: f64 = 0.593;
const BALL_MASS: f64 = 0.145;

fn peak_position(omega: f64) -> f64 {
    let z: Vec<f64> = (0..=4400).map(|k| 0.40 + 0.0001 * k as f64).collect();
    let exit = |z: f64| {
        rigid_collision(BALL_MASS, 40.0, BAT_MASS, BAT_INERTIA, z - Z_CM, omega, 0.5).exit_speed
    };
    *z.iter()
        .max_by(|a, b| exit(**a).total_cmp(&exit(**b)))
        .unwrap()
}

/// docs/physics.md: "with ω = 0 the peak is at the CM" — the effective mass is largest there.
#[test]
fn still_bat_peaks_at_the_centre_of_mass() {
    assert!((peak_position(0.0) - Z_CM).abs() < 2e-4);
}

/// docs/physics.md / paper Fig. 8: the peak moves toward the barrel as the swing gets faster.
#[test]
fn faster_swing_moves_the_peak_toward_the_barrel() {
    let peaks: Vec<f64> = [0.0, -10.0, -20.0, -40.0, -60.0]
        .iter()
        .map(|w| peak_position(*w))
        .collect();
    for pair in peaks.windows(2) {
        assert!(pair[1] > pair[0] + 1e-3, "{peaks:?}");
    }
}

/// Closed form at the CM (l = 0): exit = v (e − m/M)/(1 + m/M) for a still bat.
#[test]
fn exit_speed_at_the_cm_matches_the_closed_form() {
    let o = rigid_collision(BALL_MASS, 40.0, BAT_MASS, BAT_INERTIA, 0.0, 0.0, 0.5);
    let r = BALL_MASS / BAT_MASS;
    assert!((o.exit_speed - 40.0 * (0.5 - r) / (1.0 + r)).abs() < 1e-12);
    assert!((o.collision_efficiency - (0.5 - r) / (1.0 + r)).abs() < 1e-12);
}
