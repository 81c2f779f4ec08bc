//! Search a study's design (its `optimize` block). The request and the study are checked
//! before anything is written; the output's lock is held throughout; every evaluated
//! candidate goes to `OUT.h5.optimize` (synced) before the search goes on, so a killed
//! search loses nothing finished and a resume replays it. At the end the study is run at
//! the best feasible design (its `/summary`, `/sweet_spot`, `/bat`), `/optimize` is added,
//! and the file is renamed into place.

#![allow(clippy::result_large_err)] // StudyError: see study/mod.rs

use super::failure::{Kind, OpError};
use super::files::{check_output_of, jobs_or_all, lock_output, OutputNamed};
use super::run::{run_study, RunRequest, RunSettings};
use crate::optimize::at_design::study_at;
use crate::optimize::pareto::{front, search_pareto};
use crate::optimize::{design_of, Candidate, Design, Evaluation, Evaluator, Stop};
use crate::run::{Phase, SharedObserver};
use crate::store::optimize::{
    journal_path, write_optimize, CandidateRow, ConstraintInfo, OptimizeJournal, OptimizeTable,
    ParetoFront, VariableInfo, FAILED, FEASIBLE, INFEASIBLE,
};
use crate::study::optimize_block::OptimizeMethod;
use crate::study::output::Existing;
use crate::study::{Study, StudyError, DEFAULT_MAX_POINTS};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::Mutex;

/// What a caller asks of a design search, before it is checked.
#[derive(Debug, Clone)]
pub struct OptimizeRequest {
    /// The study's file (named in the resume command a message suggests).
    pub study: PathBuf,
    /// The results file (None: the study's `output`, else `results/<name>.h5`).
    pub output: Option<PathBuf>,
    /// Worker threads (None: every core).
    pub jobs: Option<usize>,
    /// Continue an interrupted search (its candidates are replayed from `OUT.h5.optimize`).
    pub resume: bool,
    /// Replace an existing output file and start the search over.
    pub force: bool,
    /// Largest number of points of the study's grid.
    pub max_points: usize,
    /// The words that start this front end again, for the resume command.
    pub program: String,
}

impl OptimizeRequest {
    /// A request for the study at `study` with every default.
    pub fn for_study(study: PathBuf) -> Self {
        OptimizeRequest {
            study,
            output: None,
            jobs: None,
            resume: false,
            force: false,
            max_points: DEFAULT_MAX_POINTS,
            program: "batstudy".into(),
        }
    }
}

/// A search that went through (or was interrupted).
#[derive(Debug)]
pub struct FinishedSearch {
    pub output: PathBuf,
    pub table: OptimizeTable,
    /// Candidates computed now (the rest were replayed).
    pub computed: usize,
    pub elapsed: std::time::Duration,
    pub interrupted: bool,
    /// Points of the final run at the best design that failed.
    pub failed_points: usize,
}

impl FinishedSearch {
    /// What a search that found no feasible candidate says (None when it found one, or
    /// was interrupted before it could tell).
    pub fn no_answer(&self) -> Option<String> {
        (self.table.best.is_none() && !self.interrupted).then(|| format!(
            "error: no candidate of the search met its constraints without failing: {} holds the study at the start design, which is not a feasible design (its /optimize says why each candidate was refused)",
            self.output.display()
        ))
    }

    /// How the search ends: a plain success with a feasible design and every point of its
    /// run computed; failed points without a feasible design or with failed points;
    /// interrupted.
    pub fn outcome(&self) -> Option<Kind> {
        match (self.interrupted, self.failed_points, self.table.best) {
            (true, _, _) => Some(Kind::Interrupted),
            (false, 0, Some(_)) => None,
            _ => Some(Kind::PointsFailed),
        }
    }
}

