//! `batstudy inspect`: a results file described for a person, its strings made safe for a
//! terminal.

use super::error::{H5Ctx, StoreError};
use super::header::JournalHeader;
use super::layout as l;
use super::read::{open_checked, shown, str_attr};
use crate::results::printable;
use hdf5::types::VarLenUnicode;
use std::fmt::Write as _;
use std::path::Path;

/// A human-readable description of a results file: study, layout version, dims, counts by
/// status, sweet spots. A file HDF5 cannot read is a damaged one.
pub fn inspect(path: &Path) -> Result<String, StoreError> {
    describe(path).map_err(|e| match e {
        StoreError::Hdf5 { path, what, source } => {
            super::check::damaged(&path, format!("HDF5 cannot {what} ({source})"))
        }
        e => e,
    })
}

fn describe(path: &Path) -> Result<String, StoreError> {
    let (f, header, version) = open_checked(path)?;
    let mut s = String::new();
    let name = str_attr(&f, "study_name", path)?;
    let _ = writeln!(
        s,
        "{}: batstudy results, layout version {version}",
        path.display()
    );
    let _ = writeln!(
        s,
        "study: {name} (sha256 {})",
        str_attr(&f, "study_sha256", path)?
    );
    if let Ok(c) = str_attr(&f, "created", path) {
        let _ = writeln!(s, "created: {c}");
    }
    let g = f.group(l::GROUP_SUMMARY).ctx(path, "open group summary")?;
    inspect_points(&g, &header, path, &mut s)?;
    if let Ok(sg) = f.group(l::GROUP_SWEET_SPOT) {
        inspect_sweet_spots(&sg, &g, &header, path, &mut s)?;
    }
    if let Ok(bg) = f.group(l::GROUP_BAT) {
        inspect_bats(&bg, &mut s);
    }
    super::answers::search(&f, path, &mut s);
    super::answers::sample(&f, &mut s);
    // a results file's strings (labels carry user-chosen profile paths; a file can be
    // edited) are data, never commands to the terminal
    Ok(crate::results::printable(&s, true).into_owned())
}

/// The dims, the points by status, the histories.
fn inspect_points(
    g: &hdf5::Group,
    header: &JournalHeader,
    path: &Path,
    s: &mut String,
) -> Result<(), StoreError> {
    let dims: Vec<String> = header
        .dims
        .iter()
        .map(|(n, k)| format!("{n}={k}"))
        .collect();
    let n: usize = header.dims.iter().map(|d| d.1).product();
    let _ = writeln!(s, "dims: {} ({n} points)", dims.join(" × "));
    let status = g
        .dataset(l::STATUS.name)
        .and_then(|d| d.read_raw::<i8>())
        .ctx(path, "read summary/status")?;
    let count = |v: i8| status.iter().filter(|&&x| x == v).count();
    let _ = writeln!(
        s,
        "points: {} ok, {} failed, {} not computed",
        count(l::STATUS_OK),
        count(l::STATUS_FAILED),
        count(l::STATUS_NOT_COMPUTED)
    );
    if let Some((names, nt, nz)) = &header.history {
        let _ = writeln!(
            s,
            "history: {} ({nt} samples, {nz} z positions)",
            names.join(", ")
        );
    }
    Ok(())
}

