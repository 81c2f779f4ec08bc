//! The report: every section printed as it is measured, and the figures as JSON. Facts
//! about this machine only: no targets, no reference times.

use super::batted::Batted;
use super::headroom::WriterHeadroom;
use super::machine::Machine;
use super::memory::{MemoryBench, RunMemory};
use super::scaling::{Scaling, ScalingPoint};
use serde::Serialize;
use std::io::Write;
use std::path::Path;

/// Everything measured.
#[derive(Debug, Clone, Serialize)]
pub struct BenchReport {
    pub machine: Machine,
    /// Points/s against threads for a summary, a full-history and a scalar-history study.
    pub scaling: Scaling,
    /// How many workers the one writer thread, and the disk, keep up with (history study).
    pub writer_headroom: WriterHeadroom,
    /// Peak resident memory of the runs.
    pub memory: MemoryBench,
    /// The batted ball's flight: an undercut study with and without it.
    pub batted: Batted,
    /// Design candidates per second of a profile search.
    pub optimize: super::optimize::OptimizeBench,
    /// One collision a call (`batstudy.simulate`) against a study's point.
    pub simulate: super::simulate::SimulateBench,
    /// The bat lab: an edit to its answer.
    pub lab: super::lab::LabBench,
}

fn mib(b: Option<u64>) -> String {
    b.map_or("n/a".into(), |b| format!("{:.1} MiB", b as f64 / 1048576.0))
}

fn gib(b: u64) -> String {
    format!("{:.1} GiB", b as f64 / (1u64 << 30) as f64)
}

/// Print one line and flush (the report shows as the benchmark goes).
fn line(out: &mut dyn Write, s: String) {
    let _ = writeln!(out, "{s}");
    let _ = out.flush();
}

/// Is the one-minute load average at least a quarter of the cores (other work sharing them)?
fn busy(loadavg: &str, cores: usize) -> bool {
    let load1 = loadavg.split_whitespace().next();
    load1
        .and_then(|l| l.parse::<f64>().ok())
        .is_some_and(|l| l >= 0.25 * cores as f64)
}

/// The machine: CPU, cores, memory, OS, load, where the files go.
pub(super) fn print_machine(out: &mut dyn Write, m: &Machine) {
    let quick = if m.quick {
        " --quick (cases shrunk)"
    } else {
        ""
    };
    line(
        out,
        format!("batstudy bench{quick}: what this machine does"),
    );
    line(out, format!("CPU     {}", m.cpu_model));
    line(
        out,
        format!(
            "cores   {} available to this process ({} listed by the kernel)",
            m.nproc, m.logical_cpus
        ),
    );
    let limit = m
        .memory_limit_bytes
        .map_or(String::new(), |l| format!(", limited to {} here", gib(l)));
    let memory = m.memory_bytes.map_or("unknown".into(), gib);
    line(out, format!("memory  {memory}{limit}"));
    line(out, format!("OS      {} (kernel {})", m.os, m.kernel));
    line(
        out,
        format!("load    {} (load average at the start)", m.loadavg_start),
    );
    if busy(&m.loadavg_start, m.nproc) {
        line(
            out,
            "        other work is running: the rates below are lower than this machine gives \
             idle"
                .into(),
        );
    }
    line(out, format!("files   under {} (`--dir`)", m.dir));
    line(
        out,
        format!("batstudy {} (commit {})", m.batstudy_version, m.git_commit),
    );
}

/// The scaling table's head, before the first thread count is measured.
pub(super) fn print_scaling_head(out: &mut dyn Write, threads: &[usize]) {
    let list: Vec<String> = threads.iter().map(|t| t.to_string()).collect();
    line(
        out,
        format!(
            "\n== points/s on {} threads: wave model, driver and store, as `batstudy run` does",
            list.join(", ")
        ),
    );
    line(
        out,
        "summary: the summaries only; history: force, compression, ball velocity, rigid motion \
         and the bat's displacement on a 1 cm grid; modal history: the same with the \
         displacement in modal form (the default); scalar history: the same without \
         displacement. The studies grow with the threads past a minimum. (%): parallel \
         efficiency, points/s per thread against the first row"
            .into(),
    );
    line(
        out,
        format!(
            "{:>7}  {:>18}  {:>18}  {:>18}  {:>18}",
            "threads", "summary", "history", "modal history", "scalar history"
        ),
    );
}

