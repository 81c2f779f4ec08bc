//! Store write cost (ignored; run with
//! `cargo test --release --test store_bench -- --ignored --nocapture`).

use batstudy::model::outcome::{BatProperties, Outcome};
use batstudy::results::{BatVariant, Coord, CoordValues, Dim, PointRecord, ResultShape, StudyInfo};
use batstudy::store::{self, StoreOptions};
use std::time::Instant;

fn dim(name: &str, n: usize) -> Dim {
    Dim {
        name: name.into(),
        size: n,
        coords: vec![Coord {
            name: name.into(),
            path: name.replace('_', "."),
            units: "1".into(),
            long_name: name.into(),
            description: name.into(),
            values: CoordValues::Numbers((0..n).map(|k| 0.5 + k as f64 * 1e-3).collect()),
        }],
    }
}

#[test]
#[ignore]
fn summary_only_write_cost() {
    let (a, b) = (500, 400); // 200 000 points
    let info = StudyInfo {
        name: "bench".into(),
        description: String::new(),
        study_text: "bench".into(),
        study_sha256: "0".repeat(64),
        study_path: "bench.yaml".into(),
        shape: ResultShape {
            dims: vec![dim("swing_omega", a), dim("impact_z", b)],
        },
        history: None,
        bats: vec![BatVariant {
            label: "b".into(),
            spec_json: "{}".into(),
            properties: BatProperties::default(),
            shapes: None,
        }],
        allow_implausible: false,
        sample_dim: None,
    };
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bench.h5");
    let t0 = Instant::now();
    let mut s = store::open(&path, &info, &StoreOptions::default()).unwrap();
    let n = a * b;
    for i in 0..n {
        let x = i as f64;
        let o = Outcome {
            exit_speed: 20.0 + (x * 1e-3).sin(),
            collision_efficiency: 0.2 + x * 1e-9,
            contact_time: 6e-4 + x * 1e-12,
            peak_force: 2e4 + x,
            ..Default::default()
        };
        s.write(PointRecord {
            index: i,
            id: i as u64 * 2654435761,
            bat: 0,
            result: if i % 1000 == 7 {
                Err("boom".into())
            } else {
                Ok(o)
            },
        })
        .unwrap();
    }
    let t1 = Instant::now();
    s.finish().unwrap();
    let t2 = Instant::now();
    let per = |d: std::time::Duration| d.as_secs_f64() * 1e6 / n as f64;
    println!(
        "{n} points: journal {:.2} µs/point, final HDF5 {:.2} µs/point, total {:.2} µs/point, file {} bytes",
        per(t1 - t0),
        per(t2 - t1),
        per(t2 - t0),
        std::fs::metadata(&path).unwrap().len()
    );
}
