//! `batstudy._native`: the Rust library behind the Python package. The Python side
//! (`python/batstudy/`) turns these plain results into NumPy arrays, exceptions, a progress
//! bar and xarray trees; nothing here draws or prints.

mod command;
mod fly;

use batstudy::model::outcome::Outcome;
use batstudy::operations::{self as ops, OpError, OptimizeRequest, RunRequest, RunSettings};
use batstudy::run::{self, Observer, SharedObserver};
use batstudy::store::layout as l;
use batstudy::study::{self, LoadOptions, DEFAULT_MAX_POINTS};
use pyo3::exceptions::{PyKeyboardInterrupt, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyTuple};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;

/// Lines the wrapper study puts before the user's spec (the spec's own line numbers are
/// restored in error messages).
const SPEC_LINE_OFFSET: usize = 2;

/// The lines of YAML text, split at every line break YAML knows (`\r\n`, `\r`, `\n`, and
/// YAML 1.1's NEL, LS and PS), so that every line of the spec is indented under its block
/// key (a bare `\r` would otherwise let top-level keys such as `allow_implausible` escape
/// `base:`).
fn yaml_lines(text: &str) -> impl Iterator<Item = &str> {
    text.split("\r\n")
        .flat_map(|l| l.split(['\r', '\n', '\u{85}', '\u{2028}', '\u{2029}']))
}

/// A one-point study around a spec's text (YAML or JSON), with an optional history block.
fn spec_study(spec: &str, history: Option<&str>) -> String {
    let mut s = String::from("name: simulate\n");
    for (key, text) in [("base", Some(spec)), ("history", history)] {
        let Some(text) = text else { continue };
        s.push_str(key);
        s.push_str(":\n");
        for line in yaml_lines(text) {
            s.push_str("  ");
            s.push_str(line);
            s.push('\n');
        }
    }
    s
}

/// Simulate one collision. `spec` is YAML (or JSON) text of a study's `base` block;
/// `history` the text of a `history` block or None. Returns (summary dict, history dict or
/// None); histories as (little-endian f64 bytes, shape).
#[pyfunction]
#[pyo3(signature = (spec, history=None))]
fn simulate<'py>(
    py: Python<'py>,
    spec: &str,
    history: Option<&str>,
) -> PyResult<Bound<'py, PyTuple>> {
    let text = spec_study(spec, history);
    let computed = py.detach(|| -> Result<_, String> {
        let loaded = study::load_str(
            &text,
            Path::new("spec"),
            &LoadOptions {
                max_points: DEFAULT_MAX_POINTS,
            },
        )
        .map_err(|mut e| {
            // positions in the user's text, not the wrapper's
            if let Some(line) = e.line.as_mut() {
                *line = line.saturating_sub(SPEC_LINE_OFFSET).max(1);
            }
            e.to_string()
        })?;
        // the bat prepared once across calls (run::single)
        let one = run::single::simulate_first_point(&loaded)?;
        Ok((one.outcome, one.request, one.id, one.bat))
    });
    let (outcome, request, id, bat) = computed.map_err(PyValueError::new_err)?;
    let summary = summary_dict(py, &outcome)?;
    summary.set_item("point_id", id)?;
    summary.set_item("bat", bat_dict(py, &bat)?)?;
    let hist = match (&outcome.history, &request) {
        (Some(h), Some(req)) => {
            let d = PyDict::new(py);
            let n = req.n_samples;
            let time: Vec<f64> = (0..n).map(|k| k as f64 * req.interval).collect();
            d.set_item("time", (f64_bytes(py, &time), (n,)))?;
            d.set_item("z", (f64_bytes(py, &req.z), (req.z.len(),)))?;
            if !h.trajectory_x.is_empty() {
                let t: Vec<f64> = (0..h.trajectory_x.len())
                    .map(|k| k as f64 * batstudy::model::flight::TRAJECTORY_STEP_S)
                    .collect();
                d.set_item("flight_time", (f64_bytes(py, &t), (t.len(),)))?;
            }
            for (k, (def, _, dims)) in l::HISTORY_VARS.iter().enumerate() {
                let a = l::history_array(h, k);
                if a.is_empty() {
                    continue;
                }
                let shape: Vec<usize> = match dims {
                    l::HistoryDims::Time => vec![n],
                    l::HistoryDims::TimeZ => vec![n, req.z.len()],
                    // the model's own order: (time, mode)
                    l::HistoryDims::ModeTime => vec![n, h.modal.modes],
                    l::HistoryDims::ShapePoint | l::HistoryDims::FlightTime => vec![a.len()],
                };
                d.set_item(def.name, (f64_bytes(py, a), PyTuple::new(py, shape)?))?;
            }
            Some(d)
        }
        _ => None,
    };
    PyTuple::new(py, [summary.into_any(), hist.into_pyobject(py)?.into_any()])
}

