//! The endings of an operation are one table (`operations::KINDS`): the command line's exit
//! statuses and the Python package's exceptions are read from it, and the documentation
//! states it once (docs/python.md, "How a call ends"; the README's exit statuses).

use batstudy::operations::{Kind, KINDS};
use std::path::Path;

fn doc(path: &str) -> String {
    std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join(path)).unwrap()
}

#[test]
fn every_kind_has_one_row_and_distinct_codes() {
    let kinds = [
        Kind::BadInput,
        Kind::PointsFailed,
        Kind::RunFailed,
        Kind::Interrupted,
    ];
    for k in kinds {
        assert_eq!(KINDS.iter().filter(|r| r.kind == k).count(), 1, "{k:?}");
        assert_eq!(k.info().kind, k);
    }
    let mut codes: Vec<i32> = KINDS.iter().map(|r| r.exit_code).collect();
    codes.sort();
    codes.dedup();
    assert_eq!(codes.len(), KINDS.len(), "exit statuses collide");
    assert!(!codes.contains(&0), "0 is a plain success");
}

#[test]
fn the_python_doc_states_the_table() {
    let text = doc("docs/python.md");
    for k in KINDS {
        let row = text
            .lines()
            .find(|l| l.starts_with(&format!("| `{}` |", k.name)))
            .unwrap_or_else(|| panic!("docs/python.md has no row for `{}`", k.name));
        assert!(
            row.contains(&format!("| {} |", k.exit_code)),
            "{}: {row}",
            k.name
        );
        assert!(row.contains(k.python), "{}: {row}", k.name);
        assert!(row.contains(k.meaning), "{}: {row}", k.name);
    }
}

#[test]
fn the_readme_names_every_exit_status() {
    let text = doc("README.md");
    let para = text
        .split("\n\n")
        .find(|p| p.starts_with("Exit status:"))
        .expect("README's exit statuses");
    for k in KINDS {
        assert!(
            para.contains(&format!("**{}**", k.exit_code)),
            "README's exit statuses lack {} ({})",
            k.exit_code,
            k.name
        );
    }
}
