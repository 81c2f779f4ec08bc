//! One BBCOR per bat: `/bat`'s BBCOR (what `batstudy inspect` shows) is the certification
//! protocol's with the study's own ball and hoop, the one `batstudy optimize` constrains, and
//! it names that ball. Before, `/bat` scanned with the default linear ball and no hoop, and an
//! aluminum bat certified at 0.49999 by `optimize` showed 0.502 there.
//!
//! Reference: the NCAA BBCOR protocol as batstudy models it (docs/physics.md, "BBCOR"): the
//! bat at rest and free, the ball head-on at 136 mph, the largest BBCOR along the barrel.

use batstudy::model::measures::metrics::{bat_metrics, BbcorShot};
use batstudy::optimize::rules::protocol_bbcor;
use batstudy::run::{self, ModelSimulator};
use batstudy::study::{load_str, LoadOptions};
use std::path::Path;

const STUDY: &str = "name: one_bbcor\nmodel: wave\nbase:\n  bat: {preset: aluminum}\n  \
    ball: {preset: mlb, speed: 40.0}\n  hoop: {from_geometry: true}\n\
    grid:\n  impact.z: [0.65, 0.70]\n";

#[test]
fn the_bats_bbcor_is_the_protocols_with_the_studys_ball_and_hoop() {
    let study = load_str(STUDY, Path::new("one_bbcor.yaml"), &LoadOptions::default()).unwrap();
    let pool = run::build_pool(2).unwrap();
    let bats = run::prepare_bats(&ModelSimulator, &study.plan, &pool);
    let stored = &bats.variants[0].properties.metrics;
    let point = study.plan.point(0).unwrap();
    let target = bats.handles[0].as_ref().unwrap();
    let certified = pool.install(|| protocol_bbcor(&point.spec, target));
    assert_eq!(
        stored.bbcor_max.to_bits(),
        certified.to_bits(),
        "/bat {} against optimize's {certified}",
        stored.bbcor_max
    );
    // the ball and hoop matter, so the test could fail: the default ball without a hoop
    // gives another BBCOR
    let bat = target.bat().unwrap();
    let default = bat_metrics(bat, &point.spec.bat, &point.spec.numerics).unwrap();
    assert!(
        (default.bbcor_max - certified).abs() > 0.01,
        "{} against {certified}",
        default.bbcor_max
    );
    // and the file names what gave it
    assert_eq!(stored.bbcor_shot, BbcorShot::of(&point.spec).json());
    assert!(
        stored.bbcor_shot.contains("\"preset\":\"mlb\""),
        "{}",
        stored.bbcor_shot
    );
    assert!(
        stored.bbcor_shot.contains("\"from_geometry\":true"),
        "{}",
        stored.bbcor_shot
    );
}
