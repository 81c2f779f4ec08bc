//! The crates are the architecture (docs/architecture.md): the physics crate
//! (crates/physics) is pure functions of a specification, so that another project can use it
//! and a reader can trust that nothing in it writes, waits or prints. It may depend only on
//! the numeric and serialisation crates listed here, and its code names no file system, no
//! thread, no process, no terminal. The store crate (crates/store) depends on the physics,
//! HDF5 and its codecs, never on the study layer or the command line.

use std::path::Path;

const ROOT: &str = env!("CARGO_MANIFEST_DIR");

/// What the physics may depend on: serialisation of its specification (serde, its JSON
/// form, its schema), its errors, and linear algebra.
const PHYSICS_DEPENDENCIES: &[&str] = &["serde", "serde_json", "schemars", "thiserror", "nalgebra"];

/// Names that would bring I/O, threads or printing into the physics.
const FORBIDDEN: &[&str] = &[
    "std::fs",
    "std::io",
    "std::thread",
    "std::process",
    "std::env",
    "std::net",
    "println!",
    "eprintln!",
    "print!(",
    "eprint!(",
    "dbg!(",
    "rayon",
    "hdf5",
    "indicatif",
    "std::sync::mpsc",
];

/// The keys of one `[section]` of a Cargo.toml (the text between it and the next section).
fn section_keys(toml: &str, section: &str) -> Vec<String> {
    let mut inside = false;
    let mut keys = Vec::new();
    for line in toml.lines().map(str::trim) {
        if line.starts_with('[') {
            inside = line == format!("[{section}]");
        } else if inside && !line.is_empty() && !line.starts_with('#') {
            if let Some((key, _)) = line.split_once('=') {
                keys.push(key.trim().to_string());
            }
        }
    }
    keys
}

fn rust_files(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

#[test]
fn the_physics_depends_on_numerics_and_serialisation_only() {
    let toml = std::fs::read_to_string(Path::new(ROOT).join("crates/physics/Cargo.toml")).unwrap();
    for key in section_keys(&toml, "dependencies") {
        assert!(
            PHYSICS_DEPENDENCIES.contains(&key.as_str()),
            "crates/physics depends on `{key}`; allowed: {PHYSICS_DEPENDENCIES:?}"
        );
    }
    assert!(
        section_keys(&toml, "features").is_empty(),
        "the physics has no features"
    );
}

/// What the store may depend on: the physics (the types it stores), HDF5 and the codecs'
/// crates, its worker pool, serialisation. Not the study layer, the YAML, the terminal.
const STORE_DEPENDENCIES: &[&str] = &[
    "batstudy-physics",
    "hdf5",
    "hdf5-sys",
    "ndarray",
    "rayon",
    "serde",
    "serde_json",
    "thiserror",
    "memchr",
    "sha2",
    "libc",
    "libdeflater",
];

#[test]
fn the_store_depends_on_the_physics_hdf5_and_codecs_only() {
    let toml = std::fs::read_to_string(Path::new(ROOT).join("crates/store/Cargo.toml")).unwrap();
    for key in section_keys(&toml, "dependencies") {
        assert!(
            STORE_DEPENDENCIES.contains(&key.as_str()),
            "crates/store depends on `{key}`; allowed: {STORE_DEPENDENCIES:?}"
        );
    }
}

#[test]
fn the_physics_has_no_io_threads_or_printing() {
    let mut files = Vec::new();
    rust_files(&Path::new(ROOT).join("crates/physics/src"), &mut files);
    assert!(files.len() > 10, "{files:?}");
    let mut found = Vec::new();
    for file in &files {
        let text = std::fs::read_to_string(file).unwrap();
        for (n, line) in text.lines().enumerate() {
            let code = line.split("//").next().unwrap_or("");
            for name in FORBIDDEN.iter().filter(|name| code.contains(*name)) {
                found.push(format!("{}:{}: {name}", file.display(), n + 1));
            }
        }
    }
    assert!(
        found.is_empty(),
        "the physics must stay pure:\n{}",
        found.join("\n")
    );
}

#[test]
fn the_scan_finds_what_it_looks_for() {
    // the scan itself can fail: a line that prints is found, a comment about printing is not
    let code = "    println!(\"x\"); // fine";
    assert!(FORBIDDEN
        .iter()
        .any(|n| code.split("//").next().unwrap().contains(n)));
    let comment = "    // println! is not used here";
    assert!(!FORBIDDEN
        .iter()
        .any(|n| comment.split("//").next().unwrap().contains(n)));
    let toml = "[package]\nname = \"x\"\n[dependencies]\nserde = \"1\"\nrayon = \"1\"\n[dev-dependencies]\ntempfile = \"3\"\n";
    assert_eq!(section_keys(toml, "dependencies"), ["serde", "rayon"]);
}
