//! `batstudy bench`: the performance figures of issue 7, measured in one run on one machine
//! and printed as ratios against baselines measured in the same run.
//!
//! Sections (each a field of [`BenchReport`]):
//! - `integrators`: collisions/s on one thread for the base case (R161, linear-hysteresis
//!   ball, 40 m/s, z = 0.70, default numerics) with the modal integrator and with plain
//!   velocity Verlet at 0.9 × its stability limit; both checked against a converged reference
//!   computed here (modal, dt/16, twice the segments);
//! - `curve`: a 45-point exit-speed curve (z = 0.40..0.84) on one thread with a shared
//!   prepared bat, and the bat preparation on its own;
//! - `parallel`: a few thousand points through the real driver (`run_plan`, null sink) on
//!   1 thread and on all cores;
//! - `hdf5`: the share of wall time spent in the results store (journal + final file), for a
//!   summary-only study and for one with full displacement histories (real driver + store in
//!   a temporary directory);
//! - `memory`: peak resident memory (VmHWM, reset through `/proc/self/clear_refs` before each
//!   case) for a 10-million-point summary-only plan run through the driver with the rigid
//!   model, and for the history study above.
//!
//! Timings are medians of repeats; ratios are medians of per-repeat ratios (baseline and
//! candidate timed back to back), which cancels most of the noise of a shared machine.
//! Timings never go into tests; `tests/bench_quick.rs` checks the accuracy figures only.

use crate::model::outcome::HistoryRequest;
use crate::model::spec::{CollisionSpec, Integrator};
use crate::model::{prepare_bat, simulate, simulate_with_diagnostics, PreparedBat};
use crate::results::PointRecord;
use crate::run::{self, ModelSimulator, RunOptions, Sink, StoreSink};
use crate::store;
use crate::study::{self, LoadOptions, Study};
use serde::Serialize;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;
use std::time::{Duration, Instant};

/// Relative exit-speed accuracy both integrators must reach (issue 7).
pub const ACCURACY_TARGET: f64 = 1e-4;
/// Targets of issue 7.
pub const SPEEDUP_TARGET: f64 = 20.0;
pub const CURVE_TARGET_S: f64 = 0.1;
pub const EFFICIENCY_TARGET: f64 = 0.9;
pub const HDF5_SHARE_TARGET: f64 = 0.05;

/// What to run.
#[derive(Debug, Clone, Default)]
pub struct BenchOptions {
    /// Shrink every case so that the whole benchmark takes a few seconds (for tests).
    pub quick: bool,
}

/// Facts about the machine and the run.
#[derive(Debug, Clone, Serialize)]
pub struct Machine {
    pub nproc: usize,
    pub cpu_model: String,
    /// `/proc/loadavg` at the start (other processes sharing the cores make timings noisy).
    pub loadavg_start: String,
    pub loadavg_end: String,
    pub quick: bool,
    pub batstudy_version: String,
    pub git_commit: String,
}

/// One integrator on the base case.
#[derive(Debug, Clone, Serialize)]
pub struct IntegratorFigures {
    pub exit_speed: f64,
    /// |v / v_ref − 1|.
    pub rel_error: f64,
    pub dt: f64,
    pub steps: usize,
    /// Modes time-stepped (modal) or nodes (Verlet).
    pub modes: usize,
    /// Median wall seconds per collision.
    pub seconds_per_collision: f64,
    pub collisions_per_second: f64,
    /// Median CPU seconds of the thread per collision (insensitive to other load).
    pub cpu_seconds_per_collision: f64,
    pub collisions_per_cpu_second: f64,
}

#[derive(Debug, Clone, Serialize)]
pub struct IntegratorBench {
    pub reference_exit_speed: f64,
    pub reference_dt: f64,
    pub reference_segments: usize,
    pub modal: IntegratorFigures,
    pub verlet: IntegratorFigures,
    /// Median over repeats of (Verlet time / modal time), wall clock and CPU time.
    pub speedup: f64,
    pub speedup_cpu: f64,
    pub repeats: usize,
}

#[derive(Debug, Clone, Serialize)]
pub struct CurveBench {
    pub points: usize,
    /// Median seconds for the whole curve (bat prepared beforehand, shared): wall, CPU.
    pub curve_seconds: f64,
    pub curve_cpu_seconds: f64,
    /// Median seconds of one `prepare_bat`: wall, CPU.
    pub prepare_seconds: f64,
    pub prepare_cpu_seconds: f64,
    pub exit_speed_min: f64,
    pub exit_speed_max: f64,
    pub repeats: usize,
}

#[derive(Debug, Clone, Serialize)]
pub struct ParallelBench {
    pub points: usize,
    pub threads: usize,
    /// Median wall seconds of `run_plan` on 1 thread and on `threads`.
    pub seconds_1: f64,
    pub seconds_n: f64,
    /// Median over repeats of t_1 / (threads · t_n) (wall clock: depends on what else runs).
    pub efficiency: f64,
    /// Median process CPU seconds of the two runs, and their ratio cpu_1 / cpu_n: the work
    /// added by running in parallel (1.0 = none), whatever else shares the machine.
    pub cpu_seconds_1: f64,
    pub cpu_seconds_n: f64,
    pub cpu_efficiency: f64,
    /// Cores the n-thread run actually got on average (cpu_n / t_n).
    pub cores_obtained: f64,
    /// Median µs to resolve one point of the plan (`Plan::point`), one thread.
    pub resolve_us_per_point: f64,
    pub repeats: usize,
}

