//! A hollow preset is a bat whose wall breathes: `bat.preset: alloy_bbcor` (or
//! `composite_bbcor`) without a `hoop` is resolved with the wall's own breathing modes
//! (`hoop: {from_geometry: true}`), as the bat is built; `hoop: {from_geometry: false}` alone
//! turns it off, for any bat. Before, the preset alone ran without a hoop and its BBCOR
//! lacked the trampoline that makes a hollow bat's (Nathan, Crisco, Greenwald, Russell &
//! Smith 2011: BBCOR rises as the lowest hoop frequency falls).

mod common;

use batstudy::model::spec::HoopSpec;
use batstudy::study::{self, LoadOptions};
use std::path::Path;

fn first_spec(bat: &str, hoop: &str) -> batstudy::model::spec::CollisionSpec {
    let text =
        format!("name: h\nbase:\n  bat: {{preset: {bat}}}\n{hoop}grid:\n  impact.z: [0.70]\n");
    let s = study::load_str(&text, Path::new("h.yaml"), &LoadOptions { max_points: 10 }).unwrap();
    s.plan.point(0).unwrap().spec
}

#[test]
fn a_hollow_preset_breathes_unless_told_not_to() {
    let breathing = Some(HoopSpec {
        from_geometry: true,
        ..HoopSpec::default()
    });
    for bat in ["alloy_bbcor", "composite_bbcor"] {
        assert_eq!(first_spec(bat, "").hoop, breathing, "{bat}");
        assert_eq!(
            first_spec(bat, "  hoop: {from_geometry: true}\n").hoop,
            breathing
        );
        assert_eq!(
            first_spec(bat, "  hoop: {from_geometry: false}\n").hoop,
            None
        );
    }
    // a solid bat and the paper's aluminum shell keep what the study says
    assert_eq!(first_spec("r161", "").hoop, None);
    assert_eq!(first_spec("aluminum", "").hoop, None);
}

#[test]
fn the_breathing_wall_is_the_trampoline() {
    let dir = tempfile::tempdir().unwrap();
    let bbcor = |hoop: &str| {
        let study = dir.path().join("s.yaml");
        let out = dir.path().join("s.h5");
        std::fs::write(
            &study,
            format!(
                "name: s\nbase:\n  bat: {{preset: alloy_bbcor}}\n{hoop}grid:\n  impact.z: [0.70]\n"
            ),
        )
        .unwrap();
        common::batstudy_ok(&[
            "run",
            study.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "-q",
            "--force",
        ]);
        let f = hdf5::File::open(&out).unwrap();
        f.dataset("bat/bbcor_max")
            .unwrap()
            .read_raw::<f64>()
            .unwrap()[0]
    };
    let (preset, off) = (bbcor(""), bbcor("  hoop: {from_geometry: false}\n"));
    assert!(
        preset > off + 0.005,
        "with the wall's breathing {preset}, without {off}"
    );
}
