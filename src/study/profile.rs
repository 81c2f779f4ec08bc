//! Bat profile files: `bat.profile.csv: PATH` is read here (relative to the study file)
//! and handed to the model as `ProfileSpec::Knots`.
//!
//! Two formats, told apart by the header line (lines starting with `#` are comments):
//! - `z,radius`: knots in metres, z from the knob, increasing from 0.
//! - `slice_end_cm,diameter_mm` (the R161 table in `data/`): row k is the 1-cm slice from
//!   (k−1) cm to k cm with that outer diameter. Converted to knots at each slice's middle,
//!   plus the two ends (z = 0 with the first slice's radius, z = L with the last's).

use std::path::Path;

/// Parse profile CSV text into knots `[[z, R], ...]` in metres.
pub fn parse_profile_csv(text: &str) -> Result<Vec<[f64; 2]>, String> {
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
    let (header_line, header) = lines
        .next()
        .ok_or("empty profile file (a header line is required)")?;
    let cols: Vec<String> = header.split(',').map(|c| c.trim().to_lowercase()).collect();
    // Messages never quote the file's text: a study may name any file (/etc/shadow, whose
    // first line a quoting message would print), so they say where, not what.
    let slices = match cols.iter().map(String::as_str).collect::<Vec<_>>()[..] {
        ["z", "radius"] => false,
        ["slice_end_cm", "diameter_mm"] => true,
        _ => {
            return Err(format!(
                "line {header_line}: not a profile header; expected `z,radius` (m) or `slice_end_cm,diameter_mm`"
            ))
        }
    };
    let mut rows = Vec::new();
    for (n, l) in lines {
        let f: Vec<&str> = l.split(',').map(str::trim).collect();
        if f.len() != 2 {
            return Err(format!("line {n}: expected 2 columns, found {}", f.len()));
        }
        let number = |k: usize| {
            f[k].parse::<f64>()
                .map_err(|_| format!("line {n}, column {}: not a number", k + 1))
        };
        rows.push([number(0)?, number(1)?]);
    }
    if rows.len() < 2 {
        return Err("a profile needs at least 2 rows".into());
    }
    let knots = if slices {
        let mut k = Vec::with_capacity(rows.len() + 2);
        k.push([0.0, rows[0][1] / 2000.0]);
        let mut prev = 0.0;
        for [end_cm, d_mm] in &rows {
            k.push([(prev + end_cm) / 200.0, d_mm / 2000.0]);
            prev = *end_cm;
        }
        k.push([prev / 100.0, rows.last().unwrap()[1] / 2000.0]);
        k
    } else {
        rows
    };
    check_knots(&knots)?;
    Ok(knots)
}

/// Knots must start at z = 0, increase strictly, and have positive radii.
pub fn check_knots(k: &[[f64; 2]]) -> Result<(), String> {
    if k.len() < 2 {
        return Err("a profile needs at least 2 knots".into());
    }
    if k[0][0] != 0.0 {
        return Err(format!(
            "the profile must start at z = 0 (the knob), starts at {}",
            k[0][0]
        ));
    }
    for w in k.windows(2) {
        if w[1][0].partial_cmp(&w[0][0]) != Some(std::cmp::Ordering::Greater) {
            return Err(format!(
                "profile z must increase strictly: {} then {}",
                w[0][0], w[1][0]
            ));
        }
    }
    if let Some(b) = k
        .iter()
        .find(|p| p[1].is_nan() || p[1] <= 0.0 || !p[1].is_finite())
    {
        return Err(format!(
            "profile radius must be > 0, got {} at z = {}",
            b[1], b[0]
        ));
    }
    Ok(())
}

/// Largest profile file read, bytes (a profile of 10,000 knots is about 300 kB).
pub const MAX_PROFILE_BYTES: u64 = 4 << 20;

/// Read a profile file: a regular file (not a FIFO, which would hang, nor a device such as
/// /dev/zero, which never ends) of at most [`MAX_PROFILE_BYTES`], read with that bound.
pub fn load_profile_csv(path: &Path) -> Result<Vec<[f64; 2]>, String> {
    let text = read_bounded_regular(path, MAX_PROFILE_BYTES)
        .map_err(|e| format!("cannot read profile `{}`: {e}", path.display()))?;
    parse_profile_csv(&text).map_err(|e| format!("profile `{}`: {e}", path.display()))
}

