//! The error of a bad study: where (file, line, column), what (field, value) and what
//! would have been accepted.

use std::fmt;
use std::path::PathBuf;

/// A bad-input error. Printed as
/// `FILE:LINE:COL: error in FIELD: MESSAGE` followed by `value:` and `allowed:` lines.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct StudyError {
    pub file: PathBuf,
    /// 1-based line, when the error has a place in the file.
    pub line: Option<usize>,
    /// 1-based column.
    pub column: Option<usize>,
    /// The dotted field, e.g. `bat.material.density` or `grid.impact.z`.
    pub field: Option<String>,
    /// The offending value as written (YAML/JSON form).
    pub value: Option<String>,
    /// What is allowed.
    pub allowed: Option<String>,
    pub message: String,
}

impl StudyError {
    pub fn new(file: impl Into<PathBuf>, message: impl Into<String>) -> Self {
        StudyError {
            file: file.into(),
            message: message.into(),
            ..Default::default()
        }
    }
    pub fn at(mut self, pos: Option<super::source::Pos>) -> Self {
        if let Some(p) = pos {
            self.line = Some(p.line);
            self.column = Some(p.column);
        }
        self
    }
    pub fn field(mut self, f: impl Into<String>) -> Self {
        self.field = Some(f.into());
        self
    }
    pub fn value(mut self, v: impl Into<String>) -> Self {
        self.value = Some(v.into());
        self
    }
    pub fn allowed(mut self, a: impl Into<String>) -> Self {
        self.allowed = Some(a.into());
        self
    }
}

pub use crate::results::printable;

impl fmt::Display for StudyError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let p = |s: &str| printable(s, false).into_owned();
        write!(f, "{}", p(&self.file.display().to_string()))?;
        if let Some(l) = self.line {
            write!(f, ":{l}")?;
            if let Some(c) = self.column {
                write!(f, ":{c}")?;
            }
        }
        write!(f, ": error")?;
        if let Some(field) = &self.field {
            write!(f, " in `{}`", p(field))?;
        }
        write!(f, ": {}", printable(&self.message, true))?;
        if let Some(v) = &self.value {
            write!(f, "\n  value: {}", p(v))?;
        }
        if let Some(a) = &self.allowed {
            write!(f, "\n  allowed: {}", printable(a, true))?;
        }
        Ok(())
    }
}

impl std::error::Error for StudyError {}

/// "did you mean" from a list of candidates (Levenshtein distance, at most a third of the
/// word's length, at least 2).
pub fn did_you_mean<'a>(
    word: &str,
    candidates: impl IntoIterator<Item = &'a str>,
) -> Option<String> {
    let limit = (word.len() / 3).max(2);
    candidates
        .into_iter()
        .map(|c| (strsim::levenshtein(word, c), c))
        .filter(|(d, _)| *d <= limit)
        .min_by_key(|(d, _)| *d)
        .map(|(_, c)| c.to_string())
}

/// "allowed" text from a serde message (`…, expected X`).
pub(crate) fn allowed_from_serde(msg: &str) -> Option<String> {
    if msg.starts_with("missing field") {
        return Some("this field is required".into());
    }
    // serde's untagged enums say only that no form matched: name the forms
    if let Some(kind) = msg.strip_prefix("data did not match any variant of untagged enum ") {
        return Some(
            match kind.trim() {
                "PointsBlock" => "a list of parameter sets `[{path: value, …}, …]`, or `{name: DIM, sets: [{path: value, …}, …]}`",
                "AxisValues" => "a non-empty list, {linspace: [start, stop, n]}, {range: [start, stop, step]}",
                "ProfileSpec" => "`{csv: PATH}` or a list of knots `[[z, radius], …]` (m)",
                "Knot" => "a number (fixed, m) or `{min, max, start}` (a design variable, m)",
                _ => "one of the forms in docs/study-files.md",
            }
            .to_string(),
        );
    }
    msg.split_once(", expected ").map(|(_, a)| match a {
        "f64" | "f32" => "a number".to_string(),
        "usize" | "u64" | "u32" => "a whole number >= 0".to_string(),
        _ => a.to_string(),
    })
}
