//! Oblique impacts and spin against references independent of the code:
//!
//! - the rigid-body oblique collision with Coulomb friction in closed form (Stronge's impact
//!   mechanics as Sawicki, Hubbard & Stronge, Am. J. Phys. 71, 1152 (2003), and Cross &
//!   Nathan, Am. J. Phys. 74, 896 (2006) apply it to bat and ball), derived again here from
//!   impulse and momentum: a very stiff bat must reproduce it where the ball slides
//!   throughout (gross slip), where the tangential spring plays no part;
//! - a ball that grips throughout on a stiff bat with a linear elastic normal law: the
//!   contact points' tangential motion is a harmonic oscillator of frequency
//!   Ω² = k_t w_t over the normal contact's half period π/√(k w_n), so the tangential COR is
//!   e_T = −cos(Ω t_c) (Cross, Am. J. Phys. 70, 482 (2002): the "grip" model);
//! - conservation: an elastic, frictionless collision conserves energy and both momenta,
//!   and with friction the energy balance closes (friction included);
//! - continuity with the head-on collision as the offset goes to zero.

mod common;

use batstudy::model::collision::oblique::BallContact;
use batstudy::model::spec::*;
use batstudy::model::{prepare_bat, simulate, simulate_with_diagnostics, PreparedBat};

/// A bat a thousand times stiffer than the R161 (the rigid limit), with the calibrated ball.
fn stiff_bat_spec(z: f64, offset: f64) -> CollisionSpec {
    let mut spec = CollisionSpec::base_case(z);
    spec.bat.material.youngs_modulus = Some(1.814e10 * 1000.0);
    spec.ball = ball(BallPreset::Mlb);
    spec.ball.speed = 40.0;
    spec.impact.offset = offset;
    spec
}

fn ball(preset: BallPreset) -> BallSpec {
    BallSpec {
        preset: Some(preset),
        law: batstudy::model::ball::preset_law(preset),
        ..BallSpec::default()
    }
}

/// The rigid bat's effective mass at `z` (1/M + l²/I)⁻¹ from the prepared bat's properties.
fn effective_mass(bat: &PreparedBat, z: f64) -> f64 {
    let p = bat.properties();
    1.0 / (1.0 / p.mass + (z - p.z_cm).powi(2) / p.moment_of_inertia)
}

/// The roll inertia of the bat: ∫ ρ π R⁴/2 dz of the solid wood profile (trapezoid on a fine
/// grid, independent of the model's Gauss quadrature).
fn roll_inertia(bat: &PreparedBat) -> f64 {
    let g = bat.geometry();
    let n = 20_000;
    let dz = g.length / n as f64;
    (0..=n)
        .map(|k| {
            let z = k as f64 * dz;
            let w = if k == 0 || k == n { 0.5 } else { 1.0 };
            w * g.density * std::f64::consts::PI * g.outer_radius(z).powi(4) / 2.0
        })
        .sum::<f64>()
        * dz
}

/// The closed form, derived from impulses: in the plane across the bat the ball meets it
/// along n̂ = (cos θ, sin θ), sin θ = offset/(R + r); a rigid bat has the same effective mass
/// M* in every direction across its axis. Returns the ball's velocity (along, across) and
/// spin after, for a ball that slides throughout (|J_t| = μ J_n) or rolls off (slip 0).
fn closed_form(
    (m, r, inertia): (f64, f64, f64),
    (mstar, bat_radius, roll): (f64, f64, f64),
    (v, offset, cor, mu): (f64, f64, f64, f64),
) -> (f64, f64, f64) {
    let s = offset / (bat_radius + r);
    let c = (1.0 - s * s).sqrt();
    let w_n = 1.0 / m + 1.0 / mstar;
    let w_t = w_n + r * r / inertia + bat_radius * bat_radius / roll;
    let jn = (1.0 + cor) * v * c / w_n;
    let slip = -s * v;
    let jt = if mu * jn >= slip.abs() / w_t {
        -slip / w_t
    } else {
        -mu * jn * slip.signum()
    };
    // on the ball: −J_n n̂ + J_t t̂, t̂ = (−sin θ, cos θ)
    let along = v + (-jn * c - jt * s) / m;
    let across = (-jn * s + jt * c) / m;
    (along, across, r * jt / inertia)
}

