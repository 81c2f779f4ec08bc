//! Store tests: round trip, crash/resume (torn journal and real `kill -9`), refusals.
//! `write_python_fixture` (ignored) writes files for tests/python/test_store_layout.py.

mod common;

use batstudy::model::outcome::{
    BatProperties, EnergyPartition, History, HistoryField, HistoryPrecision, HistoryRequest,
    Outcome,
};
use batstudy::results::{BatVariant, Coord, CoordValues, Dim, PointRecord, ResultShape, StudyInfo};
use batstudy::store::{self, StoreError, StoreOptions};
use std::path::{Path, PathBuf};

/// Spawned children inherit open (locked) HDF5 file descriptors of other tests' threads until
/// they exit: `kill9_at_several_moments` runs alone, the others share.
static SERIAL: std::sync::RwLock<()> = std::sync::RwLock::new(());

fn shared() -> std::sync::RwLockReadGuard<'static, ()> {
    SERIAL.read().unwrap_or_else(|e| e.into_inner())
}

fn grid(a: f64, b: f64, n: usize) -> Vec<f64> {
    (0..n)
        .map(|k| a + (b - a) * k as f64 / (n - 1) as f64)
        .collect()
}

fn coord(name: &str, path: &str, units: &str, values: CoordValues) -> Coord {
    Coord {
        name: name.into(),
        path: path.into(),
        units: units.into(),
        long_name: if path.is_empty() {
            name.into()
        } else {
            path.into()
        },
        description: format!("{path} (study parameter)"),
        values,
    }
}

fn bat(label: &str, n_modes: usize) -> BatVariant {
    let z = grid(0.0, 0.84, 6);
    BatVariant {
        label: label.into(),
        spec_json: format!("{{\"preset\":\"{label}\"}}"),
        properties: BatProperties {
            outer_radius: z.iter().map(|z| 0.012 + 0.02 * z).collect(),
            inner_radius: vec![0.0; z.len()],
            z,
            length: 0.84,
            mass: 0.9,
            z_cm: 0.56,
            moment_of_inertia: 0.045,
            moment_of_inertia_knob6: 0.2,
            mode_frequency: (1..=n_modes).map(|k| 170.0 * (k * k) as f64).collect(),
            mode_nodes: (1..=n_modes).map(|k| grid(0.1, 0.7, k + 1)).collect(),
            metrics: Default::default(),
            rule_checks: Vec::new(),
        },
        shapes: None,
    }
}

