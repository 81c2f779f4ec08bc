//! The parallel driver: rayon workers simulate points and encode them for the sink
//! (`Sink::encoder`), a bounded channel carries the encoded records to one writer thread
//! that owns the sink.
//!
//! Memory is bounded by the points in flight (rayon splits the index range lazily; the
//! channel is bounded). Each point is independent and the sink stores by flat index, so
//! results do not depend on the number of threads.

use super::observer::{Observer, Phase, SharedObserver};
use super::shard::Shard;
use super::traits::{Encode, Simulator, Sink};
use crate::model::field::squared_up;
use crate::model::outcome::{BatProperties, HistoryRequest, Outcome};
use crate::model::spec::ModelKind;
use crate::pointset::PointSet;
use crate::results::{BatVariant, PointGroups, PointRecord};
use crate::study::Plan;
use rayon::prelude::*;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

/// How long the writer waits for a point before letting the sink flush what it holds.
const IDLE_FLUSH: std::time::Duration = std::time::Duration::from_millis(50);

/// How to run.
#[derive(Debug, Clone)]
pub struct RunOptions {
    /// Worker threads (>= 1).
    pub jobs: usize,
    /// Stop dispatching at the first failed point.
    pub fail_fast: bool,
    /// Run only this shard's points.
    pub shard: Option<Shard>,
    /// Capacity of the channel to the writer.
    pub channel_capacity: usize,
    /// Who is told the run's phase and progress (the command line's bar, the Python
    /// binding's counter).
    pub observer: SharedObserver,
}

impl Default for RunOptions {
    fn default() -> Self {
        RunOptions {
            jobs: 1,
            fail_fast: false,
            shard: None,
            channel_capacity: 256,
            observer: SharedObserver::default(),
        }
    }
}

/// What happened.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RunReport {
    /// Points of the study (or shard).
    pub total: usize,
    /// Skipped because the sink had them (resume).
    pub skipped: usize,
    pub ok: usize,
    pub failed: usize,
    /// Stopped early by the stop flag (Ctrl-C).
    pub interrupted: bool,
    /// Stopped early by `fail_fast`.
    pub aborted: bool,
    /// The first few failures: (flat index, error text).
    pub failures: Vec<(usize, String)>,
}

impl RunReport {
    /// Points neither done before nor computed now.
    pub fn remaining(&self) -> usize {
        self.total - self.skipped - self.ok - self.failed
    }
}

/// A failure of the run itself (not of a point).
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    #[error("cannot start {0} worker threads: {1}")]
    Pool(usize, String),
    #[error("writing results failed: {0}")]
    Sink(String),
}

/// The study's bats, prepared once each and shared.
pub struct PreparedBats<B> {
    /// For the store's `/bat` group (same order as `Plan::bats()`).
    pub variants: Vec<BatVariant>,
    /// The prepared bats, or why preparing failed (its points then fail with that text).
    pub handles: Vec<Result<Arc<B>, String>>,
}

impl<B> PreparedBats<B> {
    /// The longest bat, m (for the history's z grid); 0 when none was prepared.
    pub fn max_length(&self) -> f64 {
        self.variants
            .iter()
            .map(|v| v.properties.length)
            .fold(0.0, f64::max)
    }
}

/// A rayon pool of `jobs` threads.
pub fn build_pool(jobs: usize) -> Result<rayon::ThreadPool, RunError> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(jobs.max(1))
        .thread_name(|i| format!("batstudy-worker-{i}"))
        .build()
        .map_err(|e| RunError::Pool(jobs, e.to_string()))
}

fn panic_text(p: Box<dyn std::any::Any + Send>) -> String {
    if let Some(s) = p.downcast_ref::<&str>() {
        s.to_string()
    } else if let Some(s) = p.downcast_ref::<String>() {
        s.clone()
    } else {
        "unknown panic payload".into()
    }
}

/// Prepare every distinct bat of the plan once, in parallel; panics and errors are kept
/// per bat.
pub fn prepare_bats<S: Simulator>(
    sim: &S,
    plan: &Plan,
    pool: &rayon::ThreadPool,
) -> PreparedBats<S::Bat> {
    type Prepared<B> = (BatProperties, Result<Arc<B>, String>);
    let results: Vec<Prepared<S::Bat>> = pool.install(|| {
        plan.bats()
            .par_iter()
            .map(|b| {
                match catch_unwind(AssertUnwindSafe(|| {
                    sim.prepare(&b.bat, &b.numerics, &b.shot)
                })) {
                    Ok(Ok((props, bat))) => (props, Ok(Arc::new(bat))),
                    Ok(Err(e)) => (
                        BatProperties::default(),
                        Err(format!("bat `{}`: {e}", b.label)),
                    ),
                    Err(p) => (
                        BatProperties::default(),
                        Err(format!("bat `{}`: panic: {}", b.label, panic_text(p))),
                    ),
                }
            })
            .collect()
    });
    let mut variants = Vec::new();
    let mut handles = Vec::new();
    for (b, (props, h)) in plan.bats().iter().zip(results) {
        variants.push(BatVariant {
            label: b.label.clone(),
            spec_json: b.key.clone(),
            properties: props,
            shapes: h.as_ref().ok().and_then(|bat| sim.shapes(bat)),
        });
        handles.push(h);
    }
    PreparedBats { variants, handles }
}

