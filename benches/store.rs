//! What the results store costs a run: the same studies through the driver into the real
//! store (journal + final HDF5 file, as `batstudy run`) and into a sink that keeps nothing,
//! the bats prepared in both. A summary-only study (2 700 points) on 1 thread and on every
//! core, and a full-history study (1 800 points; also stored without compression) on every
//! core; then the summary study's write share from store and null runs paired back to back
//! (`BATSTUDY_BENCH_PAIRS`, default 21; 0 skips it).
//!
//!     cargo bench --bench store

use batstudy::bench::{curve_study_text, dev, load_study, null_run, store_run, HISTORY_BLOCK};
use batstudy::run::{build_pool, prepare_bats, ModelSimulator};
use batstudy::study::Study;
use divan::counter::ItemsCount;
use divan::Bencher;

/// `cargo bench` (not `cargo test`, which runs each benchmark once, nor `--list`).
fn benchmarking() -> bool {
    let args: Vec<String> = std::env::args().collect();
    args.iter().any(|a| a == "--bench") && !args.iter().any(|a| a == "--list" || a == "--test")
}

fn main() {
    divan::main();
    if benchmarking() {
        print_write_share();
    }
}

/// `full` swing speeds (× 45 impact positions) when benchmarking, one in a test.
fn study(name: &str, full: usize, history: &str) -> Study {
    let omegas = if benchmarking() { full } else { 1 };
    load_study(&curve_study_text(name, omegas, history), name).expect("the study")
}

fn summary() -> Study {
    study("summary", 60, "")
}

fn history(compression: &str) -> Study {
    study("history", 40, &format!("{HISTORY_BLOCK}{compression}"))
}

fn cores() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

fn threads() -> Vec<usize> {
    let mut t = vec![1, cores()];
    t.dedup();
    t
}

/// Store runs of `study` on `threads` (the file removed after each).
fn bench_store(bencher: Bencher, study: &Study, threads: usize) {
    let dir = tempfile::tempdir().expect("a temporary directory");
    let pool = build_pool(threads).expect("pool");
    bencher
        .counter(ItemsCount::new(study.plan.n_points()))
        .bench_local(|| store_run("bench", study, dir.path(), &pool).expect("store run"));
}

/// Null-sink runs of `study` on `threads`, its histories (if any) computed and dropped.
fn bench_null(bencher: Bencher, study: &Study, threads: usize) {
    let pool = build_pool(threads).expect("pool");
    bencher
        .counter(ItemsCount::new(study.plan.n_points()))
        .bench_local(|| {
            let bats = prepare_bats(&ModelSimulator, &study.plan, &pool);
            let history = study.history_request(bats.max_length());
            null_run(study, &bats, history.as_ref(), &pool).expect("null run")
        });
}

#[divan::bench_group(sample_count = 15, sample_size = 1)]
mod summary {
    use super::*;

    #[divan::bench(args = threads())]
    fn store(bencher: Bencher, threads: usize) {
        bench_store(bencher, &summary(), threads);
    }

    #[divan::bench(args = threads())]
    fn null(bencher: Bencher, threads: usize) {
        bench_null(bencher, &summary(), threads);
    }
}

#[divan::bench_group(sample_count = 8, sample_size = 1)]
mod history {
    use super::*;

    #[divan::bench]
    fn store(bencher: Bencher) {
        bench_store(bencher, &history(""), cores());
    }

    #[divan::bench]
    fn store_uncompressed(bencher: Bencher) {
        bench_store(bencher, &history("  compression: none\n"), cores());
    }

    #[divan::bench]
    fn null(bencher: Bencher) {
        bench_null(bencher, &history(""), cores());
    }
}

/// The summary study's store runs paired with null runs (alternating which goes first),
/// and where the store's time goes.
fn print_write_share() {
    let pairs = std::env::var("BATSTUDY_BENCH_PAIRS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(21);
    if pairs == 0 {
        return;
    }
    let dir = tempfile::tempdir().expect("a temporary directory");
    let w = dev::write_share("summary", &summary(), dir.path(), cores(), pairs)
        .expect("the write share");
    println!(
        "\nwrite share, summary study ({} points, {} threads): store {:.4} s, null sink {:.4} s: \
         writing adds {:.2} % of wall (median of {} pairs, quartiles {:.2}..{:.2} %)",
        w.points,
        w.threads,
        w.store_wall_seconds,
        w.null_wall_seconds,
        w.wall_overhead * 100.0,
        w.pairs,
        w.wall_overhead_quartiles.0 * 100.0,
        w.wall_overhead_quartiles.1 * 100.0
    );
    println!(
        "in store calls (timed run): journal {:.4} s + finish {:.4} s = {:.2} % of wall; \
         {:.2} % of CPU; file {:.2} MiB",
        w.journal_seconds,
        w.final_file_seconds,
        w.share * 100.0,
        w.cpu_share * 100.0,
        w.file_bytes as f64 / 1048576.0
    );
}
