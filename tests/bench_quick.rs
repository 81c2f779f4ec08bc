//! `batstudy bench --quick`: every section is produced and in the JSON, with plausible
//! figures; and the development helpers behind `benches/` still work: both integrators are
//! within 1e-4 (relative exit speed) of the converged reference computed in the same run, and
//! the store-against-null-sink comparison runs. Accuracy only: timings are printed by the
//! benchmarks, never asserted (a shared, noisy machine would make a timed test fail at random).

use batstudy::bench::{self, dev, BenchOptions};
use batstudy::model::spec::ModelKind;
use batstudy::run::{build_pool, prepare_bats, run_plan, ModelSimulator, RunOptions, Sink};
use std::path::Path;
use std::sync::atomic::AtomicBool;

/// Relative exit-speed error both integrators stay within against the converged reference
/// (modal at 1/16 of its step, with twice the segments).
const ACCURACY_BAND: f64 = 1e-4;

fn quick_bench() -> (bench::BenchReport, String) {
    let opts = BenchOptions {
        quick: true,
        threads: vec![2, 1],
        dir: None,
    };
    let mut text = Vec::new();
    let r = bench::run(&opts, &mut text).expect("bench --quick runs");
    (r, String::from_utf8(text).unwrap())
}

#[test]
fn bench_quick_reports_every_section_and_no_targets() {
    let (r, text) = quick_bench();
    for section in [
        "CPU ",
        "cores ",
        "memory ",
        "OS ",
        "== points/s",
        "== writer and disk",
        "== peak memory",
        "== the batted ball",
    ] {
        assert!(text.contains(section), "missing section {section}:\n{text}");
    }
    // facts about the machine only: no targets, verdicts or reference times of past work
    for word in ["target", "MET", "MISSED", "NumPy", "numpy", "reference"] {
        assert!(!text.contains(word), "{word:?} in the report:\n{text}");
    }
    // the thread counts asked for, ascending, the first one the efficiencies' baseline
    let sc = &r.scaling;
    let threads: Vec<usize> = sc.points.iter().map(|p| p.threads).collect();
    assert_eq!(threads, [1, 2]);
    assert_eq!(sc.cores, 2);
    assert_eq!(sc.points[0].summary_efficiency, 1.0);
    for p in &sc.points {
        for rate in [
            p.summary_points_per_second,
            p.history_points_per_second,
            p.history_scalar_points_per_second,
            p.history_modal_points_per_second,
        ] {
            assert!(rate > 0.0 && rate.is_finite(), "{p:?}");
        }
        assert!(p.summary_efficiency > 0.0 && p.history_scalar_efficiency > 0.0);
        assert!(p.history_modal_efficiency > 0.0);
    }
    // one paired ratio per repeat: --quick runs each study once, so the one pair is the
    // ratio of the (one-run) medians
    assert_eq!(
        sc.history_modal_vs_summary_per_core_per_repeat,
        [sc.history_modal_vs_summary_per_core]
    );
    // a share of the machine's CPU time, where /proc/stat gives it
    for share in [sc.summary_stolen_share, sc.history_modal_stolen_share] {
        assert!(share.is_none_or(|x| (0.0..=1.0).contains(&x)), "{share:?}");
    }
    assert!(sc.history_compute_points_per_second > 0.0);
    assert!(sc.history_modal_compute_points_per_second > 0.0);
    // the displacement in modal form takes fewer bytes than on its 85-z grid
    assert!(sc.history_modal_file_bytes < sc.history_file_bytes);
    assert!(sc.history_uncompressed_file_bytes > sc.history_file_bytes);
    // the writer's headroom, and the disk's over the bytes a history point makes
    let wh = &r.writer_headroom;
    assert!(wh.headroom > 0.0 && wh.run_headroom > 0.0);
    assert!(wh.disk_bytes_per_second > 0.0 && wh.disk_headroom > 0.0);
    // force, compression, ball velocity, rigid motion and 85 z of displacement, 200 samples
    assert!(
        wh.file_bytes_per_point > 10e3,
        "{} B/point",
        wh.file_bytes_per_point
    );
    assert!(wh.modal_file_bytes_per_point < wh.file_bytes_per_point);
    assert!(wh.modal_headroom > 0.0 && wh.modal_disk_headroom > 0.0);
    // each history written once. On one thread the records come in order and the writer
    // places each as it comes, so the journal names where the histories are instead of
    // holding them: a small part of the file's bytes.
    for (journal, file) in [
        (wh.journal_bytes_per_point, wh.file_bytes_per_point),
        (
            wh.modal_journal_bytes_per_point,
            wh.modal_file_bytes_per_point,
        ),
    ] {
        assert!(journal > 0.0 && journal * 4.0 < file, "{journal} {file}");
    }
    let m = &r.memory;
    assert_eq!(m.large_summary.points, 10_000);
    assert!(m.history_bytes_in_memory > 0);
    assert_eq!(m.history.threads, 2);
    assert!(r.machine.nproc >= 1 && !r.machine.cpu_model.is_empty());
}