/// The bat's card, SI, as `/bat` stores it: its build, the protocol's BBCOR and sweet zone,
/// its frequencies, the field's best q, and each rule's value and margin.
fn bat_dict<'py>(
    py: Python<'py>,
    bat: &batstudy::results::BatVariant,
) -> PyResult<Bound<'py, PyDict>> {
    let (p, m) = (&bat.properties, &bat.properties.metrics);
    let d = PyDict::new(py);
    d.set_item("label", &bat.label)?;
    for (name, value) in [
        ("mass", p.mass),
        ("z_cm", p.z_cm),
        ("moment_of_inertia", p.moment_of_inertia),
        ("moment_of_inertia_knob6", p.moment_of_inertia_knob6),
        ("length", p.length),
        ("drop", p.drop()),
        ("barrel_diameter", p.barrel_diameter()),
        ("bbcor_max", m.bbcor_max),
        ("bbcor_max_position", m.bbcor_max_position),
        ("sweet_zone_start", m.sweet_zone_start),
        ("sweet_zone_end", m.sweet_zone_end),
        ("hoop_mode_frequency", m.hoop_mode_frequency),
        ("barrel_compression", m.barrel_compression),
        ("wall_stress_ratio", m.wall_stress_ratio),
        ("wall_stress_ratio_position", m.wall_stress_ratio_position),
        ("best_q", m.best_q),
        ("best_q_position", m.best_q_position),
    ] {
        d.set_item(name, value)?;
    }
    d.set_item("mode_frequency", p.mode_frequency.clone())?;
    let rules = PyDict::new(py);
    for r in &p.rule_checks {
        rules.set_item(&r.label, (r.value, &r.units, r.margin))?;
    }
    d.set_item("rules", rules)?;
    Ok(d)
}

fn f64_bytes<'py>(py: Python<'py>, v: &[f64]) -> Bound<'py, PyBytes> {
    let mut b = Vec::with_capacity(8 * v.len());
    for x in v {
        b.extend_from_slice(&x.to_le_bytes());
    }
    PyBytes::new(py, &b)
}

/// Every summary variable of the results file's `/summary`, by its public name.
fn summary_dict<'py>(py: Python<'py>, o: &Outcome) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (def, x) in l::SUMMARY_FLOATS.iter().zip(l::summary_floats(o)) {
        d.set_item(def.name, x)?;
    }
    d.set_item(l::RECONTACT.name, o.recontact)?;
    Ok(d)
}

/// The study a Python call names: a path, or YAML text (a dict arrives as JSON text) named
/// `<study text>` in messages, its relative profile paths taken from the working folder.
fn load_study(path: Option<PathBuf>, text: Option<&str>) -> Result<study::Study, OpError> {
    Ok(match (path, text) {
        (_, Some(t)) => ops::load_checked_text(t, Path::new("<study text>"), DEFAULT_MAX_POINTS)?,
        (Some(p), None) => ops::load_checked(&p, DEFAULT_MAX_POINTS)?,
        (None, None) => unreachable!("the Python side gives a path or text"),
    })
}

/// What a finished native command hands the Python side: its ending's name (None for a
/// plain success; `operations::KINDS` names them), the message of a refusal or failure,
/// the output path, the report, whether it was interrupted, and the notes it made.
type Ended = (
    Option<&'static str>,
    String,
    Option<PathBuf>,
    String,
    bool,
    Vec<String>,
);

