//! `batstudy plan`: what a study expands to, with a measured estimate of time and size.

#![allow(clippy::result_large_err)] // StudyError: see study/mod.rs

use super::common::load_or_report;
use super::EXIT_OK;
use crate::model::outcome::HistoryPrecision;
use crate::run::ModelSimulator;
use crate::run::Simulator;
use crate::study::checks::bat_length;
use crate::study::error::printable;
use crate::study::Study;
use crate::study::DEFAULT_MAX_POINTS;
use clap::Args;
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct PlanArgs {
    /// The study file (YAML).
    pub study: PathBuf,
    /// Print every point (index, id, parameters).
    #[arg(long)]
    pub list: bool,
    /// Largest number of points allowed.
    #[arg(long, default_value_t = DEFAULT_MAX_POINTS)]
    pub max_points: usize,
}

pub(super) fn cmd_plan(a: &PlanArgs) -> i32 {
    let s = match load_or_report(&a.study, a.max_points) {
        Ok(s) => s,
        Err(code) => return code,
    };
    let plan = &s.plan;
    let n = plan.n_points();
    println!(
        "study {}: {} points, {} distinct bats",
        s.file.name,
        n,
        plan.bats().len()
    );
    if !s.file.description.trim().is_empty() {
        println!("  {}", printable(s.file.description.trim(), true));
    }
    print_dims(&s);
    print_estimates(&s);
    if a.list {
        list_points(&s);
    }
    EXIT_OK
}

/// Each dimension with its coordinates' ranges or labels.
fn print_dims(s: &Study) {
    let plan = &s.plan;
    println!("dimensions (row-major, last fastest):");
    for d in &plan.shape().dims {
        println!("  {} [{}]", d.name, d.size);
        for c in &d.coords {
            let vals = match &c.values {
                crate::results::CoordValues::Numbers(v) => {
                    let (lo, hi) = v
                        .iter()
                        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                            (a.min(x), b.max(x))
                        });
                    format!("{lo} .. {hi} {}", c.units)
                }
                crate::results::CoordValues::Labels(l) => labels_text(l),
            };
            println!(
                "    {} ({}): {}",
                printable(&c.name, false),
                printable(&c.path, false),
                vals
            );
        }
    }
}

/// Labels as one short line: each quoted (labels hold commas themselves), at most
/// [`LABELS_SHOWN`] of them with a count of the rest (`plan --list` shows every point).
fn labels_text(l: &[String]) -> String {
    let quoted = |s: &String| format!("\"{}\"", printable(s, false).replace('"', "\\\""));
    let mut out: Vec<String> = l.iter().take(LABELS_SHOWN).map(quoted).collect();
    if l.len() > LABELS_SHOWN {
        out.push(format!("… and {} more", l.len() - LABELS_SHOWN));
    }
    out.join(", ")
}

/// Most labels `plan` prints of one dimension.
const LABELS_SHOWN: usize = 6;

/// The measured estimate of the run time and the output's size.
fn print_estimates(s: &Study) {
    let plan = &s.plan;
    let n = plan.n_points();
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let (per_point, per_bat, history_share) = measured_costs(s);
    let secs = (n as f64 * per_point + plan.bats().len() as f64 * per_bat) / cores as f64;
    println!(
        "estimated run time: ~{} on {cores} cores ({} per point, {} per bat, measured on a sample)",
        human_secs(secs),
        human_secs(per_point),
        human_secs(per_bat)
    );
    let max_len = plan
        .bats()
        .iter()
        .map(|b| bat_length(&b.bat))
        .fold(0.0, f64::max);
    let mut bytes_per_point = 20.0 * 8.0;
    if let Some(h) = &s.file.history {
        let req = h.request(max_len);
        let width = match h.precision {
            HistoryPrecision::F32 => 4.0,
            HistoryPrecision::F64 => 8.0,
        };
        let series: f64 = req
            .fields
            .iter()
            .map(|f| match f {
                crate::model::outcome::HistoryField::Displacement => req.z.len() as f64,
                crate::model::outcome::HistoryField::RigidMotion => 2.0,
                crate::model::outcome::HistoryField::Trajectory => 0.0,
                _ => 1.0,
            })
            .sum();
        let values = series * req.n_samples as f64
            + crate::study::history_size::trajectory_values(&req.fields);
        bytes_per_point += history_share * values * width;
    }
    println!(
        "estimated output size: ~{} uncompressed (written to {})",
        human_bytes(bytes_per_point * n as f64),
        printable(&s.output_path(None).display().to_string(), false)
    );
}

/// Every point: index, id, parameters (or its error).
fn list_points(s: &Study) {
    let plan = &s.plan;
    println!("points (index, id, parameters):");
    for i in 0..plan.n_points() {
        match plan.point(i) {
            Ok(p) => println!(
                "{i}\t{:016x}\t{}",
                p.id,
                printable(&plan.describe(i), false)
            ),
            Err(e) => println!(
                "{i}\t{:016x}\t{}\tERROR: {}",
                e.id,
                printable(&plan.describe(i), false),
                printable(&e.message, false)
            ),
        }
    }
}

/// Rough cost model for `plan`: seconds per point and per bat preparation.
/// Seconds per point and per bat preparation, measured on a few points spread over the plan
/// (the first run of a bat includes preparing it), and the share of points that record
/// histories (from a larger sample: resolving a point is cheap).
fn measured_costs(s: &Study) -> (f64, f64, f64) {
    let plan = &s.plan;
    let n = plan.n_points();
    let spread = |k: usize| (0..k.min(n)).map(move |i| i * n / k.min(n));
    let (mut simulate_secs, mut prepare_secs, mut timed) = (0.0, 0.0, 0usize);
    for i in spread(8) {
        let Ok(p) = plan.point(i) else { continue };
        let start = std::time::Instant::now();
        let Ok((_, bat)) = ModelSimulator.prepare(
            &p.spec.bat,
            &p.spec.numerics,
            &crate::model::measures::metrics::BbcorShot::of(&p.spec),
        ) else {
            continue;
        };
        let prepared = start.elapsed().as_secs_f64();
        let start = std::time::Instant::now();
        let history = s.history_request(bat_length(&p.spec.bat));
        let _ =
            ModelSimulator.simulate(&bat, &p.spec, history.as_ref().filter(|_| p.record_history));
        simulate_secs += start.elapsed().as_secs_f64();
        prepare_secs += prepared;
        timed += 1;
    }
    let sampled: Vec<bool> = spread(2000)
        .filter_map(|i| plan.point(i).ok().map(|p| p.record_history))
        .collect();
    let history_share = sampled.iter().filter(|r| **r).count() as f64 / sampled.len().max(1) as f64;
    let timed = timed.max(1) as f64;
    (simulate_secs / timed, prepare_secs / timed, history_share)
}

fn human_bytes(b: f64) -> String {
    let units = ["B", "KiB", "MiB", "GiB", "TiB"];
    let mut x = b;
    let mut u = 0;
    while x >= 1024.0 && u + 1 < units.len() {
        x /= 1024.0;
        u += 1;
    }
    format!("{x:.1} {}", units[u])
}

fn human_secs(s: f64) -> String {
    if s < 0.1 {
        format!("{:.3} ms", s * 1e3)
    } else if s < 120.0 {
        format!("{s:.1} s")
    } else if s < 7200.0 {
        format!("{:.1} min", s / 60.0)
    } else {
        format!("{:.1} h", s / 3600.0)
    }
}