/// The sweet spots: each named by its curve's coordinates (up to 10), else their ranges.
fn inspect_sweet_spots(
    sg: &hdf5::Group,
    g: &hdf5::Group,
    header: &JournalHeader,
    path: &Path,
    s: &mut String,
) -> Result<(), StoreError> {
    let rd = |v: &str| {
        sg.dataset(v)
            .and_then(|d| d.read_raw::<f64>())
            .ctx(path, "read sweet_spot")
    };
    let (p, e, w) = (rd("position")?, rd("exit_speed")?, rd("width")?);
    // the lab frame's best exit speed (files before it was stored have none)
    let lab = rd(l::SWEET_EXIT_SPEED_LAB.name).ok();
    let lab_at = |i: usize| {
        lab.as_ref()
            .and_then(|v| v.get(i))
            .filter(|x| x.is_finite())
            .map_or_else(String::new, |x| format!(" (lab frame: best {x:.3} m/s)"))
    };
    let fin: Vec<usize> = (0..p.len()).filter(|&i| p[i].is_finite()).collect();
    let edge = sg
        .dataset(l::SWEET_AT_EDGE.name)
        .and_then(|d| d.read_raw::<i8>())
        .unwrap_or_default();
    if fin.is_empty() {
        let _ = writeln!(s, "sweet spot: none computed");
    } else if fin.len() <= 10 {
        let rest: Vec<&(String, usize)> = header
            .dims
            .iter()
            .filter(|(n, _)| n != l::IMPACT_Z)
            .collect();
        let labels: Vec<Vec<String>> = rest.iter().map(|(n, k)| dim_labels(g, n, *k)).collect();
        for i in fin {
            // the curve's coordinates, last dim fastest
            let mut r = i;
            let mut at: Vec<String> = vec![String::new(); rest.len()];
            for (k, (n, size)) in rest.iter().enumerate().rev() {
                at[k] = format!("{n}={}", labels[k][r % size]);
                r /= size;
            }
            let _ = writeln!(
                s,
                "sweet spot{}{}: z = {:.4} m, exit speed {:.3} m/s{}, width {:.4} m{}",
                if at.is_empty() { "" } else { " at " },
                at.join(", "),
                p[i],
                e[i],
                lab_at(i),
                w[i],
                if edge.get(i) == Some(&1) {
                    " (at the edge of the sampled impact_z)"
                } else {
                    ""
                }
            );
        }
    } else {
        let mm = |v: &[f64]| {
            let it = fin.iter().map(|&i| v[i]);
            (
                it.clone().fold(f64::INFINITY, f64::min),
                it.fold(f64::NEG_INFINITY, f64::max),
            )
        };
        let ((p0, p1), (e0, e1), (w0, w1)) = (mm(&p), mm(&e), mm(&w));
        let lab_range = lab
            .as_ref()
            .map(|v| mm(v))
            .filter(|(a, b)| a.is_finite() && b.is_finite())
            .map_or_else(String::new, |(a, b)| {
                format!(" (lab frame: best {a:.3}..{b:.3} m/s)")
            });
        let _ = writeln!(
            s,
            "sweet spots ({} curves): z {p0:.4}..{p1:.4} m, exit speed {e0:.3}..{e1:.3} m/s{lab_range}, width {w0:.4}..{w1:.4} m",
            fin.len()
        );
    }
    let n_edge = edge.iter().filter(|&&e| e == 1).count();
    if n_edge > 0 {
        let _ = writeln!(
            s,
            "  {n_edge} of them at the edge of the sampled impact_z (the maximum may lie outside; see sweet_spot/position_at_edge)"
        );
    }
    Ok(())
}

/// Text labels of a dim's entries: its `<dim>_label` coordinate, else its coordinate values,
/// else the index.
fn dim_labels(g: &hdf5::Group, dim: &str, size: usize) -> Vec<String> {
    let text = |name: &str| -> Option<Vec<String>> {
        let ds = g.dataset(name).ok()?;
        if let Ok(v) = ds.read_raw::<VarLenUnicode>() {
            return Some(v.iter().map(shown).collect());
        }
        let v = ds.read_raw::<f64>().ok()?;
        Some(v.iter().map(|x| format!("{x}")).collect())
    };
    let label = format!("{dim}{}", crate::results::LABEL_SUFFIX);
    let mut out = text(&label)
        .map(|l| {
            let idx = text(dim).unwrap_or_default();
            l.iter()
                .enumerate()
                .map(|(i, t)| format!("{} ({t})", idx.get(i).cloned().unwrap_or_default()))
                .collect()
        })
        .or_else(|| text(dim))
        .unwrap_or_default();
    out.resize_with(size, String::new);
    out
}

/// The ball and hoop of a BBCOR scan (`/bat/bbcor_shot`'s JSON) in a few words: the ball's
/// preset or law, and the hoop.
pub(crate) fn shot_name(json: &str) -> String {
    let Ok(shot) = serde_json::from_str::<serde_json::Value>(json) else {
        return String::new();
    };
    let ball = &shot["ball"];
    let ball = match (ball["preset"].as_str(), ball["law"]["kind"].as_str()) {
        (Some(preset), _) => format!("{preset} ball"),
        (None, Some(kind)) => format!("{kind} ball, COR {}", ball["law"]["cor"]),
        (None, None) => "ball unknown".into(),
    };
    let hoop = &shot["hoop"];
    let hoop = if hoop.is_null() {
        "no hoop".to_string()
    } else if hoop["from_geometry"].as_bool() == Some(true) {
        // what a hollow bat's BBCOR rests on: the load's footprint on the wall
        match (
            hoop["patch_radius"].as_f64(),
            hoop["footprint_ratio"].as_f64(),
        ) {
            (Some(r), _) => format!("hoop from the wall, a fixed {r} m patch (a what-if)"),
            (None, ratio) => format!(
                "hoop from the wall under the ball's growing footprint (ratio {}{}), \
                 on which a hollow BBCOR rests",
                ratio.unwrap_or(0.5),
                if ratio.is_none() { ", Hertz's" } else { "" }
            ),
        }
    } else {
        format!("hoop {} Hz", hoop["frequency"])
    };
    printable(&format!("{ball}, {hoop}"), false).into_owned()
}