#[test]
fn a_stiff_bat_gives_the_rigid_closed_form_when_the_ball_slides() {
    for (z, offset, mu) in [
        (0.70, -0.02, 0.02),
        (0.62, 0.015, 0.03),
        (0.75, -0.035, 0.05),
    ] {
        let mut spec = stiff_bat_spec(z, offset);
        spec.ball.law.friction = Some(mu);
        let bat = prepare_bat(&spec.bat, &spec.numerics).unwrap();
        let o = simulate(&spec, &bat, None).unwrap();
        let ball = BallContact::of(&spec.ball);
        let r = ball.radius;
        let reach = bat.geometry().outer_radius(z) + r;
        // the ball's COR at the normal speed, as a rigid surface of the barrel's radius gives it
        let v_n = spec.ball.speed * (1.0 - (offset / reach).powi(2)).sqrt();
        let barrel = Some(bat.geometry().outer_radius(z));
        let cor = batstudy::model::ball::cor_on_target(&spec.ball.law, v_n, r, barrel);
        let (along, across, spin) = closed_form(
            (spec.ball.mass, r, ball.inertia),
            (
                effective_mass(&bat, z),
                bat.geometry().outer_radius(z),
                roll_inertia(&bat),
            ),
            (spec.ball.speed, offset, cor, mu),
        );
        let e = o.ball_exit;
        let speed = along.hypot(across);
        for (name, got, want) in [("along", e.along, along), ("across", e.across, across)] {
            assert!(
                (got - want).abs() < 5e-3 * speed,
                "z {z} offset {offset}: {name} {got} vs closed form {want}"
            );
        }
        assert!(
            (e.spin - spin).abs() < 0.02 * spin.abs(),
            "z {z} offset {offset}: spin {} vs closed form {spin}",
            e.spin
        );
    }
}

#[test]
fn a_ball_that_grips_throughout_rebounds_tangentially_as_a_harmonic_spring() {
    let (k, ratio) = (7.0e5, 0.2);
    for offset in [-0.01, -0.03] {
        let mut spec = stiff_bat_spec(0.70, offset);
        spec.ball = BallSpec {
            law: BallLaw {
                kind: BallLawKind::Elastic,
                stiffness: k,
                friction: Some(1.0e3),
                tangential_ratio: Some(ratio),
                ..BallLaw::default()
            },
            ..BallSpec::default()
        };
        let bat = prepare_bat(&spec.bat, &spec.numerics).unwrap();
        let o = simulate(&spec, &bat, None).unwrap();
        let ball = BallContact::of(&spec.ball);
        let (m, r, mstar) = (spec.ball.mass, ball.radius, effective_mass(&bat, 0.70));
        let big_r = bat.geometry().outer_radius(0.70);
        let w_n = 1.0 / m + 1.0 / mstar;
        let w_t = w_n + r * r / ball.inertia + big_r * big_r / roll_inertia(&bat);
        let contact_time = std::f64::consts::PI / (k * w_n).sqrt();
        let expected = -((ratio * k * w_t).sqrt() * contact_time).cos();
        assert!(
            (o.tangential_cor - expected).abs() < 0.02,
            "offset {offset}: e_T {} vs {expected}",
            o.tangential_cor
        );
    }
}

#[test]
fn an_elastic_frictionless_oblique_collision_conserves_energy_and_momenta() {
    let mut spec = stiff_bat_spec(0.68, -0.025);
    spec.ball.law = BallLaw {
        kind: BallLawKind::Elastic,
        friction: Some(0.0),
        ..BallLaw::default()
    };
    spec.swing.omega = -30.0;
    let bat = prepare_bat(&spec.bat, &spec.numerics).unwrap();
    // the modal integrator's energy error shrinks with the step (the contact's end falls
    // inside a step, so the order is between one and two)
    let error = |dt: f64| {
        let mut spec = spec.clone();
        spec.numerics.dt = Some(dt);
        let (o, d) = simulate_with_diagnostics(&spec, &bat, None).unwrap();
        d.energy_final / o.energy.initial - 1.0
    };
    let (coarse, fine) = (error(4e-7), error(2e-7));
    assert!(fine.abs() < 1e-6, "energy error {fine:e} at 0.2 µs");
    let order = (coarse / fine).log2();
    assert!(order > 1.0, "order {order}: {coarse:e}, {fine:e}");
    spec.numerics.dt = Some(2e-7);
    let (o, d) = simulate_with_diagnostics(&spec, &bat, None).unwrap();
    let e = &o.energy;
    assert!(e.ball_loss.abs() < 1e-9 * e.initial && e.friction.abs() < 1e-12);
    let scale = spec.ball.mass * spec.ball.speed;
    assert!((d.momentum_final - d.momentum_initial).abs() < 1e-9 * scale);
    assert!((d.angular_momentum_final - d.angular_momentum_initial).abs() < 1e-9 * scale);
    // without friction the spin is untouched and the ball's momentum across the plane is
    // what the normal impulse gave it: the closed form with μ = 0
    let ball = BallContact::of(&spec.ball);
    assert_eq!(o.ball_exit.spin, 0.0);
    assert!(o.tangential_cor.is_finite());
    let r = ball.radius;
    let big_r = bat.geometry().outer_radius(0.68);
    let approach = spec.ball.speed - spec.swing.omega * (0.68 - bat.properties().z_cm);
    let (_, across, _) = closed_form(
        (spec.ball.mass, r, ball.inertia),
        (effective_mass(&bat, 0.68), big_r, roll_inertia(&bat)),
        (approach, -0.025, 1.0, 0.0),
    );
    assert!(
        (o.ball_exit.across - across).abs() < 5e-3 * across.abs(),
        "across {} vs {across}",
        o.ball_exit.across
    );
}

