//! `batstudy fly`: a batted ball's flight on its own, from the command line, in SI or with
//! the field's units.
//!
//! Reference: A. M. Nathan's trajectory calculator's own output (mosaicCalc `Fly_ball`):
//! 103 mph, 27.5°, 2500 rpm of backspin from 3 ft; 70 °F, 50 % RH, 29.92 inHg, 15 ft of
//! elevation. Its table crosses the ground 419.49 ft from contact after 5.520 s and peaks at
//! 92.04 ft. Band, set beforehand: ±1 % each (the workbook's first-order 0.01-s step and its
//! drag factor 0.3 % larger are about a foot each; `tests/physics_flight.rs`).

mod common;

use common::batstudy_command as batstudy;

/// The command's stdout, stderr and exit code.
fn fly(args: &[&str]) -> (String, String, Option<i32>) {
    let mut all = vec!["fly"];
    all.extend_from_slice(args);
    let out = batstudy(&all)
        .stdout(std::process::Stdio::piped())
        .output()
        .unwrap();
    (
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
        out.status.code(),
    )
}

/// The number after `word` in the printed line.
fn after(text: &str, word: &str) -> f64 {
    let rest = &text[text
        .find(word)
        .unwrap_or_else(|| panic!("{word} in {text}"))
        + word.len()..];
    rest.split_whitespace().next().unwrap().parse().unwrap()
}

const FT: f64 = 0.3048;

#[test]
fn the_calculators_fly_ball_in_the_fields_units() {
    let (out, err, code) = fly(&[
        "--exit-speed=103mph",
        "--launch-angle=27.5deg",
        "--backspin=2500rpm",
        "--elevation=15ft",
        "--temperature=70F",
        "--pressure=29.92inHg",
    ]);
    assert_eq!(code, Some(0), "{err}");
    let (carry, apex, hang) = (
        after(&out, "carry"),
        after(&out, "apex"),
        after(&out, "hang time"),
    );
    eprintln!("{out}");
    assert!(
        (carry / FT / 419.49 - 1.0).abs() < 0.01,
        "carry {} ft",
        carry / FT
    );
    assert!(
        (apex / FT / 92.04 - 1.0).abs() < 0.01,
        "apex {} ft",
        apex / FT
    );
    assert!((hang / 5.520 - 1.0).abs() < 0.01, "hang {hang} s");
    // the same ball in SI: 103 mph = 46.04512 m/s, 27.5° = 0.4799655 rad, 2500 rpm =
    // 261.7994 rad/s, 15 ft = 4.572 m, 70 °F = 294.2611 K, 29.92 inHg = 101320.8 Pa
    let (si, _, _) = fly(&[
        "--exit-speed=46.04512",
        "--launch-angle=0.47996554",
        "--backspin=261.79939",
        "--elevation=4.572",
        "--temperature=294.26111",
        "--pressure=101320.76",
    ]);
    assert!((after(&si, "carry") - carry).abs() < 0.01, "{si} vs {out}");
}

/// The trajectory CSV starts at the contact height at t = 0 and ends on the ground at the
/// hang time, where the carry is; time rises; the header names the columns in SI.
#[test]
fn the_trajectory_is_written_whole() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("t.csv");
    let (out, err, code) = fly(&[
        "--exit-speed=45",
        "--launch-angle=0.45",
        "--backspin=250",
        "--trajectory",
        csv.to_str().unwrap(),
    ]);
    assert_eq!(code, Some(0), "{err}");
    let text = std::fs::read_to_string(&csv).unwrap();
    let rows: Vec<Vec<f64>> = text
        .lines()
        .filter(|l| !l.starts_with('#') && !l.starts_with("t_s"))
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    assert!(text.contains("t_s,x_m,y_m,z_m,vx_m_s,vy_m_s,vz_m_s"));
    assert!(rows.len() > 40, "{} rows", rows.len());
    assert_eq!(rows[0][0], 0.0);
    assert!((rows[0][3] - 3.0 * FT).abs() < 1e-12);
    assert!(rows.windows(2).all(|w| w[1][0] > w[0][0]));
    let last = rows.last().unwrap();
    assert!(last[3].abs() < 1e-9, "ends at z = {}", last[3]);
    assert!((last[0] - after(&out, "hang time")).abs() < 1e-3);
    assert!((last[1].hypot(last[2]) - after(&out, "carry")).abs() < 1e-2);
    assert_eq!(
        std::fs::read_dir(dir.path()).unwrap().count(),
        1,
        "only the CSV"
    );
}

/// Bad input: exit 2, the flag named, its value and what is allowed; nothing written.
#[test]
fn bad_input_names_the_flag() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("t.csv");
    let csv = csv.to_str().unwrap();
    let (_, err, code) = fly(&[
        "--exit-speed=300mph",
        "--launch-angle=0.4",
        "--trajectory",
        csv,
    ]);
    assert_eq!(code, Some(2));
    assert!(
        err.contains("--exit-speed")
            && err.contains("`300mph` is 134.112 m/s (SI), outside the plausible 0 to 60 m/s"),
        "{err}"
    );
    let (_, err, code) = fly(&["--exit-speed=40", "--launch-angle=28degs"]);
    assert_eq!(code, Some(2));
    assert!(
        err.contains("28degs") && err.contains("(rad), or with one of deg"),
        "{err}"
    );
    let (_, err, code) = fly(&["--exit-speed=40", "--launch-angle=0.4", "--humidity=1.5"]);
    assert_eq!(code, Some(2));
    assert!(
        err.contains("--humidity")
            && err.contains("`1.5` is 1.5 (SI), outside the plausible 0 to 1"),
        "{err}"
    );
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
}

