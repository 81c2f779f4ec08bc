//! The hollow BBCOR bats built in: `alloy_bbcor` (single-wall 7050) and `composite_bbcor`
//! (a carbon/glass laminate), each a 33-in bat with a 2 5/8-in barrel, the largest the
//! NCAA/NFHS BBCOR rules allow, on the R161's handle and taper (Nathan 2000's profile).
//!
//! The walls are not measured bats': no wall thickness or layup of a real BBCOR bat was found
//! in the literature this project could read (data/hollow_bats.md). They are what batstudy's
//! own design search gave for the geometry (docs/design.md, "The hollow presets") under a
//! fixed 2-cm contact patch: the alloy wall the lightest-hitting legal one in the 30-oz
//! class; the composite a balanced ±30° carbon stack between hoop-wound glass plies, as
//! patents describe (fibres near axial inside, near hoop outside), thick enough to certify
//! after break-in.

use super::laminate::AL7050_YIELD;
use crate::spec::{BatPreset, BatSpec, LayerSpec, MaterialSpec, ProfileSpec};

/// 33 in, m.
pub const LENGTH: f64 = 0.8382;
/// 2 5/8 in barrel, less 10 µm so that it is within the rule as a radius knot rounds.
pub const BARREL_RADIUS: f64 = 0.03333;

/// The outer profile: the R161's knob, handle and taper to 55 cm, then a taper to the
/// 2 5/8-in barrel at 65 cm, to the end.
pub fn profile() -> Vec<[f64; 2]> {
    vec![
        [0.0, 0.0252],
        [0.02, 0.0252],
        [0.03, 0.0177],
        [0.15, 0.0130],
        [0.35, 0.0152],
        [0.45, 0.0180],
        [0.55, 0.0252],
        [0.65, BARREL_RADIUS],
        [LENGTH, BARREL_RADIUS],
    ]
}

/// The alloy bat's wall along the bat, `[z, t]` (m): 2–2.5 mm in the handle; in the barrel
/// the design search's walls (studies/design_bbcor.yaml at this barrel), rounded to 0.1 mm.
pub fn alloy_wall() -> Vec<[f64; 2]> {
    vec![
        [0.0, 0.0020],
        [0.35, 0.0020],
        [0.45, 0.0025],
        [0.55, 0.0015],
        [0.65, 0.0024],
        [0.75, 0.0046],
        [LENGTH, 0.0061],
    ]
}

/// The composite's stack, outside in: hoop glass, four ±30° carbon plies, hoop glass (3 mm).
pub fn composite_layers() -> Vec<LayerSpec> {
    let ply = |material: &str, thickness: f64, angle: f64| LayerSpec {
        material: material.to_string(),
        thickness,
        angle,
    };
    let a = 30f64.to_radians();
    vec![
        ply("glass_epoxy", 0.0003, std::f64::consts::FRAC_PI_2),
        ply("carbon_epoxy", 0.0006, a),
        ply("carbon_epoxy", 0.0006, -a),
        ply("carbon_epoxy", 0.0006, a),
        ply("carbon_epoxy", 0.0006, -a),
        ply("glass_epoxy", 0.0003, std::f64::consts::FRAC_PI_2),
    ]
}

/// The composite's wall thickness along the bat (the stack scaled), `[z, t]` (m).
pub fn composite_wall() -> Vec<[f64; 2]> {
    vec![
        [0.0, 0.0045],
        [0.45, 0.0045],
        [0.60, 0.0052],
        [LENGTH, 0.0056],
    ]
}

/// The spec with a hollow preset's geometry and material filled in where the spec leaves
/// them out, as an aluminum-family bat; any other spec unchanged.
pub fn expand(bat: &BatSpec) -> BatSpec {
    let composite = match bat.preset {
        BatPreset::AlloyBbcor => false,
        BatPreset::CompositeBbcor => true,
        _ => return bat.clone(),
    };
    let mut out = bat.clone();
    out.preset = BatPreset::Aluminum;
    out.profile = out.profile.or(Some(ProfileSpec::Knots(profile())));
    out.length = out.length.or(Some(LENGTH));
    let mut shell = out.shell.unwrap_or_default();
    shell.from = shell.from.or(Some(0.0));
    // a wall the study describes (a thickness, knots or layers) replaces the preset's
    if shell.thickness.is_none() && shell.thickness_knots.is_none() && shell.layers.is_none() {
        shell.thickness_knots = Some(if composite {
            composite_wall()
        } else {
            alloy_wall()
        });
    }
    if composite && shell.layers.is_none() {
        shell.layers = Some(composite_layers());
    }
    out.shell = Some(shell);
    if !composite {
        // 7050-T7451 (docs/physics.md, the layer materials)
        out.material = MaterialSpec {
            density: out.material.density.or(Some(2830.0)),
            youngs_modulus: out.material.youngs_modulus.or(Some(71.7e9)),
            yield_strength: out.material.yield_strength.or(Some(AL7050_YIELD)),
            ..out.material
        };
    }
    out
}