// scripts/scaling_plot.py and the docs read these keys
#[test]
fn bench_quick_json_has_every_section_and_key() {
    let (r, _) = quick_bench();
    let json = serde_json::to_value(&r).unwrap();
    for key in [
        "machine",
        "scaling",
        "writer_headroom",
        "memory",
        "batted",
        "simulate",
    ] {
        assert!(json.get(key).is_some(), "json lacks {key}");
    }
    let batted = &r.batted;
    assert!(batted.flight_time_ratio > 0.0 && batted.flight_time_ratio.is_finite());
    let simulate = &r.simulate;
    assert!(simulate.call_to_point_ratio > 0.0 && simulate.call_to_point_ratio.is_finite());
    for key in ["nproc", "cpu_model", "memory_bytes", "os", "kernel"] {
        assert!(json["machine"].get(key).is_some(), "machine lacks {key}");
    }
    for key in [
        "cores",
        "summary_points",
        "history_points",
        "points",
        "summary_efficiency",
        "history_efficiency",
        "history_vs_summary_per_core",
        "history_compute_points_per_second",
        "history_vs_summary_ceiling",
        "history_uncompressed_points_per_second",
        "history_uncompressed_file_bytes",
        "history_file_bytes",
        "history_scalar_points_per_second",
        "history_scalar_vs_summary_per_core",
        // the history study with the displacement in modal form
        "history_modal_points_per_second",
        "history_modal_efficiency",
        "history_modal_vs_summary_per_core",
        "history_modal_file_bytes",
        "history_modal_compute_points_per_second",
        "history_modal_vs_summary_ceiling",
        "history_modal_vs_summary_per_core_per_repeat",
        // what the host of a virtual machine took meanwhile (null where unreadable)
        "summary_stolen_share",
        "history_modal_stolen_share",
    ] {
        assert!(json["scaling"].get(key).is_some(), "scaling lacks {key}");
    }
    for key in [
        "threads",
        "summary_points_per_second",
        "history_points_per_second",
        "history_modal_points_per_second",
    ] {
        assert!(
            json["scaling"]["points"][0].get(key).is_some(),
            "points lack {key}"
        );
    }
    for key in [
        "points",
        "writer_points_per_second",
        "append_points_per_second",
        "finish_seconds",
        "run_headroom",
        "worker_points_per_second",
        "worker_encode_share",
        "headroom",
        "file_bytes_per_point",
        "disk_bytes_per_second",
        "disk_headroom",
        "modal_file_bytes_per_point",
        "journal_bytes_per_point",
        "modal_journal_bytes_per_point",
        "modal_worker_points_per_second",
        "modal_writer_points_per_second",
        "modal_headroom",
        "modal_run_headroom",
        "modal_disk_headroom",
    ] {
        assert!(
            json["writer_headroom"].get(key).is_some(),
            "writer_headroom lacks {key}"
        );
    }
}