fn refused(e: OpError) -> Ended {
    ended_by(e, Vec::new())
}

/// A command that did not go through: its ending, its message, and the notes it made.
fn ended_by(e: OpError, notes: Vec<String>) -> Ended {
    (
        Some(e.kind().info().name),
        e.to_string(),
        None,
        String::new(),
        false,
        notes,
    )
}

/// Run a study as `batstudy run` does, with the GIL released: from a file (`study`) or
/// from YAML text (`text`), optionally one shard `(i, n)`. Calls `progress(done,
/// total)` about ten times a second; a KeyboardInterrupt (Ctrl-C) stops the run as the
/// CLI's first Ctrl-C does: the points in flight finish and are written, the file can be
/// resumed. Returns (exit code, message, output path or None, report text, interrupted).
#[pyfunction]
#[pyo3(signature = (study=None, text=None, output=None, jobs=None, resume=false, force=false, progress=None, shard=None))]
#[allow(clippy::too_many_arguments)]
fn run_study(
    py: Python<'_>,
    study: Option<PathBuf>,
    text: Option<String>,
    output: Option<PathBuf>,
    jobs: Option<usize>,
    resume: bool,
    force: bool,
    progress: Option<Bound<'_, PyAny>>,
    shard: Option<(usize, usize)>,
) -> PyResult<Ended> {
    let shard = match shard.map(|(i, n)| format!("{i}/{n}").parse::<run::Shard>()) {
        None => None,
        Some(Ok(s)) => Some(s),
        Some(Err(e)) => return Ok(refused(OpError::BadInput(format!("bad shard: {e}")))),
    };
    let request = RunRequest {
        output,
        jobs,
        existing: ops::existing_from(resume, force),
        shard,
        ..RunRequest::default()
    };
    let settings = match py.detach(|| {
        let loaded = load_study(study, text.as_deref())?;
        Ok::<_, OpError>(RunSettings::new(loaded, &request)?)
    }) {
        Ok(s) => s,
        Err(e) => return Ok(refused(e)),
    };
    let (result, interrupted, notes) = drive(py, progress, "batstudy-run", move |stop, seen| {
        ops::run_study(settings, &stop, seen)
    })?;
    Ok(match result {
        Err(e) => ended_by(e, notes),
        Ok(done) => (
            done.outcome().map(|k| k.info().name),
            String::new(),
            Some(done.settings.output.clone()),
            done.report_text(),
            done.report.interrupted || interrupted,
            notes,
        ),
    })
}

/// What a native command tells the Python side while it runs: the count its progress bar
/// shows, and the notes (warnings) it makes, raised as warnings once it has ended.
#[derive(Default)]
struct Seen {
    done: AtomicUsize,
    total: AtomicUsize,
    notes: Mutex<Vec<String>>,
}

impl Observer for Seen {
    fn progress(&self, done: usize, total: usize) {
        self.total.store(total, Ordering::Relaxed);
        self.done.store(done, Ordering::Relaxed);
    }

    fn note(&self, text: &str) {
        self.notes
            .lock()
            .unwrap_or_else(|p| p.into_inner())
            .push(text.to_string());
    }
}