/// [`prepare_bats`] with `side` run on a thread of its own meanwhile, for work that does not
/// need the bats: a study with fewer bats than cores leaves cores idle while they are
/// prepared (the store begins the results file there).
pub fn prepare_bats_alongside<S: Simulator, T: Send>(
    sim: &S,
    plan: &Plan,
    pool: &rayon::ThreadPool,
    side: impl FnOnce() -> T + Send,
) -> (PreparedBats<S::Bat>, T) {
    std::thread::scope(|scope| {
        let side = scope.spawn(side);
        let bats = prepare_bats(sim, plan, pool);
        let t = side.join().unwrap_or_else(|p| std::panic::resume_unwind(p));
        (bats, t)
    })
}

/// Non-finite summary numbers make a point fail.
pub fn check_finite(o: &Outcome) -> Result<(), String> {
    check_finite_for(o, ModelKind::Wave)
}

/// `check_finite` for a point of this model: the rigid model has no time scale, so its
/// contact time, peak force and compression are NaN by design (see `model::simulate`).
pub fn check_finite_for(o: &Outcome, model: ModelKind) -> Result<(), String> {
    let rigid_nan = |name: &str, v: f64| {
        model == ModelKind::Rigid
            && v.is_nan()
            && matches!(name, "contact_time" | "peak_force" | "max_compression")
    };
    let e = &o.energy;
    // The quantities every model defines. The rigid model has no time scale, so its
    // contact time, peak force and compression are NaN by definition, not by failure.
    let fields = [
        ("exit_speed", o.exit_speed),
        ("exit_speed_lab", o.exit_speed_lab),
        ("collision_efficiency", o.collision_efficiency),
        ("approach_speed", o.approach_speed),
        ("impulse", o.impulse),
        ("energy.initial", e.initial),
        ("energy.ball_final", e.ball_final),
        ("energy.ball_loss", e.ball_loss),
        ("energy.bat_rigid", e.bat_rigid),
        ("energy.bat_vibration", e.bat_vibration),
        ("energy.hoop", e.hoop),
        ("energy.bat_damping", e.bat_damping),
        ("energy.grip_damping", e.grip_damping),
        ("energy.friction", e.friction),
    ];
    match fields
        .iter()
        .find(|(n, v)| !v.is_finite() && !rigid_nan(n, *v))
    {
        Some((n, v)) => Err(format!("non-finite {n} ({v})")),
        None => Ok(()),
    }
}

/// Points ok, points failed, the first failures.
type Tally = (usize, usize, Vec<(usize, String)>);

/// A finished group of points on its way to the writer: what the report needs of each
/// point (its flat index, and its error if it failed), and the records as the sink's
/// encoder made them on the worker.
struct Finished<R> {
    points: Vec<(usize, Option<String>)>,
    records: Vec<R>,
}

