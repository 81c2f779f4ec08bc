//! `batstudy bench --quick` (issue 7): every section is produced, and both integrators are
//! within 1e-4 (relative exit speed) of the converged reference computed in the same run.
//! Accuracy only: timings are printed by the benchmark, never asserted (a shared, noisy
//! machine would make a timed test fail at random).

use batstudy::bench::{self, BenchOptions, ACCURACY_TARGET};
use batstudy::model::spec::ModelKind;
use batstudy::run::{build_pool, prepare_bats, run_plan, ModelSimulator, RunOptions, Sink};
use std::path::Path;
use std::sync::atomic::AtomicBool;

// issue 7: "tests check the accuracy of every integrator"; the bench's report has every section
#[test]
fn bench_quick_reports_every_section_and_integrators_are_accurate() {
    let mut text = Vec::new();
    let r = bench::run(&BenchOptions { quick: true }, &mut text).expect("bench --quick runs");
    let text = String::from_utf8(text).unwrap();
    for section in [
        "== integrators",
        "== exit-speed curve",
        "== parallel",
        "== HDF5 writing",
        "== memory",
    ] {
        assert!(text.contains(section), "missing section {section}:\n{text}");
    }
    let i = &r.integrators;
    assert!(
        i.modal.rel_error <= ACCURACY_TARGET,
        "modal {:e} off the reference",
        i.modal.rel_error
    );
    assert!(
        i.verlet.rel_error <= ACCURACY_TARGET,
        "verlet {:e} off the reference",
        i.verlet.rel_error
    );
    // the reference is finer than the modal default (1/16 of its step) and has more segments
    // than both (Verlet's stable step is smaller still, set by the highest beam mode)
    assert!(i.reference_dt < i.modal.dt);
    assert!(i.reference_segments > i.verlet.modes);
    // plausible figures in every section (no timing thresholds)
    assert!(i.speedup.is_finite() && i.speedup > 0.0);
    assert_eq!(r.curve.points, 45);
    assert!(r.curve.curve_seconds > 0.0 && r.curve.prepare_seconds > 0.0);
    assert!(r.parallel.points > 0 && r.parallel.efficiency > 0.0);
    assert_eq!(r.hdf5.len(), 3);
    assert_eq!(r.hdf5[0].case, "summary");
    assert_eq!(r.hdf5[1].case, "history");
    assert_eq!(r.hdf5[2].case, "summary-large");
    assert_eq!(r.hdf5[2].points, 10 * r.hdf5[0].points);
    // the summary cases are measured against a null sink
    for w in [&r.hdf5[0], &r.hdf5[2]] {
        assert!(w.null_wall_seconds.is_some_and(|t| t > 0.0) && w.wall_overhead.is_some());
        assert!(w.untimed_wall_seconds.is_some_and(|t| t > 0.0));
    }
    assert!(r.hdf5.iter().all(|w| w.file_bytes > 0 && w.share > 0.0));
    assert!(r.hdf5[1].history_bytes_in_memory > 0);
    assert!(r.memory.plan_points >= 10_000);
    // issue 22: the scalar-history study is measured, and its points are not free
    let sc = &r.scaling;
    assert!(sc.history_scalar_points_per_second > 0.0);
    assert!(
        sc.history_scalar_vs_summary_per_core > 0.0
            && sc.history_scalar_vs_summary_per_core.is_finite()
    );
    // issue 22: the writer's headroom, and the disk's over the bytes a history point makes
    let wh = &r.writer_headroom;
    assert!(wh.headroom > 0.0 && wh.run_headroom > 0.0);
    assert!(wh.disk_bytes_per_second > 0.0 && wh.disk_headroom > 0.0);
    // force, compression, ball velocity, rigid motion and 85 z of displacement, 200 samples
    assert!(
        wh.file_bytes_per_point > 10e3,
        "{} B/point",
        wh.file_bytes_per_point
    );
    // the JSON form serializes
    let json = serde_json::to_value(&r).unwrap();
    for key in [
        "machine",
        "integrators",
        "curve",
        "parallel",
        "hdf5",
        "memory",
        "scaling",
        "writer_headroom",
    ] {
        assert!(json.get(key).is_some(), "json lacks {key}");
    }
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

// issue 7 (the 10-million-point plan of the benchmark runs the rigid model through the
// driver): rigid points have NaN contact time/force/compression by design and must not fail
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