#[test]
fn with_friction_on_a_flexible_bat_the_energy_balance_closes() {
    for (offset, spin) in [(-0.02, 0.0), (0.01, 150.0), (0.0, -200.0)] {
        let mut spec = CollisionSpec::base_case(0.66);
        spec.ball = ball(BallPreset::Mlb);
        spec.swing.omega = -45.0;
        spec.impact.offset = offset;
        spec.ball.spin = spin;
        let bat = prepare_bat(&spec.bat, &spec.numerics).unwrap();
        let (o, d) = simulate_with_diagnostics(&spec, &bat, None).unwrap();
        assert!(o.energy.friction > 0.0, "offset {offset}: slides at first");
        common::assert_energy_closes(&o, &d, 2e-4, &format!("offset {offset} spin {spin}"));
    }
}

#[test]
fn a_vanishing_offset_approaches_the_head_on_collision() {
    let mut spec = CollisionSpec::base_case(0.70);
    spec.ball = ball(BallPreset::Mlb);
    spec.swing.omega = -40.0;
    let bat = prepare_bat(&spec.bat, &spec.numerics).unwrap();
    let head_on = simulate(&spec, &bat, None).unwrap();
    spec.impact.offset = -1e-7;
    let oblique = simulate(&spec, &bat, None).unwrap();
    assert!(head_on.tangential_cor.is_nan() && oblique.tangential_cor.is_finite());
    assert!(
        (oblique.exit_speed / head_on.exit_speed - 1.0).abs() < 1e-6,
        "{} vs {}",
        oblique.exit_speed,
        head_on.exit_speed
    );
    assert!(oblique.batted.launch_angle.abs() < 1e-4);
}

/// The aluminum bat with its hoop mode (from the shell).
fn aluminum_with_hoop(z: f64) -> CollisionSpec {
    let mut spec = CollisionSpec::base_case(z);
    spec.bat.preset = BatPreset::Aluminum;
    spec.hoop = Some(HoopSpec {
        from_geometry: true,
        ..HoopSpec::default()
    });
    spec.ball = ball(BallPreset::Mlb);
    spec.swing.omega = -40.0;
    spec
}

#[test]
fn with_a_hoop_mode_the_oblique_energy_balance_closes_and_momentum_is_kept() {
    for (offset, mu) in [(-0.02, 0.15), (0.015, 0.0)] {
        let mut spec = aluminum_with_hoop(0.68);
        spec.impact.offset = offset;
        spec.ball.law.friction = Some(mu);
        let bat = prepare_bat(&spec.bat, &spec.numerics).unwrap();
        let (o, d) = simulate_with_diagnostics(&spec, &bat, None).unwrap();
        assert!(o.energy.hoop >= 0.0 && o.hoop_frequency.is_finite());
        assert!(
            (d.energy_final / o.energy.initial - 1.0).abs() < 2e-4,
            "offset {offset}: {} vs {}",
            d.energy_final,
            o.energy.initial
        );
        let scale = spec.ball.mass * spec.ball.speed;
        assert!(
            (d.momentum_final - d.momentum_initial).abs() < 1e-6 * scale,
            "offset {offset}: momentum {} -> {}",
            d.momentum_initial,
            d.momentum_final
        );
    }
}

#[test]
fn with_a_hoop_mode_a_vanishing_offset_approaches_the_head_on_collision() {
    let mut spec = aluminum_with_hoop(0.70);
    let bat = prepare_bat(&spec.bat, &spec.numerics).unwrap();
    let head_on = simulate(&spec, &bat, None).unwrap();
    spec.impact.offset = -1e-7;
    let oblique = simulate(&spec, &bat, None).unwrap();
    assert!(
        (oblique.exit_speed / head_on.exit_speed - 1.0).abs() < 1e-6,
        "{} vs {}",
        oblique.exit_speed,
        head_on.exit_speed
    );
    assert!((oblique.energy.hoop / head_on.energy.hoop - 1.0).abs() < 1e-4);
}