/// The text of a regular file of at most `limit` bytes. Opened without blocking (a FIFO
/// would wait for a writer), checked on the open descriptor (no race with a swap of the
/// path), and read through a bound (files in /proc report size 0).
pub(super) fn read_bounded_regular(path: &Path, limit: u64) -> Result<String, String> {
    use std::io::Read;
    use std::os::unix::fs::OpenOptionsExt;
    let file = std::fs::OpenOptions::new()
        .read(true)
        .custom_flags(libc::O_NONBLOCK)
        .open(path)
        .map_err(|e| e.to_string())?;
    let meta = file.metadata().map_err(|e| e.to_string())?;
    if !meta.is_file() {
        return Err("not a regular file".into());
    }
    if meta.len() > limit {
        return Err(format!(
            "{} bytes, more than the {limit} allowed",
            meta.len()
        ));
    }
    let mut bytes = Vec::new();
    file.take(limit + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| e.to_string())?;
    if bytes.len() as u64 > limit {
        return Err(format!("more than the {limit} bytes allowed"));
    }
    String::from_utf8(bytes).map_err(|_| "not UTF-8 text".into())
}

/// The R161 profile (all presets use its outer shape), for the study's own checks.
pub fn r161_knots() -> &'static [[f64; 2]] {
    static K: std::sync::OnceLock<Vec<[f64; 2]>> = std::sync::OnceLock::new();
    K.get_or_init(|| {
        parse_profile_csv(include_str!("../../data/r161_profile.csv"))
            .expect("embedded R161 profile")
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn r161_slices() {
        let k = r161_knots();
        assert_eq!(k[0][0], 0.0);
        assert!((k.last().unwrap()[0] - 0.84).abs() < 1e-12);
        assert!((k[1][0] - 0.005).abs() < 1e-12);
        assert!((k[1][1] - 0.02525).abs() < 1e-12);
    }

    #[test]
    fn z_radius_format() {
        let k = parse_profile_csv("# c\nz,radius\n0,0.02\n0.5,0.03\n").unwrap();
        assert_eq!(k, vec![[0.0, 0.02], [0.5, 0.03]]);
        assert!(parse_profile_csv("z,radius\n0.1,0.02\n0.5,0.03\n").is_err());
        assert!(parse_profile_csv("x,y\n0,1\n1,2\n").is_err());
    }

    // a study may name any file; its text never reaches the message, and what is not a
    // small regular file is refused before it is read (a FIFO would hang, /dev/zero eat the
    // memory)
    #[test]
    fn messages_never_quote_the_file_and_odd_files_are_refused() {
        let secret = "root:$y$j9T$SECRET:19000:0:99999:7:::";
        let e = parse_profile_csv(&format!("{secret}\nz,radius\n")).unwrap_err();
        assert!(!e.contains("SECRET") && e.contains("line 1"), "{e}");
        let e = parse_profile_csv("z,radius\n0,0.02\n0.5,SECRET\n").unwrap_err();
        assert!(
            !e.contains("SECRET") && e.contains("line 3, column 2"),
            "{e}"
        );
        for odd in ["/dev/zero", "/dev/null"] {
            let e = load_profile_csv(Path::new(odd)).unwrap_err();
            assert!(e.contains("not a regular file"), "{odd}: {e}");
        }
        let dir = tempfile::tempdir().unwrap();
        let fifo = dir.path().join("fifo.csv");
        let c = std::ffi::CString::new(fifo.to_str().unwrap()).unwrap();
        // SAFETY: a valid NUL-terminated path
        assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0);
        let e = load_profile_csv(&fifo).unwrap_err();
        assert!(e.contains("not a regular file"), "{e}");
        let big = dir.path().join("big.csv");
        std::fs::write(&big, vec![b'#'; MAX_PROFILE_BYTES as usize + 1]).unwrap();
        assert!(load_profile_csv(&big).unwrap_err().contains("allowed"));
        let e = load_profile_csv(Path::new("/proc/self/environ")).unwrap_err();
        assert!(!e.contains("PATH="), "{e}");
    }
}
