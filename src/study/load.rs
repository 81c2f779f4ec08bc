//! Reading a study file: parse (with source positions), check every key, value and
//! combination that can be checked without running, and build the lazy `Plan`.

use super::error::allowed_from_serde;
use super::error::StudyError;
use super::expand::{build_plan, LoadOptions};
use super::locate::Ctx;
use super::plan::{path_string, value_text, Plan};
use super::source::{keys, Pos, SourceMap};
use super::syntax::{
    check_finite, check_keys, get_segs, validate_history, validate_name, yaml_segs, HISTORY_KEYS,
    TOP_KEYS,
};
use super::types::StudyFile;
use crate::model::outcome::HistoryRequest;
use crate::results::{BatVariant, StudyInfo};
use sha2::{Digest, Sha256};
use std::path::{Path, PathBuf};
use yaml_serde::Value;

/// A loaded, validated study.
#[derive(Debug, Clone)]
pub struct Study {
    /// The study file's path as given.
    pub path: PathBuf,
    /// Its text, verbatim.
    pub text: String,
    /// Hex SHA-256 of `text` and of the files it names (profiles): see `study_digest`.
    pub sha256: String,
    pub file: StudyFile,
    pub plan: Plan,
}

/// Read and validate a study file.
pub fn load(path: &Path, opts: &LoadOptions) -> Result<Study, StudyError> {
    let text = super::profile::read_bounded_regular(path, MAX_STUDY_BYTES)
        .map_err(|e| StudyError::new(path, format!("cannot read the study file: {e}")))?;
    load_str(&text, path, opts)
}

/// Largest study file read, bytes (the biggest bundled one is under 4 kB; a `points` list
/// of 100,000 sets is about 4 MB).
pub const MAX_STUDY_BYTES: u64 = 16 << 20;

/// Validate study text (`path` names it in messages and anchors relative profile paths).
pub fn load_str(text: &str, path: &Path, opts: &LoadOptions) -> Result<Study, StudyError> {
    // A byte-order mark (as some Windows editors write) is not part of the YAML: the
    // parser would take it for the content of a first document.
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let cx = Ctx {
        file: path,
        src: SourceMap::build(text),
    };
    // 1. YAML syntax (nesting bounded first: the parsers' cost grows with the depth).
    if let Some(at) = cx.src.too_deep {
        let mut err = StudyError::new(path, "malformed YAML: nested too deep")
            .value(format!("more than {} levels", super::source::MAX_DEPTH))
            .allowed(format!(
                "at most {} levels of mappings and lists",
                super::source::MAX_DEPTH
            ));
        err.line = Some(at.line);
        err.column = Some(at.column);
        return Err(err);
    }
    let mut root: Value = yaml_serde::from_str(text).map_err(|e| {
        let mut err = StudyError::new(path, format!("malformed YAML: {e}"));
        // yaml_serde gives no location for some errors (a second document): the
        // document's start then.
        let (line, column) = e.location().map_or((1, 1), |l| (l.line(), l.column()));
        err.line = Some(line);
        err.column = Some(column);
        err
    })?;
    // Quantities written with a unit (`34in`, `90mph`) in SI, before anything reads them.
    super::quantities::convert(&cx, &mut root)?;
    let Value::Mapping(top) = &root else {
        return Err(cx
            .err(
                &[],
                "a study file is a mapping with `name`, `base`, `grid`, …",
            )
            .allowed(TOP_KEYS.join(", ")));
    };
    // 2. No NaN or infinity anywhere: serde would turn a NaN into `null` on its way
    //    through JSON, and `null` means "the preset's value".
    check_finite(&cx, &root, &mut Vec::new())?;
    // 3. Unknown keys at the top and in `history`.
    check_keys(&cx, top, &[], TOP_KEYS, "study")?;
    if let Some(Value::Mapping(h)) = top.get("history") {
        check_keys(&cx, h, &keys(&["history"]), HISTORY_KEYS, "history")?;
    }
    // 4. Types of the study's own fields.
    let file: StudyFile = serde_path_to_error::deserialize(root.clone()).map_err(|e| {
        let p = path_string(e.path());
        let segs = yaml_segs(e.path());
        let value = get_segs(&root, &segs).map(value_text);
        let msg = e.into_inner().to_string();
        let whole_document = p.is_empty();
        // serde's own words for an untagged enum name a Rust type; `allowed` names the forms
        let said = match msg.starts_with("data did not match any variant of untagged enum") {
            true => "not one of the forms this field takes".to_string(),
            false => msg.clone(),
        };
        let mut err = cx
            .err(&segs, said)
            .field(if whole_document { "study".into() } else { p });
        if let Some(v) = value.filter(|_| !whole_document) {
            err = err.value(v);
        }
        if let Some(a) = allowed_from_serde(&msg) {
            err = err.allowed(a);
        }
        err
    })?;
    validate_name(&cx, &file)?;
    validate_history(&cx, &file)?;
    let plan = build_plan(&cx, &file, opts)?;
    Ok(Study {
        path: path.to_path_buf(),
        text: text.to_string(),
        sha256: study_digest(text, &plan),
        file,
        plan,
    })
}