pub(super) fn print_scaling_point(out: &mut dyn Write, p: &ScalingPoint) {
    let cell = |rate: f64, eff: f64| format!("{rate:.0} ({:.0} %)", eff * 100.0);
    line(
        out,
        format!(
            "{:>7}  {:>18}  {:>18}  {:>18}  {:>18}",
            p.threads,
            cell(p.summary_points_per_second, p.summary_efficiency),
            cell(p.history_points_per_second, p.history_efficiency),
            cell(
                p.history_modal_points_per_second,
                p.history_modal_efficiency
            ),
            cell(
                p.history_scalar_points_per_second,
                p.history_scalar_efficiency
            ),
        ),
    );
}

/// What the scaling runs on the most threads add: the studies' sizes, the history study
/// with nothing stored and without compression.
pub(super) fn print_scaling_end(out: &mut dyn Write, sc: &Scaling) {
    let last = sc.points.last();
    line(
        out,
        format!(
            "on {} threads: {} summary points, {} history points per run; a history point costs \
             {:.1} summary points ({:.1} in modal form, {:.1} with scalar histories): {:.2}, {:.2} \
             and {:.2} of the summary study's points/s per core",
            sc.cores,
            sc.summary_points,
            sc.history_points,
            1.0 / sc.history_vs_summary_per_core,
            1.0 / sc.history_modal_vs_summary_per_core,
            1.0 / sc.history_scalar_vs_summary_per_core,
            sc.history_vs_summary_per_core,
            sc.history_modal_vs_summary_per_core,
            sc.history_scalar_vs_summary_per_core
        ),
    );
    let mut runs = sc.history_modal_vs_summary_per_core_per_repeat.clone();
    runs.sort_by(f64::total_cmp);
    if let (Some(lo), Some(hi)) = (runs.first(), runs.last()) {
        line(
            out,
            format!(
                "in modal form, repeat by repeat (each modal run over the summary run of its \
                 repeat): {lo:.2} to {hi:.2} over {} repeats",
                runs.len()
            ),
        );
    }
    if let (Some(m), Some(s)) = (sc.history_modal_stolen_share, sc.summary_stolen_share) {
        line(
            out,
            format!(
                "the machine's host took {:.1} % of its CPU time during the modal runs, {:.1} % \
                 during the summary runs (steal time: in a virtual machine, the host's other \
                 work, including writing this machine's disk)",
                100.0 * m,
                100.0 * s
            ),
        );
    }
    line(
        out,
        format!(
            "history study on {} threads: {:.0} points/s stored ({:.1} MiB, {:.0} KB/point), \
             {:.0} with `compression: none` ({:.1} MiB), {:.0} computed and not stored",
            sc.cores,
            last.map_or(0.0, |p| p.history_points_per_second),
            sc.history_file_bytes as f64 / 1048576.0,
            sc.history_file_bytes as f64 / sc.history_points as f64 / 1e3,
            sc.history_uncompressed_points_per_second,
            sc.history_uncompressed_file_bytes as f64 / 1048576.0,
            sc.history_compute_points_per_second
        ),
    );
    line(
        out,
        format!(
            "modal history study on {} threads: {:.0} points/s stored ({:.1} MiB, {:.0} KB/point), \
             {:.0} computed and not stored",
            sc.cores,
            sc.history_modal_points_per_second,
            sc.history_modal_file_bytes as f64 / 1048576.0,
            sc.history_modal_file_bytes as f64 / sc.history_points as f64 / 1e3,
            sc.history_modal_compute_points_per_second
        ),
    );
}

