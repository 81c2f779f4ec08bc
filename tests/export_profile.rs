//! `batstudy export-profile` writes a bat of a results file as a profile CSV that a study
//! reads back (`bat.profile.csv`) as the same bat: mass, balance point and moments of inertia
//! within 0.1 % (the bound; the geometry is linear between the rows, so they agree
//! to round-off), in metres, millimetres and inches, with the wall as a column.
//!
//! Reference: conservation of the bat's geometry — mass = ∫ ρ A(z) dz and I = ∫ ρ A (z − z₀)²
//! dz are functionals of R(z) and r(z) alone, so equal profiles give equal values whatever
//! the route (the study's knots, or a CSV).

mod common;

use batstudy::model::prepare_bat;
use batstudy::study::{load, LoadOptions};
use std::path::{Path, PathBuf};

/// Bats that exercise every part of the export: a tube whose wall varies and whose handle is
/// scaled (the blend's parabola), a composite stack, a drilled and cork-filled wood bat.
const BATS: [(&str, &str); 3] = [
    (
        "{preset: alloy_bbcor, handle: {radius_scale: 1.2}}",
        "{preset: aluminum, material: {density: 2830, youngs_modulus: 7.17e10}}",
    ),
    ("{preset: composite_bbcor}", "COMPOSITE"),
    (
        "{bore: {diameter: 0.0254, depth: 0.254, fill_density: 240}}",
        "{preset: r161, fill: {density: 240}}",
    ),
];

/// Write the study `text` as `name.yaml` in `dir` and run it into `name.h5`.
fn run_study(dir: &Path, name: &str, text: &str) -> (PathBuf, PathBuf) {
    let (study, out) = (
        dir.join(format!("{name}.yaml")),
        dir.join(format!("{name}.h5")),
    );
    std::fs::write(&study, text).unwrap();
    let args = [
        "run",
        study.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--quiet",
    ];
    common::batstudy_ok(&args);
    (study, out)
}

fn properties(study: &Path) -> batstudy::model::outcome::BatProperties {
    let s = load(study, &LoadOptions::default()).unwrap();
    let spec = s.plan.point(0).unwrap().spec;
    prepare_bat(&spec.bat, &spec.numerics)
        .unwrap()
        .properties()
        .clone()
}

#[test]
fn an_exported_profile_reads_back_as_the_same_bat() {
    let dir = tempfile::tempdir().unwrap();
    for (i, (bat, back)) in BATS.iter().enumerate() {
        let text = format!("name: s{i}\nbase:\n  bat: {bat}\ngrid:\n  impact.z: [0.7]\n");
        let (study, out) = run_study(dir.path(), &format!("s{i}"), &text);
        let original = properties(&study);
        for units in ["m", "mm", "in"] {
            let csv = dir.path().join(format!("bat{i}_{units}.csv"));
            common::batstudy_ok(&[
                "export-profile",
                out.to_str().unwrap(),
                "--units",
                units,
                "-o",
                csv.to_str().unwrap(),
            ]);
            let header = std::fs::read_to_string(&csv).unwrap();
            assert!(
                header.contains(&format!("z_{units},diameter_{units}")),
                "{header}"
            );
            // shop-ready: stations and diameters to what a lathe holds (0.001 in, 0.01 mm),
            // walls to what a micrometer reads (0.0001 in, 0.001 mm)
            let (d, w) = match units {
                "in" => (3, 4),
                "mm" => (2, 3),
                _ => (5, 6),
            };
            for row in header.lines().filter(|l| !l.starts_with('#')).skip(1) {
                let decimals: Vec<usize> = row
                    .split(',')
                    .map(|f| f.split_once('.').map_or(0, |(_, frac)| frac.len()))
                    .collect();
                assert_eq!(&decimals[..2], &[d, d], "{units}: {row}");
                assert!(decimals.len() == 2 || decimals[2] == w, "{units}: {row}");
            }
            // the material the CSV leaves to the study (the composite's: its stack's)
            let back = if *back == "COMPOSITE" {
                format!(
                    "{{preset: aluminum, material: {{density: {}, youngs_modulus: {}}}}}",
                    original_material(&header, "density"),
                    original_material(&header, "youngs_modulus")
                )
            } else {
                back.to_string()
            };
            let read = dir.path().join(format!("r{i}_{units}.yaml"));
            let text = format!(
                "name: r{i}\nbase:\n  bat: {{profile: {{csv: {}}}, {}\ngrid:\n  impact.z: [0.7]\n",
                csv.file_name().unwrap().to_str().unwrap(),
                &back[1..]
            );
            std::fs::write(&read, text).unwrap();
            let again = properties(&read);
            for (what, a, b) in [
                ("mass", original.mass, again.mass),
                ("z_cm", original.z_cm, again.z_cm),
                ("MOI", original.moment_of_inertia, again.moment_of_inertia),
                (
                    "MOI(6 in)",
                    original.moment_of_inertia_knob6,
                    again.moment_of_inertia_knob6,
                ),
            ] {
                assert!(
                    (b / a - 1.0).abs() < 1e-3,
                    "bat {i} in {units}: {what} {a} then {b}"
                );
            }
        }
    }
}