/// Run the plan's points (those of `opts.shard`, not yet done in the sink), writing each
/// finished point to the sink. Returns the report and the sink (finished).
///
/// `stop` is polled before each point: once set (Ctrl-C), no new point starts; points
/// in flight finish and are written.
#[allow(clippy::too_many_arguments)] // each is a distinct input of the run
pub fn run_plan<S: Simulator, K: Sink>(
    plan: &Plan,
    sim: &S,
    bats: &PreparedBats<S::Bat>,
    history: Option<&HistoryRequest>,
    sink: K,
    pool: &rayon::ThreadPool,
    opts: &RunOptions,
    stop: &AtomicBool,
) -> Result<(RunReport, K), RunError> {
    let range = opts.shard.map_or(0..plan.n_points(), |s| {
        super::shard::shard_range(plan, history, s)
    });
    let total = range.len();
    opts.observer.phase(Phase::Simulating { total });
    let done = AtomicUsize::new(0);
    let skip = skip_set(&sink, plan.n_points(), range.clone());
    // Asked before the workers start, like the skip set: encoding is the costly part of
    // storing a point, and runs on the worker that computed it.
    let encoder = sink.encoder();
    let groups = sink.groups();
    let sink = Mutex::new(sink);
    let (tx, rx) = crossbeam_channel::bounded(opts.channel_capacity.max(1));
    let progress = Progress {
        observer: &*opts.observer,
        done: &done,
        total,
    };
    let dispatch = Dispatch {
        plan,
        sim,
        bats,
        history,
        skip: &skip,
        groups,
        encoder: &encoder,
        progress,
        stop,
        fail_fast: opts.fail_fast,
        abort: AtomicBool::new(false),
        skipped: AtomicUsize::new(0),
    };
    let written = std::thread::scope(|scope| {
        let sink = &sink;
        let writer = std::thread::Builder::new()
            .name("batstudy-writer".into())
            .spawn_scoped(scope, move || write_records(rx, sink, progress, pool))
            .expect("spawn writer thread");
        dispatch.run(pool, range, tx);
        writer
            .join()
            .map_err(|p| RunError::Sink(format!("writer thread panicked: {}", panic_text(p))))
    });
    opts.observer.phase(Phase::Done);
    let written = written?;
    let sink = sink.into_inner().unwrap_or_else(|p| p.into_inner());
    let (ok, failed, failures) = written.map_err(RunError::Sink)?;
    let report = RunReport {
        total,
        skipped: dispatch.skipped.into_inner(),
        ok,
        failed,
        interrupted: stop.load(Ordering::Relaxed),
        aborted: dispatch.abort.into_inner(),
        failures,
    };
    Ok((report, sink))
}

/// The points to skip, asked of the sink once, before any worker starts: the workers then
/// never wait for the sink's lock, which the writer holds while it writes (the final file's
/// skeleton, made on the writer's first record, would otherwise stall every worker).
fn skip_set<K: Sink>(sink: &K, n: usize, range: std::ops::Range<usize>) -> PointSet {
    let mut skip = PointSet::new(n);
    for i in range.filter(|&i| sink.is_done(i)) {
        skip.insert(i);
    }
    skip
}

/// What a finished or skipped point advances: the run's count, told to its observer.
#[derive(Clone, Copy)]
struct Progress<'a> {
    observer: &'a dyn Observer,
    done: &'a AtomicUsize,
    total: usize,
}

impl Progress<'_> {
    fn done(&self, points: usize) {
        let done = self.done.fetch_add(points, Ordering::Relaxed) + points;
        self.observer.progress(done, self.total);
    }
}

/// The writer thread: every record into the sink as it arrives (letting the sink flush
/// when none comes for a while), then the finish.
fn write_records<K: Sink>(
    rx: crossbeam_channel::Receiver<Finished<<K::Encoder as Encode>::Record>>,
    sink: &Mutex<K>,
    progress: Progress,
    pool: &rayon::ThreadPool,
) -> Result<Tally, String> {
    let lock = || sink.lock().unwrap_or_else(|p| p.into_inner());
    let (mut ok, mut failed, mut failures) = (0usize, 0usize, Vec::new());
    loop {
        let rec = match rx.recv_timeout(IDLE_FLUSH) {
            Ok(rec) => rec,
            Err(crossbeam_channel::RecvTimeoutError::Timeout) => {
                lock().idle()?;
                continue;
            }
            Err(crossbeam_channel::RecvTimeoutError::Disconnected) => break,
        };
        for (index, error) in rec.points.iter().cloned() {
            match error {
                None => ok += 1,
                Some(e) => {
                    failed += 1;
                    if failures.len() < 20 {
                        failures.push((index, e));
                    }
                }
            }
        }
        let mut sink = lock();
        for record in rec.records {
            sink.write(record)?;
        }
        drop(sink);
        progress.done(rec.points.len());
    }
    // Every record is in: finish here, as soon as the last worker lets go of the channel,
    // not after the main thread has woken and joined this one (each wake-up between
    // threads is on the critical path of a small study). In the run's pool, whose threads
    // have just finished their last points: the final file's parallel parts (deflate) start
    // on threads that are awake.
    progress.observer.phase(Phase::Writing);
    let mut s = lock();
    let sink = &mut *s;
    pool.install(|| sink.finish())?;
    Ok((ok, failed, failures))
}

/// The workers' side of a run: what they compute each point with, and how they stop.
struct Dispatch<'a, S: Simulator, E> {
    plan: &'a Plan,
    sim: &'a S,
    bats: &'a PreparedBats<S::Bat>,
    history: Option<&'a HistoryRequest>,
    skip: &'a PointSet,
    /// How the sink groups points.
    groups: PointGroups,
    encoder: &'a E,
    progress: Progress<'a>,
    stop: &'a AtomicBool,
    fail_fast: bool,
    abort: AtomicBool,
    skipped: AtomicUsize,
}