/// swing_omega (3) × impact_z (9), histories of force, ball velocity and displacement.
/// The study text's SHA-256, as docs/layout.md defines `study_sha256`.
fn sha256_hex(text: &str) -> String {
    use sha2::{Digest, Sha256};
    Sha256::digest(text.as_bytes())
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

fn study(history: bool, precision: HistoryPrecision) -> StudyInfo {
    let text = format!("name: synth\nhistory: {history}\nprecision: {precision:?}\n");
    StudyInfo {
        name: "synth".into(),
        description: "synthetic store test study".into(),
        study_sha256: sha256_hex(&text),
        study_text: text,
        study_path: "studies/synth.yaml".into(),
        shape: ResultShape {
            dims: vec![
                Dim {
                    name: "swing_omega".into(),
                    size: 3,
                    coords: vec![coord(
                        "swing_omega",
                        "swing.omega",
                        "rad/s",
                        CoordValues::Numbers(vec![-40.0, -30.0, -20.0]),
                    )],
                },
                Dim {
                    name: "impact_z".into(),
                    size: 9,
                    coords: vec![coord(
                        "impact_z",
                        "impact.z",
                        "m",
                        CoordValues::Numbers(grid(0.55, 0.79, 9)),
                    )],
                },
            ],
        },
        history: history.then(|| HistoryRequest {
            fields: vec![
                HistoryField::Force,
                HistoryField::BallVelocity,
                HistoryField::Displacement,
                HistoryField::Trajectory,
            ],
            interval: 1e-5,
            n_samples: 20,
            z: vec![0.2, 0.4, 0.6, 0.8, 1.0],
            precision,
            compression: Default::default(),
            displacement: batstudy::model::outcome::HistoryDisplacement::Grid,
        }),
        bats: vec![bat("r161", 3), bat("r161, bat.material.density=700", 2)],
        allow_implausible: false,
        sample_dim: None,
    }
}

/// A zip dim `point` (ball speed and a label) × impact_z, no history.
fn zip_study() -> StudyInfo {
    let mut s = study(false, HistoryPrecision::F64);
    s.study_text.push_str("zip: true\n");
    s.study_sha256 = sha256_hex(&s.study_text);
    s.shape.dims[0] = Dim {
        name: "point".into(),
        size: 2,
        coords: vec![
            coord(
                "ball_speed",
                "ball.speed",
                "m/s",
                CoordValues::Numbers(vec![30.0, 40.0]),
            ),
            coord(
                "bat_preset",
                "bat.preset",
                "",
                CoordValues::Labels(vec!["r161".into(), "c243".into()]),
            ),
            // the study layer's label of a zip dim (study::coords)
            coord(
                "point_label",
                "",
                "",
                CoordValues::Labels(vec![
                    "ball.speed=30, bat.preset=r161".into(),
                    "ball.speed=40, bat.preset=c243".into(),
                ]),
            ),
        ],
    };
    s
}

fn outcome(info: &StudyInfo, index: usize) -> Result<Outcome, String> {
    if index % 7 == 3 {
        return Err(format!(
            "synthetic failure at point {index}: solver diverged"
        ));
    }
    let idx = info.shape.unravel(index);
    let z = idx.last().map_or(0.68, |&q| grid(0.55, 0.79, 9)[q]);
    let w = if idx.len() == 2 {
        -40.0 + 10.0 * idx[0] as f64
    } else {
        -30.0
    };
    let v = 20.0 + 5.0 * (-((z - 0.68) / 0.1f64).powi(2)).exp() - 0.1 * w;
    let history = info.history.as_ref().map(|h| {
        let t = |k: usize| k as f64 * h.interval;
        // a flight on its own time axis (finite: the round trip compares with ==)
        let flight = |f: &dyn Fn(f64) -> f64| -> Vec<f64> {
            (0..batstudy::model::flight::TRAJECTORY_SAMPLES)
                .map(|k| k as f64 * batstudy::model::flight::TRAJECTORY_STEP_S)
                .map(f)
                .collect()
        };
        History {
            force: (0..h.n_samples)
                .map(|k| 1e3 * (t(k) * 1e5 + index as f64).sin())
                .collect(),
            ball_velocity: (0..h.n_samples)
                .map(|k| v * (1.0 - t(k) * 1e4) / 3.0)
                .collect(),
            displacement: (0..h.n_samples * h.z.len())
                .map(|k| 1e-4 * (k as f64 * 0.37 + index as f64).cos())
                .collect(),
            // the flight, on its own time axis: NaN once landed
            trajectory_x: flight(&|t| 0.5 * t),
            trajectory_y: flight(&|t| 30.0 * t + index as f64),
            trajectory_z: flight(&|t| 1.0 + 20.0 * t - 4.9 * t * t),
            // not requested: must be dropped
            hoop_displacement: vec![1.0; 3],
            ..Default::default()
        }
    });
    Ok(Outcome {
        exit_speed: v,
        exit_speed_lab: v + 30.0,
        collision_efficiency: 0.2 + 0.001 * index as f64,
        approach_speed: 50.0 - w * z,
        contact_time: 6e-4 + 1e-7 * index as f64,
        impulse_time_99: 4e-4 + 1e-7 * index as f64,
        bbcor: 0.45 + 1e-4 * index as f64,
        besr: 0.7 + 1e-4 * index as f64,
        bpf: 0.9 + 1e-4 * index as f64,
        // finite: the round trip compares outcomes with ==, and NaN != NaN
        hoop_frequency: 700.0 + index as f64,
        hoop_mass: 0.03,
        peak_force: 2e4 + index as f64,
        max_compression: 0.012,
        impulse: 12.3 + index as f64 / 3.0,
        energy: EnergyPartition {
            initial: 300.0,
            ball_final: 100.0,
            ball_loss: 120.0,
            bat_rigid: 60.0,
            bat_vibration: 15.0 + index as f64 / 7.0,
            hoop: 0.0,
            bat_damping: 0.5 + index as f64 / 11.0,
            grip_damping: 0.25 + index as f64 / 13.0,
            friction: 0.125 + index as f64 / 17.0,
        },
        recontact: index % 5 == 0,
        grip_vibration_amplitude: 1e-4 * (1.0 + (z - 0.7).abs()),
        grip_recoil_speed: 0.5 - z,
        wall_instants: Vec::new(),
        // not stored: what the launch is computed from
        ball_exit: Default::default(),
        tangential_cor: 0.3 + 1e-4 * index as f64,
        batted: batstudy::model::outcome::BattedBall {
            bat_speed: 30.0 + z,
            launch_angle: 0.2 + 1e-3 * index as f64,
            spray_angle: -0.1,
            backspin: 200.0 + index as f64,
            sidespin: -20.0,
            carry: 100.0 + 10.0 * z,
            apex: 20.0 + z,
            hang_time: 4.0 + z,
            bat_speed_6in: 31.0 + z,
            pitch_speed: 40.0 - z,
            collision_efficiency_q: 0.2 + 1e-4 * index as f64,
            squared_up: (index % 2) as f64,
        },
        history,
    })
}

fn record(info: &StudyInfo, index: usize) -> PointRecord {
    PointRecord {
        index,
        id: 1_000_003 * index as u64 + 17,
        bat: (index % 2) as u32,
        result: outcome(info, index),
    }
}

fn opts(resume: bool, force: bool) -> StoreOptions {
    StoreOptions {
        resume,
        force,
        ..Default::default()
    }
}

/// Write every point (in a scrambled order) and finish.
fn full_run(info: &StudyInfo, path: &Path) -> store::Summary {
    let mut s = store::open(path, info, &opts(false, true)).unwrap();
    let n = info.shape.n_points();
    for k in 0..n {
        s.write(record(info, (k * 11 + 5) % n)).unwrap();
    }
    s.finish().unwrap()
}

/// The history study (f64 histories) and its uninterrupted run, `DIR/clean.h5`.
fn history_study_run_clean(dir: &Path) -> (StudyInfo, PathBuf) {
    let info = study(true, HistoryPrecision::F64);
    let clean = dir.join("clean.h5");
    full_run(&info, &clean);
    (info, clean)
}

/// A fresh session of `path` that stores `points`, in that order, and is killed: flushed,
/// then dropped without finishing.
fn killed_after(path: &Path, info: &StudyInfo, points: &[usize]) {
    let mut s = store::open(path, info, &opts(false, false)).unwrap();
    for &k in points {
        s.write(record(info, k)).unwrap();
    }
    s.flush().unwrap();
    drop(s);
}

/// Store every point `s` does not have yet, and finish.
fn complete(mut s: store::Session, info: &StudyInfo) {
    for k in 0..info.shape.n_points() {
        if !s.is_done(k) {
            s.write(record(info, k)).unwrap();
        }
    }
    s.finish().unwrap();
}

/// Everything a file holds, as a comparable string (f64 Debug round-trips bits).
fn dump(path: &Path) -> String {
    let back = store::read_results(path).unwrap();
    let f = hdf5::File::open(path).unwrap();
    let mut s = format!("{:?}\n", back.records);
    if let Ok(g) = f.group("sweet_spot") {
        for v in ["position", "exit_speed", "width"] {
            let a = g.dataset(v).unwrap().read_raw::<f64>().unwrap();
            s += &format!(
                "{v}: {:?}\n",
                a.iter().map(|x| x.to_bits()).collect::<Vec<_>>()
            );
        }
    }
    for v in ["status", "recontact"] {
        s += &format!(
            "{v}: {:?}\n",
            f.dataset(&format!("summary/{v}"))
                .unwrap()
                .read_raw::<i8>()
                .unwrap()
        );
    }
    s
}

fn expected(info: &StudyInfo, index: usize) -> PointRecord {
    let mut r = record(info, index);
    if let Ok(o) = &mut r.result {
        if let Some(h) = &mut o.history {
            h.hoop_displacement.clear();
            if info.history.as_ref().unwrap().precision == HistoryPrecision::F32 {
                for a in [
                    &mut h.force,
                    &mut h.ball_velocity,
                    &mut h.displacement,
                    &mut h.trajectory_x,
                    &mut h.trajectory_y,
                    &mut h.trajectory_z,
                ] {
                    for x in a.iter_mut() {
                        *x = *x as f32 as f64;
                    }
                }
            }
        }
    }
    r
}

#[test]
fn round_trip_summary_history_errors_bats() {
    let _g = shared();
    for precision in [HistoryPrecision::F64, HistoryPrecision::F32] {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.h5");
        let info = study(true, precision);
        let sum = full_run(&info, &path);
        assert_eq!(
            sum,
            store::Summary {
                n_points: 27,
                n_done: 27,
                n_failed: 4
            }
        );
        assert!(!store::journal_path(&path).exists());
        let back = store::read_results(&path).unwrap();
        assert_eq!(back.records.len(), 27);
        for r in &back.records {
            let e = expected(&info, r.index);
            assert_eq!((r.id, r.bat), (e.id, e.bat));
            assert_eq!(r.result, e.result, "point {}", r.index);
        }
        let f = hdf5::File::open(&path).unwrap();
        let m = f
            .dataset("bat/mode_frequency")
            .unwrap()
            .read_2d::<f64>()
            .unwrap();
        assert_eq!(m.shape(), &[2, 3]);
        assert!(m[[1, 2]].is_nan() && m[[1, 1]] == 680.0);
        let msg = f
            .dataset("errors/message")
            .unwrap()
            .read_raw::<hdf5::types::VarLenUnicode>()
            .unwrap();
        assert_eq!(msg.len(), 4);
        assert!(msg[0].as_str().contains("point 3"));
        let text = store::inspect(&path).unwrap();
        assert!(text.contains("23 ok, 4 failed, 0 not computed"), "{text}");
        assert!(text.contains("swing_omega=3 × impact_z=9"), "{text}");
    }
}

#[test]
fn sweet_spot_group_matches_function() {
    let _g = shared();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("out.h5");
    let info = study(false, HistoryPrecision::F64);
    full_run(&info, &path);
    let f = hdf5::File::open(&path).unwrap();
    let pos = f
        .dataset("sweet_spot/position")
        .unwrap()
        .read_raw::<f64>()
        .unwrap();
    let z = grid(0.55, 0.79, 9);
    for (w, &p) in pos.iter().enumerate() {
        let (zz, vv): (Vec<f64>, Vec<f64>) = (0..9)
            .filter_map(|q| outcome(&info, w * 9 + q).ok().map(|o| (z[q], o.exit_speed)))
            .unzip();
        let want = batstudy::model::measures::sweet::find_sweet_spot(&zz, &vv).unwrap();
        assert_eq!(p.to_bits(), want.position.to_bits());
    }
}

#[test]
fn torn_journal_resume_equals_uninterrupted() {
    let _g = shared();
    let dir = tempfile::tempdir().unwrap();
    let info = study(true, HistoryPrecision::F32);
    let clean = dir.path().join("clean.h5");
    full_run(&info, &clean);

    let path = dir.path().join("out.h5");
    let mut s = store::open(&path, &info, &opts(false, false)).unwrap();
    for k in (0..27).rev().take(15) {
        s.write(record(&info, k)).unwrap();
    }
    s.flush().unwrap();
    drop(s); // killed: no finish
    let j = store::journal_path(&path);
    let len = std::fs::metadata(&j).unwrap().len();
    // tear the last record
    std::fs::OpenOptions::new()
        .write(true)
        .open(&j)
        .unwrap()
        .set_len(len - 37)
        .unwrap();

    let mut s = store::open(&path, &info, &opts(true, false)).unwrap();
    assert_eq!(s.n_done(), 14);
    assert!(s.dropped_bytes > 0);
    let mut computed = 0;
    for k in 0..27 {
        let r = record(&info, k);
        if !s.is_done(r.index) {
            computed += 1;
            s.write(r).unwrap();
        }
    }
    assert_eq!(computed, 13);
    s.finish().unwrap();
    assert_eq!(dump(&path), dump(&clean));
}

/// Each history written once (`store::by_reference`): the points the placer wrote
/// as they arrived are journalled by where their chunks are in `OUT.h5.partial`, not with
/// them, and a session that ends unfinished keeps that file. The resume reads every chunk
/// back, checked against its CRC-32, and completes the same file as an uninterrupted run;
/// with the file damaged, the points whose chunks changed are dropped and computed again,
/// and the result is still the same.
#[test]
fn histories_journalled_by_place_resume_and_damage_is_recomputed() {
    let _g = shared();
    let dir = tempfile::tempdir().unwrap();
    let (info, clean) = history_study_run_clean(dir.path());
    let with_history = |k: usize| matches!(&outcome(&info, k), Ok(o) if o.history.is_some());
    let first: Vec<usize> = (0..18).collect();
    let in_file = first.iter().filter(|&&k| with_history(k)).count();
    assert!(in_file >= 10, "{in_file} of 18 points have histories");

    for damage in [false, true] {
        let path = dir.path().join(format!("out-{damage}.h5"));
        killed_after(&path, &info, &first);
        let (journal, partial) = (store::journal_path(&path), store::partial_path(&path));
        assert!(partial.exists(), "the file the journal names is kept");
        // the records with their histories in them, for scale
        let encoder = store::RecordEncoder::new(&path, &info);
        let whole: usize = first
            .iter()
            .map(|&k| encoder.encode(record(&info, k)).unwrap().framed.len())
            .sum();
        let len = std::fs::metadata(&journal).unwrap().len() as usize;
        assert!(
            len * 3 < whole * 2,
            "journal {len} bytes, {whole} for the records with their histories"
        );
        if damage {
            // one byte changed in the force history of each of the last three points placed
            let places = all_chunks(&partial, "history");
            let (_, force) = places.iter().find(|(name, _)| name == "force").unwrap();
            let mut force = force.clone();
            force.sort_by_key(|&(_, addr, _)| addr);
            let mut bytes = std::fs::read(&partial).unwrap();
            for (_, addr, size) in &force[force.len() - 3..] {
                bytes[(addr + size / 2) as usize] ^= 0x5A;
            }
            std::fs::write(&partial, bytes).unwrap();
        }

        let s = store::open(&path, &info, &opts(true, false)).unwrap();
        let r = s.recovered;
        // every point with histories but the first, whose chunks made the variables' chunk
        // indexes as they were written (so their places are not known: journalled whole)
        assert_eq!(r.kept + r.dropped, in_file - 1, "{r:?}");
        assert_eq!(r.dropped, if damage { 3 } else { 0 }, "{r:?}");
        assert_eq!(s.n_done(), first.len() - r.dropped);
        let prev = path.with_extension("h5.partial.prev");
        assert!(
            !prev.exists(),
            "the set-aside file is removed once read back"
        );
        complete(s, &info);
        assert_eq!(dump(&path), dump(&clean), "damaged: {damage}");
        assert!(!partial.exists() && !journal.exists());
    }
}

/// The file a resume reads chunks back from is only ever read, and never through a
/// symbolic link: one planted in place of the killed run's `OUT.h5.partial` (pointing at a
/// copy of it) is set aside as it is, not followed, so every point it would have given is
/// computed again and the copy is left as it was; a stale `OUT.h5.partial.prev` does not
/// outlive a fresh run's start.
#[test]
fn a_planted_link_is_not_followed_and_a_stale_set_aside_file_is_removed() {
    let _g = shared();
    let dir = tempfile::tempdir().unwrap();
    let (info, clean) = history_study_run_clean(dir.path());
    let path = dir.path().join("out.h5");
    let prev = path.with_extension("h5.partial.prev");
    std::fs::write(&prev, b"stale").unwrap();
    killed_after(&path, &info, &(0..18).collect::<Vec<_>>());
    assert!(!prev.exists(), "a fresh run removes a stale set-aside file");
    let partial = store::partial_path(&path);
    let copy = dir.path().join("elsewhere.h5");
    std::fs::rename(&partial, &copy).unwrap();
    std::os::unix::fs::symlink(&copy, &partial).unwrap();
    let before = std::fs::read(&copy).unwrap();

    let s = store::open(&path, &info, &opts(true, false)).unwrap();
    assert_eq!(s.recovered.kept, 0, "{:?}", s.recovered);
    assert!(s.recovered.dropped > 0, "{:?}", s.recovered);
    complete(s, &info);
    assert_eq!(dump(&path), dump(&clean));
    assert_eq!(
        std::fs::read(&copy).unwrap(),
        before,
        "the link's target untouched"
    );
    assert!(!prev.exists() && !partial.exists());
}

#[test]
fn resume_from_finished_partial_file() {
    let _g = shared();
    // interrupted, then finished incomplete (e.g. Ctrl-C path or a shard), then resumed
    let dir = tempfile::tempdir().unwrap();
    let (info, clean) = history_study_run_clean(dir.path());
    let path = dir.path().join("out.h5");
    let mut s = store::open(&path, &info, &opts(false, false)).unwrap();
    for k in 0..10 {
        s.write(record(&info, k)).unwrap();
    }
    let sum = s.finish().unwrap();
    assert_eq!((sum.n_done, sum.n_points), (10, 27));
    assert!(store::inspect(&path).unwrap().contains("17 not computed"));
    let s = store::open(&path, &info, &opts(true, false)).unwrap();
    assert_eq!(s.n_done(), 10);
    complete(s, &info);
    assert_eq!(dump(&path), dump(&clean));
}

#[test]
fn refuses_other_study_and_overwrite() {
    let _g = shared();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("out.h5");
    let info = study(false, HistoryPrecision::F64);
    full_run(&info, &path);
    // no resume, no force
    let e = store::open(&path, &info, &opts(false, false))
        .err()
        .unwrap();
    assert!(matches!(e, StoreError::Exists { .. }), "{e}");
    assert!(e.to_string().contains("--force"), "{e}");
    // resume with another study: from the finished file
    let other = study(true, HistoryPrecision::F64);
    let e = store::open(&path, &other, &opts(true, false))
        .err()
        .unwrap();
    assert!(matches!(e, StoreError::WrongStudy { .. }), "{e}");
    assert!(e.to_string().contains("out.h5"), "{e}");
    // and from a journal
    let p2 = dir.path().join("b.h5");
    let s = store::open(&p2, &info, &opts(false, false)).unwrap();
    drop(s);
    let e = store::open(&p2, &other, &opts(true, false)).err().unwrap();
    assert!(
        e.to_string().contains("b.h5.journal") && e.to_string().contains("sha256"),
        "{e}"
    );
    // a journal left behind also blocks a fresh run without force
    let e = store::open(&p2, &info, &opts(false, false)).err().unwrap();
    assert!(matches!(e, StoreError::Exists { .. }));
    // force overwrites
    store::open(&path, &info, &opts(false, true))
        .unwrap()
        .finish()
        .unwrap();
    // garbage is reported, not panicked on
    let g = dir.path().join("garbage.h5");
    std::fs::write(&g, b"not hdf5").unwrap();
    let e = store::inspect(&g).err().unwrap();
    assert!(e.to_string().contains("garbage.h5"), "{e}");
    std::fs::write(store::journal_path(&g), b"BATSJRN1\xff").unwrap();
    let e = store::open(&g, &info, &opts(true, false)).err().unwrap();
    assert!(e.to_string().contains("garbage.h5.journal"), "{e}");
}

#[test]
fn rejects_bad_records() {
    let _g = shared();
    let dir = tempfile::tempdir().unwrap();
    let info = study(true, HistoryPrecision::F64);
    let mut s = store::open(&dir.path().join("o.h5"), &info, &opts(false, false)).unwrap();
    let mut r = record(&info, 0);
    r.index = 27;
    assert!(s.write(r).is_err());
    let mut r = record(&info, 1);
    r.result
        .as_mut()
        .unwrap()
        .history
        .as_mut()
        .unwrap()
        .force
        .pop();
    assert!(s.write(r).is_err());
    s.write(record(&info, 2)).unwrap();
    s.write(record(&info, 2)).unwrap(); // duplicate ignored
    s.idle().unwrap();
    // flushed by idle(): visible to a scan without finish
    let mut seen = Vec::new();
    store::journal::scan(&store::journal_path(s.path()), |r| seen.push(r.index)).unwrap();
    assert_eq!(seen, vec![2]);
    assert_eq!(s.n_done(), 1);
}

/// Child side of `kill9_at_several_moments`: writes points slowly until killed.
#[test]
#[ignore]
fn child_writer() {
    let Ok(out) = std::env::var("BATSTUDY_STORE_CHILD_OUT") else {
        return;
    };
    let info = study(true, HistoryPrecision::F64);
    let mut s = store::open(Path::new(&out), &info, &opts(true, false)).unwrap();
    for k in 0..27 {
        let r = record(&info, (k * 11 + 5) % 27);
        if !s.is_done(r.index) {
            s.write(r).unwrap();
            std::thread::sleep(std::time::Duration::from_millis(15));
        }
    }
    s.finish().unwrap();
}

#[test]
fn kill9_at_several_moments() {
    let _g = SERIAL.write().unwrap_or_else(|e| e.into_inner());
    let dir = tempfile::tempdir().unwrap();
    let (_, clean) = history_study_run_clean(dir.path());
    let exe = std::env::current_exe().unwrap();
    for (n, ms) in [30u64, 120, 250, 600].into_iter().enumerate() {
        let path = dir.path().join(format!("k{n}.h5"));
        // run 1: killed after `ms`; run 2: killed again a bit later; run 3: completes
        for kill_after in [Some(ms), Some(ms / 2 + 20), None] {
            let mut child = std::process::Command::new(&exe)
                .args(["--exact", "child_writer", "--ignored", "--quiet"])
                .env("BATSTUDY_STORE_CHILD_OUT", &path)
                .stdout(std::process::Stdio::null())
                .stderr(std::process::Stdio::null())
                .spawn()
                .unwrap();
            match kill_after {
                Some(ms) => {
                    std::thread::sleep(std::time::Duration::from_millis(ms));
                    child.kill().unwrap(); // SIGKILL
                    child.wait().unwrap();
                }
                None => assert!(child.wait().unwrap().success()),
            }
        }
        assert!(!store::journal_path(&path).exists());
        assert_eq!(dump(&path), dump(&clean), "kill at {ms} ms");
    }
}

#[test]
fn zip_dim_with_aux_coords() {
    let _g = shared();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("zip.h5");
    let info = zip_study();
    full_run(&info, &path);
    let f = hdf5::File::open(&path).unwrap();
    let c = f
        .dataset("summary/exit_speed")
        .unwrap()
        .attr("coordinates")
        .unwrap();
    let c: hdf5::types::VarLenUnicode = c.read_scalar().unwrap();
    assert_eq!(c.as_str(), "ball_speed bat_preset point_label");
    // a label has no parameter path (layout 3)
    assert!(f
        .dataset("summary/point_label")
        .unwrap()
        .attr("parameter_path")
        .is_err());
    assert_eq!(
        f.dataset("summary/point")
            .unwrap()
            .read_raw::<i64>()
            .unwrap(),
        vec![0, 1]
    );
}

#[test]
fn merge_shards_equals_single_run_and_refuses_bad_sets() {
    let _g = shared();
    let dir = tempfile::tempdir().unwrap();
    let info = study(true, HistoryPrecision::F32);
    let clean = dir.path().join("clean.h5");
    full_run(&info, &clean);
    let mut shards = Vec::new();
    for k in 0..3 {
        let p = dir.path().join(format!("shard{k}.h5"));
        let mut o = opts(false, false);
        o.run_meta.shard = Some(format!("{}/3", k + 1));
        let mut s = store::open(&p, &info, &o).unwrap();
        for i in (0..27).filter(|i| i % 3 == k) {
            s.write(record(&info, i)).unwrap();
        }
        s.finish().unwrap();
        shards.push(p);
    }
    let out = dir.path().join("merged.h5");
    // the ids `record` gives, as a study would recompute them
    let ids = |i: usize| 1_000_003 * i as u64 + 17;
    let sum = store::merge(&out, &info, &shards, &opts(false, false), &ids).unwrap();
    assert_eq!(sum.n_done, 27);
    assert_eq!(dump(&out), dump(&clean));
    let bad = dir.path().join("bad.h5");
    let e = store::merge(&bad, &info, &shards[..2], &opts(false, false), &ids)
        .err()
        .unwrap();
    assert!(e.to_string().contains("lack 9"), "{e}");
    let twice = [
        shards[0].clone(),
        shards[1].clone(),
        shards[2].clone(),
        shards[1].clone(),
    ];
    let e = store::merge(&bad, &info, &twice, &opts(false, false), &ids)
        .err()
        .unwrap();
    assert!(e.to_string().contains("also in"), "{e}");
    let e = store::merge(
        &bad,
        &small_study(vec![]),
        &shards,
        &opts(false, false),
        &ids,
    )
    .err()
    .unwrap();
    // merge refuses another study with its own error kind
    assert!(matches!(e, StoreError::CannotMerge { .. }), "{e}");
    // a point whose id is not the study's is refused, before anything is written
    let altered = |i: usize| ids(i) + u64::from(i == 13);
    let e = store::merge(&bad, &info, &shards, &opts(false, false), &altered)
        .err()
        .unwrap();
    assert!(e.to_string().contains("flat index 13"), "{e}");
    assert!(!bad.exists() && !store::journal_path(&bad).exists());
}

/// A single-point study (no dims) and a study over impact_z only (scalar sweet spot).
fn small_study(dims: Vec<Dim>) -> StudyInfo {
    let mut s = study(false, HistoryPrecision::F64);
    s.study_text.push_str(&format!("dims: {}\n", dims.len()));
    s.study_sha256 = sha256_hex(&s.study_text);
    s.shape.dims = dims;
    s
}

#[test]
fn degenerate_shapes() {
    let _g = shared();
    let dir = tempfile::tempdir().unwrap();
    let single = small_study(vec![]);
    let p = dir.path().join("single.h5");
    full_run(&single, &p);
    let back = store::read_results(&p).unwrap();
    assert_eq!(back.records.len(), 1);
    assert!(store::inspect(&p).unwrap().contains("1 ok, 0 failed"));
    let only_z = small_study(vec![
        study(false, HistoryPrecision::F64).shape.dims[1].clone()
    ]);
    let p = dir.path().join("z.h5");
    full_run(&only_z, &p);
    let f = hdf5::File::open(&p).unwrap();
    let pos: f64 = f
        .dataset("sweet_spot/position")
        .unwrap()
        .read_scalar()
        .unwrap();
    assert!(pos > 0.6 && pos < 0.75, "{pos}");
}

/// Writes fixtures for tests/python/test_store_layout.py into $BATSTUDY_STORE_FIXTURES.
#[test]
#[ignore]
fn write_python_fixture() {
    let Ok(dir) = std::env::var("BATSTUDY_STORE_FIXTURES") else {
        return;
    };
    let dir = PathBuf::from(dir);
    full_run(&study(true, HistoryPrecision::F32), &dir.join("synth.h5"));
    full_run(&zip_study(), &dir.join("zip.h5"));
    full_run(&small_study(vec![]), &dir.join("single.h5"));
    let info = study(false, HistoryPrecision::F64);
    let p = dir.join("partial.h5");
    let mut s = store::open(&p, &info, &opts(false, true)).unwrap();
    for k in 0..5 {
        s.write(record(&info, k)).unwrap();
    }
    s.finish().unwrap();
}

/// A study of 72 000 points whose summary chunks make two blocks (36 × 200 × 9 and
/// 4 × 200 × 9): big enough for several build passes and several read-back slabs.
fn many_blocks_study() -> StudyInfo {
    let base = study(false, HistoryPrecision::F64);
    let index_dim = |name: &str, size: usize| Dim {
        name: name.into(),
        size,
        coords: vec![],
    };
    let mut s = small_study(vec![
        index_dim("case", 40),
        index_dim("repeat", 200),
        base.shape.dims[1].clone(),
    ]);
    s.study_text.push_str("points: 72000\n");
    s.study_sha256 = sha256_hex(&s.study_text);
    s
}

// the final file is built in windows that hold at most `build_memory` bytes of
// summary values, so that the store's memory does not grow with the study (several windows:
// the journal is first split into one spill file per window). The file must not depend on
// how many windows it took: a one-block-per-window build must equal the one-window build, and both must read back (in 65 536-point slabs) as the
// records that were written.
#[test]
fn multi_pass_build_equals_single_pass_and_reads_back_in_slabs() {
    let _g = shared();
    let dir = tempfile::tempdir().unwrap();
    let info = many_blocks_study();
    let n = info.shape.n_points();
    let mut dumps = Vec::new();
    for (name, build_memory) in [("one_pass.h5", 64 << 20), ("per_block.h5", 1)] {
        let path = dir.path().join(name);
        let mut s = store::open(
            &path,
            &info,
            &StoreOptions {
                build_memory,
                ..opts(false, false)
            },
        )
        .unwrap();
        for k in 0..n {
            s.write(record(&info, (k * 7919 + 13) % n)).unwrap();
        }
        let sum = s.finish().unwrap();
        assert_eq!((sum.n_done, sum.n_points), (n, n));
        assert_eq!(sum.n_failed, (0..n).filter(|i| i % 7 == 3).count());
        let back = store::read_results(&path).unwrap();
        assert_eq!(back.records.len(), n);
        for (i, r) in back.records.iter().enumerate() {
            let e = expected(&info, i);
            assert_eq!((r.index, r.id, r.bat), (i, e.id, e.bat));
            assert_eq!(r.result, e.result, "point {i} of {name}");
        }
        dumps.push(dump(&path));
    }
    assert!(dumps[0] == dumps[1], "the two builds differ");
    // the per-window spill files of the second build are gone
    let mut left: Vec<String> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    left.sort();
    assert_eq!(left, ["one_pass.h5", "per_block.h5"]);
}

/// Guards the finish without a second scan: what the writer says it wrote is what
/// a scan of the file finds, for a new journal and for one resumed after a torn tail.
#[test]
fn journal_writer_extent_equals_a_scan() {
    use store::journal::{scan, JournalHeader, JournalWriter};
    let dir = tempfile::tempdir().unwrap();
    let info = study(true, HistoryPrecision::F64);
    let header = JournalHeader::of(&info);
    let path = dir.path().join("o.h5.journal");
    let check = |w: &JournalWriter| {
        let mine = w.extent(header.clone());
        let found = scan(&path, |_| {}).unwrap();
        assert_eq!(mine.header, found.header);
        assert_eq!(mine.header_len, found.header_len);
        assert_eq!(mine.valid_len, found.valid_len);
        assert_eq!(found.dropped_bytes, 0);
    };
    let encoder = store::RecordEncoder::new(&dir.path().join("o.h5"), &info);
    let framed = |k| encoder.encode(record(&info, k)).unwrap().framed;
    let mut w = JournalWriter::create(&path, &header).unwrap();
    w.flush().unwrap();
    check(&w);
    // ok points with histories, a failed point with its message (index 3 fails in `outcome`)
    for k in 0..9 {
        w.append(&framed(k)).unwrap();
    }
    w.flush().unwrap();
    check(&w);
    drop(w);
    let len = std::fs::metadata(&path).unwrap().len();
    std::fs::OpenOptions::new()
        .write(true)
        .open(&path)
        .unwrap()
        .set_len(len - 5)
        .unwrap();
    let torn = scan(&path, |_| {}).unwrap();
    assert!(torn.dropped_bytes > 0);
    let mut w = JournalWriter::append_to(&path, &torn).unwrap();
    for k in 9..14 {
        w.append(&framed(k)).unwrap();
    }
    w.flush().unwrap();
    check(&w);
}

/// Finishing reads every record it takes from the journal against its checksum: a journal
/// changed under a running session makes `finish` fail loudly instead of storing the changed
/// values. A fresh session builds the file from the records it was handed (the summaries it
/// gathered, the histories it placed or held: the journal is not read back), so the change
/// cannot reach the file.
#[test]
fn finish_refuses_a_journal_changed_after_it_was_written() {
    let _g = shared();
    let dir = tempfile::tempdir().unwrap();
    // flip one byte near the end of the journal: inside the last record's payload (its
    // history when there is one)
    let corrupt = |path: &Path| {
        let j = store::journal_path(path);
        let mut bytes = std::fs::read(&j).unwrap();
        let at = bytes.len() - 3;
        bytes[at] ^= 0x55;
        std::fs::write(&j, &bytes).unwrap();
    };
    for (history, resumed) in [(true, false), (true, true), (false, true), (false, false)] {
        let info = study(history, HistoryPrecision::F64);
        let path = dir.path().join(format!("o{history}{resumed}.h5"));
        let mut s = store::open(&path, &info, &opts(false, false)).unwrap();
        for k in 0..3 {
            s.write(record(&info, k)).unwrap();
        }
        if resumed {
            s.flush().unwrap();
            drop(s);
            s = store::open(&path, &info, &opts(true, false)).unwrap();
        }
        for k in 3..6 {
            s.write(record(&info, k)).unwrap();
        }
        s.flush().unwrap();
        corrupt(&path);
        if resumed {
            let e = s.finish().unwrap_err().to_string();
            assert!(e.contains("checksum") || e.contains("changed"), "{e}");
            assert!(!path.exists(), "no final file from a changed journal");
        } else {
            s.finish().unwrap();
            let back = store::read_results(&path).unwrap();
            let want: Vec<_> = (0..6).map(|k| expected(&info, k)).collect();
            assert_eq!(format!("{:?}", back.records), format!("{want:?}"));
        }
    }
}

/// Guards the file begun before the bats are known: begun from the shape, then
/// taken over by the session, it holds exactly what a file made in one go holds; unused or
/// refused, it leaves nothing behind.
#[test]
fn begun_file_equals_one_made_in_one_go() {
    let _g = shared();
    let dir = tempfile::tempdir().unwrap();
    for history in [false, true] {
        let info = study(history, HistoryPrecision::F32);
        let clean = dir.path().join(format!("clean{history}.h5"));
        full_run(&info, &clean);
        let path = dir.path().join(format!("begun{history}.h5"));
        let begun = store::begin(&path, &info.shape).unwrap();
        assert!(store::partial_path(&path).exists());
        let mut s = store::open_begun(&path, &info, &opts(false, false), Some(begun)).unwrap();
        let n = info.shape.n_points();
        for k in 0..n {
            s.write(record(&info, (k * 11 + 5) % n)).unwrap();
        }
        s.finish().unwrap();
        assert_eq!(dump(&path), dump(&clean));
        assert!(!store::partial_path(&path).exists());
        let a = hdf5::File::open(&clean).unwrap();
        let b = hdf5::File::open(&path).unwrap();
        let names = |f: &hdf5::File| {
            let mut v: Vec<String> = f.attr_names().unwrap();
            for g in f.member_names().unwrap() {
                for m in f.group(&g).unwrap().member_names().unwrap() {
                    v.push(format!("{g}/{m}"));
                }
            }
            v.sort();
            v
        };
        assert_eq!(names(&a), names(&b));
    }

    let info = study(false, HistoryPrecision::F64);
    // dropped unused: no partial file left
    let path = dir.path().join("unused.h5");
    drop(store::begin(&path, &info.shape).unwrap());
    assert!(!store::partial_path(&path).exists());
    // begun for another output: refused, and both partial files gone
    let other = dir.path().join("other.h5");
    let begun = store::begin(&other, &info.shape).unwrap();
    assert!(store::open_begun(&path, &info, &opts(false, false), Some(begun)).is_err());
    assert!(!store::partial_path(&other).exists());
    assert!(!store::partial_path(&path).exists());
    // begun for another shape: the first record fails, the file goes with the session
    let mut smaller = info.clone();
    smaller.shape.dims.truncate(1);
    let begun = store::begin(&path, &smaller.shape).unwrap();
    let mut s = store::open_begun(&path, &info, &opts(false, false), Some(begun)).unwrap();
    let e = s.write(record(&info, 0)).unwrap_err().to_string();
    assert!(e.contains("another study shape"), "{e}");
    drop(s);
    assert!(!store::partial_path(&path).exists());
    // an existing output without --force: refused, the begun file removed
    std::fs::write(&path, b"x").unwrap();
    let begun = store::begin(&path, &info.shape).unwrap();
    assert!(matches!(
        store::open_begun(&path, &info, &opts(false, false), Some(begun)),
        Err(StoreError::Exists { .. })
    ));
    assert!(!store::partial_path(&path).exists());
}

extern "C" {
    // libhdf5 ≥ 1.10.5; declared here so as not to depend on the -sys crate's version gates
    fn H5Dget_chunk_info_by_coord(
        dset: i64,
        offset: *const u64,
        filter_mask: *mut u32,
        addr: *mut u64,
        size: *mut u64,
    ) -> i32;
}

/// (variable, [(file address, stored bytes)] of the chunks at `starts`) for every chunked
/// summary variable of `path`.
fn chunk_layout(path: &Path, starts: &[Vec<u64>]) -> Vec<(String, Vec<(u64, u64)>)> {
    let f = hdf5::File::open(path).unwrap();
    let g = f.group("summary").unwrap();
    let mut names = g.member_names().unwrap();
    names.sort();
    let mut out = Vec::new();
    for name in names {
        let ds = g.dataset(&name).unwrap();
        if !ds.is_chunked() || ds.ndim() != starts[0].len() {
            continue;
        }
        let chunks = starts
            .iter()
            .map(|start| {
                let (mut mask, mut addr, mut size) = (0, 0, 0);
                let r = hdf5::sync::sync(|| unsafe {
                    H5Dget_chunk_info_by_coord(
                        ds.id(),
                        start.as_ptr(),
                        &mut mask,
                        &mut addr,
                        &mut size,
                    )
                });
                assert!(r >= 0, "{name} chunk at {start:?}");
                (addr, size)
            })
            .collect();
        out.push((name, chunks));
    }
    out
}

// the summary chunks are compressed on every core and each is written as soon as
// the ones before it are. Where a chunk lands in the file must not depend on which thread
// finished first: a file built on one thread and one built on three hold every chunk of
// every summary variable at the same address, with the same size.
#[test]
fn chunk_layout_does_not_depend_on_the_threads() {
    let _g = shared();
    let dir = tempfile::tempdir().unwrap();
    let info = many_blocks_study();
    let n = info.shape.n_points();
    let mut layouts = Vec::new();
    for threads in [1, 3] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let path = dir.path().join(format!("threads{threads}.h5"));
        pool.install(|| {
            let mut s = store::open(&path, &info, &opts(false, false)).unwrap();
            for k in 0..n {
                s.write(record(&info, (k * 7919 + 13) % n)).unwrap();
            }
            s.finish().unwrap();
        });
        // the two blocks of `many_blocks_study`
        layouts.push(chunk_layout(&path, &[vec![0, 0, 0], vec![36, 0, 0]]));
    }
    // 28 variables × 2 blocks: enough pieces for three threads to finish out of order
    assert!(layouts[0].len() >= 20);
    assert!(layouts[0]
        .iter()
        .all(|(_, c)| c.iter().all(|&(a, s)| a > 0 && s > 0)));
    assert_eq!(layouts[0], layouts[1]);
}