/// A number the export's comment names (`bat.material.density 1620 kg/m3`).
fn original_material(csv: &str, field: &str) -> f64 {
    let key = format!("bat.material.{field} ");
    let at = csv.find(&key).unwrap() + key.len();
    csv[at..]
        .split_whitespace()
        .next()
        .unwrap()
        .trim_end_matches(',')
        .parse()
        .unwrap()
}

#[test]
fn the_bat_asked_for_must_be_in_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let text = "name: two\nbase: {}\ngrid:\n  bat.preset: [r161, aluminum]\n  impact.z: [0.7]\n";
    let (_, out) = run_study(dir.path(), "two", text);
    let csv = dir.path().join("x.csv");
    for args in [vec![], vec!["--bat", "steel"], vec!["--bat", "7"]] {
        let mut all = vec![
            "export-profile",
            out.to_str().unwrap(),
            "-o",
            csv.to_str().unwrap(),
        ];
        all.extend(args.iter());
        let o = common::batstudy_command(&all).output().unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(
            err.contains("0: r161") && err.contains("1: aluminum"),
            "{err}"
        );
        assert!(!csv.exists(), "{args:?} wrote a file");
    }
    common::batstudy_ok(&[
        "export-profile",
        out.to_str().unwrap(),
        "--bat",
        "aluminum",
        "-o",
        csv.to_str().unwrap(),
    ]);
    assert!(std::fs::read_to_string(&csv).unwrap().contains("wall_m"));
}

#[test]
fn a_wall_given_twice_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("p.csv"),
        "z_mm,radius_mm,wall_mm\n0,25,0\n500,30,3\n840,33,3\n",
    )
    .unwrap();
    let study = dir.path().join("w.yaml");
    let text = "name: w\nbase:\n  bat: {preset: aluminum, profile: {csv: p.csv}, shell: {thickness: 0.002}}\ngrid:\n  impact.z: [0.7]\n";
    std::fs::write(&study, text).unwrap();
    let o = common::batstudy_command(&["validate", study.to_str().unwrap()])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("bat.shell.thickness") && err.contains("wall column"),
        "{err}"
    );
}

/// The CSV never replaces the results file it was read from, nor another results file:
/// `export-profile r.h5 -o r.h5` turned a finished file into 1.8 KB of text, exit 0.
#[test]
fn the_export_never_replaces_a_results_file() {
    let dir = tempfile::tempdir().unwrap();
    let text = "name: one\nbase: {}\ngrid:\n  impact.z: [0.7]\n";
    let (_, out) = run_study(dir.path(), "one", text);
    let (_, other) = run_study(dir.path(), "other", &text.replace("one", "other"));
    let before = std::fs::read(&out).unwrap();
    for target in [&out, &other] {
        let o = common::batstudy_command(&[
            "export-profile",
            out.to_str().unwrap(),
            "-o",
            target.to_str().unwrap(),
        ])
        .output()
        .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{err}");
        assert!(
            err.contains("is an input of the same command") || err.contains("is an HDF5 file"),
            "{err}"
        );
    }
    assert_eq!(std::fs::read(&out).unwrap(), before);
    batstudy::store::is_results_file(&other).unwrap();
}
