//! Records the git commit of the build (and whether the tree was dirty) for the results
//! files' root attributes. Outside a git checkout both stay unknown.
use std::process::Command;

fn git(args: &[&str]) -> Option<String> {
    let out = Command::new("git").args(args).output().ok()?;
    out.status
        .success()
        .then(|| String::from_utf8_lossy(&out.stdout).trim().to_string())
}

/// The results file's HDF5 driver (`direct`), in C: its structures differ between
/// HDF5 1.10 and 2.x, and the compiler sets their fields by name from the headers of the
/// HDF5 linked (`DEP_HDF5_INCLUDE`, from the -sys crate's `links = "hdf5"`).
fn compile_driver() {
    let source = "src/direct/driver.c";
    println!("cargo:rerun-if-changed={source}");
    let mut build = cc::Build::new();
    build.file(source).warnings(true).extra_warnings(true);
    if let Ok(dir) = std::env::var("DEP_HDF5_INCLUDE") {
        build.include(dir);
    }
    build.compile("batstudy_direct_driver");
}

fn main() {
    compile_driver();
    if let Some(commit) = git(&["rev-parse", "HEAD"]) {
        println!("cargo:rustc-env=BATSTUDY_GIT_COMMIT={commit}");
        let dirty =
            git(&["status", "--porcelain", "--untracked-files=no"]).is_some_and(|s| !s.is_empty());
        println!("cargo:rustc-env=BATSTUDY_GIT_DIRTY={}", u8::from(dirty));
    }
    // Rebuild when the checked-out commit moves.
    for path in ["../../.git/HEAD", "../../.git/index"] {
        if std::path::Path::new(path).exists() {
            println!("cargo:rerun-if-changed={path}");
        }
    }
}
