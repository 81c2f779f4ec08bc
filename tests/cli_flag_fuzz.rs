//! The commands that take a flag or a file rather than a study — `fly`, `export-profile`,
//! `card` and `compare` — under seeded random flags: hostile numbers (NaN, infinities,
//! overflows, bare numbers in the trade's units), unit suffixes, paths that are devices,
//! pipes, folders, links or the command's own input. The oracle (README's exit statuses):
//! no panic; exit 0 or 2 (3 for I/O); a refusal says what is wrong; an accepted `fly`
//! prints a physical flight (finite carry between 0 and 250 m, a hang time under 15 s);
//! nothing a command reads is changed, and no output lands on a device, pipe or input.

mod common;

use common::Rng;
use std::path::Path;
use std::process::Stdio;

/// Values a hostile or careless user types.
const VALUES: &[&str] = &[
    "NaN",
    "nan",
    "inf",
    "-inf",
    "1e400",
    "-1e400",
    "1e-300",
    "-1",
    "0",
    "",
    " ",
    "100",
    "28",
    "2500",
    "29.92",
    "5280",
    "70",
    "50",
    "3",
    "0.5",
    "45",
    "100mph",
    "28deg",
    "2500rpm",
    "29.92inHg",
    "5280ft",
    "70F",
    "21C",
    "300K",
    "50%",
    "3ft",
    "-5mph",
    "1e9rpm",
    "mph",
    "deg",
    "12abc",
    "0x10",
    "--",
    "-",
    "1,5",
    "١٠٠",
];

const FLY_FLAGS: &[&str] = &[
    "--exit-speed",
    "--launch-angle",
    "--backspin",
    "--sidespin",
    "--spray-angle",
    "--height",
    "--temperature",
    "--elevation",
    "--humidity",
    "--pressure",
    "--tail-wind",
];

fn run(args: &[String]) -> (String, String, i32) {
    let out = common::batstudy_command(&args.iter().map(String::as_str).collect::<Vec<_>>())
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .output()
        .unwrap();
    let code = out.status.code().expect("exited, not killed");
    (
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
        code,
    )
}

/// The number after `word` in `text`.
fn after(text: &str, word: &str) -> f64 {
    let rest = &text[text.find(word).unwrap() + word.len()..];
    rest.split_whitespace().next().unwrap().parse().unwrap()
}

#[test]
fn fly_under_random_flags_exits_2_or_flies_a_physical_ball() {
    let mut rng = Rng(0xF1EE_7001);
    let (mut flown, mut refused) = (0, 0);
    for case in 0..300 {
        let mut args = vec![
            "fly".to_string(),
            "--exit-speed=40".into(),
            "--launch-angle=0.4".into(),
        ];
        for _ in 0..1 + rng.below(3) {
            let flag = FLY_FLAGS[rng.below(FLY_FLAGS.len())];
            let value = VALUES[rng.below(VALUES.len())];
            args.push(format!("{flag}={value}"));
        }
        // the spin is required: a plausible one unless the draw gave its own
        if !args.iter().any(|a| a.starts_with("--backspin")) {
            args.push("--backspin=200".into());
        }
        let (out, err, code) = run(&args);
        match code {
            0 => {
                flown += 1;
                let (carry, hang) = (after(&out, "carry"), after(&out, "hang time"));
                assert!(
                    carry.is_finite() && (0.0..250.0).contains(&carry) && hang < 15.0,
                    "case {case} {args:?}: {out}"
                );
            }
            2 => {
                refused += 1;
                assert!(err.contains("error"), "case {case} {args:?}: {err}");
            }
            c => panic!("case {case} {args:?}: exit {c}: {err}"),
        }
    }
    eprintln!("{flown} flown, {refused} refused");
    assert!(
        flown >= 20 && refused >= 100,
        "{flown} flown, {refused} refused"
    );
}

/// A small results file to read (a rigid study: two bats, three points each).
fn results(dir: &Path) -> std::path::PathBuf {
    let study = dir.join("two.yaml");
    std::fs::write(
        &study,
        "name: two\nmodel: rigid\nbase: {}\ngrid:\n  bat.preset: [r161, aluminum]\n  impact.z: [0.6, 0.7, 0.8]\n",
    )
    .unwrap();
    let out = dir.join("two.h5");
    common::batstudy_ok(&[
        "run",
        study.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--quiet",
    ]);
    out
}

