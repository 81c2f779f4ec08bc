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
//! - `scaling`: points/s of a summary and of a full-history study at 1, 2, 4, … threads up to
//!   every core; `writer_headroom`: the points/s the writer alone absorbs (appending
//!   encoded records, then finishing the file) over the points/s one worker computes and
//!   encodes (the cores the writer can keep up with), overall and while the run computes,
//!   and the disk's durable write rate over the bytes one worker produces (the cores any
//!   store on this disk can keep up with);
//!   `curve_process`: the 45-point curve as a whole `batstudy run` process (issue 22);
//! - `memory`: peak resident memory (VmHWM, reset through `/proc/self/clear_refs` before each
//!   case) for a 10-million-point summary-only plan run through the driver with the rigid
//!   model, and for the history study above.
//!
//! Timings are medians of repeats; ratios are medians of per-repeat ratios (baseline and
//! candidate timed back to back), which cancels most of the noise of a shared machine.
//! Timings never go into tests; `tests/bench_quick.rs` checks the accuracy figures only.
//!
//! Files: `cases` (the sizes and studies), `measure` (clocks, timing, peak memory, medians),
//! `sinks` (a null sink and a timing one), `speed` (`integrators`, `curve`), `parallel`,
//! `write_share` (`hdf5`), `memory`, `scaling` (`scaling`, `writer_headroom`,
//! `curve_process`), `report` (targets, printing, JSON). Off the run path:
//! nothing in `run`, `store`, `study` or `model` uses it; the CLI's `bench` command (and
//! `tests/bench_quick.rs`) call it.

mod cases;
mod measure;
mod memory;
mod parallel;
mod report;
mod scaling;
mod sinks;
mod speed;
mod write_share;

pub use cases::{base_spec, curve_positions, curve_study_text, load_study};
pub use memory::MemoryBench;
pub use parallel::ParallelBench;
pub use report::{
    BenchReport, Machine, ACCURACY_TARGET, CURVE_TARGET_S, EFFICIENCY_TARGET, HDF5_SHARE_TARGET,
    SPEEDUP_TARGET,
};
pub use scaling::{CurveProcess, Scaling, ScalingPoint, WriterHeadroom};
pub use speed::{CurveBench, IntegratorBench, IntegratorFigures};
pub use write_share::{bench_write_vs_null, WriteShare};

use std::io::Write;
use std::path::Path;

/// What to run.
#[derive(Debug, Clone, Default)]
pub struct BenchOptions {
    /// Shrink every case so that the whole benchmark takes a few seconds (for tests).
    pub quick: bool,
}

/// Run every section, printing as it goes. Returns the figures.
pub fn run(opts: &BenchOptions, out: &mut dyn Write) -> Result<BenchReport, String> {
    let sz = cases::Sizes::of(opts.quick);
    let mut machine = report::machine(opts.quick);
    // issue 7 asks for 2 threads (the machine's core count is printed alongside)
    let threads = 2;
    report::print_machine(out, &machine);

    let ib = speed::bench_integrators(&sz)?;
    report::print_integrators(out, &ib);

    let cb = speed::bench_curve(&sz)?;
    report::print_curve(out, &cb);

    let pb = parallel::bench_parallel(&sz, threads)?;
    report::print_parallel(out, &pb);

    let dir = write_share::tempfile_dir()?;
    let (ws, wh, wl) = write_share::bench_hdf5(&sz, dir.path(), threads)?;
    report::print_hdf5(out, threads, [&ws, &wl, &wh]);

    let (mb, small_seconds) = memory::bench_memory(&sz, threads, dir.path(), &wh)?;
    report::print_memory(out, threads, &mb, small_seconds, wh.rss_before_bytes);

    let scaling = scaling::bench_scaling(&sz, dir.path())?;
    let headroom = scaling::bench_writer_headroom(&sz, dir.path())?;
    let curve_process = scaling::bench_curve_process(&sz, dir.path())?;
    report::print_scaling(out, &scaling, &headroom, curve_process.as_ref());

    machine.loadavg_end = report::loadavg();
    report::print_end(out, &machine);
    Ok(BenchReport {
        machine,
        integrators: ib,
        curve: cb,
        parallel: pb,
        hdf5: vec![ws, wh, wl],
        memory: mb,
        scaling,
        writer_headroom: headroom,
        curve_process,
    })
}

/// `batstudy bench`: run, print, optionally write the figures as JSON. Returns the exit code
/// (0, or 3 when a case could not run).
pub fn main(opts: &BenchOptions, json: Option<&Path>) -> i32 {
    let stdout = std::io::stdout();
    let mut lock = stdout.lock();
    match run(opts, &mut lock) {
        Ok(report) => {
            if let Some(path) = json {
                if let Err(e) = report::write_json(&report, path) {
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
