//! Checking an output path before anything runs: nothing is created or touched.

use std::path::Path;

/// What may happen to an existing output file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Existing {
    /// Refuse an existing file.
    #[default]
    Refuse,
    /// Continue it (`--resume`).
    Resume,
    /// Replace it (`--force`).
    Overwrite,
}

/// Can `path` be written? Its nearest existing ancestor folder must be a writable folder
/// (missing folders are created when the run starts); an existing file needs `--resume`
/// or `--force`. Returns a message (what is wrong) and what is allowed.
pub fn check_output(path: &Path, existing: Existing) -> Result<(), (String, String)> {
    if path.as_os_str().is_empty() {
        return Err((
            "empty output path".into(),
            "a file path such as results/study.h5".into(),
        ));
    }
    // The C library that writes the file ends a path at its first NUL byte.
    if path.as_os_str().as_encoded_bytes().contains(&0) {
        return Err((
            format!(
                "output `{}` holds a NUL byte",
                path.display().to_string().escape_debug()
            ),
            "a file path without NUL bytes, such as results/study.h5".into(),
        ));
    }
    if path.is_dir() {
        return Err((
            format!("output `{}` is a folder", path.display()),
            "a file path such as results/study.h5".into(),
        ));
    }
    if path.exists() {
        match existing {
            Existing::Refuse => {
                return Err((
                    format!("output `{}` exists", path.display()),
                    "a new file; --resume to continue it, --force to replace it".into(),
                ))
            }
            Existing::Resume | Existing::Overwrite => {
                let meta = std::fs::metadata(path).map_err(|e| (e.to_string(), String::new()))?;
                if meta.permissions().readonly() {
                    return Err((
                        format!("output `{}` is read-only", path.display()),
                        "a writable file".into(),
                    ));
                }
            }
        }
    }
    let mut dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    while !dir.exists() {
        match dir.parent() {
            Some(p) if !p.as_os_str().is_empty() => dir = p,
            _ => {
                dir = Path::new(".");
                break;
            }
        }
    }
    if !dir.is_dir() {
        return Err((
            format!("`{}` is not a folder", dir.display()),
            "an output path inside a writable folder".into(),
        ));
    }
    if !dir_writable(dir) {
        return Err((
            format!("folder `{}` is not writable", dir.display()),
            "an output path inside a writable folder".into(),
        ));
    }
    Ok(())
}

/// Writable folder: a probe file is created and removed at once (the output itself is
/// not touched).
fn dir_writable(dir: &Path) -> bool {
    let probe = dir.join(format!(".batstudy-probe-{}", std::process::id()));
    match std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&probe)
    {
        Ok(_) => {
            let _ = std::fs::remove_file(&probe);
            true
        }
        Err(e) => e.kind() == std::io::ErrorKind::AlreadyExists,
    }
}

/// Can a command's small output (a CSV, a JSON report) be written whole at `path`? It is
/// written beside the path and renamed onto it, so whatever is at the path is replaced:
/// refused are one of the command's own `inputs`, anything that is not a regular file (a
/// device, a pipe, a folder, a symbolic link) and an HDF5 file (a results file is never
/// replaced by a text), and a path whose folder does not exist or cannot be written.
pub fn check_side_output(path: &Path, inputs: &[&Path]) -> Result<(), (String, String)> {
    check_output(path, Existing::Overwrite)?;
    let shown = path.display().to_string().escape_debug().to_string();
    let allowed = "a new path, or a regular file that is not one of the command's inputs";
    if let Ok(meta) = std::fs::symlink_metadata(path) {
        if !meta.file_type().is_file() {
            return Err((
                format!("output `{shown}` exists and is not a regular file"),
                allowed.into(),
            ));
        }
        if inputs.iter().any(|i| same_file(path, i)) {
            return Err((
                format!("output `{shown}` is an input of the same command"),
                allowed.into(),
            ));
        }
        if is_hdf5(path) {
            return Err((
                format!("output `{shown}` is an HDF5 file (results are never replaced by a text)"),
                allowed.into(),
            ));
        }
    }
    let parent = path.parent().filter(|p| !p.as_os_str().is_empty());
    if parent.is_some_and(|p| !p.is_dir()) {
        return Err((
            format!("the folder of output `{shown}` does not exist"),
            "a path in an existing folder".into(),
        ));
    }
    Ok(())
}

/// Do two paths name one file (the same device and inode)?
fn same_file(a: &Path, b: &Path) -> bool {
    use std::os::unix::fs::MetadataExt;
    match (std::fs::metadata(a), std::fs::metadata(b)) {
        (Ok(x), Ok(y)) => x.dev() == y.dev() && x.ino() == y.ino(),
        _ => false,
    }
}

/// Does the file start with HDF5's signature (at offset 0, where batstudy writes it)?
fn is_hdf5(path: &Path) -> bool {
    use std::io::Read;
    let mut head = [0u8; 8];
    std::fs::File::open(path)
        .and_then(|mut f| f.read_exact(&mut head))
        .is_ok_and(|()| head == *b"\x89HDF\r\n\x1a\n")
}
