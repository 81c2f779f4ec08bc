//! The driver with fake simulators and sinks: failure isolation, bit-identical results
//! whatever --jobs is, resume skips done points.

use batstudy::model::outcome::{BatProperties, HistoryRequest, Outcome};
use batstudy::model::spec::{BatSpec, CollisionSpec, NumericsSpec};
use batstudy::results::{PointId, PointRecord};
use batstudy::run::{build_pool, prepare_bats, run_plan, RunOptions, Shard, Simulator, Sink};
use batstudy::study::{load_str, LoadOptions, Plan};
use std::collections::{BTreeMap, HashSet};
use std::path::Path;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

fn plan() -> Plan {
    load_str(
        "name: t\nbase: {impact: {z: 0.7}}\ngrid:\n  bat.material.density: [600, 700]\n  impact.z: {range: [0.5, 0.8, 0.05]}\n  swing.omega: [0, -10, -20]\n",
        Path::new("t.yaml"),
        &LoadOptions::default(),
    )
    .unwrap()
    .plan
}

/// A deterministic fake physics; panics, errors or returns NaN at chosen points.
struct Fake {
    prepared: AtomicUsize,
}

impl Simulator for Fake {
    type Bat = f64;
    fn prepare(
        &self,
        bat: &BatSpec,
        _: &NumericsSpec,
        _: &batstudy::model::measures::metrics::BbcorShot,
    ) -> Result<(BatProperties, f64), String> {
        self.prepared.fetch_add(1, Ordering::SeqCst);
        let rho = bat.material.density.unwrap_or(649.0);
        Ok((
            BatProperties {
                length: 0.84,
                mass: rho * 1e-3,
                ..Default::default()
            },
            rho,
        ))
    }
    fn simulate(
        &self,
        rho: &f64,
        s: &CollisionSpec,
        _: Option<&HistoryRequest>,
    ) -> Result<Outcome, String> {
        let z = s.impact.z;
        if (z - 0.55).abs() < 1e-9 && s.swing.omega == -10.0 {
            panic!("boom at z={z}");
        }
        if (z - 0.6).abs() < 1e-9 && s.swing.omega == -20.0 {
            return Err("solver diverged".into());
        }
        let exit = (z * 17.0).sin() * 30.0 + s.swing.omega * 0.1 + rho * 1e-3;
        Ok(Outcome {
            exit_speed: if (z - 0.65).abs() < 1e-9 && *rho == 700.0 && s.swing.omega == 0.0 {
                f64::NAN
            } else {
                exit
            },
            contact_time: 1e-3 + z * 1e-5,
            ..Default::default()
        })
    }
}

#[derive(Default)]
struct MemSink {
    done: HashSet<usize>,
    records: BTreeMap<usize, (PointId, u32, Result<u64, String>)>,
    finished: bool,
}

impl Sink for MemSink {
    type Encoder = batstudy::run::AsIs;
    fn encoder(&self) -> batstudy::run::AsIs {
        batstudy::run::AsIs
    }
    fn is_done(&self, index: usize) -> bool {
        self.done.contains(&index)
    }
    fn write(&mut self, r: PointRecord) -> Result<(), String> {
        let v = r.result.map(|o| o.exit_speed.to_bits());
        assert!(
            self.records.insert(r.index, (r.id, r.bat, v)).is_none(),
            "written twice"
        );
        Ok(())
    }
    fn finish(&mut self) -> Result<(), String> {
        self.finished = true;
        Ok(())
    }
}

fn run(
    jobs: usize,
    sink: MemSink,
    opts: RunOptions,
    stop: &AtomicBool,
) -> (batstudy::run::RunReport, MemSink, usize) {
    let p = plan();
    let sim = Fake {
        prepared: AtomicUsize::new(0),
    };
    let pool = build_pool(jobs).unwrap();
    let bats = prepare_bats(&sim, &p, &pool);
    let opts = RunOptions { jobs, ..opts };
    let (rep, sink) = run_plan(&p, &sim, &bats, None, sink, &pool, &opts, stop).unwrap();
    (rep, sink, sim.prepared.load(Ordering::SeqCst))
}

