//! Every field a study may set changes a result where it is accepted: a field that is
//! taken and then ignored gives a user the answer to a question they did not ask. The
//! oracle is the model's own dependence, stated independently of its numbers: a wall's
//! mass per length is ρ·2πR·h (a thicker layer is a heavier bat), a ply's stiffness along
//! the axis depends on its fibre angle (classical lamination theory, Jones 1999 §2.6), a
//! softened matrix lowers the wall's hoop stiffness, and the load's footprint sets which
//! breathing modes it drives. Each pair below differs only in the one field.

use batstudy::model::{prepare_bat, simulate};
use batstudy::study::{load_str, LoadOptions};
use std::path::Path;

/// The exit speed (m/s) and the bat's mass (kg) of the study's one point.
fn outcome(bat: &str, hoop: &str) -> (f64, f64) {
    let text = format!("name: t\nbase:\n  bat: {bat}\n  hoop: {hoop}\n  ball: {{preset: mlb}}\n  impact: {{z: 0.72}}\n");
    let study = load_str(&text, Path::new("t.yaml"), &LoadOptions::default())
        .unwrap_or_else(|e| panic!("{e}\n{text}"));
    let spec = study.plan.point(0).unwrap().spec;
    let prepared = prepare_bat(&spec.bat, &spec.numerics).unwrap();
    let o = simulate(&spec, &prepared, None).unwrap();
    (o.exit_speed, prepared.properties().mass)
}

const BREATHES: &str = "{from_geometry: true}";

#[test]
fn a_layer_on_a_hollow_preset_is_the_wall() {
    let preset = outcome("{preset: alloy_bbcor}", BREATHES);
    let thin = outcome(
        "{preset: alloy_bbcor, shell: {layers: [{material: al7050, thickness: 0.003}]}}",
        BREATHES,
    );
    let thick = outcome(
        "{preset: alloy_bbcor, shell: {layers: [{material: al7050, thickness: 0.004}]}}",
        BREATHES,
    );
    eprintln!("preset {preset:?}, 3 mm {thin:?}, 4 mm {thick:?}");
    // a 1-mm thicker wall over the whole bat is heavier (ρ 2830 kg/m³ × 2πR × 1 mm × L)
    assert!(thick.1 > thin.1 + 0.05, "{thin:?} {thick:?}");
    assert_ne!(thin.0.to_bits(), thick.0.to_bits());
    assert_ne!(thin.0.to_bits(), preset.0.to_bits());
}

#[test]
fn a_fibre_angle_and_a_break_in_change_a_composite_wall() {
    let stack = |angle: f64, break_in: f64| {
        format!(
            "{{preset: composite_bbcor, shell: {{break_in: {break_in}, layers: [\
             {{material: glass_epoxy, thickness: 0.0008, angle: 1.5707963}}, \
             {{material: carbon_epoxy, thickness: 0.0034, angle: {angle}}}, \
             {{material: glass_epoxy, thickness: 0.0008, angle: 1.5707963}}]}}}}"
        )
    };
    let base = outcome(&stack(0.3, 0.0), BREATHES).0;
    let turned = outcome(&stack(0.8, 0.0), BREATHES).0;
    let broken = outcome(&stack(0.3, 0.3), BREATHES).0;
    eprintln!("exit speed {base}, fibres turned {turned}, broken in {broken}");
    assert_ne!(base.to_bits(), turned.to_bits());
    assert_ne!(base.to_bits(), broken.to_bits());
}

#[test]
fn the_patch_radius_changes_a_hollow_bat() {
    let small = outcome(
        "{preset: alloy_bbcor}",
        "{from_geometry: true, patch_radius: 0.015}",
    )
    .0;
    let large = outcome(
        "{preset: alloy_bbcor}",
        "{from_geometry: true, patch_radius: 0.025}",
    )
    .0;
    eprintln!("patch 1.5 cm {small}, 2.5 cm {large}");
    assert_ne!(small.to_bits(), large.to_bits());
}

#[test]
fn the_footprint_ratio_changes_a_hollow_bat() {
    let hertz = outcome(
        "{preset: alloy_bbcor}",
        "{from_geometry: true, footprint_ratio: 0.5}",
    )
    .0;
    let flat = outcome(
        "{preset: alloy_bbcor}",
        "{from_geometry: true, footprint_ratio: 1.0}",
    )
    .0;
    eprintln!("footprint 0.5 {hertz}, 1.0 {flat}");
    assert_ne!(hertz.to_bits(), flat.to_bits());
}