#[test]
fn thread_counts_are_sorted_and_checked() {
    let opts = |threads: Vec<usize>| BenchOptions {
        threads,
        ..BenchOptions::default()
    };
    assert_eq!(opts(vec![4, 1, 4, 2]).thread_counts().unwrap(), [1, 2, 4]);
    assert!(opts(vec![2, 0]).thread_counts().is_err());
    // by default 1, 2, 4, … up to every core, every core included
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let t = opts(vec![]).thread_counts().unwrap();
    assert_eq!((t[0], *t.last().unwrap()), (1, cores));
}

// the accuracy of every integrator: against a reference computed here, not against pasted
// numbers
#[test]
fn integrators_are_within_the_band_of_the_converged_reference() {
    let a = dev::integrator_accuracy().expect("the base case runs");
    assert!(
        a.modal.rel_error <= ACCURACY_BAND,
        "modal {:e} off the reference",
        a.modal.rel_error
    );
    assert!(
        a.verlet.rel_error <= ACCURACY_BAND,
        "verlet {:e} off the reference",
        a.verlet.rel_error
    );
    // the reference is finer than the modal default (1/16 of its step) and has more segments
    // than both (Verlet's stable step is smaller still, set by the highest beam mode)
    assert!(a.reference_dt < a.modal.dt && a.verlet.dt < a.modal.dt);
    assert!(a.reference_segments > a.verlet.modes);
    assert!(a.modal.modes < a.verlet.modes && a.modal.steps < a.verlet.steps);
}

// the HDF5 share of `benches/store.rs`: store runs paired with null-sink runs
#[test]
fn write_share_pairs_store_and_null_runs() {
    let study = bench::load_study(&bench::curve_study_text("ws", 1, ""), "ws").unwrap();
    let dir = tempfile::tempdir().unwrap();
    let w = dev::write_share("ws", &study, dir.path(), 2, 2).unwrap();
    assert_eq!((w.points, w.threads, w.pairs), (45, 2, 2));
    assert!(w.store_wall_seconds > 0.0 && w.null_wall_seconds > 0.0);
    assert!(w.wall_overhead.is_finite() && w.wall_overhead < 1.0);
    assert!(w.file_bytes > 0 && w.share > 0.0 && w.cpu_share > 0.0);
    // the store's files are gone: the bench leaves nothing behind
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
}

/// A sink that only counts.
struct Count(usize);
impl Sink for Count {
    type Encoder = batstudy::run::AsIs;
    fn encoder(&self) -> batstudy::run::AsIs {
        batstudy::run::AsIs
    }
    fn is_done(&self, _: usize) -> bool {
        false
    }
    fn write(&mut self, rec: batstudy::results::PointRecord) -> Result<(), String> {
        rec.result?;
        self.0 += 1;
        Ok(())
    }
    fn finish(&mut self) -> Result<(), String> {
        Ok(())
    }
}

// the 10-million-point plan of the benchmark runs the rigid model through the driver:
// rigid points have NaN contact time/force/compression by design and must not fail
#[test]
fn rigid_points_pass_the_driver() {
    let study = batstudy::study::load_str(
        "name: r\nmodel: rigid\nbase: {impact: {z: 0.7}}\ngrid:\n  impact.z: [0.5, 0.7]\n",
        Path::new("r.yaml"),
        &Default::default(),
    )
    .unwrap();
    assert_eq!(study.plan.point(0).unwrap().spec.model, ModelKind::Rigid);
    let pool = build_pool(1).unwrap();
    let bats = prepare_bats(&ModelSimulator, &study.plan, &pool);
    let (report, sink) = run_plan(
        &study.plan,
        &ModelSimulator,
        &bats,
        None,
        Count(0),
        &pool,
        &RunOptions::default(),
        &AtomicBool::new(false),
    )
    .unwrap();
    assert_eq!((report.ok, report.failed), (2, 0), "{:?}", report.failures);
    assert_eq!(sink.0, 2);
}
