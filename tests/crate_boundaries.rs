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

/// The lines of every Rust file under `dir` (relative to the repository) that name one of
/// `names`, outside comments: `file:line: name`.
fn naming(dir: &str, names: &[&str], skip: &[&str]) -> Vec<String> {
    let mut files = Vec::new();
    rust_files(&Path::new(ROOT).join(dir), &mut files);
    assert!(!files.is_empty(), "no Rust files under {dir}");
    let mut found = Vec::new();
    for file in files
        .iter()
        .filter(|f| !skip.iter().any(|s| f.ends_with(s)))
    {
        let text = std::fs::read_to_string(file).unwrap();
        for (n, line) in text.lines().enumerate() {
            let code = line.split("//").next().unwrap_or("");
            for name in names.iter().filter(|name| code.contains(*name)) {
                found.push(format!("{}:{}: {name}", file.display(), n + 1));
            }
        }
    }
    found
}

/// The command line's names, as another module would spell them.
const COMMAND_LINE: &[&str] = &["cli::", "crate::cli", "batstudy::cli", "clap", "RunArgs"];

/// The Python binding is a front end of the operations, beside the command line: its API
/// names nothing of the command line. The one exception is the `batstudy` command the wheel
/// installs (python/src/command.rs), which is the command line, started with Python's argv.
#[test]
fn the_python_binding_calls_the_operations_not_the_command_line() {
    let found = naming("python/src", COMMAND_LINE, &["command.rs"]);
    assert!(
        found.is_empty(),
        "the Python API reaches into the command line:\n{}",
        found.join("\n")
    );
    let command = std::fs::read_to_string(Path::new(ROOT).join("python/src/command.rs")).unwrap();
    let named: Vec<&str> = command
        .lines()
        .map(|l| l.split("//").next().unwrap_or(""))
        .flat_map(|l| l.match_indices("cli::").map(move |(i, _)| &l[i..]))
        .collect();
    assert!(
        named
            .iter()
            .all(|n| n.starts_with("cli::Invocation") || n.starts_with("cli::main_exit_code_as")),
        "python/src/command.rs names more of the command line than its entry: {named:?}"
    );
    let lib = std::fs::read_to_string(Path::new(ROOT).join("python/src/lib.rs")).unwrap();
    assert!(
        lib.contains("batstudy::operations"),
        "the binding calls the operations"
    );
}

/// The operations are the library under every front end: they name nothing of the command
/// line, parse no flags, print nothing and end no process; no other library module names
/// the command line either (only the binary's `main`).
#[test]
fn the_operations_know_no_front_end() {
    let mut names = COMMAND_LINE.to_vec();
    names.extend([
        "println!",
        "eprintln!",
        "print!(",
        "eprint!(",
        "std::process::exit",
        "indicatif",
        "ctrlc",
        "pyo3",
    ]);
    let found = naming("src/operations", &names, &[]);
    assert!(
        found.is_empty(),
        "the operations reach a front end:\n{}",
        found.join("\n")
    );
    let mut library = Vec::new();
    for dir in ["src/run", "src/study", "src/optimize", "src/operations"] {
        library.extend(naming(dir, COMMAND_LINE, &[]));
    }
    assert!(
        library.is_empty(),
        "library modules name the command line:\n{}",
        library.join("\n")
    );
}

/// A run's progress reaches a front end only through its observer: the run's own modules
/// draw nothing.
#[test]
fn the_run_draws_nothing() {
    let found = naming("src/run", &["indicatif", "eprintln!", "println!"], &[]);
    assert!(found.is_empty(), "the run draws:\n{}", found.join("\n"));
}
