//! A very stiff bat reproduces Brody's rigid-body model.
//!
//! Reference: docs/physics.md "The rigid-body model (Brody)" and "Numbers to validate against": with
//! Y × 1000 the wave model must give the rigid-body exit speed with e = the ball's COR.
//! The rigid value is computed here from Brody's three equations, independently of the code:
//!   M V_f = m (v_i − v_f),  I (ω_f − ω_i) = m l (v_i − v_f),  e (v_i − ω_i l) = −v_f + V_f + ω_f l.

mod common;

use batstudy::model::{prepare_bat, simulate};

/// Solve Brody's equations for v_f (ball velocity after, + toward the bat). Returns the exit
/// speed −v_f.
fn brody_exit_speed(
    m: f64,
    v_i: f64,
    big_m: f64,
    inertia: f64,
    l: f64,
    omega_i: f64,
    e: f64,
) -> f64 {
    // V_f = m (v_i − v_f)/M, ω_f = ω_i + m l (v_i − v_f)/I; substitute into the COR equation:
    // e (v_i − ω_i l) = −v_f + m (v_i − v_f)/M + ω_i l + m l² (v_i − v_f)/I
    // ⇒ v_f (1 + m/M + m l²/I) = (m/M + m l²/I) v_i + ω_i l − e (v_i − ω_i l)
    let k = m / big_m + m * l * l / inertia;
    let v_f = (k * v_i + omega_i * l - e * (v_i - omega_i * l)) / (1.0 + k);
    -v_f
}

#[test]
fn stiff_bat_matches_brody_along_the_barrel() {
    for omega in [0.0, -30.0] {
        for z in [0.55, 0.60, 0.65, 0.70, 0.75, 0.80] {
            let mut spec = common::base_spec(z);
            spec.bat.material.youngs_modulus = Some(1.814e10 * 1000.0);
            spec.swing.omega = omega;
            let bat = prepare_bat(&spec.bat, &spec.numerics).unwrap();
            let p = bat.properties();
            let rigid = brody_exit_speed(
                spec.ball.mass,
                spec.ball.speed,
                p.mass,
                p.moment_of_inertia,
                z - p.z_cm,
                omega,
                spec.ball.law.cor,
            );
            let wave = simulate(&spec, &bat, None).unwrap().exit_speed;
            assert!(
                (wave / rigid - 1.0).abs() < 5e-3,
                "z {z}, omega {omega}: wave {wave} vs rigid {rigid}"
            );
        }
    }
}
