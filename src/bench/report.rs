//! The report: the machine, the targets, every section printed as it is measured, and the
//! figures as JSON.

use super::memory::MemoryBench;
use super::parallel::ParallelBench;
use super::speed::{CurveBench, IntegratorBench};
use super::write_share::WriteShare;
use serde::Serialize;
use std::io::Write;
use std::path::Path;

/// Relative exit-speed accuracy both integrators must reach (issue 7).
pub const ACCURACY_TARGET: f64 = 1e-4;
/// Targets of issue 7.
pub const SPEEDUP_TARGET: f64 = 20.0;
pub const CURVE_TARGET_S: f64 = 0.1;
pub const EFFICIENCY_TARGET: f64 = 0.9;
pub const HDF5_SHARE_TARGET: f64 = 0.05;

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
    /// Points/s against threads for a summary and a full-history study.
    pub scaling: super::Scaling,
    /// How many cores the one writer thread keeps up with on the history study.
    pub writer_headroom: super::WriterHeadroom,
    /// The 45-point curve as a whole `batstudy run` process (absent when the bench does not
    /// run as the `batstudy` binary, e.g. in tests).
    pub curve_process: Option<super::CurveProcess>,
}

pub(super) fn machine(quick: bool) -> Machine {
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

pub(super) fn loadavg() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .map(|s| s.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
        .unwrap_or_default()
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

/// Print one line and flush (the report shows as the benchmark goes).
fn line(out: &mut dyn Write, s: String) {
    let _ = writeln!(out, "{s}");
    let _ = out.flush();
}

/// The first line: the machine and its load.
pub(super) fn print_machine(out: &mut dyn Write, machine: &Machine) {
    line(
        out,
        format!(
            "batstudy bench{}: {} cores ({}), load average {}",
            if machine.quick { " --quick" } else { "" },
            machine.nproc,
            machine.cpu_model,
            machine.loadavg_start
        ),
    );
}

pub(super) fn print_integrators(out: &mut dyn Write, ib: &IntegratorBench) {
    line(out, "\n== integrators: base case (R161, linear hysteresis, 40 m/s, z = 0.70, ω = 0), one thread".into());
    line(
        out,
        format!(
            "reference (modal, dt/16 = {:.3} µs, {} segments): exit speed {:.7} m/s",
            ib.reference_dt * 1e6,
            ib.reference_segments,
            ib.reference_exit_speed
        ),
    );
    for (name, f) in [("modal ", &ib.modal), ("verlet", &ib.verlet)] {
        line(
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
    line(
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
}

pub(super) fn print_curve(out: &mut dyn Write, cb: &CurveBench) {
    line(
        out,
        "\n== exit-speed curve: 45 impact positions 0.40..0.84 m, bat prepared once, one thread"
            .into(),
    );
    line(
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
}

pub(super) fn print_scaling(
    out: &mut dyn Write,
    sc: &super::Scaling,
    wh: &super::WriterHeadroom,
    cp: Option<&super::CurveProcess>,
) {
    line(
        out,
        format!(
            "\n== scaling: points/s through the driver and the store ({} summary points, {} history points)",
            sc.summary_points, sc.history_points
        ),
    );
    for p in &sc.points {
        line(
            out,
            format!(
                "{:>3} threads: summary {:.0} points/s, history {:.0} points/s",
                p.threads, p.summary_points_per_second, p.history_points_per_second
            ),
        );
    }
    line(
        out,
        format!(
            "on {} cores: efficiency summary {:.1} %, history {:.1} %; history/summary per core {:.2} \
             (with histories computed but not stored: {:.0} points/s, {:.2})",
            sc.cores,
            sc.summary_efficiency * 100.0,
            sc.history_efficiency * 100.0,
            sc.history_vs_summary_per_core,
            sc.history_compute_points_per_second,
            sc.history_vs_summary_ceiling
        ),
    );
    line(
        out,
        format!(
            "history study on {} cores: deflated {:.0} points/s ({:.1} MiB), `compression: none` \
             {:.0} points/s ({:.1} MiB)",
            sc.cores,
            sc.points
                .last()
                .map_or(0.0, |p| p.history_points_per_second),
            sc.history_file_bytes as f64 / (1 << 20) as f64,
            sc.history_uncompressed_points_per_second,
            sc.history_uncompressed_file_bytes as f64 / (1 << 20) as f64
        ),
    );
    line(
        out,
        format!(
            "history study without displacement (scalar series only) on {} cores: {:.0} points/s, \
             {:.2} of the summary study's per core",
            sc.cores, sc.history_scalar_points_per_second, sc.history_scalar_vs_summary_per_core
        ),
    );
    line(
        out,
        format!(
            "writer headroom: the store's writer absorbs {:.0} points/s ({:.0} while the run \
             computes, then {:.3} s to finish {} points), one worker computes and encodes {:.0} \
             ({:.0} % of it encoding): {:.1} cores ({:.1} while the run computes)",
            wh.writer_points_per_second,
            wh.append_points_per_second,
            wh.finish_seconds,
            wh.points,
            wh.worker_points_per_second,
            wh.worker_encode_share * 100.0,
            wh.headroom,
            wh.run_headroom
        ),
    );
    line(
        out,
        format!(
            "the disk takes {:.0} MB/s made durable (fdatasync); at {:.0} KB of results per point, \
             the output of {:.1} such workers: the most any store on this disk keeps up with",
            wh.disk_bytes_per_second / 1e6,
            wh.file_bytes_per_point / 1e3,
            wh.disk_headroom
        ),
    );
    if let Some(cp) = cp {
        line(
            out,
            format!(
                "the {}-point curve as a `batstudy run` process: median {:.1} ms, min {:.1} ms over {} \
                 runs (`--version` alone {:.1} ms); {:.0}× the NumPy reference's {} s",
                cp.points,
                cp.median_ms,
                cp.min_ms,
                cp.runs,
                cp.version_median_ms,
                cp.speedup_vs_numpy,
                cp.numpy_reference_seconds
            ),
        );
    }
}

pub(super) fn print_parallel(out: &mut dyn Write, pb: &ParallelBench) {
    line(
        out,
        format!(
            "\n== parallel: {} points through run_plan (null sink)",
            pb.points
        ),
    );
    line(
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
    line(
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
}

/// The HDF5 section: summary, summary-large, history.
pub(super) fn print_hdf5(out: &mut dyn Write, threads: usize, shares: [&WriteShare; 3]) {
    line(
        out,
        format!("\n== HDF5 writing: real driver + store, {threads} threads"),
    );
    for w in shares {
        line(
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
}

/// The memory section (`small_seconds`: the small store study's wall time; `history_before`:
/// the history study's resident memory before its run).
pub(super) fn print_memory(
    out: &mut dyn Write,
    threads: usize,
    mb: &MemoryBench,
    small_seconds: f64,
    history_before: Option<u64>,
) {
    line(
        out,
        "\n== memory: peak resident set (VmHWM reset before each case)".into(),
    );
    line(
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
            small_seconds,
        ),
        (
            mb.store_points,
            mb.store_peak_rss_bytes,
            mb.store_rss_before_bytes,
            mb.store_seconds,
        ),
    ] {
        line(
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
    line(
        out,
        format!(
            "history study of {} points (store included): peak {} (before {}); the study's histories \
             as f64 would be {:.1} MiB; channel capacity {} records",
            mb.history_points,
            mib(mb.history_peak_rss_bytes),
            mib(history_before),
            mb.history_bytes_in_memory as f64 / 1048576.0,
            mb.channel_capacity
        ),
    );
}

pub(super) fn print_end(out: &mut dyn Write, machine: &Machine) {
    line(
        out,
        format!("\nload average at the end: {}", machine.loadavg_end),
    );
}

/// Write the figures as JSON to `path`.
pub(super) fn write_json(report: &BenchReport, path: &Path) -> std::io::Result<()> {
    let text = serde_json::to_string_pretty(report).expect("report serializes");
    std::fs::write(path, text + "\n")
}