/// Run `work` on a thread of its own with the GIL released, as a command runs: calls
/// `progress(done, total)` about ten times a second from its counter; a KeyboardInterrupt
/// (Ctrl-C, or raised by a signal handler or the progress bar) sets its stop flag, as the
/// CLI's first Ctrl-C does, and is reported as `interrupted`; any other exception of the
/// progress bar stops the work too and is raised once the work has stopped. Returns what
/// `work` returned, whether it was interrupted, and the notes it made.
fn drive<T: Send + 'static>(
    py: Python<'_>,
    progress: Option<Bound<'_, PyAny>>,
    name: &str,
    work: impl FnOnce(Arc<AtomicBool>, SharedObserver) -> T + Send + 'static,
) -> PyResult<(T, bool, Vec<String>)> {
    let stop = Arc::new(AtomicBool::new(false));
    let counter = Arc::new(Seen::default());
    let handle = {
        let stop = Arc::clone(&stop);
        let seen = SharedObserver(Arc::clone(&counter) as Arc<dyn Observer>);
        std::thread::Builder::new()
            .name(name.into())
            .spawn(move || work(stop, seen))
            .map_err(|e| PyValueError::new_err(format!("cannot start {name}: {e}")))?
    };
    let mut callback_error: Option<PyErr> = None;
    let mut interrupted = false;
    loop {
        let finished = py.detach(|| {
            for _ in 0..10 {
                if handle.is_finished() {
                    return true;
                }
                std::thread::sleep(Duration::from_millis(10));
            }
            handle.is_finished()
        });
        if let Some(cb) = &progress {
            let (done, total) = (
                counter.done.load(Ordering::Relaxed),
                counter.total.load(Ordering::Relaxed),
            );
            if let Err(e) = cb.call1((done, total)) {
                stop.store(true, Ordering::SeqCst);
                if e.is_instance_of::<PyKeyboardInterrupt>(py) {
                    // Ctrl-C arrived while Python ran the progress bar
                    interrupted = true;
                } else {
                    // a progress bar that breaks must not leave the run going on unseen
                    callback_error.get_or_insert(e);
                }
            }
        }
        if finished {
            break;
        }
        if let Err(e) = py.check_signals() {
            // Ctrl-C: finish the points in flight; the wrapper raises KeyboardInterrupt. A
            // signal handler's own exception is raised as itself once the work stopped.
            stop.store(true, Ordering::SeqCst);
            match e.is_instance_of::<PyKeyboardInterrupt>(py) {
                true => interrupted = true,
                false => {
                    callback_error.get_or_insert(e);
                }
            }
        }
    }
    let result = handle
        .join()
        .map_err(|_| PyValueError::new_err(format!("{name}'s thread panicked")))?;
    if let Some(e) = callback_error {
        return Err(e);
    }
    let notes = std::mem::take(&mut *counter.notes.lock().unwrap_or_else(|p| p.into_inner()));
    Ok((result, interrupted, notes))
}

/// Search a study's design as `batstudy optimize` does, in this process, with the GIL
/// released: from a file (`study`) or YAML text (`text`, its relative profile paths taken
/// from the working folder). Progress is in candidates; Ctrl-C stops the search as the
/// CLI's first Ctrl-C does (the candidate in flight finishes and is recorded; `resume`
/// continues it). Returns (exit code, message, output path or None, report text,
/// interrupted).
#[pyfunction]
#[pyo3(signature = (study=None, text=None, output=None, jobs=None, resume=false, force=false, progress=None))]
#[allow(clippy::too_many_arguments)]
fn optimize_study(
    py: Python<'_>,
    study: Option<PathBuf>,
    text: Option<String>,
    output: Option<PathBuf>,
    jobs: Option<usize>,
    resume: bool,
    force: bool,
    progress: Option<Bound<'_, PyAny>>,
) -> PyResult<Ended> {
    let request = OptimizeRequest {
        output,
        jobs,
        resume,
        force,
        ..OptimizeRequest::for_study(
            study
                .clone()
                .unwrap_or_else(|| PathBuf::from("<study text>")),
        )
    };
    let loaded = match py.detach(|| load_study(study, text.as_deref())) {
        Ok(s) => s,
        Err(e) => return Ok(refused(e)),
    };
    let (result, interrupted, notes) =
        drive(py, progress, "batstudy-optimize", move |stop, seen| {
            let done = ops::optimize_study(loaded, &request, &stop, seen);
            done.map(|d| (ops::optimize::report_text(&d, &request), d))
        })?;
    Ok(match result {
        Err(e) => ended_by(e, notes),
        Ok((report, done)) => (
            done.outcome().map(|k| k.info().name),
            done.no_answer().unwrap_or_default(),
            Some(done.output.clone()),
            report,
            done.interrupted || interrupted,
            notes,
        ),
    })
}