#[test]
fn export_card_and_compare_under_random_flags_never_damage_what_they_read() {
    let dir = tempfile::tempdir().unwrap();
    let h5 = results(dir.path());
    let before = std::fs::read(&h5).unwrap();
    let fifo = dir.path().join("fifo");
    assert!(std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .unwrap()
        .success());
    let link = dir.path().join("link.csv");
    std::os::unix::fs::symlink(&h5, &link).unwrap();
    let s = |p: &Path| p.to_str().unwrap().to_string();
    let files = [
        s(&h5),
        s(&fifo),
        s(&link),
        "/dev/zero".into(),
        "/dev/null".into(),
        s(dir.path()),
        s(&dir.path().join("missing.h5")),
        s(&dir.path().join("no/such/dir/x.csv")),
        s(&dir.path().join("out.csv")),
    ];
    let bats = [
        "0",
        "1",
        "2",
        "-1",
        "r161",
        "aluminum",
        "",
        "1e400",
        "r161\u{1b}[2J",
    ];
    let units = ["m", "mm", "in", "ft", "furlong", ""];
    let mut rng = Rng(0xCA2D_0001);
    for case in 0..150 {
        let pick = |rng: &mut Rng, from: &[&str]| from[rng.below(from.len())].to_string();
        let input = if rng.below(4) == 0 {
            files[rng.below(files.len())].clone()
        } else {
            s(&h5)
        };
        let args: Vec<String> = match rng.below(3) {
            0 => {
                let mut a = vec!["export-profile".to_string(), input];
                if rng.below(2) == 0 {
                    a.extend(["--bat".to_string(), pick(&mut rng, &bats)]);
                }
                if rng.below(2) == 0 {
                    a.extend(["--units".to_string(), pick(&mut rng, &units)]);
                }
                a.extend(["-o".to_string(), files[rng.below(files.len())].clone()]);
                a
            }
            1 => {
                let mut a = vec!["card".to_string(), input];
                if rng.below(2) == 0 {
                    a.extend(["--bat".to_string(), pick(&mut rng, &bats)]);
                }
                a
            }
            _ => vec!["compare".to_string(), input],
        };
        let (_, err, code) = run(&args);
        assert!(
            matches!(code, 0 | 2 | 3),
            "case {case} {args:?}: exit {code}: {err}"
        );
        if code != 0 {
            assert!(err.contains("error"), "case {case} {args:?}: {err}");
        }
        assert_eq!(std::fs::read(&h5).unwrap(), before, "case {case} {args:?}");
        let kind = std::fs::symlink_metadata(&fifo).unwrap().file_type();
        assert!(
            std::os::unix::fs::FileTypeExt::is_fifo(&kind),
            "case {case}"
        );
        assert!(std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink());
    }
}

/// A pipe where a command reads (a results file, a run's or a search's journal) is refused
/// at once: opening it would wait for a writer that never comes (`compare FIFO` hung).
#[test]
fn readers_never_wait_on_a_pipe() {
    let dir = tempfile::tempdir().unwrap();
    let fifo = |name: &str| {
        let p = dir.path().join(name);
        let made = std::process::Command::new("mkfifo")
            .arg(&p)
            .status()
            .unwrap();
        assert!(made.success());
        p.to_str().unwrap().to_string()
    };
    let study = dir.path().join("s.yaml");
    std::fs::write(
        &study,
        "name: s\nmodel: rigid\nbase: {impact: {z: 0.7}}\noptimize:\n  max_evaluations: 5\n  \
         variables: {impact.z: {min: 0.5, max: 0.8}}\n  objective: {maximize: exit_speed}\n",
    )
    .unwrap();
    let study = study.to_str().unwrap().to_string();
    let input = fifo("in.h5");
    let out = dir.path().join("o.h5").to_str().unwrap().to_string();
    fifo("o.h5.journal");
    let out2 = dir.path().join("p.h5").to_str().unwrap().to_string();
    fifo("p.h5.optimize");
    let cases: Vec<Vec<String>> = vec![
        vec!["inspect".into(), input.clone()],
        vec!["card".into(), input.clone()],
        vec!["compare".into(), input.clone()],
        vec!["export-profile".into(), input.clone()],
        vec![
            "merge".into(),
            "-o".into(),
            out2.clone() + "x",
            input.clone(),
        ],
        vec!["validate".into(), input.clone()],
        vec![
            "run".into(),
            study.clone(),
            "-o".into(),
            out.clone(),
            "--resume".into(),
            "--quiet".into(),
        ],
        vec![
            "optimize".into(),
            study.clone(),
            "-o".into(),
            out2.clone(),
            "--resume".into(),
            "--quiet".into(),
        ],
    ];
    for args in cases {
        let mut child =
            common::batstudy_command(&args.iter().map(String::as_str).collect::<Vec<_>>())
                .stdin(Stdio::null())
                .stdout(Stdio::null())
                .stderr(Stdio::piped())
                .spawn()
                .unwrap();
        let start = std::time::Instant::now();
        let status = loop {
            if let Some(s) = child.try_wait().unwrap() {
                break s;
            }
            if start.elapsed().as_secs() > 30 {
                child.kill().unwrap();
                panic!("{args:?} waited on a pipe");
            }
            std::thread::sleep(std::time::Duration::from_millis(20));
        };
        let mut err = String::new();
        std::io::Read::read_to_string(child.stderr.as_mut().unwrap(), &mut err).unwrap();
        assert_eq!(status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains("not a regular file"), "{args:?}: {err}");
    }
}
