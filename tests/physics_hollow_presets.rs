//! The hollow presets (`alloy_bbcor`, `composite_bbcor`) and the break-in.
//!
//! References:
//! - NCAA/NFHS BBCOR rules (NCAA Rule 1-12, NFHS Rule 1-3-2): barrel at most 2 5/8 in; the
//!   presets are 33-in bats.
//! - Rayleigh's principle: softening a structure's stiffness (the matrix of its plies) cannot
//!   raise any of its natural frequencies, and a metal has no matrix to soften.

mod common;

use batstudy::model::collision::wave::resolve_shell;
use batstudy::model::prepare_bat;
use batstudy::model::spec::*;

fn spec(preset: BatPreset, break_in: f64) -> CollisionSpec {
    let mut s = common::base_spec(0.70);
    s.bat.preset = preset;
    s.bat.shell = Some(ShellSpec {
        break_in,
        ..ShellSpec::default()
    });
    s.hoop = Some(HoopSpec {
        from_geometry: true,
        ..HoopSpec::default()
    });
    s
}

#[test]
fn presets_are_33_in_bats_within_the_barrel_rule() {
    for preset in [BatPreset::AlloyBbcor, BatPreset::CompositeBbcor] {
        let s = spec(preset, 0.0);
        let bat = prepare_bat(&s.bat, &s.numerics).unwrap();
        assert!((bat.length() - 33.0 * 0.0254).abs() < 1e-9, "{preset:?}");
        let widest = (0..=100)
            .map(|i| {
                bat.geometry()
                    .outer_radius(bat.length() * f64::from(i) / 100.0)
            })
            .fold(0.0, f64::max);
        assert!(2.0 * widest <= 2.625 * 0.0254, "{preset:?}: {widest}");
    }
}

#[test]
fn break_in_lowers_a_composite_hoop_frequency_and_is_refused_on_a_metal() {
    let frequency = |preset, b| {
        let s = spec(preset, b);
        let bat = prepare_bat(&s.bat, &s.numerics).unwrap();
        resolve_shell(&s, &bat).unwrap().unwrap().frequency
    };
    let f: Vec<f64> = [0.0, 0.2, 0.5]
        .iter()
        .map(|&b| frequency(BatPreset::CompositeBbcor, b))
        .collect();
    assert!(f[0] > f[1] && f[1] > f[2], "{f:?}");
    // a metal has no matrix to crack: a break-in there would change nothing, so it is
    // refused rather than ignored
    let broken = spec(BatPreset::AlloyBbcor, 0.5);
    let err = prepare_bat(&broken.bat, &broken.numerics).unwrap_err();
    assert!(err.to_string().contains("bat.shell.break_in"), "{err}");
}

#[test]
fn a_spec_overrides_the_preset_wall() {
    let mut s = spec(BatPreset::AlloyBbcor, 0.0);
    s.bat.shell = Some(ShellSpec {
        thickness: Some(0.003),
        ..ShellSpec::default()
    });
    let bat = prepare_bat(&s.bat, &s.numerics).unwrap();
    let g = bat.geometry();
    assert!((g.outer_radius(0.7) - g.inner_radius(0.7) - 0.003).abs() < 1e-12);
}
