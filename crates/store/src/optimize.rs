//! The record of a design search: `OUT.h5.optimize` while it runs (a journal
//! of one JSON line per evaluated candidate, each line synced before the search goes on;
//! a torn last line is dropped on resume), and the group `/optimize` of the results file
//! (docs/layout.md): one row per candidate, the best feasible design as attributes.

use super::dimscale::{self as h5u, attr_num, attr_str, attr_vec, describe, Attacher};
use super::error::{H5Ctx, StoreError};
use super::layout::VarDef;
use hdf5::types::VarLenUnicode;
use hdf5::{Dataset, Group};
use serde::{Deserialize, Serialize};
use std::io::{BufRead, Write};
use std::path::{Path, PathBuf};

/// The group's name.
pub const GROUP_OPTIMIZE: &str = "optimize";
/// Status of a candidate: within every limit.
pub const FEASIBLE: i8 = 0;
/// Status: evaluated, outside a limit.
pub const INFEASIBLE: i8 = 1;
/// Status: its evaluation failed (the message says why).
pub const FAILED: i8 = 2;

/// Version 2: each row carries a checksum (a flipped bit is a torn row, not a candidate).
const JOURNAL_FORMAT: &str = "batstudy-optimize-journal-2";

/// One evaluated candidate. Numbers are kept as their bits in the journal (exact, NaN too).
#[derive(Debug, Clone, PartialEq)]
pub struct CandidateRow {
    /// The scaled design the search asked for.
    pub u: Vec<f64>,
    /// The design evaluated, SI.
    pub x: Vec<f64>,
    pub objective: f64,
    /// Each limit's quantity.
    pub constraints: Vec<f64>,
    pub error: Option<String>,
    /// What the search minimised.
    pub penalized: f64,
}

#[derive(Serialize, Deserialize)]
struct Line {
    u: Vec<u64>,
    x: Vec<u64>,
    objective: u64,
    constraints: Vec<u64>,
    error: Option<String>,
    penalized: u64,
}

fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|x| x.to_bits()).collect()
}
fn floats(v: &[u64]) -> Vec<f64> {
    v.iter().map(|&b| f64::from_bits(b)).collect()
}

/// A row's checksum: the first 8 bytes of the SHA-256 of its JSON, in hex.
fn checksum(json: &str) -> String {
    use sha2::{Digest, Sha256};
    let d = Sha256::digest(json.as_bytes());
    d[..8].iter().map(|b| format!("{b:02x}")).collect()
}

/// A journal line (`CHECKSUM JSON`) whose checksum holds and whose row has `shape` =
/// (variables, constraints) numbers.
fn checked_line(line: &str, (vars, limits): (usize, usize)) -> Option<Line> {
    let (sum, json) = line.split_once(' ')?;
    if sum != checksum(json) {
        return None;
    }
    let l: Line = serde_json::from_str(json).ok()?;
    (l.u.len() == vars && l.x.len() == vars && l.constraints.len() == limits).then_some(l)
}

/// The journal of a search: `OUT.h5.optimize`.
pub fn journal_path(output: &Path) -> PathBuf {
    let mut s = output.as_os_str().to_owned();
    s.push(".optimize");
    PathBuf::from(s)
}

/// An open journal, appended to.
pub struct OptimizeJournal {
    file: std::fs::File,
    path: PathBuf,
}

impl OptimizeJournal {
    /// A new journal for the search identified by `id` (the study's sha256).
    pub fn create(output: &Path, id: &str) -> Result<Self, StoreError> {
        let path = journal_path(output);
        let mut file = super::paths::create_fresh(&path, "create the search's journal")?;
        let head = serde_json::json!({ "format": JOURNAL_FORMAT, "study_sha256": id });
        writeln!(file, "{head}")
            .and_then(|_| file.sync_data())
            .map_err(|e| StoreError::io(&path, "write the search's journal", e))?;
        Ok(OptimizeJournal { file, path })
    }

