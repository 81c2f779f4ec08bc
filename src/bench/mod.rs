//! `batstudy bench`: what this machine does with batstudy, measured in one run and printed
//! as facts about the machine (no targets, no reference times).
//!
//! Sections (each a field of [`BenchReport`]):
//! - `machine`: CPU model, cores available and listed, memory (and a cgroup's limit), OS,
//!   load average, where the files went;
//! - `scaling`: points/s of three wave-model studies through the real driver and store, as
//!   `batstudy run` runs them (a summary-only study, one with full histories including the
//!   bat's displacement, one with the scalar histories only), at 1, 2, 4, … threads up to
//!   every core (or `--threads`), with the parallel efficiency of each against the first
//!   thread count; a study grows with the threads past a minimum, so that every run lasts
//!   long enough to time. On the most threads, the history study also with nothing stored
//!   and with `compression: none`;
//! - `writer_headroom`: the points/s the one writer thread absorbs on the history study
//!   (appending encoded records, then finishing the file) over the points/s one worker
//!   computes and encodes: the workers it keeps up with; and the disk's durable write rate
//!   (`fdatasync`) over the bytes one worker produces: the workers any store on this disk
//!   keeps up with;
//! - `optimize`: design candidates per second of a 6-variable profile search;
//! - `simulate`: one collision a call (`batstudy.simulate`, each its own one-point study, the
//!   bat prepared once across calls) against the same collisions as a study's points on one
//!   thread: the ratio of a call's time to a point's;
//! - `lab`: the bat lab's latency, from an edit (a knot moved: a new bat) to its answer, for
//!   a solid and a hollow bat, on every core;
//! - `memory`: peak resident memory (VmHWM, reset through `/proc/self/clear_refs` before
//!   each run) of the scaling studies on the most threads and of a large summary-only study.
//!
//! Rates are medians of repeats. `--quick` shrinks every case to seconds (for tests).
//!
//! Files: `cases` (sizes, the base case, the studies), `machine`, `measure` (clocks, peak
//! memory, medians), `sinks` (a null sink), `store_run` (one run through the store, a
//! temporary directory), `scaling`, `headroom` (`writer_headroom`), `memory`, `report`
//! (printing, JSON). `dev` holds what the development benchmarks in `benches/` and the
//! tests use (integrator accuracy, the HDF5 share); the shipped bench does not run it.
//! Off the run path: nothing in `run`, `store`, `study` or `model` uses this module.

mod batted;
mod cases;
pub mod dev;
mod headroom;
mod lab;
mod machine;
mod measure;
mod memory;
mod optimize;
mod report;
mod scaling;
mod simulate;
mod sinks;
mod store_run;

pub use batted::Batted;
pub use cases::{
    base_spec, curve_positions, curve_study_text, load_study, HISTORY_BLOCK, MODAL_HISTORY_BLOCK,
    SCALAR_HISTORY_BLOCK,
};
pub use headroom::WriterHeadroom;
pub use machine::Machine;
pub use measure::thread_cpu_seconds;
pub use memory::{MemoryBench, RunMemory};
pub use report::BenchReport;
pub use scaling::{Scaling, ScalingPoint};
pub use simulate::SimulateBench;
pub use sinks::{null_run, NullSink};
pub use store_run::{store_run, store_run_with, StoreRun, TempDir};

use std::io::Write;
use std::path::{Path, PathBuf};

/// What to run.
#[derive(Debug, Clone, Default)]
pub struct BenchOptions {
    /// Shrink every case so that the whole benchmark takes a few seconds (for tests).
    pub quick: bool,
    /// Thread counts to measure (empty: 1, 2, 4, … up to every core).
    pub threads: Vec<usize>,
    /// Where the results files and the disk probe go (None: the system's temporary
    /// directory). The disk measured is the one under it.
    pub dir: Option<PathBuf>,
}

impl BenchOptions {
    /// The thread counts to measure, ascending, without repeats; an error for 0.
    pub fn thread_counts(&self) -> Result<Vec<usize>, String> {
        if self.threads.contains(&0) {
            return Err("--threads: a thread count must be at least 1".into());
        }
        let mut t = if self.threads.is_empty() {
            let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
            scaling::thread_counts(cores)
        } else {
            self.threads.clone()
        };
        t.sort_unstable();
        t.dedup();
        Ok(t)
    }
}

/// Run every section, printing as it goes. Returns the figures.
pub fn run(opts: &BenchOptions, out: &mut dyn Write) -> Result<BenchReport, String> {
    let threads = opts.thread_counts()?;
    let sz = cases::Sizes::of(opts.quick);
    let base = opts.dir.clone().unwrap_or_else(std::env::temp_dir);
    let dir = TempDir::new_in(&base)?;
    let mut machine = machine::describe(opts.quick, &base);
    report::print_machine(out, &machine);

    report::print_scaling_head(out, &threads);
    let mut print_point = |p: &ScalingPoint| report::print_scaling_point(out, p);
    let (scaling, peaks) = scaling::bench_scaling(&sz, &threads, dir.path(), &mut print_point)?;
    report::print_scaling_end(out, &scaling);

    let headroom = headroom::bench_writer_headroom(sz.headroom_omegas, sz.disk_mib, dir.path())?;
    report::print_headroom(out, &headroom, scaling.cores);

    let memory = memory::bench_memory(&sz, scaling.cores, dir.path(), &peaks)?;
    report::print_memory(out, &memory);

    let batted = batted::bench_batted(&sz, scaling.cores, dir.path())?;
    report::print_batted(out, &batted);
    let (candidates, sample) = if opts.quick { (8, 8) } else { (120, 64) };
    let optimize = optimize::bench_optimize(candidates, sample, scaling.cores)?;
    optimize::print(out, &optimize);
    let simulate = simulate::bench_simulate(&sz, dir.path())?;
    report::print_simulate(out, &simulate);
    let lab = lab::bench_lab(opts.quick, scaling.cores)?;
    lab::print(out, &lab);

    machine.loadavg_end = machine::loadavg();
    report::print_end(out, &machine);
    Ok(BenchReport {
        machine,
        scaling,
        writer_headroom: headroom,
        memory,
        batted,
        optimize,
        simulate,
        lab,
    })
}

/// `batstudy bench`: run, print, optionally write the figures as JSON. Returns the exit code
/// (0; 2 for bad options; 3 when a case could not run or the JSON could not be written).
pub fn main(opts: &BenchOptions, json: Option<&Path>) -> i32 {
    if let Err(e) = opts.thread_counts() {
        eprintln!("error: {e}");
        return 2;
    }
    if let Some(path) = json {
        if let Err((msg, allowed)) = crate::study::output::check_side_output(path, &[]) {
            eprintln!("error: --json: {msg}\n  allowed: {allowed}");
            return 2;
        }
    }
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
