//! Bad study files: exit status 2, a message naming file, line, field, value and what is
//! allowed, and nothing written.

use std::path::Path;
use std::process::Command;

fn batstudy(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_batstudy"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("run batstudy")
}

/// (file, substrings the message must contain: file:line, field, value, allowed)
const CASES: &[(&str, &[&str])] = &[
    // a wall's layers, held to plausible plies, walls and stacks, and to fields that act
    (
        "layer_wall_too_thin",
        &["layer_wall_too_thin.yaml:5:66", "`bat.shell.layers[0].thickness`", "value: 0.000001", "allowed: 0.00002 to 0.05 m"],
    ),
    (
        "layer_stack_too_thin",
        &["layer_stack_too_thin.yaml:5:38", "`bat.shell.layers`", "value: 0.0001", "allowed: each wall between gaps: 0.0005 to 0.05 m"],
    ),
    (
        "layers_too_many",
        &["layers_too_many.yaml:6:38", "`bat.shell.layers`", "value: 201", "allowed: 1 to 200 layers"],
    ),
    (
        "fibre_angle_in_degrees",
        &["fibre_angle_in_degrees.yaml:9:55", "`bat.shell.layers[1].angle`", "value: 45", "45 degrees is 0.7854 rad"],
    ),
    (
        "angle_on_metal",
        &["angle_on_metal.yaml:4:84", "`bat.shell.layers[0].angle`", "value: 0.5", "0 (or unset) for a metal or a gap"],
    ),
    (
        "layers_off_the_knots",
        &["layers_off_the_knots.yaml:9:7", "`bat.shell.layers`", "value: 0.003", "allowed: layers adding up to 0.006 m"],
    ),
    (
        "break_in_on_metal",
        &["break_in_on_metal.yaml:4:38", "`bat.shell.break_in`", "value: 0.2", "without composite plies"],
    ),
    (
        "break_in_rigid",
        &["break_in_rigid.yaml:4:42", "`bat.shell.break_in`", "no point of the study uses it", "by the wave model"],
    ),
    (
        "patch_radius_solid",
        &["patch_radius_solid.yaml:5:31", "`hoop.patch_radius`", "no point of the study uses it", "on a hollow bat"],
    ),
    // what validated and then failed at every point, or stored only NaN
    (
        "trajectory_without_flight",
        &["trajectory_without_flight.yaml:5:27", "`history.fields[1]`", "value: trajectory", "allowed: a `flight` block"],
    ),
    (
        "history_too_long",
        &["history_too_long.yaml:5:46", "`history.duration`", "value: 0.05", "allowed: at most 0.02 s"],
    ),
    (
        "bat_speed_at_tiny",
        &["bat_speed_at_tiny.yaml:6:44", "`batter.bat_speed_at`", "value: 1e-300", "allowed: at least 0.05 m beyond batter.pivot"],
    ),
    // the optimize block as `batstudy optimize` checks it, at this file's own lines
    (
        "optimize_seed_nelder_mead",
        &["optimize_seed_nelder_mead.yaml:4:33", "`optimize.seed`", "value: 3", "allowed: leave it out, or `method: cma_es`"],
    ),
    (
        "optimize_tolerance_huge",
        &["optimize_tolerance_huge.yaml:4:33", "`optimize.tolerance`", "value: 1e308", "allowed: 0 to 0.01"],
    ),
    (
        "optimize_unused_variable",
        &["optimize_unused_variable.yaml:5:33", "`bat.grip.damping`", "the study at a design of its `optimize` block", "used only with bat.grip.kind: spring"],
    ),
    // what a hostile or careless study may hold, refused before anything is written
    (
        "history_too_big",
        &["history_too_big.yaml:5:1", "`history`", "MiB per point", "allowed: at most 256 MiB per point"],
    ),
    (
        "history_field_twice",
        &["history_field_twice.yaml:5:27", "`history.fields[1]`", "value: force", "allowed: each field once"],
    ),
    (
        "history_z_step_tiny",
        &["history_z_step_tiny.yaml:5:71", "`history.z_step`", "value: 0.00000001", "allowed: a step that gives at most"],
    ),
    (
        "points_named_like_a_variable",
        &["points_named_like_a_variable.yaml:6:3", "value: exit_speed", "allowed: a name the results file does not use"],
    ),
    (
        "zip_name_with_slash",
        &["zip_name_with_slash.yaml:6:5", "value: a/b", "allowed: a name of letters, digits"],
    ),
    (
        "zip_name_empty",
        &["zip_name_empty.yaml:6:5", "value: \n", "allowed: a name of letters, digits"],
    ),
    (
        "zip_name_is_a_coordinate",
        &["zip_name_is_a_coordinate.yaml:10:5", "value: swing_omega", "allowed: a name not already used"],
    ),
    (
        "points_malformed",
        &["points_malformed.yaml:5:1", "`points`", "allowed: a list of parameter sets"],
    ),
    (
        "profile_not_a_profile",
        &["profile_not_a_profile.yaml:5:19", "`bat.profile.csv`", "value: /dev/zero", "not a regular file"],
    ),
    (
        "malformed_yaml",
        &["malformed_yaml.yaml:5:5", "malformed YAML"],
    ),
    (
        "unknown_top_key",
        &[
            "unknown_top_key.yaml:5:1",
            "`gird`",
            "did you mean `grid`",
            "allowed: name, description",
        ],
    ),
    (
        "unknown_base_key",
        &[
            "unknown_base_key.yaml:5:5",
            "`bat.materal`",
            "did you mean `material`",
            "value: materal",
            "allowed: fields of `bat`",
        ],
    ),
    (
        "unknown_grid_path",
        &[
            "unknown_grid_path.yaml:6:3",
            "`swing.omgea`",
            "did you mean `swing.omega`",
            "allowed: swing.attack_angle, swing.attack_direction, swing.cm_speed, swing.omega, swing.tilt",
        ],
    ),
    (
        "wrong_type",
        &[
            "wrong_type.yaml:5:5",
            "`ball.speed`",
            "value: fast",
            "allowed: a number",
        ],
    ),
    (
        "missing_field",
        &[
            "missing_field.yaml:4:3",
            "`hoop.mass`",
            "missing field `mass`",
            "allowed: this field is required",
        ],
    ),
    (
        "negative_density",
        &[
            "negative_density.yaml:6:7",
            "`bat.material.density`",
            "value: -649",
            "allowed: a finite number > 0",
        ],
    ),
    (
        "zero_ball_mass",
        &[
            "zero_ball_mass.yaml:6:22",
            "`ball.mass`",
            "value: 0",
            "grid axis `ball.mass`, value #2",
            "allowed: a finite number > 0",
        ],
    ),
    (
        "shell_too_thick",
        &[
            "shell_too_thick.yaml:5:13",
            "`bat.shell.thickness`",
            "value: 0.05",
            "allowed: < the bat's outer radius",
        ],
    ),
    (
        "offset_misses_the_bat",
        &[
            "offset_misses_the_bat.yaml:8:",
            "`impact.offset`",
            "value: -0.06",
            "allowed: |offset| < bat radius + ball radius",
        ],
    ),
    (
        "impact_off_bat",
        &[
            "impact_off_bat.yaml:7:24",
            "`impact.z`",
            "value: 0.95",
            "allowed: on the bat: 0 <= z <= 0.84 m",
        ],
    ),
    (
        "hoop_frequency_range",
        &[
            "hoop_frequency_range.yaml:7:31",
            "`hoop.frequency`",
            "value: 2000000",
            "allowed: 1 to 100000 Hz",
        ],
    ),
    (
        "hoop_mass_range",
        &[
            "hoop_mass_range.yaml:7:23",
            "`hoop.mass`",
            "value: 5",
            "zip group #1",
            "allowed: > 0 and < 1.45",
        ],
    ),
    (
        "too_many_points",
        &[
            "too_many_points.yaml:5:1",
            "25000000 points",
            "value: 25000000",
            "allowed: at most 10000000 points (raise with --max-points)",
        ],
    ),
    (
        "unwritable_output",
        &[
            "unwritable_output.yaml:5:1",
            "`output`",
            "not writable",
            "value: /proc/batstudy-nowhere/out.h5",
            "allowed: an output path inside a writable folder",
        ],
    ),
    (
        "zip_length_mismatch",
        &[
            "zip_length_mismatch.yaml:7:5",
            "swing.omega",
            "differ in length",
            "value: 2 values",
            "allowed: 3 values",
        ],
    ),
    (
        "bad_preset",
        &[
            "bad_preset.yaml:6:22",
            "`bat.preset`",
            "value: aluminium",
            "did you mean `aluminum`",
            "allowed: r161, aluminum, corked, alloy_bbcor, composite_bbcor, wall",
        ],
    ),
    (
        "bad_range",
        &[
            "bad_range.yaml:6:3",
            "grid.swing.omega",
            "value: {range: [0, -60, 10]}",
            "goes away from stop",
            "allowed: a non-empty list",
        ],
    ),
    (
        "bad_history_field",
        &[
            "bad_history_field.yaml:6:19",
            "history.fields[1]",
            "value: forse",
            "allowed: one of `force`",
        ],
    ),
    (
        "missing_profile",
        &[
            "missing_profile.yaml:5:15",
            "bat.profile.csv",
            "value: no_such_profile.csv",
            "allowed: a readable CSV",
        ],
    ),
    // values that are not numbers, and values no bat has
    (
        "nan_density",
        &[
            "nan_density.yaml:6:26",
            "`grid.bat.material.density[0]`",
            "not a finite number",
            "value: .nan",
            "allowed: a finite number",
        ],
    ),
    (
        "infinite_speed",
        &[
            "infinite_speed.yaml:4:10",
            "`base.ball.speed`",
            "value: .inf",
            "allowed: a finite number",
        ],
    ),
    (
        "implausible_speed",
        &[
            "implausible_speed.yaml:4:10",
            "`ball.speed`",
            "outside its plausible range",
            "value: 1000000",
            "allowed: 0.5 to 100 m/s",
            "allow_implausible: true",
        ],
    ),
    (
        "implausible_youngs_modulus",
        &[
            "implausible_youngs_modulus.yaml:5:43",
            "`bat.material.youngs_modulus`",
            "value: 1000",
            "grid axis `bat.material.youngs_modulus`, value #2",
            "allowed: 100000000 to 500000000000 Pa",
        ],
    ),
    (
        "implausible_density",
        &[
            "implausible_density.yaml:4:16",
            "`bat.material.density`",
            "value: 1e30",
            "allowed: 100 to 10000 kg/m^3",
        ],
    ),
    (
        "implausible_shell",
        &[
            "implausible_shell.yaml:3:35",
            "`bat.shell.thickness`",
            "value: 0.0001",
            "allowed: 0.0005 to 0.05 m",
        ],
    ),
    // a point that never ends is refused before it runs
    (
        "stiff_ball",
        &[
            "stiff_ball.yaml:6:41",
            "`ball.law.stiffness`",
            "needs at least 1737020835 time steps",
            "numerics.max_steps = 10000000",
            "allowed: at most 10000000 steps",
        ],
    ),
    // fields that the chosen kind or option ignores
    (
        "unused_law_field",
        &[
            "unused_law_field.yaml:5:28",
            "`ball.law.stiffness`",
            "no point of the study uses it",
            "allowed: leave it out (it is used only by the wave model with ball.law.kind linear_hysteresis or elastic, or speed_dependent with loading linear)",
        ],
    ),
    (
        "unused_grip_damping",
        &[
            "unused_grip_damping.yaml:6:22",
            "`bat.grip.damping`",
            "allowed: leave it out (it is used only with bat.grip.kind: spring)",
        ],
    ),
    // studies that quietly do nothing
    (
        "history_only_off_grid",
        &[
            "history_only_off_grid.yaml:6:88",
            "`history.only.impact.z`",
            "would record no history",
            "value: 0.703",
            "allowed: values `impact.z` takes in the study: 0.4, 0.41",
        ],
    ),
    // the displacement's modal form is the modal integrator's own state
    (
        "modal_history_with_verlet",
        &[
            "modal_history_with_verlet.yaml:7:1",
            "`history.displacement`",
            "point numerics.integrator=verlet records the displacement in modal form",
            "value: modal",
            "allowed: grid",
        ],
    ),
    (
        "base_type_under_grid",
        &[
            "base_type_under_grid.yaml:4:10",
            "`ball.speed`",
            "value: fast",
            "allowed: a number",
        ],
    ),
];

