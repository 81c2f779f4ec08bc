//! Points/s against threads: a summary-only study, a full-history study (the displacement on
//! its grid, and in modal form) and a scalar-history study, each run through the driver and
//! the real store at every thread count asked for; then, on the most threads, the history
//! studies with nothing stored and the grid form stored without compression.

use super::cases::{
    curve_study_text, load_study, Sizes, HISTORY_BLOCK, MODAL_HISTORY_BLOCK, SCALAR_HISTORY_BLOCK,
};
use super::measure::{err, median};
use super::sinks::null_run;
use super::store_run::{store_run, StoreRun};
use crate::run::{self, ModelSimulator};
use crate::study::Study;
use serde::Serialize;
use std::path::Path;

/// Points/s at one thread count.
#[derive(Debug, Clone, Serialize)]
pub struct ScalingPoint {
    pub threads: usize,
    pub summary_points_per_second: f64,
    pub history_points_per_second: f64,
    pub history_scalar_points_per_second: f64,
    /// The history study with the displacement in modal form (`history` has it on the grid).
    pub history_modal_points_per_second: f64,
    /// Points of each run's summary and history studies (they grow with the thread count).
    pub summary_points: usize,
    pub history_points: usize,
    /// Parallel efficiency against the fewest threads measured (t₀):
    /// (rate / threads) / (rate(t₀) / t₀).
    pub summary_efficiency: f64,
    pub history_efficiency: f64,
    pub history_scalar_efficiency: f64,
    pub history_modal_efficiency: f64,
    /// Each repeat's modal history points/s over the summary points/s of the same repeat
    /// (the two runs half a second apart): the spread of the ratio the medians give.
    pub history_modal_vs_summary_per_repeat: Vec<f64>,
    /// The share of the machine's CPU time its host took during the summary and the modal
    /// history runs (medians over the repeats; `StoreRun::stolen_share`), None where it
    /// cannot be read: what a virtual machine's host, writing its disk, takes from a study
    /// that writes more bytes.
    pub summary_stolen_share: Option<f64>,
    pub history_modal_stolen_share: Option<f64>,
}

#[derive(Debug, Clone, Serialize)]
pub struct Scaling {
    /// The most threads measured (every core, unless `--threads` says otherwise); "on every
    /// core" below means on this many threads.
    pub cores: usize,
    /// Points of the summary and history studies on `cores` threads.
    pub summary_points: usize,
    pub history_points: usize,
    pub points: Vec<ScalingPoint>,
    /// Parallel efficiency of each study on `cores` threads (see [`ScalingPoint`]).
    pub summary_efficiency: f64,
    pub history_efficiency: f64,
    /// History points/s per core over summary points/s per core, on every core.
    pub history_vs_summary_per_core: f64,
    /// Points/s of the history study on every core with its histories recorded but not
    /// stored (a null sink): what a store that cost nothing would give.
    pub history_compute_points_per_second: f64,
    /// history_compute / summary on every core: the most `history_vs_summary_per_core` can
    /// be with this study, whatever the store.
    pub history_vs_summary_ceiling: f64,
    /// Points/s of the history study on every core, stored with `history.compression: none`
    /// (no filters: more bytes, less CPU per point), and its file's size.
    pub history_uncompressed_points_per_second: f64,
    pub history_uncompressed_file_bytes: u64,
    /// The default (deflated) history study's file size.
    pub history_file_bytes: u64,
    /// Points/s on every core of the history study without `displacement` (the scalar
    /// series: force, compression, ball velocity, rigid motion), and per core over the
    /// summary study's.
    pub history_scalar_points_per_second: f64,
    pub history_scalar_vs_summary_per_core: f64,
    /// The history study with the displacement in modal form on every core: its
    /// points/s, efficiency, points/s per core over the summary study's, file size, and the
    /// points/s and ratio with its histories recorded but not stored.
    pub history_modal_points_per_second: f64,
    pub history_modal_efficiency: f64,
    pub history_modal_vs_summary_per_core: f64,
    pub history_modal_file_bytes: u64,
    pub history_modal_compute_points_per_second: f64,
    pub history_modal_vs_summary_ceiling: f64,
    /// `history_modal_vs_summary_per_core` repeat by repeat on every core: each modal run's
    /// points/s over the summary run's of the same repeat (what other work on the machine
    /// does to one ratio; the headline is the ratio of the medians).
    pub history_modal_vs_summary_per_core_per_repeat: Vec<f64>,
    /// The host's share of the machine's CPU time during the summary and the modal runs on
    /// every core (see [`ScalingPoint`]).
    pub summary_stolen_share: Option<f64>,
    pub history_modal_stolen_share: Option<f64>,
}

