//! Ball force laws against a rigid, immovable wall.
//!
//! Reference: docs/physics.md "The ball" — a ball fired at a rigid wall must come back at e·v;
//! the paper's linear loading with the unloading branch p = 2/e² − 1, and Nathan (2000)'s
//! power law k₁ s^α / k₂ s^β with β = (1 + α)/e² − 1 (k₁ = 6.53e7, α = 1.84).

use batstudy::model::ball::{wall_rebound_speed, ContactLaw};
use batstudy::model::spec::{BallLaw, BallLawKind};

fn rebound(kind: BallLawKind, cor: f64, speed: f64) -> f64 {
    let law = ContactLaw::new(
        &BallLaw {
            kind,
            cor,
            ..BallLaw::default()
        },
        speed,
    );
    wall_rebound_speed(&law, 0.145, speed)
}

#[test]
fn linear_hysteresis_returns_cor_times_speed() {
    for (cor, speed) in [(0.5, 40.0), (0.546, 26.8), (0.8, 10.0)] {
        let v = rebound(BallLawKind::LinearHysteresis, cor, speed);
        assert!(
            (v / (cor * speed) - 1.0).abs() < 5e-3,
            "e {cor}, v {speed}: {v}"
        );
    }
}

#[test]
fn power_law_returns_cor_times_speed() {
    // Nathan's e₀ = 0.53 at 58 m/s, and the MLB test speed 26 m/s
    for (cor, speed) in [(0.53, 58.0), (0.53, 26.0), (0.5, 40.0)] {
        let v = rebound(BallLawKind::PowerLaw, cor, speed);
        assert!(
            (v / (cor * speed) - 1.0).abs() < 5e-3,
            "e {cor}, v {speed}: {v}"
        );
    }
}

#[test]
fn elastic_returns_the_full_speed() {
    let v = rebound(BallLawKind::Elastic, 0.5, 40.0);
    assert!((v / 40.0 - 1.0).abs() < 5e-3, "{v}");
}
