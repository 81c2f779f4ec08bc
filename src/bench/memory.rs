//! Peak resident memory: each scaling study's run on the most threads, and a large
//! summary-only study through the store (the store's memory does not grow with the study:
//! one bit per point, and a capped window for the final file's build).

use super::cases::{load_study, rigid_study_text, Sizes};
use super::measure::err;
use super::scaling::Peaks;
use super::store_run::{store_run, StoreRun};
use crate::model::outcome::HistoryRequest;
use crate::run::{self, RunOptions};
use crate::store;
use serde::Serialize;
use std::path::Path;

/// Peak and starting resident memory of one run, bytes (None where Linux does not say).
#[derive(Debug, Clone, Serialize)]
pub struct RunMemory {
    pub points: usize,
    pub threads: usize,
    pub seconds: f64,
    pub peak_rss_bytes: Option<u64>,
    pub rss_before_bytes: Option<u64>,
}

impl From<&StoreRun> for RunMemory {
    fn from(r: &StoreRun) -> Self {
        RunMemory {
            points: r.points,
            threads: r.threads,
            seconds: r.wall_seconds,
            peak_rss_bytes: r.peak_rss_bytes,
            rss_before_bytes: r.rss_before_bytes,
        }
    }
}

#[derive(Debug, Clone, Serialize)]
pub struct MemoryBench {
    /// The scaling studies' runs on the most threads.
    pub summary: RunMemory,
    pub history: RunMemory,
    pub history_scalar: RunMemory,
    pub history_modal: RunMemory,
    /// The history study's histories, were they all held as f64 (what the store does not do).
    pub history_bytes_in_memory: u64,
    /// A summary-only study of many cheap points (rigid model) through the store.
    pub large_summary: RunMemory,
    /// The final file's build holds at most this many bytes of summary values.
    pub build_memory: usize,
    /// Records in flight between the workers and the writer.
    pub channel_capacity: usize,
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

/// The memory section on `threads` threads, from the scaling runs and one more study.
pub(super) fn bench_memory(
    sz: &Sizes,
    threads: usize,
    dir: &Path,
    peaks: &Peaks,
) -> Result<MemoryBench, String> {
    let [a, b, c] = sz.large_points;
    let large = load_study(&rigid_study_text("bench-large", a, b, c), "large")?;
    let pool = run::build_pool(threads).map_err(err("pool"))?;
    let large_run = store_run("large", &large, dir, &pool)?;
    // the history study's request, as its run made it (the bat's length bounds the z)
    let history = super::cases::curve_study_text("h", 1, super::cases::HISTORY_BLOCK);
    let history = load_study(&history, "history")?;
    let bats = run::prepare_bats(&crate::run::ModelSimulator, &history.plan, &pool);
    let per_point = history
        .history_request(bats.max_length())
        .as_ref()
        .map_or(0, history_bytes);
    Ok(MemoryBench {
        summary: (&peaks.summary).into(),
        history: (&peaks.history).into(),
        history_scalar: (&peaks.scalar).into(),
        history_modal: (&peaks.modal).into(),
        history_bytes_in_memory: per_point * peaks.history.points as u64,
        large_summary: (&large_run).into(),
        build_memory: store::StoreOptions::default().build_memory,
        channel_capacity: RunOptions::default().channel_capacity,
    })
}
