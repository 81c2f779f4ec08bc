//! Bat profile files: `bat.profile.csv: PATH` is read here (relative to the study file)
//! and handed to the model as `ProfileSpec::Knots` (and a wall column as
//! `bat.shell.thickness_knots`).
//!
//! Formats, told apart by the header line (lines starting with `#` are comments):
//! - `z,radius` (or `z,diameter`) with an optional third column `wall`: knots, z from the
//!   knob, increasing from 0, linear between rows. Each column may name its unit as a
//!   suffix: `_m` (the default), `_mm` or `_in` (`z_in,diameter_in,wall_in`). A wall of 0 is
//!   solid; the hollow part starts at the first row with a wall and stays hollow to the end
//!   (`batstudy export-profile` writes this form, with diameters).
//! - `slice_end_cm,diameter_mm` (the R161 table in `data/`): row k is the 1-cm slice from
//!   (k−1) cm to k cm with that outer diameter. Converted to knots at each slice's middle,
//!   plus the two ends (z = 0 with the first slice's radius, z = L with the last's).

use std::path::Path;

/// A profile file read: the outer radius's knots `[[z, R], ...]` and, with a wall column,
/// where the hollow part starts and the wall's knots `[[z, t], ...]` from there (m).
#[derive(Debug, Clone, PartialEq)]
pub struct ProfileTable {
    pub knots: Vec<[f64; 2]>,
    pub wall: Option<(f64, Vec<[f64; 2]>)>,
}

/// Metres per unit of a column named `name` with one of the unit suffixes, if it is `base`.
fn column_scale(name: &str, base: &str) -> Option<f64> {
    match name.strip_prefix(base)? {
        "" | "_m" => Some(1.0),
        "_mm" => Some(1e-3),
        "_in" => Some(0.0254),
        _ => None,
    }
}

/// The header's columns: (z, radius, wall) scales for the knot form, or None for slices.
fn header_scales(cols: &[String]) -> Option<Option<(f64, f64, Option<f64>)>> {
    if cols == ["slice_end_cm", "diameter_mm"] {
        return Some(None);
    }
    let z = column_scale(cols.first()?, "z")?;
    let second = cols.get(1)?;
    // a diameter column (as a lathe's drawing gives it) is half a radius's
    let r =
        column_scale(second, "radius").or_else(|| Some(0.5 * column_scale(second, "diameter")?))?;
    let wall = match cols.get(2) {
        None => None,
        Some(c) => Some(column_scale(c, "wall")?),
    };
    (cols.len() <= 3).then_some(Some((z, r, wall)))
}

/// Parse profile CSV text (see the module's formats).
pub fn parse_profile_csv(text: &str) -> Result<ProfileTable, String> {
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
    let scales = header_scales(&cols).ok_or_else(|| {
        format!(
            "line {header_line}: not a profile header; expected `z,radius` or `z,diameter` with \
             an optional `wall` column, each in m or with a unit suffix `_m`, `_mm`, `_in` \
             (`z_mm,diameter_mm,wall_mm`), or `slice_end_cm,diameter_mm`"
        )
    })?;
    let width = cols.len();
    let mut rows = Vec::new();
    for (n, l) in lines {
        let f: Vec<&str> = l.split(',').map(str::trim).collect();
        if f.len() != width {
            return Err(format!(
                "line {n}: expected {width} columns, found {}",
                f.len()
            ));
        }
        let number = |k: usize| {
            f[k].parse::<f64>()
                .map_err(|_| format!("line {n}, column {}: not a number", k + 1))
        };
        rows.push((0..width).map(number).collect::<Result<Vec<f64>, _>>()?);
    }
    if rows.len() < 2 {
        return Err("a profile needs at least 2 rows".into());
    }
    let table = match scales {
        None => ProfileTable {
            knots: slice_knots(&rows),
            wall: None,
        },
        Some((z, r, wall)) => ProfileTable {
            knots: rows.iter().map(|v| [v[0] * z, v[1] * r]).collect(),
            wall: wall.map(|w| wall_knots(&rows, z, w)).transpose()?,
        },
    };
    check_knots(&table.knots)?;
    Ok(table)
}

/// The R161 table's slices as knots at their middles, plus the two ends.
fn slice_knots(rows: &[Vec<f64>]) -> Vec<[f64; 2]> {
    let mut k = Vec::with_capacity(rows.len() + 2);
    k.push([0.0, rows[0][1] / 2000.0]);
    let mut prev = 0.0;
    for v in rows {
        k.push([(prev + v[0]) / 200.0, v[1] / 2000.0]);
        prev = v[0];
    }
    k.push([prev / 100.0, rows[rows.len() - 1][1] / 2000.0]);
    k
}

/// The wall column: where the hollow part starts (the first row with a wall) and its
/// knots from there; a wall is ≥ 0, and once hollow a bat stays hollow to its end.
fn wall_knots(rows: &[Vec<f64>], z: f64, w: f64) -> Result<(f64, Vec<[f64; 2]>), String> {
    if let Some(v) = rows.iter().find(|v| !(v[2] >= 0.0 && v[2].is_finite())) {
        return Err(format!(
            "wall must be ≥ 0, got {} at z = {}",
            v[2] * w,
            v[0] * z
        ));
    }
    let first = rows
        .iter()
        .position(|v| v[2] > 0.0)
        .ok_or("the wall column is 0 everywhere (a solid bat needs no wall column)")?;
    if let Some(v) = rows[first..].iter().find(|v| v[2] == 0.0) {
        return Err(format!(
            "the wall returns to 0 at z = {} after the hollow part starts (one hollow part, \
             to the end)",
            v[0] * z
        ));
    }
    let knots = rows[first..].iter().map(|v| [v[0] * z, v[2] * w]).collect();
    Ok((rows[first][0] * z, knots))
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
pub fn load_profile_csv(path: &Path) -> Result<ProfileTable, String> {
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
            .knots
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
        assert_eq!(k.knots, vec![[0.0, 0.02], [0.5, 0.03]]);
        assert_eq!(k.wall, None);
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