/// A file or link planted beside the trajectory's path (a shared folder) is neither
/// followed nor overwritten: the CSV is written to a new file of this process's own and
/// renamed into place. A fixed `t.csv.partial`, opened with truncation, was followed.
#[test]
fn a_planted_link_beside_the_trajectory_is_not_followed() {
    let dir = tempfile::tempdir().unwrap();
    let victim = dir.path().join("victim");
    std::fs::write(&victim, b"keep me").unwrap();
    let csv = dir.path().join("t.csv");
    std::os::unix::fs::symlink(&victim, dir.path().join("t.csv.partial")).unwrap();
    let (_, err, code) = fly(&[
        "--exit-speed=45",
        "--launch-angle=0.45",
        "--backspin=200",
        "--trajectory",
        csv.to_str().unwrap(),
    ]);
    assert_eq!(code, Some(0), "{err}");
    assert_eq!(std::fs::read(&victim).unwrap(), b"keep me");
    assert!(std::fs::read_to_string(&csv).unwrap().contains("t_s,x_m"));
}

/// A bare number in the trade's unit where SI is expected (100 for 100 mph, 29.92 for
/// 29.92 inHg, 5280 for a mile of elevation in feet) lies outside the plausible range of the
/// same quantity in a study's `flight` block (model::plausible): refused, naming the suffix
/// that says what was meant. Each flew before (29.92 Pa is near vacuum: 561 ft for 359).
#[test]
fn a_bare_number_in_the_trades_unit_is_refused_with_its_suffix() {
    let base = ["--exit-speed=45", "--launch-angle=0.45", "--backspin=250"];
    for (flag, bare, suffix) in [
        ("--exit-speed", "100", "write `100mph`"),
        ("--launch-angle", "28", "write `28deg`"),
        ("--backspin", "2500", "write `2500rpm`"),
        ("--pressure", "29.92", "write `29.92inHg`"),
        ("--elevation", "5280", "write `5280ft`"),
        ("--temperature", "70", "write `70F`"),
        ("--height", "3", "write `3ft`"),
        ("--humidity", "50", "write `50%`"),
    ] {
        let mut args: Vec<String> = base
            .iter()
            .filter(|a| !a.starts_with(&format!("{flag}=")))
            .map(|a| a.to_string())
            .collect();
        args.push(format!("{flag}={bare}"));
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let (out, err, code) = fly(&args);
        assert_eq!(code, Some(2), "{flag} {bare}: {out}{err}");
        assert!(err.contains(flag) && err.contains(suffix), "{flag}: {err}");
    }
    // with their units the same numbers fly
    let (_, err, code) = fly(&[
        "--exit-speed=100mph",
        "--launch-angle=28deg",
        "--backspin=2500rpm",
        "--pressure=29.92inHg",
        "--elevation=5280ft",
        "--temperature=70F",
        "--height=3ft",
        "--humidity=50%",
    ]);
    assert_eq!(code, Some(0), "{err}");
}

/// The trajectory never replaces what is not a regular file: a pipe or a symbolic link at
/// its path is refused before anything flies (`/dev/null` as root was replaced by a file).
#[test]
fn the_trajectory_never_replaces_a_pipe_or_a_link() {
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("fifo");
    let made = std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .unwrap();
    assert!(made.success());
    let victim = dir.path().join("victim.csv");
    std::fs::write(&victim, b"keep me").unwrap();
    let link = dir.path().join("link.csv");
    std::os::unix::fs::symlink(&victim, &link).unwrap();
    for path in [&fifo, &link] {
        let (_, err, code) = fly(&[
            "--exit-speed=45",
            "--launch-angle=0.45",
            "--backspin=200",
            "--trajectory",
            path.to_str().unwrap(),
        ]);
        assert_eq!(code, Some(2), "{err}");
        assert!(err.contains("is not a regular file"), "{err}");
    }
    let fifo_kind = std::fs::symlink_metadata(&fifo).unwrap().file_type();
    assert!(std::os::unix::fs::FileTypeExt::is_fifo(&fifo_kind));
    assert!(std::fs::symlink_metadata(&link)
        .unwrap()
        .file_type()
        .is_symlink());
    assert_eq!(std::fs::read(&victim).unwrap(), b"keep me");
}

/// A batted ball leaves with 1,000-3,000 rpm; one without spin is a knuckleball that carries
/// tens of feet less (100 mph at 28 deg: 358 ft against 408.6 ft with 2,000 rpm). Without
/// `--backspin` the command flew that knuckleball; now it asks for the spin, and `0` still
/// flies one on purpose.
#[test]
fn a_flight_without_backspin_is_asked_for() {
    let (out, err, code) = fly(&["--exit-speed=100mph", "--launch-angle=28deg"]);
    assert_eq!(code, Some(2), "{out}{err}");
    assert!(err.contains("--backspin"), "{err}");
    let (knuckle, _, code) = fly(&[
        "--exit-speed=100mph",
        "--launch-angle=28deg",
        "--backspin=0",
    ]);
    assert_eq!(code, Some(0));
    let (spun, _, _) = fly(&[
        "--exit-speed=100mph",
        "--launch-angle=28deg",
        "--backspin=2000rpm",
    ]);
    assert!(after(&spun, "carry") - after(&knuckle, "carry") > 10.0 * FT);
}