    /// Open an existing journal of the search `id`: its candidates, and the journal cut
    /// after the last whole one, ready to append. A row is whole when its checksum holds
    /// and it has `shape` = (variables, constraints) numbers; the first that is not ends
    /// the record (what follows it is computed again: the search is deterministic).
    pub fn resume(
        output: &Path,
        id: &str,
        shape: (usize, usize),
    ) -> Result<(Self, Vec<CandidateRow>), StoreError> {
        let path = journal_path(output);
        let f = super::journal::open_journal(&path)?;
        let mut lines = std::io::BufReader::new(f).lines();
        let head: serde_json::Value = lines
            .next()
            .and_then(|l| l.ok())
            .and_then(|l| serde_json::from_str(&l).ok())
            .unwrap_or_default();
        if head["format"] != JOURNAL_FORMAT || head["study_sha256"] != id {
            return Err(StoreError::BadRecord {
                path: path.clone(),
                what: "it is not the journal of this study's search (start over with --force)"
                    .into(),
            });
        }
        let mut rows = Vec::new();
        let mut keep = head.to_string().len() as u64 + 1;
        for line in lines {
            let Ok(line) = line else { break };
            let Some(l) = checked_line(&line, shape) else {
                break;
            };
            keep += line.len() as u64 + 1;
            rows.push(CandidateRow {
                u: floats(&l.u),
                x: floats(&l.x),
                objective: f64::from_bits(l.objective),
                constraints: floats(&l.constraints),
                error: l.error,
                penalized: f64::from_bits(l.penalized),
            });
        }
        let file = std::fs::OpenOptions::new()
            .append(true)
            .open(&path)
            .and_then(|f| f.set_len(keep).map(|_| f))
            .map_err(|e| StoreError::io(&path, "cut the search's journal", e))?;
        Ok((OptimizeJournal { file, path }, rows))
    }

    /// Append one candidate, synced to the disk.
    pub fn append(&mut self, row: &CandidateRow) -> Result<(), StoreError> {
        let line = Line {
            u: bits(&row.u),
            x: bits(&row.x),
            objective: row.objective.to_bits(),
            constraints: bits(&row.constraints),
            error: row.error.clone(),
            penalized: row.penalized.to_bits(),
        };
        let text = serde_json::to_string(&line).expect("a line serializes");
        writeln!(self.file, "{} {text}", checksum(&text))
            .and_then(|_| self.file.sync_data())
            .map_err(|e| StoreError::io(&self.path, "append to the search's journal", e))
    }

    /// Remove the journal (the results file holds the search now).
    pub fn remove(self) -> Result<(), StoreError> {
        drop(self.file);
        super::paths::remove_if_exists(&self.path)
    }
}

/// A design variable, as `/optimize` describes it.
#[derive(Debug, Clone, PartialEq)]
pub struct VariableInfo {
    pub name: String,
    pub units: String,
    pub min: f64,
    pub max: f64,
}

/// A limit, as `/optimize` describes it.
#[derive(Debug, Clone, PartialEq)]
pub struct ConstraintInfo {
    /// E.g. `bat.bbcor <= 0.5`.
    pub label: String,
    pub quantity: String,
    pub units: String,
    pub min: f64,
    pub max: f64,
    pub source: String,
    /// What its relative margin is measured in (the bound's magnitude).
    pub scale: f64,
}

/// Everything `/optimize` holds.
#[derive(Debug, Clone, PartialEq)]
pub struct OptimizeTable {
    pub method: String,
    pub objective: String,
    pub objective_units: String,
    /// `maximize` or `minimize`.
    pub sense: String,
    /// `mean`, `min` or `max` over the study's grid.
    pub over: String,
    /// Why the search stopped: `converged`, `max_evaluations`.
    pub stopped: String,
    pub variables: Vec<VariableInfo>,
    pub constraints: Vec<ConstraintInfo>,
    pub rows: Vec<CandidateRow>,
    /// Each row's status (FEASIBLE, INFEASIBLE, FAILED) and margins (per limit, in its
    /// quantity's units, positive inside).
    pub status: Vec<i8>,
    pub margins: Vec<Vec<f64>>,
    /// The best feasible row.
    pub best: Option<usize>,
    /// A two-objective search's front, if it was one.
    pub pareto: Option<ParetoFront>,
}