#[derive(Debug, Clone, Serialize)]
pub struct WriteShare {
    pub case: String,
    pub points: usize,
    pub threads: usize,
    /// Bytes of the final file.
    pub file_bytes: u64,
    /// Wall seconds of the run (driver + store, bats prepared beforehand).
    pub wall_seconds: f64,
    /// Seconds inside the sink's `write`/`idle` calls (journal) and in `finish` (HDF5 file).
    pub journal_seconds: f64,
    pub final_file_seconds: f64,
    /// (journal + final) / wall.
    pub share: f64,
    /// The same in CPU time: process CPU seconds of the run, the store's CPU seconds (writer
    /// thread in `write`/`idle`, caller in `finish`) and their ratio (insensitive to load).
    pub cpu_seconds: f64,
    pub journal_cpu_seconds: f64,
    pub final_file_cpu_seconds: f64,
    pub cpu_share: f64,
    /// Peak resident memory during the run (VmHWM after a reset), bytes; None where
    /// `/proc/self/clear_refs` is unavailable.
    pub peak_rss_bytes: Option<u64>,
    /// Resident memory before the run, bytes.
    pub rss_before_bytes: Option<u64>,
    /// Size of all the study's histories held as f64 (0 for summary-only).
    pub history_bytes_in_memory: u64,
    /// What writing costs the user: the same plan run with a sink that keeps nothing,
    /// back to back with the store run (median wall seconds), and the median over repeats of
    /// (wall − null wall) / wall. `None` where not measured (the history case: one long run).
    pub null_wall_seconds: Option<f64>,
    pub wall_overhead: Option<f64>,
    /// First and third quartiles of the per-pair overheads (the machine's noise).
    pub wall_overhead_quartiles: Option<(f64, f64)>,
    /// Median wall seconds of the untimed store runs paired with the null runs.
    pub untimed_wall_seconds: Option<f64>,
    /// Pairs behind the medians (the other fields are from the timed store run of median
    /// wall time).
    pub repeats: usize,
}

#[derive(Debug, Clone, Serialize)]
pub struct MemoryBench {
    /// Points of the summary-only plan (10 million; fewer with --quick).
    pub plan_points: usize,
    pub plan_seconds: f64,
    pub plan_peak_rss_bytes: Option<u64>,
    pub plan_rss_before_bytes: Option<u64>,
    /// Channel capacity of the driver (records in flight).
    pub channel_capacity: usize,
    /// Summary-only studies through the driver and the real store (rigid model), full size and
    /// four times that: the store keeps one bit per point, and the final file's build holds
    /// at most `build_memory` bytes of summary values (more points → more windows, not more
    /// memory).
    pub build_memory: usize,
    pub store_small_points: usize,
    pub store_small_peak_rss_bytes: Option<u64>,
    pub store_small_rss_before_bytes: Option<u64>,
    pub store_points: usize,
    pub store_seconds: f64,
    pub store_peak_rss_bytes: Option<u64>,
    pub store_rss_before_bytes: Option<u64>,
    /// The history study's peak (same run as `hdf5[1]`).
    pub history_points: usize,
    pub history_peak_rss_bytes: Option<u64>,
    pub history_bytes_in_memory: u64,
}

/// Everything measured.
#[derive(Debug, Clone, Serialize)]
pub struct BenchReport {
    pub machine: Machine,
    pub integrators: IntegratorBench,
    pub curve: CurveBench,
    pub parallel: ParallelBench,
    /// Summary-only, history, summary-only with ten times the points.
    pub hdf5: Vec<WriteShare>,
    pub memory: MemoryBench,
}

/// Sizes of the cases.
struct Sizes {
    repeats: usize,
    min_time: f64,
    curve_repeats: usize,
    parallel_omegas: usize,
    parallel_repeats: usize,
    summary_omegas: usize,
    history_omegas: usize,
    plan_points: [usize; 3],
    store_points: [usize; 3],
    /// Store + null-sink pairs of the summary case. On a shared 2-core machine a 0.3 s run
    /// varies by ±10 %; the median of 121 pairs pins the overhead to about ±1 %.
    write_repeats: usize,
}