/// Peak memory of each study's run on the most threads.
pub(super) struct Peaks {
    pub(super) summary: StoreRun,
    pub(super) history: StoreRun,
    pub(super) scalar: StoreRun,
    pub(super) modal: StoreRun,
}

/// 1, 2, 4, … below `cores`, and `cores` itself.
pub(super) fn thread_counts(cores: usize) -> Vec<usize> {
    let mut t: Vec<usize> = std::iter::successors(Some(1usize), |&n| Some(n * 2))
        .take_while(|&n| n < cores)
        .collect();
    t.push(cores.max(1));
    t
}

/// The four studies at `threads`: summary, history (grid), scalar history, modal history.
fn studies(sz: &Sizes, threads: usize) -> Result<[Study; 4], String> {
    let s = Sizes::omegas(sz.summary_omegas, threads);
    let h = Sizes::omegas(sz.history_omegas, threads);
    Ok([
        load_study(&curve_study_text("bench-summary", s, ""), "summary")?,
        load_study(
            &curve_study_text("bench-history", h, HISTORY_BLOCK),
            "history",
        )?,
        load_study(
            &curve_study_text("bench-history-scalar", h, SCALAR_HISTORY_BLOCK),
            "history-scalar",
        )?,
        load_study(
            &curve_study_text("bench-history-modal", h, MODAL_HISTORY_BLOCK),
            "history-modal",
        )?,
    ])
}

/// `repeats` store runs of `study`: the median points/s and the last run.
pub(super) fn rate(
    study: &Study,
    file: &str,
    dir: &Path,
    pool: &rayon::ThreadPool,
    repeats: usize,
) -> Result<(f64, StoreRun), String> {
    let mut rates = Vec::new();
    let mut last = None;
    for _ in 0..repeats.max(1) {
        let r = store_run(file, study, dir, pool)?;
        rates.push(r.points_per_second());
        last = Some(r);
    }
    Ok((median(rates), last.ok_or("no run")?))
}

/// One thread count: the four studies' rates (efficiencies left at 1) and their last runs.
fn measure_point(
    sz: &Sizes,
    threads: usize,
    dir: &Path,
) -> Result<(ScalingPoint, [StoreRun; 4]), String> {
    let [summary, history, scalar, modal] = studies(sz, threads)?;
    let pool = run::build_pool(threads).map_err(err("pool"))?;
    // the four studies in turn, `repeats` times: what the machine does meanwhile (another
    // process, the kernel's own threads) falls on all four alike, and their ratios, which
    // the report gives, do not drift with it as when each study ran its repeats together
    let cases = [
        (&summary, "summary"),
        (&history, "history"),
        (&scalar, "history-scalar"),
        (&modal, "history-modal"),
    ];
    let mut rates: [Vec<f64>; 4] = Default::default();
    let mut stolen: [Vec<Option<f64>>; 4] = Default::default();
    let mut last: [Option<StoreRun>; 4] = Default::default();
    for _ in 0..sz.repeats.max(1) {
        for (k, (study, file)) in cases.iter().enumerate() {
            let r = store_run(file, study, dir, &pool)?;
            rates[k].push(r.points_per_second());
            stolen[k].push(r.stolen_share);
            last[k] = Some(r);
        }
    }
    let stolen_median = |k: usize| -> Option<f64> {
        let shares: Option<Vec<f64>> = stolen[k].iter().copied().collect();
        shares.map(median)
    };
    let per_repeat = rates[3].iter().zip(&rates[0]).map(|(m, s)| m / s).collect();
    let [s, h, c, m] = rates.map(median);
    let [rs, rh, rc, rm] = last.map(|r| r.expect("at least one run"));
    let point = ScalingPoint {
        threads,
        summary_points_per_second: s,
        history_points_per_second: h,
        history_scalar_points_per_second: c,
        history_modal_points_per_second: m,
        summary_points: summary.plan.n_points(),
        history_points: history.plan.n_points(),
        summary_efficiency: 1.0,
        history_efficiency: 1.0,
        history_scalar_efficiency: 1.0,
        history_modal_efficiency: 1.0,
        history_modal_vs_summary_per_repeat: per_repeat,
        summary_stolen_share: stolen_median(0),
        history_modal_stolen_share: stolen_median(3),
    };
    Ok((point, [rs, rh, rc, rm]))
}

