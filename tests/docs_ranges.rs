//! docs/study-files.md, "Plausible ranges", states every bound of `model::plausible::RANGES`
//! (the table a user reads is the table the code applies), and every path it bounds is a
//! parameter of study files.

use batstudy::model::plausible::RANGES;
use batstudy::study::paths::known_paths;

/// `1e-4`, `0.5`, `−200`: the forms the table writes numbers in.
fn parse(cell: &str) -> Option<f64> {
    cell.trim().replace('−', "-").parse().ok()
}

#[test]
fn the_documented_ranges_are_the_ranges_in_force() {
    let doc = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/study-files.md"))
        .unwrap();
    for r in RANGES {
        assert!(
            known_paths().contains_key(r.path),
            "{} is not a parameter",
            r.path
        );
        let row = doc
            .lines()
            .find(|l| l.starts_with(&format!("| `{}` |", r.path)))
            .unwrap_or_else(|| panic!("docs/study-files.md has no row for {}", r.path));
        let cells: Vec<&str> = row.split('|').collect();
        assert_eq!(parse(cells[2]), Some(r.min), "{}: min in {row}", r.path);
        assert_eq!(parse(cells[3]), Some(r.max), "{}: max in {row}", r.path);
    }
}