/// A two-objective search's second objective and which rows are on the front.
#[derive(Debug, Clone, PartialEq)]
pub struct ParetoFront {
    /// The second objective's quantity, its units, and `minimize` or `maximize`.
    pub quantity: String,
    pub units: String,
    pub sense: String,
    /// 1 for a row on the front (feasible, and beaten in both objectives by no other).
    pub on_front: Vec<i8>,
}

/// Write `/optimize` into the results file at `path`.
pub fn write_optimize(path: &Path, t: &OptimizeTable) -> Result<(), StoreError> {
    let f = hdf5::File::open_rw(path).ctx(path, "open the results file")?;
    let g = f
        .create_group(GROUP_OPTIMIZE)
        .ctx(path, "create group optimize")?;
    let att = Attacher::default();
    let n = t.rows.len();
    let cand = h5u::index_coord(&g, "candidate", n).ctx(path, "write an index coordinate")?;
    let var = labels(
        &g,
        "variable",
        t.variables.iter().map(|v| v.name.as_str()),
        path,
    )?;
    let con = labels(
        &g,
        "constraint",
        t.constraints.iter().map(|c| c.label.as_str()),
        path,
    )?;
    let rows = Rows {
        g: &g,
        cand: &cand,
        att: &att,
        path,
    };
    rows.per_candidate(t)?;
    rows.scaled(t, &var, &con)?;
    write_status(&g, t, &cand, &att, path)?;
    if let Some(front) = &t.pareto {
        write_front(&g, front, &cand, &att, path)?;
    }
    attrs(&g, t, path)?;
    att.write().ctx(path, "attach the dimension scales")?;
    f.flush().ctx(path, "flush the results file")
}

/// Where `/optimize`'s variables along `candidate` go.
struct Rows<'a> {
    g: &'a Group,
    cand: &'a Dataset,
    att: &'a Attacher,
    path: &'a Path,
}