#[test]
fn every_bad_study_is_covered() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/bad_studies");
    for e in std::fs::read_dir(dir).unwrap() {
        let name = e
            .unwrap()
            .path()
            .file_stem()
            .unwrap()
            .to_string_lossy()
            .to_string();
        assert!(
            CASES.iter().any(|(c, _)| *c == name),
            "no test case for {name}"
        );
    }
}

#[test]
fn validate_reports_each_bad_study() {
    for (name, needles) in CASES {
        let file = format!("tests/bad_studies/{name}.yaml");
        let out = batstudy(&["validate", &file]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{name}: {err}");
        for n in *needles {
            assert!(err.contains(n), "{name}: message lacks {n:?}:\n{err}");
        }
    }
}

#[test]
fn run_rejects_bad_studies_before_writing() {
    let tmp = tempfile::tempdir().unwrap();
    for (name, _) in CASES {
        if *name == "unwritable_output" {
            // -o overrides the study's output: that study is otherwise valid (and would run).
            continue;
        }
        let file = format!("tests/bad_studies/{name}.yaml");
        let out_path = tmp.path().join("sub").join(format!("{name}.h5"));
        let out = batstudy(&["run", &file, "-o", out_path.to_str().unwrap(), "--quiet"]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{name}: {err}");
        assert!(err.contains(&format!("{name}.yaml:")), "{name}: {err}");
        assert!(
            !tmp.path().join("sub").exists(),
            "{name}: something was written"
        );
    }
}

#[test]
fn run_refuses_unwritable_output_and_existing_file() {
    let out = batstudy(&["run", "tests/bad_studies/unwritable_output.yaml", "--quiet"]);
    assert_eq!(out.status.code(), Some(2));
    let tmp = tempfile::tempdir().unwrap();
    let existing = tmp.path().join("x.h5");
    std::fs::write(&existing, b"old").unwrap();
    let out = batstudy(&[
        "run",
        "studies/smoke.yaml",
        "-o",
        existing.to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("exists") && err.contains("--resume") && err.contains("--force"),
        "{err}"
    );
    assert_eq!(std::fs::read(&existing).unwrap(), b"old");
}

#[test]
fn max_points_flag_raises_the_limit() {
    let out = batstudy(&[
        "validate",
        "tests/bad_studies/too_many_points.yaml",
        "--max-points",
        "30000000",
    ]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn bad_flags_exit_2() {
    let out = batstudy(&["run", "studies/smoke.yaml", "--shard", "5/4"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("1 <= I <= N"));
    let out = batstudy(&["run", "studies/smoke.yaml", "--jobs", "0"]);
    assert_eq!(out.status.code(), Some(2));
}

#[test]
fn example_studies_validate() {
    // Every bundled study, not just the two CI runs.
    let mut files: Vec<String> = std::fs::read_dir("studies")
        .unwrap()
        .map(|e| e.unwrap().path().display().to_string())
        .filter(|p| p.ends_with(".yaml"))
        .collect();
    files.sort();
    assert!(files.len() >= 2, "{files:?}");
    let mut args = vec!["validate"];
    args.extend(files.iter().map(String::as_str));
    let out = batstudy(&args);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

// the schema is generated from the Rust types, committed, and this fails when stale.
#[test]
fn committed_schema_is_current() {
    let committed = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("schemas/study.schema.json"),
    )
    .unwrap();
    assert_eq!(
        committed,
        batstudy::study::schema_json(),
        "schemas/study.schema.json is stale: run `batstudy schema > schemas/study.schema.json`"
    );
}
