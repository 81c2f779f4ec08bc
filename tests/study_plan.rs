//! Grid expansion, zip/points dimensions, point ids.

use batstudy::results::CoordValues;
use batstudy::study::{load_str, LoadOptions};
use std::path::Path;

fn load(text: &str) -> batstudy::study::Study {
    load_str(
        text,
        Path::new("studies/test.yaml"),
        &LoadOptions::default(),
    )
    .unwrap_or_else(|e| panic!("{e}"))
}

// range 0.40..0.84 step 0.01 gives 45 values and includes 0.84.
#[test]
fn range_axis_has_exact_endpoints() {
    let s = load("name: t\nbase: {}\ngrid:\n  impact.z: {range: [0.40, 0.84, 0.01]}\n");
    let d = &s.plan.shape().dims[0];
    assert_eq!(d.name, "impact_z");
    assert_eq!(d.size, 45);
    let CoordValues::Numbers(v) = &d.coords[0].values else {
        panic!()
    };
    assert_eq!(v[0], 0.40);
    assert_eq!(v[44], 0.84);
    assert_eq!(v[10], 0.50);
    assert_eq!(d.coords[0].units, "m");
}

#[test]
fn product_is_row_major_last_fastest() {
    let s = load(
        "name: t\nmodel: rigid\nbase: {impact: {z: 0.7}}\ngrid:\n  impact.z: {linspace: [0.6, 0.8, 3]}\n  swing.omega: [0, -30]\n  bat.preset: [r161, aluminum]\n",
    );
    let p = &s.plan;
    assert_eq!(p.n_points(), 12);
    let names: Vec<_> = p.shape().dims.iter().map(|d| d.name.as_str()).collect();
    assert_eq!(names, ["impact_z", "swing_omega", "bat_preset"]);
    let pt = p.point(7).unwrap(); // (1, 1, 1)
    assert_eq!(pt.spec.impact.z, 0.7);
    assert_eq!(pt.spec.swing.omega, -30.0);
    assert_eq!(pt.spec.model, batstudy::model::spec::ModelKind::Rigid);
    assert_eq!(format!("{:?}", pt.spec.bat.preset), "Aluminum");
    assert!(
        matches!(&p.shape().dims[2].coords[0].values, CoordValues::Labels(l) if l == &["r161", "aluminum"])
    );
    // Two distinct bats; points share them by preset.
    assert_eq!(p.bats().len(), 2);
    assert_eq!(p.point(0).unwrap().bat, 0);
    assert_eq!(p.point(1).unwrap().bat, 1);
    assert_eq!(p.point(7).unwrap().bat, 1);
    assert_eq!(pt.bat_key(), p.bats()[1].key);
}

#[test]
fn zip_and_points_dimensions() {
    let s = load(
        "name: t\nbase: {impact: {z: 0.7}, hoop: null}\ngrid:\n  swing.omega: [0, -30]\nzip:\n  - {hoop.frequency: [700, 1500], hoop.mass: [0.01, 0.02]}\npoints:\n  - {ball.speed: 30, ball.mass: 0.145}\n  - {ball.speed: 40, ball.mass: 0.15}\n  - {ball.speed: 50, ball.mass: 0.16}\n",
    );
    let p = &s.plan;
    let names: Vec<_> = p.shape().dims.iter().map(|d| d.name.as_str()).collect();
    assert_eq!(names, ["swing_omega", "point", "point_2"]);
    assert_eq!(p.n_points(), 2 * 2 * 3);
    let zip = &p.shape().dims[1];
    let cn: Vec<_> = zip.coords.iter().map(|c| c.name.as_str()).collect();
    assert_eq!(cn, ["hoop_frequency", "hoop_mass", "point_label"]);
    assert_eq!(zip.coords[0].units, "Hz");
    assert!(matches!(&zip.coords[2].values,
        CoordValues::Labels(l) if l == &["hoop.frequency=700, hoop.mass=0.01", "hoop.frequency=1500, hoop.mass=0.02"]));
    assert_eq!(zip.coords[2].units, "", "text has no unit");
    let pt = p.point(p.n_points() - 1).unwrap();
    let hoop = pt.spec.hoop.unwrap();
    assert_eq!((hoop.frequency, hoop.mass), (Some(1500.0), Some(0.02)));
    assert_eq!((pt.spec.ball.speed, pt.spec.ball.mass), (50.0, 0.16));
}

#[test]
fn named_zip_group() {
    let s =
        load("name: t\nbase: {impact: {z: 0.7}}\nzip:\n  - {name: speeds, ball.speed: [30, 40]}\n");
    assert_eq!(s.plan.shape().dims[0].name, "speeds");
}

#[test]
fn zip_length_mismatch_is_an_error() {
    let e = load_str(
        "name: t\nbase: {impact: {z: 0.7}}\nzip:\n  - {ball.speed: [30, 40], swing.omega: [0]}\n",
        Path::new("x.yaml"),
        &LoadOptions::default(),
    )
    .unwrap_err();
    assert!(e.message.contains("differ in length"), "{e}");
    assert_eq!(e.line, Some(4));
}