/// One line per bat (at most 10): mass, centre of mass, swing weight, first mode, BBCOR with
/// the ball and hoop that gave it.
fn inspect_bats(bg: &hdf5::Group, s: &mut String) {
    let f64s = |n: &str| {
        bg.dataset(n)
            .and_then(|d| d.read_raw::<f64>())
            .unwrap_or_default()
    };
    let labels: Vec<String> = bg
        .dataset(l::BAT_DIM.name)
        .and_then(|d| d.read_raw::<VarLenUnicode>())
        .map(|v| v.iter().map(shown).collect())
        .unwrap_or_default();
    let (mass, zcm, moi6, bbcor) = (
        f64s("mass"),
        f64s("z_cm"),
        f64s("moment_of_inertia_knob6"),
        f64s("bbcor_max"),
    );
    let shots: Vec<String> = bg
        .dataset(l::BAT_BBCOR_SHOT.name)
        .and_then(|d| d.read_raw::<VarLenUnicode>())
        .map(|v| v.iter().map(|j| shot_name(j.as_str())).collect())
        .unwrap_or_default();
    let modes = f64s("mode_frequency");
    let per = if labels.is_empty() {
        0
    } else {
        modes.len() / labels.len()
    };
    let _ = writeln!(s, "bats: {}", labels.len());
    for (i, label) in labels.iter().enumerate().take(10) {
        let get = |v: &[f64]| v.get(i).copied().unwrap_or(f64::NAN);
        let f1 = if per > 0 { modes[i * per] } else { f64::NAN };
        let _ = writeln!(
            s,
            "  {label}: mass {:.3} kg, CM {:.3} m, MOI(6 in) {:.4} kg m^2, mode 1 {:.0} Hz, max BBCOR {:.3}{}",
            get(&mass),
            get(&zcm),
            get(&moi6),
            f1,
            get(&bbcor),
            shots.get(i).map_or(String::new(), |n| format!(" ({n})"))
        );
    }
    if labels.len() > 10 {
        let _ = writeln!(s, "  … and {} more (group /bat)", labels.len() - 10);
    }
}

/// Each bat of a results file: its label and its resolved parameters as canonical JSON
/// (`/bat/bat` and `/bat/spec_json`), in the file's order.
pub fn bat_specs(path: &Path) -> Result<Vec<(String, String)>, StoreError> {
    let (f, _, _) = open_checked(path)?;
    let bg = f.group(l::GROUP_BAT).ctx(path, "open group bat")?;
    let strings = |name: &str| {
        bg.dataset(name)
            .and_then(|d| d.read_raw::<VarLenUnicode>())
            .map(|v| v.iter().map(|s| s.as_str().to_string()).collect::<Vec<_>>())
            .ctx(path, "read the bats' labels and specs")
    };
    let (labels, specs) = (strings(l::BAT_DIM.name)?, strings(l::BAT_SPEC.name)?);
    Ok(labels.into_iter().zip(specs).collect())
}

/// The bat `want` names (its label, or its index from 0) among a file's `labels`: its index,
/// or what is allowed. Without `want`, the file's only bat.
pub fn pick_bat(labels: &[String], want: Option<&str>) -> Result<usize, String> {
    let listed = || {
        labels
            .iter()
            .enumerate()
            .map(|(i, l)| format!("{i}: {}", printable(l, false)))
            .collect::<Vec<_>>()
            .join("; ")
    };
    let found = match want {
        None if labels.len() == 1 => Some(0),
        None => None,
        Some(w) => labels
            .iter()
            .position(|l| l == w)
            .or_else(|| w.parse::<usize>().ok().filter(|&i| i < labels.len())),
    };
    match (found, want) {
        (Some(k), _) => Ok(k),
        (None, None) => Err(format!(
            "the file holds {} bats; name one of {}",
            labels.len(),
            listed()
        )),
        (None, Some(w)) => Err(format!(
            "{} is not a bat of the file; allowed: {}",
            printable(w, false),
            listed()
        )),
    }
}
