//! What a results file answers beyond its curves, for `batstudy inspect`: a design search's
//! best feasible design (`/optimize`) and a `sample` study's answers over the sample
//! (`/uncertainty`), each as the file stores it.

use super::read::str_attr;
use std::fmt::Write as _;
use std::path::Path;

/// The design search's record in a few lines: candidates, how it stopped, the best feasible
/// design and its objective; nothing for a file without `/optimize`.
pub(super) fn search(f: &hdf5::File, path: &Path, s: &mut String) {
    let Ok(o) = f.group("optimize") else { return };
    let text = |name: &str| str_attr(&o, name, path).unwrap_or_default();
    let number = |name: &str| {
        o.attr(name)
            .and_then(|a| a.read_raw::<f64>())
            .ok()
            .and_then(|v| v.first().copied())
    };
    let evaluations = o
        .attr("evaluations")
        .and_then(|a| a.read_scalar::<u64>())
        .map_or_else(|_| "?".into(), |n| n.to_string());
    let _ = writeln!(
        s,
        "design search: {evaluations} candidates ({}), stopped: {}",
        text("method"),
        text("stopped")
    );
    let best: serde_json::Value = serde_json::from_str(&text("best")).unwrap_or_default();
    match (number("best_objective"), best.as_object()) {
        (Some(v), Some(design)) if v.is_finite() => {
            let _ = writeln!(
                s,
                "  best feasible: {} = {v:.6} {} ({})",
                text("objective"),
                text("objective_units"),
                text("sense")
            );
            for (name, x) in design {
                let _ = writeln!(
                    s,
                    "    {name} = {:.6} {}",
                    x["value"].as_f64().unwrap_or(f64::NAN),
                    x["units"].as_str().unwrap_or("")
                );
            }
        }
        _ => {
            let _ = writeln!(s, "  no feasible candidate");
        }
    }
}

/// The answers of a `sample` study, their mean and 2.5 / 50 / 97.5 % quantiles, and the
/// probability that the best BBCOR exceeds the limit; nothing for a file without
/// `/uncertainty`. Where the answers have more dimensions than the quantile, the first
/// curve's.
pub(super) fn sample(f: &hdf5::File, s: &mut String) {
    let Ok(u) = f.group("uncertainty") else {
        return;
    };
    let read = |name: &str| {
        u.dataset(name)
            .and_then(|d| d.read_raw::<f64>())
            .unwrap_or_default()
    };
    let quantiles = read("quantile");
    let _ = writeln!(s, "over the sample (mean; 2.5 / 50 / 97.5 %):");
    for (name, units) in [
        ("bbcor_max", ""),
        ("sweet_spot_position", " m"),
        ("sweet_spot_exit_speed", " m/s"),
    ] {
        let values = read(name);
        let mean = read(&format!("{name}_mean"));
        let at = |q: f64| {
            quantiles
                .iter()
                .position(|&x| (x - q).abs() < 1e-9)
                .and_then(|k| values.get(k))
                .map_or_else(|| "?".into(), |v| format!("{v:.4}"))
        };
        if let Some(m) = mean.first() {
            let _ = writeln!(
                s,
                "  {name}: {m:.4}{units}; {} / {} / {}{units}",
                at(0.025),
                at(0.5),
                at(0.975)
            );
        }
    }
    if let Some(p) = read("bbcor_max_above_limit").first() {
        let _ = writeln!(s, "  P(best BBCOR > 0.50) = {p:.3}");
    }
}