impl Sizes {
    fn of(quick: bool) -> Sizes {
        if quick {
            Sizes {
                repeats: 3,
                min_time: 0.005,
                curve_repeats: 3,
                parallel_omegas: 2,
                parallel_repeats: 1,
                summary_omegas: 2,
                history_omegas: 1,
                plan_points: [100, 10, 10],
                store_points: [100, 10, 10],
                write_repeats: 1,
            }
        } else {
            Sizes {
                repeats: 7,
                min_time: 0.25,
                curve_repeats: 9,
                parallel_omegas: 60,
                parallel_repeats: 3,
                summary_omegas: 60,
                history_omegas: 40,
                plan_points: [1000, 100, 100],
                store_points: [1000, 100, 10],
                write_repeats: 121,
            }
        }
    }
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(|a, b| a.total_cmp(b));
    let n = v.len();
    if n == 0 {
        f64::NAN
    } else if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

/// CPU seconds of a POSIX CPU-time clock (NaN if it cannot be read).
fn cpu_clock_seconds(clock: libc::clockid_t) -> f64 {
    let mut t = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: clock_gettime writes one timespec through a valid pointer.
    if unsafe { libc::clock_gettime(clock, &mut t) } != 0 {
        return f64::NAN;
    }
    t.tv_sec as f64 + t.tv_nsec as f64 * 1e-9
}

/// CPU seconds this thread has run (ns resolution). On a shared machine a thread waits for a
/// core part of the wall time; its CPU time does not. A clock call, not a /proc read: the
/// store's calls are timed one by one, and reading /proc for each cost ~15 µs, more than a
/// journal write (issue 7: it inflated the measured store share).
fn thread_cpu_seconds() -> f64 {
    cpu_clock_seconds(libc::CLOCK_THREAD_CPUTIME_ID)
}

/// (wall, CPU) seconds per call of `f`, calling it until at least `min_time` of wall time has
/// passed (at least once).
fn time_per_call(min_time: f64, mut f: impl FnMut()) -> (f64, f64) {
    let c0 = thread_cpu_seconds();
    let t0 = Instant::now();
    let mut calls = 0u64;
    loop {
        f();
        calls += 1;
        let e = t0.elapsed().as_secs_f64();
        if e >= min_time {
            let c = thread_cpu_seconds() - c0;
            return (e / calls as f64, c / calls as f64);
        }
    }
}

/// The base case of issue 7 at impact position `z`.
pub fn base_spec(z: f64) -> CollisionSpec {
    CollisionSpec::base_case(z)
}

fn proc_status_kib(key: &str) -> Option<u64> {
    let s = std::fs::read_to_string("/proc/self/status").ok()?;
    s.lines()
        .find(|l| l.starts_with(key))?
        .split_whitespace()
        .nth(1)?
        .parse()
        .ok()
}

/// Reset the peak-RSS mark (Linux ≥ 4.0); returns the current RSS in bytes.
fn reset_peak() -> Option<u64> {
    std::fs::write("/proc/self/clear_refs", "5").ok()?;
    proc_status_kib("VmRSS:").map(|k| k * 1024)
}

fn peak_rss() -> Option<u64> {
    proc_status_kib("VmHWM:").map(|k| k * 1024)
}

fn machine(quick: bool) -> Machine {
    let cpu_model = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split_once(':'))
                .map(|(_, v)| v.trim().to_string())
        })
        .unwrap_or_else(|| "unknown".into());
    Machine {
        nproc: std::thread::available_parallelism().map_or(1, |n| n.get()),
        cpu_model,
        loadavg_start: loadavg(),
        loadavg_end: String::new(),
        quick,
        batstudy_version: env!("CARGO_PKG_VERSION").to_string(),
        git_commit: option_env!("BATSTUDY_GIT_COMMIT")
            .unwrap_or("unknown")
            .to_string(),
    }
}

fn loadavg() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .map(|s| s.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
        .unwrap_or_default()
}

fn err<E: std::fmt::Display>(what: &str) -> impl FnOnce(E) -> String + '_ {
    move |e| format!("{what}: {e}")
}

/// Integrator speed and accuracy on the base case.
fn bench_integrators(sz: &Sizes) -> Result<IntegratorBench, String> {
    let spec = base_spec(0.70);
    let bat = prepare_bat(&spec.bat, &spec.numerics).map_err(err("prepare the bat"))?;
    let mut verlet_spec = spec.clone();
    verlet_spec.numerics.integrator = Integrator::Verlet;
    let (mo, md) = simulate_with_diagnostics(&spec, &bat, None).map_err(err("modal"))?;
    let (vo, vd) = simulate_with_diagnostics(&verlet_spec, &bat, None).map_err(err("verlet"))?;

    // converged reference: modal, dt/16, twice the segments
    let mut reference = spec.clone();
    reference.numerics.segments = Some(2 * md.segments);
    reference.numerics.dt = Some(md.dt / 16.0);
    let ref_bat = prepare_bat(&reference.bat, &reference.numerics)
        .map_err(err("prepare the reference bat"))?;
    let (ro, rd) =
        simulate_with_diagnostics(&reference, &ref_bat, None).map_err(err("reference"))?;
    let v_ref = ro.exit_speed;

    let (mut tm, mut tv, mut ratio) = (Vec::new(), Vec::new(), Vec::new());
    let (mut cm, mut cv, mut cratio) = (Vec::new(), Vec::new(), Vec::new());
    for _ in 0..sz.repeats {
        let (m, mc) = time_per_call(sz.min_time, || {
            std::hint::black_box(simulate(&spec, &bat, None).ok());
        });
        let (v, vc) = time_per_call(sz.min_time, || {
            std::hint::black_box(simulate(&verlet_spec, &bat, None).ok());
        });
        tm.push(m);
        tv.push(v);
        ratio.push(v / m);
        cm.push(mc);
        cv.push(vc);
        cratio.push(vc / mc);
    }
    let figures = |o: &crate::model::outcome::Outcome,
                   d: &crate::model::collision::wave::Diagnostics,
                   t: f64,
                   c: f64| IntegratorFigures {
        exit_speed: o.exit_speed,
        rel_error: (o.exit_speed / v_ref - 1.0).abs(),
        dt: d.dt,
        steps: d.steps,
        modes: d.modes,
        seconds_per_collision: t,
        collisions_per_second: 1.0 / t,
        cpu_seconds_per_collision: c,
        collisions_per_cpu_second: 1.0 / c,
    };
    Ok(IntegratorBench {
        reference_exit_speed: v_ref,
        reference_dt: rd.dt,
        reference_segments: rd.segments,
        modal: figures(&mo, &md, median(tm), median(cm)),
        verlet: figures(&vo, &vd, median(tv), median(cv)),
        speedup: median(ratio),
        speedup_cpu: median(cratio),
        repeats: sz.repeats,
    })
}

/// The 45 impact positions 0.40, 0.41, …, 0.84 m.
pub fn curve_positions() -> Vec<f64> {
    (0..45).map(|k| (40 + k) as f64 / 100.0).collect()
}