impl Rows<'_> {
    /// A variable of one value per candidate.
    fn one(&self, def: VarDef, data: Vec<f64>) -> Result<(), StoreError> {
        let n = [self.cand.size()];
        write_f64(self.g, &def, &n, &data, &[self.cand], self.att, self.path).map(drop)
    }

    /// The objective, the penalized objective, and each design variable, constraint
    /// quantity and margin: one value per candidate each.
    fn per_candidate(&self, t: &OptimizeTable) -> Result<(), StoreError> {
        let col =
            |of: &dyn Fn(&CandidateRow) -> f64| -> Vec<f64> { t.rows.iter().map(of).collect() };
        let about = format!(
            "{} ({} over the grid) of each candidate",
            t.objective, t.over
        );
        let objective = v("objective", &t.objective_units, "objective", &about);
        self.one(objective, col(&|r| r.objective))?;
        self.one(v("penalized", "1", "penalized objective", "what the search minimised: the objective over its magnitude at the start (negated to maximise) plus the penalties"), col(&|r| r.penalized))?;
        for (k, vi) in t.variables.iter().enumerate() {
            let (name, about) = (
                format!("design_{k}"),
                format!("design variable {} of each candidate", vi.name),
            );
            self.one(v(&name, &vi.units, &vi.name, &about), col(&|r| r.x[k]))?;
        }
        for (k, ci) in t.constraints.iter().enumerate() {
            let (name, about) = (
                format!("constraint_{k}"),
                format!("{} of each candidate (limit: {})", ci.quantity, ci.label),
            );
            let values = col(&|r| r.constraints[k]);
            self.one(v(&name, &ci.units, &ci.quantity, &about), values)?;
            let (name, long, about) = (
                format!("margin_{k}"),
                format!("margin: {}", ci.quantity),
                format!("how far inside the limit {} (negative: outside)", ci.label),
            );
            let margins = t.margins.iter().map(|m| m[k]).collect();
            self.one(v(&name, &ci.units, &long, &about), margins)?;
        }
        Ok(())
    }

    /// The design and the margins as the search saw them: candidate × variable, each over
    /// its range, and candidate × constraint, each over its bound's magnitude.
    fn scaled(&self, t: &OptimizeTable, var: &Dataset, con: &Dataset) -> Result<(), StoreError> {
        let n = t.rows.len();
        let scaled: Vec<f64> = t.rows.iter().flat_map(|r| r.u.iter().copied()).collect();
        let def = v("design_scaled", "1", "design (scaled)", "each variable as the search saw it: (x - min)/(max - min), outside [0, 1] where the search asked beyond a bound");
        let shape = [n, t.variables.len()];
        write_f64(
            self.g,
            &def,
            &shape,
            &scaled,
            &[self.cand, var],
            self.att,
            self.path,
        )?;
        let rel: Vec<f64> = (0..n)
            .flat_map(|r| {
                t.constraints
                    .iter()
                    .enumerate()
                    .map(move |(k, c)| t.margins[r][k] / c.scale)
            })
            .collect();
        let def = v(
            "margin_scaled",
            "1",
            "margin (relative)",
            "each limit's margin over the bound's magnitude (negative: outside)",
        );
        let shape = [n, t.constraints.len()];
        write_f64(
            self.g,
            &def,
            &shape,
            &rel,
            &[self.cand, con],
            self.att,
            self.path,
        )?;
        Ok(())
    }
}

fn v<'a>(name: &'a str, units: &'a str, long: &'a str, desc: &'a str) -> VarDef<'a> {
    VarDef {
        name,
        units,
        long_name: long,
        description: desc,
    }
}

fn labels<'a>(
    g: &Group,
    name: &str,
    items: impl Iterator<Item = &'a str>,
    path: &Path,
) -> Result<Dataset, StoreError> {
    let s: Vec<VarLenUnicode> = items.map(h5u::vlstr).collect();
    let description = format!("the {name}s, by label");
    let def = v(name, "", name, &description);
    h5u::scale_coord(g, name, &s, &def).ctx(path, &format!("write coordinate {name}"))
}

fn write_f64(
    g: &Group,
    def: &VarDef,
    shape: &[usize],
    data: &[f64],
    scales: &[&Dataset],
    att: &Attacher,
    path: &Path,
) -> Result<Dataset, StoreError> {
    let what = format!("write optimize/{}", def.name);
    let ds = g
        .new_dataset::<f64>()
        .shape(shape.to_vec())
        .create(def.name)
        .ctx(path, &what)?;
    h5u::write_small(&ds, data).ctx(path, &what)?;
    describe(&ds, def).ctx(path, &what)?;
    att.add(&ds, scales);
    Ok(ds)
}

/// `pareto` along `candidate`: 1 on the front; its second objective in the attributes.
fn write_front(
    g: &Group,
    front: &ParetoFront,
    cand: &Dataset,
    att: &Attacher,
    path: &Path,
) -> Result<(), StoreError> {
    let ctx = "write optimize/pareto";
    let ds = g
        .new_dataset::<i8>()
        .shape(front.on_front.len())
        .create("pareto")
        .ctx(path, ctx)?;
    h5u::write_small(&ds, &front.on_front).ctx(path, ctx)?;
    let meaning = format!(
        "1: on the front of the objective against {} ({}; feasible, and beaten in both by no other candidate)",
        front.quantity, front.sense
    );
    describe(&ds, &v("pareto", "1", "on the Pareto front", &meaning)).ctx(path, ctx)?;
    attr_vec(&ds, "flag_values", &[0i8, 1]).ctx(path, ctx)?;
    attr_str(&ds, "flag_meanings", "dominated on_front").ctx(path, ctx)?;
    for (k, s) in [
        ("pareto_quantity", &front.quantity),
        ("pareto_units", &front.units),
        ("pareto_sense", &front.sense),
    ] {
        attr_str(g, k, s).ctx(path, ctx)?;
    }
    att.add(&ds, &[cand]);
    Ok(())
}