#[test]
fn failures_are_isolated_and_bats_prepared_once() {
    let (rep, sink, prepared) = run(
        2,
        MemSink::default(),
        RunOptions::default(),
        &AtomicBool::new(false),
    );
    let n = plan().n_points();
    assert_eq!(n, 2 * 7 * 3);
    assert_eq!(prepared, 2, "one preparation per distinct bat");
    assert_eq!(rep.total, n);
    assert_eq!(rep.ok + rep.failed, n);
    assert_eq!(
        rep.failed,
        2 + 2 + 1,
        "panic ×2 bats, error ×2 bats, NaN ×1"
    );
    assert!(sink.finished);
    assert_eq!(sink.records.len(), n);
    let errs: Vec<&String> = sink
        .records
        .values()
        .filter_map(|r| r.2.as_ref().err())
        .collect();
    assert!(errs.iter().any(|e| e.contains("panic: boom")));
    assert!(errs.iter().any(|e| e.contains("solver diverged")));
    assert!(errs.iter().any(|e| e.contains("non-finite exit_speed")));
    // The bat index follows bat.material.density (first dimension).
    assert_eq!(sink.records[&0].1, 0);
    assert_eq!(sink.records[&(n - 1)].1, 1);
}

// results are bit-identical whatever --jobs is (tested with 1 and 2).
#[test]
fn jobs_1_and_2_give_identical_records() {
    let (_, a, _) = run(
        1,
        MemSink::default(),
        RunOptions::default(),
        &AtomicBool::new(false),
    );
    let (_, b, _) = run(
        2,
        MemSink::default(),
        RunOptions::default(),
        &AtomicBool::new(false),
    );
    assert_eq!(a.records, b.records);
}

// resume computes only the points that are not done.
#[test]
fn resume_skips_done_points() {
    let (_, full, _) = run(
        2,
        MemSink::default(),
        RunOptions::default(),
        &AtomicBool::new(false),
    );
    let done: HashSet<usize> = full.records.keys().take(10).copied().collect();
    let sink = MemSink {
        done: done.clone(),
        ..Default::default()
    };
    let (rep, part, _) = run(2, sink, RunOptions::default(), &AtomicBool::new(false));
    assert_eq!(rep.skipped, 10);
    assert_eq!(part.records.len(), full.records.len() - 10);
    for (i, r) in &part.records {
        assert_eq!(&full.records[i], r);
        assert!(!done.contains(i));
    }
}

#[test]
fn stop_flag_starts_nothing() {
    let (rep, sink, _) = run(
        2,
        MemSink::default(),
        RunOptions::default(),
        &AtomicBool::new(true),
    );
    assert!(rep.interrupted);
    assert_eq!(sink.records.len(), 0);
    assert_eq!(rep.remaining(), rep.total);
    assert!(sink.finished, "the sink is flushed even when interrupted");
}

#[test]
fn fail_fast_stops_early() {
    let opts = RunOptions {
        fail_fast: true,
        ..Default::default()
    };
    let (rep, _, _) = run(1, MemSink::default(), opts, &AtomicBool::new(false));
    assert!(rep.aborted);
    assert!(rep.failed >= 1);
    assert!(rep.ok + rep.failed < rep.total);
}

// shards are disjoint and together give the single-process result.
#[test]
fn shards_cover_the_study() {
    let (_, full, _) = run(
        2,
        MemSink::default(),
        RunOptions::default(),
        &AtomicBool::new(false),
    );
    let mut merged = BTreeMap::new();
    for i in 1..=3 {
        let opts = RunOptions {
            shard: Some(Shard { index: i, count: 3 }),
            ..Default::default()
        };
        let (rep, s, _) = run(2, MemSink::default(), opts, &AtomicBool::new(false));
        assert_eq!(rep.total, s.records.len());
        for (k, v) in s.records {
            assert!(merged.insert(k, v).is_none());
        }
    }
    assert_eq!(merged, full.records);
}