fn bench_curve(sz: &Sizes) -> Result<CurveBench, String> {
    let spec = base_spec(0.70);
    let (mut prep, mut prep_cpu) = (Vec::new(), Vec::new());
    let mut bat: Option<PreparedBat> = None;
    for _ in 0..sz.curve_repeats {
        let c0 = thread_cpu_seconds();
        let t0 = Instant::now();
        let b = prepare_bat(&spec.bat, &spec.numerics).map_err(err("prepare the bat"))?;
        prep.push(t0.elapsed().as_secs_f64());
        prep_cpu.push(thread_cpu_seconds() - c0);
        bat = Some(b);
    }
    let bat = bat.ok_or("no repeats")?;
    let zs = curve_positions();
    let specs: Vec<CollisionSpec> = zs.iter().map(|&z| base_spec(z)).collect();
    let (mut times, mut cpu) = (Vec::new(), Vec::new());
    let mut speeds = Vec::new();
    for _ in 0..sz.curve_repeats {
        let c0 = thread_cpu_seconds();
        let t0 = Instant::now();
        speeds = specs
            .iter()
            .map(|s| simulate(s, &bat, None).map(|o| o.exit_speed))
            .collect::<Result<Vec<f64>, _>>()
            .map_err(err("curve"))?;
        times.push(t0.elapsed().as_secs_f64());
        cpu.push(thread_cpu_seconds() - c0);
    }
    Ok(CurveBench {
        points: zs.len(),
        curve_seconds: median(times),
        curve_cpu_seconds: median(cpu),
        prepare_seconds: median(prep),
        prepare_cpu_seconds: median(prep_cpu),
        exit_speed_min: speeds.iter().copied().fold(f64::INFINITY, f64::min),
        exit_speed_max: speeds.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        repeats: sz.curve_repeats,
    })
}

/// A sink that keeps nothing.
struct NullSink;

impl Sink for NullSink {
    fn is_done(&self, _index: usize) -> bool {
        false
    }
    fn write(&mut self, rec: PointRecord) -> Result<(), String> {
        std::hint::black_box(rec);
        Ok(())
    }
    fn finish(&mut self) -> Result<(), String> {
        Ok(())
    }
}

/// A sink that times the calls into another (wall and CPU time of the calling thread; each
/// call runs on one thread), or, switched off, only passes them on: reading a thread's CPU
/// clock is a system call (~0.6 µs here), two per record, which the store runs compared with
/// null runs must not pay (a bias of about 0.5 % of the small study's wall against the store).
struct TimedSink<K> {
    inner: K,
    on: bool,
    journal: Duration,
    finish: Duration,
    journal_cpu: f64,
    finish_cpu: f64,
}

impl<K> TimedSink<K> {
    fn new(inner: K, on: bool) -> Self {
        TimedSink {
            inner,
            on,
            journal: Duration::ZERO,
            finish: Duration::ZERO,
            journal_cpu: 0.0,
            finish_cpu: 0.0,
        }
    }
}

fn timed<R>(on: bool, wall: &mut Duration, cpu: &mut f64, f: impl FnOnce() -> R) -> R {
    if !on {
        return f();
    }
    let c0 = thread_cpu_seconds();
    let t0 = Instant::now();
    let r = f();
    *wall += t0.elapsed();
    *cpu += thread_cpu_seconds() - c0;
    r
}

impl<K: Sink> Sink for TimedSink<K> {
    fn is_done(&self, index: usize) -> bool {
        self.inner.is_done(index)
    }
    fn write(&mut self, rec: PointRecord) -> Result<(), String> {
        let inner = &mut self.inner;
        timed(self.on, &mut self.journal, &mut self.journal_cpu, || {
            inner.write(rec)
        })
    }
    fn idle(&mut self) -> Result<(), String> {
        let inner = &mut self.inner;
        timed(self.on, &mut self.journal, &mut self.journal_cpu, || {
            inner.idle()
        })
    }
    fn finish(&mut self) -> Result<(), String> {
        let inner = &mut self.inner;
        timed(self.on, &mut self.finish, &mut self.finish_cpu, || {
            inner.finish()
        })
    }
}

/// A wave-model study: the 45-point curve × `omegas` swing speeds, optional history block.
pub fn curve_study_text(name: &str, omegas: usize, history: &str) -> String {
    let omega = if omegas <= 1 {
        "[0]".to_string()
    } else {
        format!("{{linspace: [0, -50, {omegas}]}}")
    };
    format!(
        "name: {name}\nmodel: wave\nbase:\n  bat: {{preset: r161}}\n  ball: {{speed: 40}}\n  \
         impact: {{z: 0.7}}\ngrid:\n  swing.omega: {omega}\n  impact.z: {{range: [0.40, 0.84, 0.01]}}\n{history}"
    )
}

pub fn load_study(text: &str, name: &str) -> Result<Study, String> {
    study::load_str(
        text,
        Path::new(&format!("{name}.yaml")),
        &LoadOptions::default(),
    )
    .map_err(|e| format!("bench study {name}: {e}"))
}

/// CPU seconds (user + system) of this process so far, all threads (ns resolution).
fn process_cpu_seconds() -> f64 {
    cpu_clock_seconds(libc::CLOCK_PROCESS_CPUTIME_ID)
}

/// Wall and CPU seconds of one null-sink run.
fn run_null(
    study: &Study,
    bats: &run::PreparedBats<crate::model::Target>,
    pool: &rayon::ThreadPool,
) -> Result<(f64, f64), String> {
    let stop = AtomicBool::new(false);
    let c0 = process_cpu_seconds();
    let t0 = Instant::now();
    let (report, _) = run::run_plan(
        &study.plan,
        &ModelSimulator,
        bats,
        None,
        NullSink,
        pool,
        &RunOptions::default(),
        &stop,
    )
    .map_err(err("run"))?;
    let t = t0.elapsed().as_secs_f64();
    let c = process_cpu_seconds() - c0;
    if report.failed > 0 {
        return Err(format!("bench run: {} points failed", report.failed));
    }
    Ok((t, c))
}