impl<S: Simulator, E: Encode> Dispatch<'_, S, E> {
    /// Points are handed out in index order, a group at a time (`Sink::groups`: one point,
    /// unless the sink stores groups whole), to whichever worker is free: records then reach
    /// the writer nearly in order, and it places their histories in the final file as the
    /// run goes on (`store::placer`). (Rayon's splitting of the range would give each
    /// worker its own far-apart part.)
    fn run(
        &self,
        pool: &rayon::ThreadPool,
        range: std::ops::Range<usize>,
        tx: crossbeam_channel::Sender<Finished<E::Record>>,
    ) {
        let next = AtomicUsize::new(range.start);
        let workers = pool.current_num_threads().max(1);
        let end = range.end;
        let group_end = |i: usize| self.groups.end(i).min(end);
        pool.install(|| {
            (0..workers)
                .into_par_iter()
                .with_max_len(1)
                .for_each_with(tx, |tx, _| loop {
                    let taken = next.fetch_update(Ordering::Relaxed, Ordering::Relaxed, |i| {
                        (i < end).then(|| group_end(i))
                    });
                    let Ok(i) = taken else { break };
                    if !self.group(tx, i..group_end(i)) {
                        break;
                    }
                });
        });
    }

    /// One group of points, computed one after the other and encoded together (the points
    /// the sink has are skipped): false once the run stops (Ctrl-C, --fail-fast, the
    /// writer gone).
    fn group(
        &self,
        tx: &crossbeam_channel::Sender<Finished<E::Record>>,
        points: std::ops::Range<usize>,
    ) -> bool {
        if self.stop.load(Ordering::Relaxed) || self.abort.load(Ordering::Relaxed) {
            return false;
        }
        let n = points.len();
        let todo: Vec<usize> = points.filter(|&i| !self.skip.contains(i)).collect();
        if todo.len() < n {
            self.skipped.fetch_add(n - todo.len(), Ordering::Relaxed);
            self.progress.done(n - todo.len());
        }
        let recs: Vec<PointRecord> = todo.iter().map(|&i| self.compute(i)).collect();
        if recs.iter().any(|r| r.result.is_err()) && self.fail_fast {
            self.abort.store(true, Ordering::Relaxed);
        }
        if recs.is_empty() {
            return true;
        }
        let finished = Finished {
            points: recs
                .iter()
                .map(|r| (r.index, r.result.as_ref().err().cloned()))
                .collect(),
            records: self.encoder.encode_group(recs),
        };
        if tx.send(finished).is_err() {
            // The writer has stopped (a sink error): stop dispatching.
            self.abort.store(true, Ordering::Relaxed);
            return false;
        }
        true
    }

    /// Point `i` computed ([`compute_point`]).
    fn compute(&self, i: usize) -> PointRecord {
        compute_point(self.plan, self.sim, self.bats, self.history, i)
    }
}

/// Point `i` of `plan` computed as a run stores it, its failure (a bad point, a bat that
/// could not be prepared, an error or a panic of the model) kept as its result: the one
/// function every front end's numbers come from (the run, the lab).
pub fn compute_point<S: Simulator>(
    plan: &Plan,
    sim: &S,
    bats: &PreparedBats<S::Bat>,
    history: Option<&HistoryRequest>,
    i: usize,
) -> PointRecord {
    let p = match plan.point(i) {
        Err(e) => {
            return PointRecord {
                index: i,
                id: e.id,
                bat: 0,
                result: Err(e.message),
            }
        }
        Ok(p) => p,
    };
    let history = history.filter(|_| p.record_history);
    let result = match &bats.handles[p.bat as usize] {
        Err(e) => Err(e.clone()),
        Ok(bat) => match catch_unwind(AssertUnwindSafe(|| sim.simulate(bat, &p.spec, history))) {
            Ok(Ok(o)) => check_finite_for(&o, p.spec.model).map(|_| o),
            Ok(Err(e)) => Err(e),
            Err(payload) => Err(format!("panic: {}", panic_text(payload))),
        },
    };
    // squared up against the bat's own best q, which preparing the bat found
    let best_q = bats.variants[p.bat as usize].properties.metrics.best_q;
    let result = result.map(|mut o| {
        o.batted.squared_up = squared_up(&o.batted, o.exit_speed_lab, best_q);
        o
    });
    PointRecord {
        index: i,
        id: p.id,
        bat: p.bat,
        result,
    }
}
