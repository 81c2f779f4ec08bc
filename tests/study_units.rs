//! Quantities in a study file may carry the trade's units (`bat.length: 34in`,
//! `ball.speed: 90mph`, `swing.omega: -1500rpm`): each is its SI value by the unit's
//! definition (NIST SP 811: 1 in = 0.0254 m, 1 mph = 0.44704 m/s exactly, 1 rpm = π/30
//! rad/s), wherever it is written (base, a grid axis and its range, a points set, an optimize
//! variable's bounds). A unit the field does not take is refused with its position and the
//! units it does; a bare number in the trade's unit where SI is implausible is refused with
//! the suffix that says what was meant.

#![allow(clippy::result_large_err)] // StudyError: see study/mod.rs

mod common;

use batstudy::study::{self, LoadOptions};
use std::path::Path;

const INCH: f64 = 0.0254;
const MPH: f64 = 0.44704;
const RPM: f64 = std::f64::consts::PI / 30.0;

fn load(text: &str) -> Result<study::Study, study::StudyError> {
    study::load_str(text, Path::new("s.yaml"), &LoadOptions { max_points: 1000 })
}

/// Every point's resolved specification as JSON text, in order.
fn specs(s: &study::Study) -> Vec<String> {
    (0..s.plan.n_points())
        .map(|i| serde_json::to_string(&s.plan.point(i).unwrap().spec).unwrap())
        .collect()
}

#[test]
fn a_study_with_units_is_the_same_study_in_si() {
    let with_units =
        "name: u\nbase:\n  bat: {preset: r161, length: 34in}\n  ball: {speed: 90mph}\n  \
                      swing: {omega: -1500rpm}\ngrid:\n  impact.z: {range: [24in, 30in, 2in]}\n\
                      points:\n  name: case\n  sets:\n    - {bat.length: 35in}\n    - {}\n";
    let si = format!(
        "name: u\nbase:\n  bat: {{preset: r161, length: {}}}\n  ball: {{speed: {}}}\n  \
         swing: {{omega: {}}}\ngrid:\n  impact.z: {{range: [{}, {}, {}]}}\n\
         points:\n  name: case\n  sets:\n    - {{bat.length: {}}}\n    - {{}}\n",
        34.0 * INCH,
        90.0 * MPH,
        -1500.0 * RPM,
        24.0 * INCH,
        30.0 * INCH,
        2.0 * INCH,
        35.0 * INCH
    );
    let (a, b) = (load(with_units).unwrap(), load(&si).unwrap());
    assert_eq!(a.plan.n_points(), 8);
    assert_eq!(specs(&a), specs(&b));
}

#[test]
fn an_optimize_variable_takes_units_too() {
    let text = |lo: &str, hi: &str| {
        format!(
            "name: o\nbase:\n  bat: {{preset: r161}}\ngrid:\n  impact.z: [0.7]\n\
             optimize:\n  variables:\n    bat.length: {{min: {lo}, max: {hi}}}\n  \
             objective: {{maximize: bat.bbcor}}\n"
        )
    };
    let a = load(&text("34in", "36in"));
    let b = load(&text(
        &(34.0 * INCH).to_string(),
        &(36.0 * INCH).to_string(),
    ));
    match (a, b) {
        (Ok(a), Ok(b)) => {
            let bounds =
                |s: &study::Study| s.file.optimize.as_ref().unwrap().variables["bat.length"];
            assert_eq!(bounds(&a), bounds(&b));
            assert_eq!(bounds(&a).min, 34.0 * INCH);
        }
        (a, b) => panic!("{:?} / {:?}", a.err(), b.err()),
    }
}

#[test]
fn a_unit_the_field_does_not_take_is_refused_where_it_is_written() {
    let e = load("name: u\nbase:\n  bat: {preset: r161, length: 34oz}\ngrid:\n  impact.z: [0.7]\n")
        .unwrap_err()
        .to_string();
    assert!(e.contains("s.yaml:3:"), "{e}");
    assert!(e.contains("bat.length") && e.contains("34oz"), "{e}");
    assert!(e.contains("m, ft, in, mm, cm"), "{e}");
}

#[test]
fn text_that_is_not_a_quantity_is_left_alone() {
    // a name with a unit's look, and words after a number, are text
    let s =
        load("name: 34in\ndescription: a 2mm wall\nbase: {}\ngrid:\n  impact.z: [0.7]\n").unwrap();
    assert_eq!(s.file.name, "34in");
}

#[test]
fn a_bare_number_in_the_trades_unit_names_the_suffix_meant() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("s.yaml");
    std::fs::write(
        &path,
        "name: u\nbase:\n  bat: {preset: r161, length: 34}\ngrid:\n  impact.z: [0.7]\n",
    )
    .unwrap();
    let o = common::batstudy_command(&["validate", path.to_str().unwrap()])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("write `34in`"), "{err}");
}

/// The loading coefficient's coordinate carries its power where every point has the same α
/// (N/m^α by F = k₁ s^α: `N m^-1.84` for Nathan 2000's α), a unit pint and UDUNITS parse; a
/// study that sweeps α keeps the symbol.
#[test]
fn the_loading_coefficients_units_carry_the_studys_power() {
    let units_of_k1 = |text: &str| {
        let s = load(text).unwrap_or_else(|e| panic!("{e}"));
        s.plan
            .shape()
            .dims
            .iter()
            .flat_map(|d| d.coords.iter())
            .find(|c| c.path == "ball.law.k1")
            .map(|c| c.units.clone())
            .unwrap()
    };
    let base = "name: k\nbase:\n  ball: {law: {kind: power_law}}\n  impact: {z: 0.7}\ngrid:\n  ball.law.k1: [5.0e7, 6.5e7]\n";
    assert_eq!(units_of_k1(base), "N m^-1.84");
    let set = base.replace("kind: power_law}", "kind: power_law, alpha: 1.5}");
    assert_eq!(units_of_k1(&set), "N m^-1.5");
    let swept = format!("{base}  ball.law.alpha: [1.5, 1.84]\n");
    assert_eq!(units_of_k1(&swept), "N m^-alpha");
}