fn bench_parallel(sz: &Sizes, threads: usize) -> Result<ParallelBench, String> {
    let study = load_study(
        &curve_study_text("bench-parallel", sz.parallel_omegas, ""),
        "bench-parallel",
    )?;
    let pool1 = run::build_pool(1).map_err(err("pool"))?;
    let pool_n = run::build_pool(threads).map_err(err("pool"))?;
    let bats = run::prepare_bats(&ModelSimulator, &study.plan, &pool1);
    // warm-up (page faults, lazy statics)
    run_null(&study, &bats, &pool_n)?;
    let (mut t1, mut tn, mut eff) = (Vec::new(), Vec::new(), Vec::new());
    let (mut c1, mut cn, mut ceff, mut cores) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for _ in 0..sz.parallel_repeats {
        let (a, ca) = run_null(&study, &bats, &pool1)?;
        let (b, cb) = run_null(&study, &bats, &pool_n)?;
        t1.push(a);
        tn.push(b);
        eff.push(a / (threads as f64 * b));
        c1.push(ca);
        cn.push(cb);
        ceff.push(ca / cb);
        cores.push(cb / b);
    }
    let n = study.plan.n_points();
    let resolve = {
        let mut v = Vec::new();
        for _ in 0..3 {
            let t0 = Instant::now();
            for i in 0..n.min(2000) {
                std::hint::black_box(study.plan.point(i).ok());
            }
            v.push(t0.elapsed().as_secs_f64() * 1e6 / n.min(2000) as f64);
        }
        median(v)
    };
    Ok(ParallelBench {
        points: n,
        threads,
        seconds_1: median(t1),
        seconds_n: median(tn),
        efficiency: median(eff),
        cpu_seconds_1: median(c1),
        cpu_seconds_n: median(cn),
        cpu_efficiency: median(ceff),
        cores_obtained: median(cores),
        resolve_us_per_point: resolve,
        repeats: sz.parallel_repeats,
    })
}

fn history_bytes(h: &HistoryRequest) -> u64 {
    use crate::model::outcome::HistoryField as F;
    let series: usize = h
        .fields
        .iter()
        .map(|f| match f {
            F::Displacement => h.z.len(),
            F::RigidMotion => 2,
            _ => 1,
        })
        .sum();
    (series * h.n_samples * 8) as u64
}

/// Run `study` through the driver and the real store in `dir`; time the store's calls.
fn bench_write(
    case: &str,
    study: &Study,
    dir: &Path,
    threads: usize,
) -> Result<WriteShare, String> {
    let pool = run::build_pool(threads).map_err(err("pool"))?;
    bench_write_to(case, case, study, dir, &pool, true)
}

/// `repeats` store runs, each beside a null-sink run of the same plan (the medians of the
/// store walls, the null walls and the per-pair overheads), then a few store runs that time
/// the store's calls: the breakdown comes from the timed run of median wall time. The pairs
/// run untimed: the timing itself costs the store runs a clock system call per call.
pub fn bench_write_vs_null(
    case: &str,
    study: &Study,
    dir: &Path,
    threads: usize,
    repeats: usize,
) -> Result<WriteShare, String> {
    let pool = run::build_pool(threads).map_err(err("pool"))?;
    let (mut stores, mut nulls, mut overheads) = (Vec::new(), Vec::new(), Vec::new());
    // from the bats' preparation on, as in `batstudy run`: the store begins its file while
    // the bats are prepared
    let null_run = || -> Result<f64, String> {
        let t0 = Instant::now();
        let bats = run::prepare_bats(&ModelSimulator, &study.plan, &pool);
        let (run, _) = run_null(study, &bats, &pool)?;
        std::hint::black_box(run);
        Ok(t0.elapsed().as_secs_f64())
    };
    let store_run = |k: usize, timed: bool| {
        bench_write_to(case, &format!("{case}-{k}"), study, dir, &pool, timed)
    };
    let repeats = repeats.max(1);
    for k in 0..repeats {
        // the order alternates within pairs: whichever runs second is measurably faster on
        // this machine, by a few percent either way
        let (null, store) = if k % 2 == 0 {
            let null = null_run()?;
            (null, store_run(k, false)?.wall_seconds)
        } else {
            let store = store_run(k, false)?.wall_seconds;
            (null_run()?, store)
        };
        overheads.push((store - null) / store);
        nulls.push(null);
        stores.push(store);
    }
    let mut timed = (0..(repeats / 8).clamp(1, 9))
        .map(|k| store_run(repeats + k, true))
        .collect::<Result<Vec<_>, _>>()?;
    timed.sort_by(|a, b| a.wall_seconds.total_cmp(&b.wall_seconds));
    let mut w = timed.swap_remove(timed.len() / 2);
    w.null_wall_seconds = Some(median(nulls));
    w.untimed_wall_seconds = Some(median(stores));
    overheads.sort_by(|a, b| a.total_cmp(b));
    let n = overheads.len();
    w.wall_overhead_quartiles = Some((overheads[n / 4], overheads[(3 * n) / 4]));
    w.wall_overhead = Some(median(overheads));
    w.repeats = repeats;
    Ok(w)
}