/// (variable, its chunks) for every chunked variable of `group`, chunks in HDF5's order.
fn all_chunks(path: &Path, group: &str) -> Vec<(String, Vec<common::ChunkPlace>)> {
    let f = hdf5::File::open(path).unwrap();
    let g = f.group(group).unwrap();
    let mut names = g.member_names().unwrap();
    names.sort();
    names
        .into_iter()
        .filter_map(|name| {
            let ds = g.dataset(&name).unwrap();
            ds.is_chunked().then(|| (name, common::chunk_places(&ds)))
        })
        .collect()
}

// the histories are written into the final file while the run goes on, in
// flat-index order (`store::placer`), and the finish writes the rest after them. Where every
// chunk lands must not depend on the order the points arrived in, on whether the placer kept
// up or gave up, nor on a resume (whose histories all come from the journal at the finish):
// the files are the same size and every chunk of `/history` and `/summary` is at the same
// address with the same size.
#[test]
fn history_layout_does_not_depend_on_arrival_order_placer_or_resume() {
    let _g = shared();
    let dir = tempfile::tempdir().unwrap();
    let info = study(true, HistoryPrecision::F32);
    let n = info.shape.n_points();
    let scrambled: Vec<usize> = (0..n).map(|k| (k * 11 + 5) % n).collect();
    let in_order: Vec<usize> = (0..n).collect();
    let layout = |path: &Path| {
        (
            std::fs::metadata(path).unwrap().len(),
            all_chunks(path, "history"),
            all_chunks(path, "summary"),
        )
    };
    let run = |name: &str, order: &[usize], hold: usize, resume_after: Option<usize>| {
        let path = dir.path().join(format!("{name}.h5"));
        let o = StoreOptions {
            history_hold: hold,
            ..opts(false, false)
        };
        let mut s = store::open(&path, &info, &o).unwrap();
        for (k, &i) in order.iter().enumerate() {
            if resume_after == Some(k) {
                s.flush().unwrap();
                drop(s); // as if killed: the journal stays
                s = store::open(&path, &info, &opts(true, false)).unwrap();
            }
            s.write(record(&info, i)).unwrap();
        }
        s.finish().unwrap();
        layout(&path)
    };
    let want = run("in_order", &in_order, usize::MAX, None);
    // 27 points, 23 with histories (every 7th from 3 failed), 6 variables (force, ball
    // velocity, displacement and the trajectory's x, y, z): one chunk each
    assert_eq!(want.1.len(), 6);
    assert!(want.1.iter().all(|(_, c)| c.len() == 23), "{:?}", want.1);
    assert_eq!(run("scrambled", &scrambled, usize::MAX, None), want);
    assert_eq!(run("gave_up", &scrambled, 0, None), want);
    assert_eq!(run("resumed", &scrambled, usize::MAX, Some(n / 2)), want);
    assert_eq!(
        run("resumed_in_order", &in_order, usize::MAX, Some(n / 3)),
        want
    );
}
