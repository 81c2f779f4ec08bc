//! `batstudy lab`: start the bat lab's server (`crate::lab`) and print its URL.

use crate::lab::{session, Lab, LabSettings};
use crate::operations::{EXIT_BAD_INPUT, EXIT_OK, EXIT_RUN_FAILED};
use std::io::Write;
use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub struct LabArgs {
    /// A study file or a results file to start from (its first point's bat, ball, pitch and
    /// swing). Default: the R161 wood bat, the MLB ball, a 90-mph pitch, a 70-mph swing.
    pub input: Option<PathBuf>,
    /// Port on 127.0.0.1 (default: any free one).
    #[arg(long, default_value_t = 0)]
    pub port: u16,
    /// The directory the page's "save" writes into (default: the current directory).
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Threads the computations use (default: every core).
    #[arg(long)]
    pub jobs: Option<usize>,
}

/// The sessions to start with (one per bat of a study or a results file, labelled; the
/// default one alone), from the input's kind.
fn start_sessions(input: Option<&PathBuf>) -> Result<Vec<(String, serde_json::Value)>, String> {
    let Some(path) = input else {
        return Ok(vec![("r161".into(), session::default_session()?)]);
    };
    let is_h5 = path.extension().is_some_and(|e| e == "h5");
    let text = if is_h5 {
        crate::store::read::file_info(path)
            .map_err(|e| e.to_string())?
            .study_yaml
    } else {
        std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?
    };
    session::sessions_of_study(&text, path)
}

pub(super) fn cmd_lab(a: &LabArgs) -> i32 {
    let starts = match start_sessions(a.input.as_ref()) {
        Ok(s) if !s.is_empty() => s,
        Ok(_) => {
            eprintln!("error: the study has no point to start from");
            return EXIT_BAD_INPUT;
        }
        Err(e) => {
            eprintln!("error: {e}");
            return EXIT_BAD_INPUT;
        }
    };
    let out_dir = a.out.clone().unwrap_or_else(|| PathBuf::from("."));
    if !out_dir.is_dir() {
        eprintln!("error: --out {}: not a directory", out_dir.display());
        return EXIT_BAD_INPUT;
    }
    let settings = LabSettings {
        starts,
        out_dir,
        port: a.port,
        threads: a.jobs.unwrap_or(0),
    };
    let lab = match Lab::bind(settings) {
        Ok(l) => l,
        Err(e) => {
            eprintln!("error: {e}");
            return EXIT_BAD_INPUT;
        }
    };
    // a reader that has gone (a closed pipe) must not stop the server
    let mut out = std::io::stdout();
    let _ = writeln!(out, "batstudy lab: open {}", lab.url());
    let _ = writeln!(
        out,
        "(127.0.0.1 only; the token in the URL is this session's key; Ctrl-C stops)"
    );
    let _ = out.flush();
    match lab.serve() {
        Ok(()) => EXIT_OK,
        Err(e) => {
            eprintln!("error: {e}");
            EXIT_RUN_FAILED
        }
    }
}