/// Hex SHA-256 of the study's text and of every file it names (each profile CSV's path
/// and knots, in the order of their paths): what `--resume` and `merge` compare, so that
/// a profile changed between two runs is a changed study. A study that names no file
/// keeps the digest of its text alone.
fn study_digest(text: &str, plan: &Plan) -> String {
    let mut h = Sha256::new();
    h.update(text.as_bytes());
    let mut named: Vec<_> = plan.profiles.iter().collect();
    named.sort_by(|a, b| a.0.cmp(b.0));
    for (path, table) in named {
        h.update(b"\0profile\0");
        h.update(path.as_bytes());
        h.update(b"\0");
        for x in table.knots.iter().flatten() {
            h.update(x.to_le_bytes());
        }
        // a wall column is part of the file's bat; a file without one hashes as before
        if let Some((from, wall)) = &table.wall {
            h.update(b"\0wall\0");
            h.update(from.to_le_bytes());
            for x in wall.iter().flatten() {
                h.update(x.to_le_bytes());
            }
        }
    }
    hex(&h.finalize())
}

fn hex(b: &[u8]) -> String {
    b.iter().map(|x| format!("{x:02x}")).collect()
}

impl Study {
    /// The output path: `-o` if given, else the study's `output`, else `results/<name>.h5`
    /// (relative paths are relative to the current working directory).
    pub fn output_path(&self, cli_override: Option<&Path>) -> PathBuf {
        if let Some(p) = cli_override {
            return p.to_path_buf();
        }
        match &self.file.output {
            Some(o) => PathBuf::from(o),
            None => PathBuf::from("results").join(format!("{}.h5", self.file.name)),
        }
    }

    /// The history request for bats up to `max_length` m long (None: summaries only).
    pub fn history_request(&self, max_length: f64) -> Option<HistoryRequest> {
        self.file
            .history
            .as_ref()
            .filter(|h| !h.fields.is_empty())
            .map(|h| h.request(max_length))
    }

    /// What the store needs before the first point.
    pub fn info(&self, bats: Vec<BatVariant>, history: Option<HistoryRequest>) -> StudyInfo {
        StudyInfo {
            name: self.file.name.clone(),
            description: self.file.description.clone(),
            study_text: self.text.clone(),
            study_sha256: self.sha256.clone(),
            study_path: self.path.display().to_string(),
            shape: self.plan.shape.clone(),
            history,
            bats,
            allow_implausible: self.file.allow_implausible,
            sample_dim: self
                .file
                .sample
                .as_ref()
                .map(|s| s.name.clone().unwrap_or_else(|| "sample".into())),
        }
    }

    /// Position of a top-level key in the file (for messages about `output`).
    pub fn position_of(&self, key: &str) -> Option<Pos> {
        SourceMap::build(&self.text).get(&keys(&[key]))
    }
}