/// The study's design problem, the output and the threads, all checked.
fn settings(study: Study, a: &OptimizeRequest) -> Result<(Study, Design, PathBuf, usize), OpError> {
    let design = design_of(&study)?.ok_or_else(|| {
        StudyError::new(&study.path, "the study has no `optimize` block")
            .field("optimize")
            .allowed("a study with an `optimize` block (docs/study-files.md, \"Optimize\")")
    })?;
    let jobs = jobs_or_all(a.jobs, &study.path)?;
    let output = study.output_path(a.output.as_deref());
    // a resumed search replaces the output it finishes (one killed between the rename of
    // the final file and the journal's removal has both)
    let existing = match (a.resume, a.force) {
        (true, _) | (_, true) => Existing::Overwrite,
        _ => Existing::Refuse,
    };
    check_output_of(
        &study,
        &output,
        OutputNamed::of(a.output.is_some()),
        existing,
    )?;
    // the final run writes beside the output first: a file there that is not a leftover
    // results file would be found only after the whole search
    check_output_of(
        &study,
        &optimum_path(&output),
        OutputNamed::ByCaller,
        Existing::Overwrite,
    )?;
    Ok((study, design, output, jobs))
}

/// An interrupted search's journal is continued only when asked (`--resume`) or replaced
/// (`--force`); checked under the output's lock, so that a search still running is
/// reported as busy, not as interrupted.
fn check_interrupted(study: &Study, output: &Path, a: &OptimizeRequest) -> Result<(), OpError> {
    if !journal_path(output).exists() || a.resume || a.force {
        return Ok(());
    }
    Err(
        StudyError::new(&study.path, "an interrupted search of this output exists")
            .field("--output")
            .value(journal_path(output).display().to_string())
            .allowed("--resume to continue it, or --force to start over")
            .into(),
    )
}

/// Search a study's design: check, search, run the best design, write. `observer` is told
/// the candidates done (the recorded ones of a resume at once) against the budget.
pub fn optimize_study(
    study: Study,
    a: &OptimizeRequest,
    stop: &AtomicBool,
    observer: SharedObserver,
) -> Result<FinishedSearch, OpError> {
    let (study, design, output, jobs) = settings(study, a)?;
    let budget = design.block.max_evaluations;
    let _lock = lock_output(&output, &*observer)?;
    check_interrupted(&study, &output, a)?;
    let started = std::time::Instant::now();
    let io = OpError::io;
    let (journal, recorded) = match a.resume && journal_path(&output).exists() {
        true => OptimizeJournal::resume(
            &output,
            &study.sha256,
            (design.variables.len(), design.limits.len()),
        )
        .map_err(OpError::refused)?,
        false => (
            OptimizeJournal::create(&output, &study.sha256).map_err(io)?,
            Vec::new(),
        ),
    };
    let pool = crate::run::build_pool(jobs).map_err(OpError::io)?;
    let evaluator = Evaluator::new(&study, &design);
    let journal = Mutex::new(journal);
    let computed = AtomicUsize::new(0);
    let record = |c: &Candidate| {
        computed.fetch_add(1, Ordering::Relaxed);
        journal
            .lock()
            .expect("journal")
            .append(&row_of(c))
            .map_err(|e| e.to_string())
    };
    let recorded: Vec<Candidate> = recorded.into_iter().map(candidate_of).collect();
    // replayed candidates are answered at once
    let done = AtomicUsize::new(recorded.len());
    observer.phase(Phase::Simulating { total: budget });
    observer.progress(recorded.len(), budget);
    let eval = |x: &[f64]| {
        let e = evaluator.evaluate(x);
        observer.progress(done.fetch_add(1, Ordering::Relaxed) + 1, budget);
        e
    };
    let outcome = pool.install(|| search_pareto(&design, &eval, &record, recorded, stop));
    observer.phase(Phase::Done);
    let journal = journal.into_inner().expect("journal");
    let table = table_of(&design, &outcome.candidates, outcome.stopped);
    let finished = |interrupted, failed_points| FinishedSearch {
        output: output.clone(),
        table: table.clone(),
        computed: computed.load(Ordering::Relaxed),
        elapsed: started.elapsed(),
        interrupted,
        failed_points,
    };
    match outcome.stopped {
        Some(Stop::Interrupted) => return Ok(finished(true, 0)),
        Some(Stop::Record) => {
            return Err(OpError::io(format!(
                "cannot write {}",
                journal_path(&output).display()
            )))
        }
        _ => {}
    }
    let best = table
        .best
        .map_or_else(|| design.start(), |b| table.rows[b].x.clone());
    let failed_points = write_results(&study, &design, &best, &output, jobs, &table, a, stop)?;
    journal.remove().map_err(io)?;
    Ok(finished(false, failed_points))
}

