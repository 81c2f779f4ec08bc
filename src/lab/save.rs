//! The lab's "save": a session's study file and its bat's profile as a CSV, written into
//! the one directory the user named when starting the lab, under a plain name, never over
//! an existing file and never half-written (each file is written aside and linked into
//! place whole).

use super::session;
use serde_json::{json, Value};
use std::io::Write;
use std::path::{Path, PathBuf};

/// Longest name a save may take.
const MAX_NAME: usize = 64;

/// Save `{name, session}` into `dir`: `NAME.yaml` (the study) and `NAME_profile.csv` (the
/// profile's knots, m). Returns the paths written.
pub fn save(body: &Value, dir: &Path) -> Result<Value, String> {
    let name = body
        .get("name")
        .and_then(Value::as_str)
        .ok_or("save: a name is needed")?;
    let plain = !name.is_empty()
        && name.len() <= MAX_NAME
        && name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
    if !plain {
        return Err(format!(
            "save: name {name:?} is not allowed: 1 to {MAX_NAME} letters, digits, '_' or '-'"
        ));
    }
    let session = body.get("session").ok_or("save: the session is missing")?;
    let study = session::study_text(session)?;
    let profile = &session["base"]["bat"]["profile"];
    let knots = profile.get("knots").unwrap_or(profile);
    let study_path = dir.join(format!("{name}.yaml"));
    let profile_path = dir.join(format!("{name}_profile.csv"));
    for p in [&study_path, &profile_path] {
        if p.exists() {
            return Err(format!(
                "save: {} exists; choose another name (the lab never overwrites a file)",
                p.display()
            ));
        }
    }
    write_new(&study_path, &study)?;
    let mut wrote = vec![study_path];
    if let Some(csv) = profile_csv(knots) {
        write_new(&profile_path, &csv)?;
        wrote.push(profile_path);
    }
    let shown: Vec<String> = wrote.iter().map(|p| p.display().to_string()).collect();
    Ok(json!({ "saved": shown }))
}

/// The profile's knots as the CSV `bat.profile: {csv: ...}` reads (`None` unless knots).
fn profile_csv(knots: &Value) -> Option<String> {
    let rows = knots.as_array()?;
    let mut s = String::from(
        "# outer profile of a batstudy lab bat: z from the knob, radius (m)\nz,radius\n",
    );
    for r in rows {
        let (z, radius) = (r.get(0)?.as_f64()?, r.get(1)?.as_f64()?);
        s.push_str(&format!("{z},{radius}\n"));
    }
    Some(s)
}

/// Write `text` to `path`, which must not exist: aside first, then linked into place whole.
fn write_new(path: &Path, text: &str) -> Result<(), String> {
    let aside: PathBuf = path.with_extension(format!("part-{}", std::process::id()));
    let fail = |e: std::io::Error| format!("save: cannot write {}: {e}", path.display());
    let mut f = std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&aside)
        .map_err(fail)?;
    let written = f.write_all(text.as_bytes()).and_then(|_| f.sync_all());
    let linked = written.and_then(|_| std::fs::hard_link(&aside, path));
    let _ = std::fs::remove_file(&aside);
    linked.map_err(fail)
}