/// Efficiencies of `p` against the first point measured.
fn set_efficiency(p: &mut ScalingPoint, first: &ScalingPoint) {
    let per_thread = |rate: f64, t: usize| rate / t as f64;
    let eff = |a: f64, b: f64| per_thread(a, p.threads) / per_thread(b, first.threads);
    p.summary_efficiency = eff(p.summary_points_per_second, first.summary_points_per_second);
    p.history_efficiency = eff(p.history_points_per_second, first.history_points_per_second);
    p.history_scalar_efficiency = eff(
        p.history_scalar_points_per_second,
        first.history_scalar_points_per_second,
    );
    p.history_modal_efficiency = eff(
        p.history_modal_points_per_second,
        first.history_modal_points_per_second,
    );
}

/// What the history studies give on `threads` beyond their stored runs.
struct Variants {
    /// Points/s of the grid and the modal study with nothing stored.
    compute: f64,
    modal_compute: f64,
    /// Points/s of the grid study stored without compression, and its file's bytes.
    uncompressed: f64,
    uncompressed_bytes: u64,
}

/// Points/s of `study` on `pool` with its histories recorded and not stored.
fn compute_rate(study: &Study, pool: &rayon::ThreadPool, repeats: usize) -> Result<f64, String> {
    let bats = run::prepare_bats(&ModelSimulator, &study.plan, pool);
    let request = study.history_request(bats.max_length());
    let walls = (0..repeats.max(1))
        .map(|_| null_run(study, &bats, request.as_ref(), pool).map(|(w, _)| w))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(study.plan.n_points() as f64 / median(walls))
}

/// The history studies on `threads` with nothing stored, and the grid one stored without
/// compression.
fn history_variants(sz: &Sizes, threads: usize, dir: &Path) -> Result<Variants, String> {
    let [_, history, _, modal] = studies(sz, threads)?;
    let pool = run::build_pool(threads).map_err(err("pool"))?;
    let h = Sizes::omegas(sz.history_omegas, threads);
    let block = format!("{HISTORY_BLOCK}  compression: none\n");
    let uncompressed = load_study(
        &curve_study_text("bench-history", h, &block),
        "history-none",
    )?;
    let (rate, run) = rate(&uncompressed, "history-none", dir, &pool, sz.repeats)?;
    Ok(Variants {
        compute: compute_rate(&history, &pool, sz.repeats)?,
        modal_compute: compute_rate(&modal, &pool, sz.repeats)?,
        uncompressed: rate,
        uncompressed_bytes: run.file_bytes,
    })
}

/// Every thread count in `threads` (ascending), `on_point` called as each is measured.
pub(super) fn bench_scaling(
    sz: &Sizes,
    threads: &[usize],
    dir: &Path,
    on_point: &mut dyn FnMut(&ScalingPoint),
) -> Result<(Scaling, Peaks), String> {
    let mut points: Vec<ScalingPoint> = Vec::new();
    let mut runs = None;
    for &t in threads {
        let (mut p, r) = measure_point(sz, t, dir)?;
        if let Some(first) = points.first() {
            set_efficiency(&mut p, first);
        }
        on_point(&p);
        points.push(p);
        runs = Some(r);
    }
    let [summary, history, scalar, modal] = runs.ok_or("no thread count to measure")?;
    let last = points.last().ok_or("no thread count")?.clone();
    let v = history_variants(sz, last.threads, dir)?;
    let per_summary = |rate: f64| rate / last.summary_points_per_second;
    let scaling = Scaling {
        cores: last.threads,
        summary_points: last.summary_points,
        history_points: last.history_points,
        summary_efficiency: last.summary_efficiency,
        history_efficiency: last.history_efficiency,
        history_vs_summary_per_core: per_summary(last.history_points_per_second),
        history_compute_points_per_second: v.compute,
        history_vs_summary_ceiling: per_summary(v.compute),
        history_uncompressed_points_per_second: v.uncompressed,
        history_uncompressed_file_bytes: v.uncompressed_bytes,
        history_file_bytes: history.file_bytes,
        history_scalar_points_per_second: last.history_scalar_points_per_second,
        history_scalar_vs_summary_per_core: per_summary(last.history_scalar_points_per_second),
        history_modal_points_per_second: last.history_modal_points_per_second,
        history_modal_efficiency: last.history_modal_efficiency,
        history_modal_vs_summary_per_core: per_summary(last.history_modal_points_per_second),
        history_modal_file_bytes: modal.file_bytes,
        history_modal_compute_points_per_second: v.modal_compute,
        history_modal_vs_summary_ceiling: per_summary(v.modal_compute),
        history_modal_vs_summary_per_core_per_repeat: last
            .history_modal_vs_summary_per_repeat
            .clone(),
        summary_stolen_share: last.summary_stolen_share,
        history_modal_stolen_share: last.history_modal_stolen_share,
        points,
    };
    let peaks = Peaks {
        summary,
        history,
        scalar,
        modal,
    };
    Ok((scaling, peaks))
}