/// Merge shard files into `output` as `batstudy merge` does. Returns (ending's name or
/// None, message, points stored, points failed); the message is empty on success.
#[pyfunction]
#[pyo3(signature = (output, shards, force=false, jobs=None, study=None))]
fn merge(
    py: Python<'_>,
    output: PathBuf,
    shards: Vec<PathBuf>,
    force: bool,
    jobs: Option<usize>,
    study: Option<PathBuf>,
) -> (Option<&'static str>, String, usize, usize) {
    let request = ops::MergeRequest {
        output,
        shards,
        study,
        force,
        jobs,
    };
    let seen = Seen::default();
    match py.detach(|| ops::merge_shards(&request, &seen)) {
        Ok(sum) => (
            ops::outcome_of_failed(sum.n_failed).map(|k| k.info().name),
            String::new(),
            sum.n_done,
            sum.n_failed,
        ),
        Err(e) => (Some(e.kind().info().name), e.to_string(), 0, 0),
    }
}

/// The table of endings (`operations::KINDS`): (name, the command line's exit status, the
/// Python exception, what it means), from which the Python side raises.
#[pyfunction]
fn endings() -> Vec<(&'static str, i32, &'static str, &'static str)> {
    ops::KINDS
        .iter()
        .map(|k| (k.name, k.exit_code, k.python, k.meaning))
        .collect()
}

/// What a study expands to (validating it as `batstudy validate` does): a dict with the
/// name, the number of points, the dimensions `[(name, size), …]`, the bats' labels and
/// the number of histories it records (None when not counted: over 20,000 points).
/// Raises ValueError (the Python side: StudyError) for a bad study.
#[pyfunction]
#[pyo3(signature = (study=None, text=None))]
fn describe<'py>(
    py: Python<'py>,
    study: Option<PathBuf>,
    text: Option<String>,
) -> PyResult<Bound<'py, PyDict>> {
    let loaded = py
        .detach(|| load_study(study, text.as_deref()))
        .map_err(|e| PyValueError::new_err(e.to_string()))?;
    let plan = &loaded.plan;
    let d = PyDict::new(py);
    d.set_item("name", &loaded.file.name)?;
    d.set_item("points", plan.n_points())?;
    let dims: Vec<(String, usize)> = plan
        .shape()
        .dims
        .iter()
        .map(|x| (x.name.clone(), x.size))
        .collect();
    d.set_item("dims", dims)?;
    let bats: Vec<String> = plan.bats().iter().map(|b| b.label.clone()).collect();
    d.set_item("bats", bats)?;
    d.set_item("histories", plan.history_count())?;
    d.set_item("output", loaded.output_path(None))?;
    Ok(d)
}

/// A bat of a results file as a profile CSV (`batstudy export-profile`): the text. `bat`:
/// its label or index (may be left out when the file holds one bat); `units`: m, mm or in.
/// Raises ValueError naming the file and what is allowed.
#[pyfunction]
#[pyo3(signature = (results, bat=None, units="m"))]
fn export_profile(
    py: Python<'_>,
    results: PathBuf,
    bat: Option<String>,
    units: &str,
) -> PyResult<String> {
    let units: batstudy::profile_export::Units = units.parse().map_err(PyValueError::new_err)?;
    py.detach(|| batstudy::profile_export::profile_csv(&results, bat.as_deref(), units))
        .map_err(PyValueError::new_err)
}

#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(merge, m)?)?;
    m.add_function(wrap_pyfunction!(describe, m)?)?;
    m.add_function(wrap_pyfunction!(command::cli_main, m)?)?;
    m.add_function(wrap_pyfunction!(endings, m)?)?;
    m.add_function(wrap_pyfunction!(simulate, m)?)?;
    m.add_function(wrap_pyfunction!(run_study, m)?)?;
    m.add_function(wrap_pyfunction!(optimize_study, m)?)?;
    m.add_function(wrap_pyfunction!(export_profile, m)?)?;
    m.add_function(wrap_pyfunction!(fly::fly, m)?)?;
    m.add_function(wrap_pyfunction!(fly::standard_air, m)?)?;
    m.add_function(wrap_pyfunction!(fly::to_si, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