/// The study run at `x` into a file beside the output, `/optimize` added, renamed into
/// place. Returns how many of its points failed.
#[allow(clippy::too_many_arguments)] // each is a distinct input of the final step
fn write_results(
    study: &Study,
    design: &Design,
    x: &[f64],
    output: &Path,
    jobs: usize,
    table: &OptimizeTable,
    a: &OptimizeRequest,
    stop: &AtomicBool,
) -> Result<usize, OpError> {
    let at_best = study_at(study, design, x, a.max_points)?;
    let tmp = optimum_path(output);
    let request = RunRequest {
        output: Some(tmp.clone()),
        jobs: Some(jobs),
        existing: Existing::Overwrite,
        program: a.program.clone(),
        ..RunRequest::default()
    };
    let settings = RunSettings::new(at_best, &request)?;
    let run = run_study(settings, stop, SharedObserver::default())?;
    write_optimize(&tmp, table).map_err(OpError::io)?;
    std::fs::File::open(&tmp)
        .and_then(|f| f.sync_all())
        .and_then(|_| std::fs::rename(&tmp, output))
        .map_err(|e| OpError::io(format!("{}: {e}", output.display())))?;
    crate::store::journal::sync_parent_dir(output);
    Ok(run.report.failed)
}

/// Where the study at the best design is run before it is renamed to the output.
fn optimum_path(output: &Path) -> PathBuf {
    let mut tmp = output.as_os_str().to_owned();
    tmp.push(".optimum.h5");
    PathBuf::from(tmp)
}

fn row_of(c: &Candidate) -> CandidateRow {
    CandidateRow {
        u: c.u.clone(),
        x: c.x.clone(),
        objective: c.evaluation.objective,
        constraints: c.evaluation.constraints.clone(),
        error: c.evaluation.error.clone(),
        penalized: c.penalized,
    }
}

fn candidate_of(r: CandidateRow) -> Candidate {
    Candidate {
        u: r.u,
        x: r.x,
        evaluation: Evaluation {
            objective: r.objective,
            constraints: r.constraints,
            error: r.error,
        },
        penalized: r.penalized,
    }
}

/// The record of the search: rows, statuses, margins and the best feasible row.
fn table_of(design: &Design, cands: &[Candidate], stopped: Option<Stop>) -> OptimizeTable {
    let margins: Vec<Vec<f64>> = cands
        .iter()
        .map(|c| {
            design
                .limits
                .iter()
                .zip(&c.evaluation.constraints)
                .map(|(l, &v)| l.margin(v))
                .collect()
        })
        .collect();
    let status: Vec<i8> = cands
        .iter()
        .zip(&margins)
        .map(|(c, m)| match c.evaluation.error {
            Some(_) => FAILED,
            None if m.iter().all(|&x| x >= 0.0) => FEASIBLE,
            None => INFEASIBLE,
        })
        .collect();
    let sign = if design.objective.maximize { 1.0 } else { -1.0 };
    let best = (0..cands.len())
        .filter(|&i| status[i] == FEASIBLE)
        .max_by(|&a, &b| {
            (sign * cands[a].evaluation.objective)
                .total_cmp(&(sign * cands[b].evaluation.objective))
                .then(b.cmp(&a))
        });
    let nan = |x: Option<f64>| x.unwrap_or(f64::NAN);
    OptimizeTable {
        method: match design.block.method {
            OptimizeMethod::NelderMead => "nelder_mead (argmin 0.11)".into(),
            OptimizeMethod::CmaEs => format!("cma_es (seed {})", design.block.seed()),
        },
        objective: design.objective.quantity.name().into(),
        objective_units: design.objective.quantity.units().into(),
        sense: if design.objective.maximize {
            "maximize"
        } else {
            "minimize"
        }
        .into(),
        over: design.objective.over.name(),
        stopped: match stopped {
            Some(Stop::Budget) => "max_evaluations",
            Some(Stop::Interrupted) => "interrupted",
            Some(Stop::Record) => "journal_failed",
            None => "converged",
        }
        .into(),
        variables: design
            .variables
            .iter()
            .map(|v| VariableInfo {
                name: v.name.clone(),
                units: v.units.clone(),
                min: v.min,
                max: v.max,
            })
            .collect(),
        constraints: design
            .limits
            .iter()
            .map(|l| ConstraintInfo {
                label: l.label(),
                quantity: l.quantity.name().into(),
                units: l.quantity.units().into(),
                min: nan(l.min),
                max: nan(l.max),
                source: l.source.clone(),
                scale: l.scale(),
            })
            .collect(),
        rows: cands.iter().map(row_of).collect(),
        pareto: design.pareto.as_ref().map(|p| ParetoFront {
            quantity: p.quantity.name().into(),
            units: p.quantity.units().into(),
            sense: if p.maximize { "maximize" } else { "minimize" }.into(),
            on_front: front(design, cands).into_iter().map(i8::from).collect(),
        }),
        status,
        margins,
        best,
    }
}