/// One store run on `pool` (the null runs it is compared with use the same pool: a pool
/// built for each store run alone made its threads start cold, a bias of about 1 % against
/// the store on the small study).
fn bench_write_to(
    case: &str,
    file: &str,
    study: &Study,
    dir: &Path,
    pool: &rayon::ThreadPool,
    timed: bool,
) -> Result<WriteShare, String> {
    let threads = pool.current_num_threads();
    let out: PathBuf = dir.join(format!("{file}.h5"));
    let rss_before = reset_peak();
    let c0 = process_cpu_seconds();
    // from the bats' preparation on, as in `batstudy run` (`cli::run_with`)
    let t0 = Instant::now();
    let (bats, begun) = run::prepare_bats_alongside(&ModelSimulator, &study.plan, pool, || {
        store::begin(&out, &study.plan.shape)
    });
    let history = study.history_request(bats.max_length());
    let info = study.info(bats.variants.clone(), history.clone());
    let session = begun
        .and_then(|b| store::open_begun(&out, &info, &store::StoreOptions::default(), Some(b)))
        .map_err(err("open the results file"))?;
    let sink = TimedSink::new(StoreSink::new(session), timed);
    let stop = AtomicBool::new(false);
    let opts = RunOptions {
        jobs: threads,
        ..RunOptions::default()
    };
    let (report, sink) = run::run_plan(
        &study.plan,
        &ModelSimulator,
        &bats,
        history.as_ref(),
        sink,
        pool,
        &opts,
        &stop,
    )
    .map_err(err("run"))?;
    let wall = t0.elapsed().as_secs_f64();
    let cpu = process_cpu_seconds() - c0;
    let peak = rss_before.and_then(|_| peak_rss());
    if report.failed > 0 {
        return Err(format!("bench {case}: {} points failed", report.failed));
    }
    let n = study.plan.n_points();
    let journal = sink.journal.as_secs_f64();
    let fin = sink.finish.as_secs_f64();
    Ok(WriteShare {
        case: case.to_string(),
        points: n,
        threads,
        file_bytes: std::fs::metadata(&out).map_or(0, |m| m.len()),
        wall_seconds: wall,
        journal_seconds: journal,
        final_file_seconds: fin,
        share: (journal + fin) / wall,
        cpu_seconds: cpu,
        journal_cpu_seconds: sink.journal_cpu,
        final_file_cpu_seconds: sink.finish_cpu,
        cpu_share: (sink.journal_cpu + sink.finish_cpu) / cpu,
        peak_rss_bytes: peak,
        rss_before_bytes: rss_before,
        history_bytes_in_memory: history.as_ref().map_or(0, history_bytes) * n as u64,
        null_wall_seconds: None,
        wall_overhead: None,
        wall_overhead_quartiles: None,
        untimed_wall_seconds: None,
        repeats: 1,
    })
}

/// The 10-million-point summary-only plan (rigid model, null sink): memory stays flat.
fn bench_plan_memory(
    sz: &Sizes,
    threads: usize,
) -> Result<(usize, f64, Option<u64>, Option<u64>), String> {
    let [a, b, c] = sz.plan_points;
    let text = format!(
        "name: bench-plan\nmodel: rigid\nbase:\n  bat: {{preset: r161}}\n  ball: {{speed: 40}}\n  \
         impact: {{z: 0.7}}\ngrid:\n  ball.speed: {{linspace: [30, 50, {c}]}}\n  \
         swing.omega: {{linspace: [0, -50, {b}]}}\n  impact.z: {{linspace: [0.40, 0.84, {a}]}}\n"
    );
    let rss_before = reset_peak();
    let t0 = Instant::now();
    let study = load_study(&text, "bench-plan")?;
    let pool = run::build_pool(threads).map_err(err("pool"))?;
    let bats = run::prepare_bats(&ModelSimulator, &study.plan, &pool);
    let stop = AtomicBool::new(false);
    let (report, _) = run::run_plan(
        &study.plan,
        &ModelSimulator,
        &bats,
        None,
        NullSink,
        &pool,
        &RunOptions {
            jobs: threads,
            ..RunOptions::default()
        },
        &stop,
    )
    .map_err(err("run"))?;
    let t = t0.elapsed().as_secs_f64();
    if report.failed > 0 || report.ok != study.plan.n_points() {
        return Err(format!(
            "bench plan: {} ok, {} failed of {}",
            report.ok,
            report.failed,
            study.plan.n_points()
        ));
    }
    Ok((
        study.plan.n_points(),
        t,
        rss_before.and_then(|_| peak_rss()),
        rss_before,
    ))
}

fn mib(b: Option<u64>) -> String {
    b.map_or("n/a".into(), |b| format!("{:.1} MiB", b as f64 / 1048576.0))
}

fn status(ok: bool) -> &'static str {
    if ok {
        "met"
    } else {
        "MISSED"
    }
}

