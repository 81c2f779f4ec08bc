//! The hollow barrel's resolution is a study's to set (`numerics.shell_elements`,
//! `.shell_wave_numbers`, `.shell_modes_per_wave`), and its convergence can be checked from a
//! study (`studies/shell_convergence.yaml` runs the same grid). References: the cubic
//! Hermite elements' convergence (tests/physics_shell.rs measures 4th order against Love's
//! closed form), so that the exit speed's change with elements must shrink as they double;
//! and the modal expansion, whose truncation is not yet converged at the default four axial
//! modes per wave number (docs/physics.md, "The barrel as a shell", states by how much).

use batstudy::model::{prepare_bat, simulate};
use batstudy::study::{load_str, LoadOptions};
use std::path::Path;

/// Exit speed (m/s) of the calibrated ball at 60.8 m/s on `alloy_bbcor` at 70 cm, the
/// breathing modes solved with `numerics`.
fn exit_speed(numerics: &str) -> f64 {
    let text = format!(
        "name: r\nbase:\n  bat: {{preset: alloy_bbcor}}\n  ball: {{preset: mlb, speed: 60.8}}\n  \
         hoop: {{from_geometry: true}}\n  numerics: {numerics}\n  impact: {{z: 0.70}}\n"
    );
    let study = load_str(&text, Path::new("r.yaml"), &LoadOptions::default())
        .unwrap_or_else(|e| panic!("{e}"));
    let spec = study.plan.point(0).unwrap().spec;
    let bat = prepare_bat(&spec.bat, &spec.numerics).unwrap();
    simulate(&spec, &bat, None).unwrap().exit_speed
}

#[test]
fn the_answer_converges_with_the_shells_elements() {
    let v: Vec<f64> = [12, 24, 48, 96]
        .iter()
        .map(|n| exit_speed(&format!("{{shell_elements: {n}}}")))
        .collect();
    eprintln!("exit speed on 12, 24, 48, 96 elements: {v:.6?}");
    let steps: Vec<f64> = v.windows(2).map(|w| (w[1] - w[0]).abs()).collect();
    // each doubling changes the answer less, and the default (24) is within 1e-4 of 96
    assert!(steps[1] < steps[0] && steps[2] < steps[0], "{steps:?}");
    assert!((v[1] - v[3]).abs() < 1e-4 * v[3], "{v:?}");
    assert_eq!(
        exit_speed("{}").to_bits(),
        v[1].to_bits(),
        "24 is the default"
    );
}

#[test]
fn wave_numbers_and_modes_per_wave_number_are_the_studys() {
    let default = exit_speed("{}");
    let with_n5 = exit_speed("{shell_wave_numbers: [2, 3, 4, 5]}");
    let modes: Vec<f64> = [4, 8, 16]
        .iter()
        .map(|n| exit_speed(&format!("{{shell_modes_per_wave: {n}}}")))
        .collect();
    eprintln!("default {default:.4}; n = 2–5 {with_n5:.4}; 4, 8, 16 axial modes {modes:.4?}");
    assert_eq!(modes[0].to_bits(), default.to_bits(), "4 is the default");
    // n = 5 stiffer than the trampoline's n = 2: it adds little
    assert!((with_n5 - default).abs() < 0.01 * default.abs());
    // more axial modes add compliance under the ball (each mode's static compliance
    // φ²/ω² > 0), and the trampoline returns more: the exit speed rises with them
    assert!(modes[0] < modes[1] && modes[1] < modes[2], "{modes:?}");
}

#[test]
fn a_resolution_out_of_bounds_is_refused() {
    for numerics in [
        "{shell_elements: 2}",
        "{shell_elements: 100000}",
        "{shell_wave_numbers: []}",
        "{shell_wave_numbers: [1, 2]}",
        "{shell_wave_numbers: [2, 2]}",
        "{shell_modes_per_wave: 0}",
        "{shell_modes_per_wave: 1000}",
    ] {
        let text = format!(
            "name: r\nbase:\n  bat: {{preset: alloy_bbcor}}\n  hoop: {{from_geometry: true}}\n  \
             numerics: {numerics}\n  impact: {{z: 0.70}}\n"
        );
        let e = load_str(&text, Path::new("r.yaml"), &LoadOptions::default())
            .map(|_| ())
            .expect_err(numerics);
        assert!(
            e.line.is_some() && e.message.contains("numerics.shell"),
            "{numerics}: {e}"
        );
    }
}
