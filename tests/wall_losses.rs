//! Losses in a hollow barrel's wall (`bat::laminate` loss stiffnesses, `bat::shell` modal
//! loss factors), verified against what must hold whatever the numbers:
//! - a wall of one isotropic material with loss factor η has K″ = η K, so every mode's loss
//!   factor is η exactly (the definition of a loss factor as a Rayleigh quotient, Ungar &
//!   Kerwin, J. Acoust. Soc. Am. 34, 954 (1962): η = dissipated per cycle / (2π stored));
//! - a laminate's mode dissipates a share of each ply's strain energies (Adams & Bacon,
//!   J. Compos. Mater. 7, 402 (1973)), so its loss factor lies between the smallest and the
//!   largest of its plies' loss factors;
//! - energy is conserved with the loss counted (an elastic ball's energy before equals the
//!   ball's after, the beam's, the shell's and what the wall dissipated).
//!
//! What it does to BBCOR is measured, and stated in docs/physics.md.

mod common;

use batstudy::model::bat::laminate::{Ply, Wall, ALUMINIUM_LOSS};
use batstudy::model::bat::shell::{mesh, modes_of, ShellEnd, WallAlong};
use batstudy::model::spec::*;
use batstudy::model::{prepare_bat, simulate};

struct Lossy {
    ply: Ply,
    h: f64,
    a: f64,
}

impl WallAlong for Lossy {
    fn wall(&self, _x: f64) -> Wall {
        Wall::isotropic(self.ply.e1, self.ply.nu12, self.ply.density, self.h, self.a)
    }
    fn loss(&self, x: f64) -> Option<Wall> {
        Some(self.wall(x).stiffness_times(self.ply.loss[0]))
    }
}

#[test]
fn an_isotropic_walls_modes_have_its_loss_factor() {
    let eta = 3e-3;
    let wall = Lossy {
        ply: Ply::isotropic_lossy(71.7e9, 0.33, 2830.0, eta),
        h: 2.5e-3,
        a: 0.032,
    };
    let nodes = mesh(0.0, 0.5, &[], 24);
    for n in [2, 3, 4] {
        for m in modes_of(n, &nodes, &wall, (ShellEnd::Free, ShellEnd::Supported), 4).unwrap() {
            assert!(
                (m.loss_factor / eta - 1.0).abs() < 1e-9,
                "n {n}: {}",
                m.loss_factor
            );
        }
    }
}

#[test]
fn a_laminates_modes_lose_between_their_plies_extremes() {
    let bat: BatSpec = serde_json::from_str(r#"{"preset": "composite_bbcor"}"#).unwrap();
    let prepared = prepare_bat(&bat, &NumericsSpec::default()).unwrap();
    let modes = prepared.shell_modes().unwrap().unwrap();
    // carbon/epoxy and glass/epoxy: 1.11e-3 along the fibres, 1.1e-2 across and in shear
    for m in &modes.modes {
        assert!(
            (1.11e-3..=1.1e-2).contains(&m.loss_factor),
            "n {} at {:.0} Hz: η {}",
            m.wave_number,
            m.omega / std::f64::consts::TAU,
            m.loss_factor
        );
    }
    // the ovalling modes bend the wall around the hoop, where the 90° glass plies carry it
    // along their fibres and the ±30° carbon across theirs: a mix, well above the fibres'
    let lowest = modes.modes[0].loss_factor;
    assert!(lowest > 2e-3, "lowest mode's η {lowest}");
    // an alloy's modes have the metal's
    let alloy: BatSpec = serde_json::from_str(r#"{"preset": "alloy_bbcor"}"#).unwrap();
    let prepared = prepare_bat(&alloy, &NumericsSpec::default()).unwrap();
    for m in &prepared.shell_modes().unwrap().unwrap().modes {
        assert!((m.loss_factor / ALUMINIUM_LOSS - 1.0).abs() < 1e-9);
    }
}

#[test]
fn energy_is_conserved_with_the_walls_loss_counted() {
    let mut spec = common::base_spec(0.70);
    spec.bat = serde_json::from_str(r#"{"preset": "composite_bbcor"}"#).unwrap();
    spec.ball.law = common::elastic();
    spec.hoop = Some(HoopSpec {
        from_geometry: true,
        ..HoopSpec::default()
    });
    let bat = prepare_bat(&spec.bat, &spec.numerics).unwrap();
    let out = simulate(&spec, &bat, None).unwrap();
    let e = &out.energy;
    // the beam has no damping here: all of bat_damping is the wall's
    assert!(e.hoop > 0.0 && e.bat_damping > 0.0, "{e:?}");
    let total = e.ball_final + e.ball_loss + e.bat_rigid + e.bat_vibration + e.hoop + e.bat_damping;
    assert!(
        (total / e.initial - 1.0).abs() < 1e-3,
        "{total} vs {}",
        e.initial
    );
    eprintln!(
        "composite_bbcor at 0.70 m: the wall took {:.2e} J of {:.3} J in the modes",
        e.bat_damping, e.hoop
    );
}