/// The front's candidates, ordered by the second objective (at most 12 of them, evenly
/// spread; `/optimize/pareto` has every one).
fn front_text(s: &mut String, t: &OptimizeTable, front: &ParetoFront) {
    use std::fmt::Write;
    let Some(k) = t.constraints.iter().position(|c| c.source == "pareto") else {
        return;
    };
    let mut on: Vec<usize> = (0..t.rows.len())
        .filter(|&i| front.on_front[i] == 1)
        .collect();
    on.sort_by(|&a, &b| t.rows[a].constraints[k].total_cmp(&t.rows[b].constraints[k]));
    let _ = writeln!(
        s,
        "Pareto front: {} candidates; {} ({}) against {} ({}):",
        on.len(),
        t.objective,
        t.sense,
        front.quantity,
        front.sense
    );
    let shown = on.len().min(12);
    for j in 0..shown {
        let i = on[j * (on.len() - 1) / (shown - 1).max(1)];
        let r = &t.rows[i];
        let _ = writeln!(
            s,
            "  candidate {i:>5}: {:.6} {} at {:.6} {}",
            r.objective, t.objective_units, r.constraints[k], front.units
        );
    }
}

/// The summary a front end shows: candidates, the best feasible design with its margins,
/// the Pareto front, and the command that finishes a search stopped early.
pub fn report_text(d: &FinishedSearch, a: &OptimizeRequest) -> String {
    use std::fmt::Write;
    let t = &d.table;
    let mut s = String::new();
    let secs = d.elapsed.as_secs_f64();
    let _ = writeln!(
        s,
        "{}: {} candidates ({} computed now, {:.1} evaluations/s), stopped: {}",
        d.output.display(),
        t.rows.len(),
        d.computed,
        d.computed as f64 / secs.max(1e-9),
        if d.interrupted {
            "interrupted"
        } else {
            &t.stopped
        }
    );
    match t.best {
        None => {
            let _ = writeln!(s, "no feasible candidate");
        }
        Some(b) => {
            let r = &t.rows[b];
            let _ = writeln!(
                s,
                "best feasible: candidate {b}, {} = {:.6} {} ({})",
                t.objective, r.objective, t.objective_units, t.sense
            );
            for (v, x) in t.variables.iter().zip(&r.x) {
                let _ = writeln!(s, "  {} = {x:.6} {}", v.name, v.units);
            }
            for ((c, x), m) in t.constraints.iter().zip(&r.constraints).zip(&t.margins[b]) {
                let _ = writeln!(s, "  {}: {x:.6} (margin {m:.6} {})", c.label, c.units);
            }
        }
    }
    if let Some(front) = &t.pareto {
        front_text(&mut s, t, front);
    }
    if d.interrupted {
        let _ = writeln!(
            s,
            "stopped early; to finish the search run:\n  {} optimize {} --resume -o {}",
            a.program,
            a.study.display(),
            d.output.display()
        );
    }
    s
}