#[test]
fn one_block_per_parameter() {
    let e = load_str(
        "name: t\nbase: {impact: {z: 0.7}}\ngrid: {impact.z: [0.6]}\npoints: [{impact.z: 0.7}]\n",
        Path::new("x.yaml"),
        &LoadOptions::default(),
    )
    .unwrap_err();
    assert!(e.message.contains("also set"), "{e}");
}

// a point has a stable id (a hash of its canonical parameters).
#[test]
fn point_ids_are_stable_and_ignore_key_order() {
    let a = load("name: a\nbase:\n  ball: {speed: 40, mass: 0.145}\n  impact: {z: 0.7}\n");
    let b = load("name: b\nbase:\n  impact: {z: 7.0e-1}\n  ball: {mass: 0.145, speed: 40.0}\n");
    let c = load("name: c\nbase:\n  impact: {z: 0.71}\n");
    let (pa, pb, pc) = (
        a.plan.point(0).unwrap(),
        b.plan.point(0).unwrap(),
        c.plan.point(0).unwrap(),
    );
    assert_eq!(pa.id, pb.id);
    assert_ne!(pa.id, pc.id);
    // Pinned: a change of this value means every stored file's ids changed.
    assert_eq!(pa.id, batstudy::study::point_id(&pa.spec));
    let again = load("name: a\nbase:\n  ball: {speed: 40, mass: 0.145}\n  impact: {z: 0.7}\n");
    assert_eq!(again.plan.point(0).unwrap().id, pa.id);
}

#[test]
fn profile_csv_is_loaded_relative_to_the_study() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("p.csv"),
        "z,radius\n0,0.015\n0.5,0.02\n0.8,0.03\n",
    )
    .unwrap();
    let study = dir.path().join("s.yaml");
    std::fs::write(
        &study,
        "name: s\nbase:\n  bat: {profile: {csv: p.csv}}\n  impact: {z: 0.7}\n",
    )
    .unwrap();
    let s =
        batstudy::study::load(&study, &LoadOptions::default()).unwrap_or_else(|e| panic!("{e}"));
    let pt = s.plan.point(0).unwrap();
    match pt.spec.bat.profile {
        Some(batstudy::model::spec::ProfileSpec::Knots(k)) => assert_eq!(k.len(), 3),
        other => panic!("{other:?}"),
    }
    // the bat is not labelled as if it were the preset's own
    assert_eq!(s.plan.bats()[0].label, "r161, profile p.csv");
}

// memory bounded — a 10-million-point plan is lazy.
#[test]
fn ten_million_points_are_lazy() {
    let s = load(
        "name: big\nmodel: rigid\nbase: {impact: {z: 0.7}}\ngrid:\n  impact.z: {linspace: [0.4, 0.84, 2000]}\n  swing.omega: {linspace: [0, -60, 5000]}\n",
    );
    assert_eq!(s.plan.n_points(), 10_000_000);
    let last = s.plan.point(9_999_999).unwrap();
    assert_eq!(last.spec.impact.z, 0.84);
    assert_eq!(last.spec.swing.omega, -60.0);
}

// A points dim shows what each entry ran with. The base case leaves the density to
// the r161 preset (649 kg/m³, Nathan 2000) and the aluminum case to its preset (2700 kg/m³,
// the paper); a record (`bat.grip`) becomes one coordinate per field; every entry has a label.
#[test]
fn points_coordinates_are_resolved_flattened_and_labelled() {
    let s = load(
        "name: t\nbase: {impact: {z: 0.7}}\npoints:\n  name: case\n  sets:\n    - {}\n    - {bat.material.density: 700}\n    - {bat.preset: aluminum}\n    - {bat.grip: {kind: spring, z: 0.15, stiffness: 2.0e5}}\n",
    );
    let d = &s.plan.shape().dims[0];
    let coord = |n: &str| {
        d.coords
            .iter()
            .find(|c| c.name == n)
            .unwrap_or_else(|| panic!("no coordinate {n}: {:?}", d.coords))
    };
    assert_eq!(
        coord("bat_material_density").values,
        CoordValues::Numbers(vec![649.0, 700.0, 2700.0, 649.0])
    );
    assert_eq!(
        coord("bat_preset").values,
        CoordValues::Labels(vec![
            "r161".into(),
            "r161".into(),
            "aluminum".into(),
            "r161".into()
        ])
    );
    match &coord("bat_grip_stiffness").values {
        CoordValues::Numbers(k) => {
            assert!(k[..3].iter().all(|x| x.is_nan()), "no grip: {k:?}");
            assert_eq!(k[3], 2.0e5);
        }
        v => panic!("{v:?}"),
    }
    assert_eq!(coord("bat_grip_stiffness").units, "N/m");
    assert_eq!(
        coord("case_label").values,
        CoordValues::Labels(vec![
            "base".into(),
            "bat.material.density=700".into(),
            "bat.preset=aluminum".into(),
            r#"bat.grip={"kind":"spring","z":0.15,"stiffness":200000.0}"#.into(),
        ])
    );
}