/// Run every section, printing as it goes. Returns the figures.
pub fn run(opts: &BenchOptions, out: &mut dyn Write) -> Result<BenchReport, String> {
    let sz = Sizes::of(opts.quick);
    let mut machine = machine(opts.quick);
    // issue 7 asks for 2 threads (the machine's core count is printed alongside)
    let threads = 2;
    let p = |out: &mut dyn Write, s: String| {
        let _ = writeln!(out, "{s}");
        let _ = out.flush();
    };
    p(
        out,
        format!(
            "batstudy bench{}: {} cores ({}), load average {}",
            if opts.quick { " --quick" } else { "" },
            machine.nproc,
            machine.cpu_model,
            machine.loadavg_start
        ),
    );

    let ib = bench_integrators(&sz)?;
    p(out, "\n== integrators: base case (R161, linear hysteresis, 40 m/s, z = 0.70, ω = 0), one thread".into());
    p(
        out,
        format!(
            "reference (modal, dt/16 = {:.3} µs, {} segments): exit speed {:.7} m/s",
            ib.reference_dt * 1e6,
            ib.reference_segments,
            ib.reference_exit_speed
        ),
    );
    for (name, f) in [("modal ", &ib.modal), ("verlet", &ib.verlet)] {
        p(
            out,
            format!(
                "{name}: exit {:.7} m/s, rel. error {:.2e} ({}), dt {:.3} µs, {} steps, {} modes/nodes, \
                 {:.3} ms/collision ({:.3} ms CPU), {:.0} collisions/s ({:.0} per CPU-second)",
                f.exit_speed,
                f.rel_error,
                if f.rel_error <= ACCURACY_TARGET { "≤ 1e-4" } else { "ABOVE 1e-4" },
                f.dt * 1e6,
                f.steps,
                f.modes,
                f.seconds_per_collision * 1e3,
                f.cpu_seconds_per_collision * 1e3,
                f.collisions_per_second,
                f.collisions_per_cpu_second
            ),
        );
    }
    p(
        out,
        format!(
            "speed-up modal/verlet: {:.1}× wall, {:.1}× CPU (medians of {} repeats; target ≥ \
             {SPEEDUP_TARGET}×: {})",
            ib.speedup,
            ib.speedup_cpu,
            ib.repeats,
            status(ib.speedup.min(ib.speedup_cpu) >= SPEEDUP_TARGET)
        ),
    );

    let cb = bench_curve(&sz)?;
    p(
        out,
        "\n== exit-speed curve: 45 impact positions 0.40..0.84 m, bat prepared once, one thread"
            .into(),
    );
    p(
        out,
        format!(
            "curve {:.2} ms wall, {:.2} ms CPU (target < {:.0} ms: {}), {:.3} ms CPU per point; \
             prepare_bat {:.2} ms wall, {:.2} ms CPU; exit speed {:.3}..{:.3} m/s",
            cb.curve_seconds * 1e3,
            cb.curve_cpu_seconds * 1e3,
            CURVE_TARGET_S * 1e3,
            status(cb.curve_seconds < CURVE_TARGET_S),
            cb.curve_cpu_seconds * 1e3 / cb.points as f64,
            cb.prepare_seconds * 1e3,
            cb.prepare_cpu_seconds * 1e3,
            cb.exit_speed_min,
            cb.exit_speed_max
        ),
    );

    let pb = bench_parallel(&sz, threads)?;
    p(
        out,
        format!(
            "\n== parallel: {} points through run_plan (null sink)",
            pb.points
        ),
    );
    p(
        out,
        format!(
            "1 thread {:.3} s ({:.0} points/s), {} threads {:.3} s ({:.0} points/s): efficiency {:.1} % \
             (target ≥ {:.0} %: {}); plan resolve {:.1} µs/point",
            pb.seconds_1,
            pb.points as f64 / pb.seconds_1,
            pb.threads,
            pb.seconds_n,
            pb.points as f64 / pb.seconds_n,
            pb.efficiency * 100.0,
            EFFICIENCY_TARGET * 100.0,
            status(pb.efficiency >= EFFICIENCY_TARGET),
            pb.resolve_us_per_point
        ),
    );
    p(
        out,
        format!(
            "CPU time: 1 thread {:.3} s, {} threads {:.3} s: CPU efficiency {:.1} % (work added by \
             running in parallel); the {}-thread run got {:.2} cores on average",
            pb.cpu_seconds_1,
            pb.threads,
            pb.cpu_seconds_n,
            pb.cpu_efficiency * 100.0,
            pb.threads,
            pb.cores_obtained
        ),
    );

    let dir = tempfile_dir()?;
    let summary_study = load_study(
        &curve_study_text("bench-summary", sz.summary_omegas, ""),
        "bench-summary",
    )?;
    let hist =
        "history:\n  fields: [force, compression, ball_velocity, displacement, rigid_motion]\n  \
                interval: 1.0e-5\n  duration: 2.0e-3\n  z_step: 0.01\n";
    let history_study = load_study(
        &curve_study_text("bench-history", sz.history_omegas, hist),
        "bench-history",
    )?;
    let ws = bench_write_vs_null(
        "summary",
        &summary_study,
        dir.path(),
        threads,
        sz.write_repeats,
    )?;
    let wh = bench_write("history", &history_study, dir.path(), threads)?;
    // ten times the points: the store's fixed cost (file skeleton, fsyncs) spread thinner
    let large_study = load_study(
        &curve_study_text("bench-summary-large", 10 * sz.summary_omegas, ""),
        "bench-summary-large",
    )?;
    let wl = bench_write_vs_null(
        "summary-large",
        &large_study,
        dir.path(),
        threads,
        sz.write_repeats.div_ceil(2).min(24),
    )?;
    p(
        out,
        format!("\n== HDF5 writing: real driver + store, {threads} threads"),
    );
    for w in [&ws, &wl, &wh] {
        p(
            out,
            format!(
                "{:13}: {} points in {:.3} s{}; in store calls: journal {:.3} s + finish {:.3} s = {:.2} % of wall; \
                 CPU: {:.3} s, store {:.3} + {:.3} s = {:.2} % of CPU; file {:.1} MiB",
                w.case,
                w.points,
                w.wall_seconds,
                match (w.untimed_wall_seconds, w.null_wall_seconds, w.wall_overhead, w.wall_overhead_quartiles) {
                    (Some(store), Some(null), Some(o), Some((q1, q3))) => format!(
                        " (timed); untimed {store:.3} s vs {null:.3} s with a null sink: writing adds {:.2} % of wall \
                         (median of {} pairs, quartiles {:.2}..{:.2} %; target ≤ 5 %: {})",
                        o * 100.0,
                        w.repeats,
                        q1 * 100.0,
                        q3 * 100.0,
                        status(o <= HDF5_SHARE_TARGET)
                    ),
                    _ => String::new(),
                },
                w.journal_seconds,
                w.final_file_seconds,
                w.share * 100.0,
                w.cpu_seconds,
                w.journal_cpu_seconds,
                w.final_file_cpu_seconds,
                w.cpu_share * 100.0,
                w.file_bytes as f64 / 1048576.0
            ),
        );
    }

    let (plan_points, plan_seconds, plan_peak, plan_before) = bench_plan_memory(&sz, threads)?;
    let [a, b, c] = sz.store_points;
    let store_study = |name: &str, omegas: usize| {
        load_study(
            &format!(
                "name: {name}\nmodel: rigid\nbase:\n  bat: {{preset: r161}}\n  ball: {{speed: 40}}\n  \
                 impact: {{z: 0.7}}\ngrid:\n  ball.speed: {{linspace: [30, 50, {c}]}}\n  \
                 swing.omega: {{linspace: [0, -50, {omegas}]}}\n  impact.z: {{linspace: [0.40, 0.84, {a}]}}\n"
            ),
            name,
        )
    };
    // the study at full size and at four times that: the build's window is capped, so the
    // store's memory above the start should not grow between the two
    let small_study = store_study("bench-store", b)?;
    let store_study = store_study("bench-store-large", 4 * b)?;
    let wsm = bench_write("store-small", &small_study, dir.path(), threads)?;
    let wst = bench_write("store", &store_study, dir.path(), threads)?;
    let mb = MemoryBench {
        plan_points,
        plan_seconds,
        plan_peak_rss_bytes: plan_peak,
        plan_rss_before_bytes: plan_before,
        channel_capacity: RunOptions::default().channel_capacity,
        history_points: wh.points,
        history_peak_rss_bytes: wh.peak_rss_bytes,
        history_bytes_in_memory: wh.history_bytes_in_memory,
        build_memory: store::StoreOptions::default().build_memory,
        store_small_points: wsm.points,
        store_small_peak_rss_bytes: wsm.peak_rss_bytes,
        store_small_rss_before_bytes: wsm.rss_before_bytes,
        store_points: wst.points,
        store_seconds: wst.wall_seconds,
        store_peak_rss_bytes: wst.peak_rss_bytes,
        store_rss_before_bytes: wst.rss_before_bytes,
    };
    p(
        out,
        "\n== memory: peak resident set (VmHWM reset before each case)".into(),
    );
    p(
        out,
        format!(
            "summary-only plan of {} points (rigid model, driver, null sink, {threads} threads, {:.1} s): \
             peak {} (before {})",
            mb.plan_points,
            mb.plan_seconds,
            mib(mb.plan_peak_rss_bytes),
            mib(mb.plan_rss_before_bytes)
        ),
    );
    let above = |peak: Option<u64>, before: Option<u64>, n: usize| match (peak, before) {
        (Some(p), Some(b)) => format!(
            "{} above the start ({:.0} B/point)",
            mib(Some(p.saturating_sub(b))),
            p.saturating_sub(b) as f64 / n as f64
        ),
        _ => "n/a".into(),
    };
    for (n, peak, before, secs) in [
        (
            mb.store_small_points,
            mb.store_small_peak_rss_bytes,
            mb.store_small_rss_before_bytes,
            wsm.wall_seconds,
        ),
        (
            mb.store_points,
            mb.store_peak_rss_bytes,
            mb.store_rss_before_bytes,
            mb.store_seconds,
        ),
    ] {
        p(
            out,
            format!(
                "summary-only study of {n} points with the store (rigid model, {threads} threads, {secs:.1} s): \
                 peak {}: {}; build budget {}",
                mib(peak),
                above(peak, before, n),
                mib(Some(mb.build_memory as u64))
            ),
        );
    }
    p(
        out,
        format!(
            "history study of {} points (store included): peak {} (before {}); the study's histories \
             as f64 would be {:.1} MiB; channel capacity {} records",
            mb.history_points,
            mib(mb.history_peak_rss_bytes),
            mib(wh.rss_before_bytes),
            mb.history_bytes_in_memory as f64 / 1048576.0,
            mb.channel_capacity
        ),
    );
    machine.loadavg_end = loadavg();
    p(
        out,
        format!("\nload average at the end: {}", machine.loadavg_end),
    );
    Ok(BenchReport {
        machine,
        integrators: ib,
        curve: cb,
        parallel: pb,
        hdf5: vec![ws, wh, wl],
        memory: mb,
    })
}

/// A temporary directory removed on drop (no dev-dependency in the library).
struct TempDir(PathBuf);

impl TempDir {
    fn path(&self) -> &Path {
        &self.0
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn tempfile_dir() -> Result<TempDir, String> {
    let base = std::env::temp_dir();
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_nanos());
    let p = base.join(format!("batstudy-bench-{}-{nanos}", std::process::id()));
    std::fs::create_dir_all(&p).map_err(err("create a temporary directory"))?;
    Ok(TempDir(p))
}

/// `batstudy bench`: run, print, optionally write the figures as JSON. Returns the exit code
/// (0, or 3 when a case could not run).
pub fn main(opts: &BenchOptions, json: Option<&Path>) -> i32 {
    let stdout = std::io::stdout();
    let mut lock = stdout.lock();
    match run(opts, &mut lock) {
        Ok(report) => {
            if let Some(path) = json {
                let text = serde_json::to_string_pretty(&report).expect("report serializes");
                if let Err(e) = std::fs::write(path, text + "\n") {
                    eprintln!("error: cannot write {}: {e}", path.display());
                    return 3;
                }
            }
            0
        }
        Err(e) => {
            eprintln!("error: bench: {e}");
            3
        }
    }
}