fn write_status(
    g: &Group,
    t: &OptimizeTable,
    cand: &Dataset,
    att: &Attacher,
    path: &Path,
) -> Result<(), StoreError> {
    let ds = g
        .new_dataset::<i8>()
        .shape(t.status.len())
        .create("status")
        .ctx(path, "write optimize/status")?;
    h5u::write_small(&ds, &t.status).ctx(path, "write optimize/status")?;
    describe(
        &ds,
        &v(
            "status",
            "1",
            "status",
            "0 feasible (within every limit), 1 infeasible, 2 failed",
        ),
    )
    .ctx(path, "describe status")?;
    attr_vec(&ds, "flag_values", &[FEASIBLE, INFEASIBLE, FAILED]).ctx(path, "describe status")?;
    attr_str(&ds, "flag_meanings", "feasible infeasible failed").ctx(path, "describe status")?;
    att.add(&ds, &[cand]);
    let msg: Vec<VarLenUnicode> = t
        .rows
        .iter()
        .map(|r| h5u::vlstr(r.error.as_deref().unwrap_or("")))
        .collect();
    let m = h5u::write_1d(g, "message", &msg).ctx(path, "write optimize/message")?;
    describe(
        &m,
        &v(
            "message",
            "",
            "message",
            "why a candidate failed (empty otherwise)",
        ),
    )
    .ctx(path, "describe message")?;
    att.add(&m, &[cand]);
    Ok(())
}

/// The search's description and its best feasible design, as attributes of `/optimize`.
fn attrs(g: &Group, t: &OptimizeTable, path: &Path) -> Result<(), StoreError> {
    let ctx = "write the attributes of optimize";
    for (k, s) in [
        ("method", &t.method),
        ("objective", &t.objective),
        ("objective_units", &t.objective_units),
        ("sense", &t.sense),
        ("over", &t.over),
        ("stopped", &t.stopped),
    ] {
        attr_str(g, k, s).ctx(path, ctx)?;
    }
    attr_num(g, "evaluations", t.rows.len() as i64).ctx(path, ctx)?;
    let sources: Vec<String> = t
        .constraints
        .iter()
        .map(|c| format!("{}: {}", c.label, c.source))
        .collect();
    attr_str(g, "constraint_sources", &sources.join("; ")).ctx(path, ctx)?;
    attr_num(g, "best_candidate", t.best.map_or(-1, |b| b as i64)).ctx(path, ctx)?;
    let Some(b) = t.best else { return Ok(()) };
    let r = &t.rows[b];
    attr_num(g, "best_objective", r.objective).ctx(path, ctx)?;
    attr_vec(g, "best_design", &r.x).ctx(path, ctx)?;
    attr_vec(g, "best_constraint_values", &r.constraints).ctx(path, ctx)?;
    attr_vec(g, "best_margins", &t.margins[b]).ctx(path, ctx)?;
    let mut best = serde_json::Map::new();
    for (vi, x) in t.variables.iter().zip(&r.x) {
        best.insert(
            vi.name.clone(),
            serde_json::json!({ "value": x, "units": vi.units }),
        );
    }
    for ((ci, x), m) in t.constraints.iter().zip(&r.constraints).zip(&t.margins[b]) {
        best.insert(
            ci.label.clone(),
            serde_json::json!({ "value": x, "margin": m, "units": ci.units, "source": ci.source }),
        );
    }
    attr_str(g, "best", &serde_json::Value::Object(best).to_string()).ctx(path, ctx)
}