/// The writer's and the disk's headroom, against the cores measured: the displacement on its
/// grid, then in modal form.
pub(super) fn print_headroom(out: &mut dyn Write, wh: &WriterHeadroom, cores: usize) {
    line(
        out,
        format!(
            "\n== writer and disk: the history study ({} points), displacement on the grid / modal",
            wh.points
        ),
    );
    let forms = [
        (
            "grid ",
            wh.worker_points_per_second,
            wh.worker_encode_share,
            wh.writer_points_per_second,
            wh.append_points_per_second,
            wh.finish_seconds,
            wh.headroom,
            wh.run_headroom,
        ),
        (
            "modal",
            wh.modal_worker_points_per_second,
            wh.modal_worker_encode_share,
            wh.modal_writer_points_per_second,
            wh.modal_append_points_per_second,
            wh.modal_finish_seconds,
            wh.modal_headroom,
            wh.modal_run_headroom,
        ),
    ];
    for (form, worker, share, writer, append, finish, headroom, run) in forms {
        line(
            out,
            format!(
                "{form}: one worker computes and encodes {worker:.0} points/s ({:.0} % of it \
                 compressing); the one writer thread absorbs {writer:.0} points/s ({append:.0} \
                 while the run computes, then {finish:.3} s to finish the file): it keeps up with \
                 {headroom:.1} workers ({run:.1} while the run computes)",
                share * 100.0
            ),
        );
    }
    line(
        out,
        format!(
            "the disk makes {:.0} MB/s durable (fdatasync of {} MiB); at {:.0} KB per history \
             point on the grid, the output of {:.1} workers; at {:.0} KB in modal form, of {:.1}",
            wh.disk_bytes_per_second / 1e6,
            wh.disk_probe_mib,
            wh.file_bytes_per_point / 1e3,
            wh.disk_headroom,
            wh.modal_file_bytes_per_point / 1e3,
            wh.modal_disk_headroom
        ),
    );
    line(
        out,
        format!(
            "the journal: {:.1} KB per history point on the grid, {:.1} KB in modal form (the \
             histories placed in the file as they came are journalled by their place there)",
            wh.journal_bytes_per_point / 1e3,
            wh.modal_journal_bytes_per_point / 1e3
        ),
    );
    for (form, headroom, disk) in [
        ("grid", wh.headroom, wh.disk_headroom),
        ("modal", wh.modal_headroom, wh.modal_disk_headroom),
    ] {
        let bound = headroom.min(disk);
        let verdict = if bound >= cores as f64 {
            "the writer and the disk keep up with every thread"
        } else if disk < headroom {
            "the disk, not the cores, bounds full-history studies"
        } else {
            "the writer, not the cores, bounds full-history studies"
        };
        line(
            out,
            format!("{form}: on {cores} threads, {bound:.1} workers' worth of headroom: {verdict}"),
        );
    }
}

fn print_run_memory(out: &mut dyn Write, what: &str, r: &RunMemory) {
    line(
        out,
        format!(
            "{what}: {} points on {} threads, {:.2} s: peak {} (before the run {})",
            r.points,
            r.threads,
            r.seconds,
            mib(r.peak_rss_bytes),
            mib(r.rss_before_bytes)
        ),
    );
}

pub(super) fn print_memory(out: &mut dyn Write, mb: &MemoryBench) {
    line(
        out,
        "\n== peak memory: resident set of this process (VmHWM, reset before each run)".into(),
    );
    print_run_memory(out, "summary study       ", &mb.summary);
    print_run_memory(out, "history study       ", &mb.history);
    print_run_memory(out, "scalar-history study", &mb.history_scalar);
    print_run_memory(out, "modal-history study ", &mb.history_modal);
    print_run_memory(out, "large summary study ", &mb.large_summary);
    line(
        out,
        format!(
            "(the history study's histories would take {} as f64; the store keeps at most {} \
             records in flight and builds the final file in windows of {}: memory does not grow \
             with a study's points)",
            mib(Some(mb.history_bytes_in_memory)),
            mb.channel_capacity,
            mib(Some(mb.build_memory as u64))
        ),
    );
}

pub(super) fn print_batted(out: &mut dyn Write, b: &Batted) {
    line(
        out,
        format!(
            "\n== the batted ball: an undercut study ({} points, {} threads) with and without its flight\n\
             {:.0} points/s without, {:.0} with: the flight costs {:.2}× the time per point",
            b.points,
            b.threads,
            b.without_flight_points_per_second,
            b.with_flight_points_per_second,
            b.flight_time_ratio
        ),
    );
}

pub(super) fn print_simulate(out: &mut dyn Write, s: &super::simulate::SimulateBench) {
    line(
        out,
        format!(
            "\n== one collision a call (batstudy.simulate), {} calls, against a study's point, 1 thread\n\
             a point of the study {:.2} ms, a call {:.2} ms (the first, its bat prepared: {:.1} ms): \
             a call costs {:.2}× a point",
            s.points,
            s.study_seconds_per_point * 1e3,
            s.call_seconds * 1e3,
            s.first_call_seconds * 1e3,
            s.call_to_point_ratio
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
    crate::store::journal::write_whole(path, (text + "\n").as_bytes())
}
