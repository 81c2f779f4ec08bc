//! `batstudy inspect`: sweet spots named by their coordinates and labels, not by
//! an index; the bats' properties; a maximum at the edge of the sampled range flagged.

mod common;

use common::batstudy_ok;
use std::process::Command;

/// HDF5 opens files without close-on-exec, with a lock: a child forked while a test holds
/// one open would keep it locked. The file is edited under [`no_spawns`], children run under
/// [`spawn_guard`] (as in tests/shards_merge_slurm.rs).
static FORK: std::sync::RwLock<()> = std::sync::RwLock::new(());

fn spawn_guard() -> std::sync::RwLockReadGuard<'static, ()> {
    FORK.read().unwrap_or_else(|e| e.into_inner())
}

fn no_spawns() -> std::sync::RwLockWriteGuard<'static, ()> {
    FORK.write().unwrap_or_else(|e| e.into_inner())
}

/// Run `study` (YAML text) into a results file in a new folder; returns both.
fn results_of(study: &str) -> (tempfile::TempDir, std::path::PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("s.yaml");
    std::fs::write(&path, study).unwrap();
    let out = dir.path().join("s.h5");
    let _g = spawn_guard();
    batstudy_ok(&[
        "run",
        path.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "-q",
    ]);
    (dir, out)
}

/// `batstudy COMMAND FILE ARGS…` run to its end (children only under [`spawn_guard`]).
fn command(cmd: &str, out: &std::path::Path, args: &[&str]) -> std::process::Output {
    let _g = spawn_guard();
    Command::new(env!("CARGO_BIN_EXE_batstudy"))
        .args([cmd, out.to_str().unwrap()])
        .args(args)
        .output()
        .unwrap()
}

/// `batstudy COMMAND FILE`'s standard output (it must succeed).
fn stdout_of(cmd: &str, out: &std::path::Path) -> String {
    let o = command(cmd, out, &[]);
    let text = String::from_utf8(o.stdout).unwrap();
    assert!(o.status.success(), "{text}");
    text
}

/// `batstudy inspect FILE`'s standard output (it must succeed).
fn inspect(out: &std::path::Path) -> String {
    stdout_of("inspect", out)
}

#[test]
fn inspect_names_sweet_spots_by_coordinates_and_lists_the_bats() {
    // The R161 base case's sweet spot lies near 0.65 m on the still bat and moves toward the
    // barrel with the swing (the paper's Fig. 6: about 0.71 m at -60 rad/s); a range that
    // starts at 0.66 m cuts off the still bat's at its edge.
    let (_dir, out) = results_of(
        "name: s\nmodel: wave\nbase: {bat: {preset: r161}, ball: {speed: 40}}\n\
         grid:\n  impact.z: {range: [0.66, 0.80, 0.02]}\n\
         points:\n  name: case\n  sets:\n    - {}\n    - {swing.omega: -60}\n",
    );
    let text = inspect(&out);
    let line = |prefix: &str| {
        text.lines()
            .find(|l| l.starts_with(prefix))
            .unwrap_or_else(|| panic!("no line {prefix}: {text}"))
            .to_string()
    };
    let still = line("sweet spot at case=0 (base): z = 0.6600 m");
    assert!(
        still.ends_with("(at the edge of the sampled impact_z)"),
        "{text}"
    );
    let swung = line("sweet spot at case=1 (swing.omega=-60): z = 0.7");
    assert!(!swung.contains("edge"), "{text}");
    assert!(!text.contains("sweet spot [0]"), "{text}");
    assert!(
        text.contains("bats: 1") && text.contains("r161: mass 0.8"),
        "{text}"
    );
}

// `inspect` never prints terminal escape sequences from the file's strings raw
#[test]
fn inspect_prints_no_terminal_control_sequences() {
    let (_dir, out) = results_of(
        "name: s\nmodel: rigid\nbase: {ball: {speed: 40}}\ngrid:\n  impact.z: [0.6, 0.7]\n",
    );
    {
        let _g = no_spawns();
        let f = hdf5::File::open_rw(&out).unwrap();
        let name: hdf5::types::VarLenUnicode =
            "s\u{1b}]0;pwned\u{7}\u{1b}[2J\r\u{202e}x".parse().unwrap();
        f.attr("study_name").unwrap().write_scalar(&name).unwrap();
    }
    let text = inspect(&out);
    assert!(
        !text.contains('\u{1b}') && !text.contains('\r') && !text.contains('\u{202e}'),
        "{text:?}"
    );
    assert!(text.contains("\\u{1b}]0;pwned"), "{text}");
}

/// `/bat/NAME` of a results file, one value per bat.
fn bat_floats(out: &std::path::Path, name: &str) -> Vec<f64> {
    let _g = no_spawns();
    let f = hdf5::File::open(out).unwrap();
    f.dataset(&format!("bat/{name}"))
        .unwrap()
        .read_raw::<f64>()
        .unwrap()
}

#[test]
fn the_bat_card_states_what_each_bat_is_and_how_it_stands_under_each_rule() {
    // A solid wood bat and a hollow alloy BBCOR bat whose hoop mode comes from its wall.
    let (_dir, out) = results_of(
        "name: card\nmodel: wave\nbase: {bat: {preset: r161}, ball: {preset: mlb}, \
         hoop: {from_geometry: true}}\n\
         grid:\n  impact.z: [0.70]\n\
         points:\n  name: case\n  sets:\n    - {hoop: null}\n    - {bat.preset: alloy_bbcor}\n",
    );
    the_cards_numbers_follow_their_definitions(&out);
    let text = stdout_of("card", &out);
    // The rules: the rule books' own numbers, and the verdicts they give.
    for line in [
        "ncaa_bbcor: bat.barrel_diameter <= 0.066675", // 2 5/8 in (NCAA Rule 1-12)
        "mlb_wood: bat.barrel_diameter <= 0.066294",   // 2.61 in (OBR 3.02(a))
        "mlb_wood: bat.length <= 1.0668",              // 42 in
    ] {
        assert!(text.contains(line), "{line} in\n{text}");
    }
    let cards: Vec<&str> = text.split("\n\n").collect();
    assert_eq!(cards.len(), 2, "{text}");
    let verdict = |card: &str, rule: &str| {
        let line = card.lines().find(|l| l.contains(rule)).unwrap().to_string();
        line.trim_end().ends_with("passes")
    };
    assert!(verdict(cards[0], "one piece of solid wood"));
    // MLB's rules are for wood bats: a hollow alloy bat is not judged by them (it does not
    // "fail" them); its NCAA lines stay, with the trade's units beside SI
    let not_for = cards[1].lines().find(|l| l.contains("mlb_wood:")).unwrap();
    assert!(not_for.contains("not for this bat"), "{not_for}");
    assert!(
        !cards[1]
            .lines()
            .any(|l| l.contains("mlb_wood") && l.contains("FAILS")),
        "{}",
        cards[1]
    );
    assert!(
        cards[1].contains("m       margin") && cards[1].contains(" in)"),
        "{}",
        cards[1]
    );
    assert!(cards[0].contains("none (a solid bat)"));
    assert!(cards[1].contains("breathing mode"));
    // the trade's barrel compression: the hollow bat's, in lbf beside N, and no line for wood
    assert!(!cards[0].contains("barrel compression"), "{}", cards[0]);
    let squeeze = bat_floats(&out, "barrel_compression");
    assert!(squeeze[0].is_nan() && squeeze[1] > 0.0, "{squeeze:?}");
    let line = format!("{:.0} lbf at 0.040 in", squeeze[1] / (0.45359237 * 9.80665));
    assert!(cards[1].contains(&line), "{line} in\n{}", cards[1]);
    // the best q in the field's convention, where the bat's BBCOR scan is
    assert!(
        cards.iter().all(|c| c.contains("best q             0.")),
        "{text}"
    );
    // the table: a row per bat under two header lines, the rules kept as the cards count them
    let table = stdout_of("compare", &out);
    let rows: Vec<&str> = table.lines().skip(2).collect();
    assert_eq!(rows.len(), 2, "{table}");
    for ((row, card), judged) in rows.iter().zip(&cards).zip([6, 3]) {
        let kept = card.matches("passes").count();
        assert!(row.contains(&format!(" {kept}/{judged} ")), "{row}\n{card}");
    }
    // several files in one table, each bat named by its file
    let path = out.to_str().unwrap();
    let o = command("compare", &out, &[path]);
    let both = String::from_utf8(o.stdout).unwrap();
    assert!(o.status.success(), "{both}");
    let rows: Vec<&str> = both.lines().skip(2).collect();
    assert_eq!(rows.len(), 4, "{both}");
    assert!(
        rows.iter().all(|r| r.contains(&format!("{path}: "))),
        "{both}"
    );
    // one bat by label; an unknown one is refused with the labels allowed (exit 2)
    let o = Command::new(env!("CARGO_BIN_EXE_batstudy"))
        .args(["card", out.to_str().unwrap(), "--bat", "1"])
        .output()
        .unwrap();
    assert!(o.status.success());
    assert_eq!(
        String::from_utf8(o.stdout).unwrap(),
        format!("{}\n", cards[1].trim_end())
    );
    let o = command("card", &out, &["--bat", "nope"]);
    let err = String::from_utf8(o.stderr).unwrap();
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("nope is not a bat of the file") && err.contains("0: "),
        "{err}"
    );
}

/// The card's numbers in `/bat` against their definitions: drop, the parallel axes, the
/// sweet zone's ends on the stored scan, the hoop mode the collisions used (bats 0 and 1).
fn the_cards_numbers_follow_their_definitions(out: &std::path::Path) {
    let (mass, length, drop) = (
        bat_floats(out, "mass"),
        bat_floats(out, "length"),
        bat_floats(out, "drop"),
    );
    let (zcm, knob, knob6) = (
        bat_floats(out, "z_cm"),
        bat_floats(out, "moment_of_inertia_knob"),
        bat_floats(out, "moment_of_inertia_knob6"),
    );
    for b in 0..2 {
        // The rule books' drop: ounces (28.349523125 g, avoirdupois) minus inches (25.4 mm).
        let want = mass[b] / 0.028349523125 - length[b] / 0.0254;
        assert!(
            (drop[b] - want).abs() < 1e-9,
            "bat {b}: {} vs {want}",
            drop[b]
        );
        // Parallel axes (Steiner): I_knob − I_6in = M (z_cm² − (z_cm − 6 in)²).
        let steiner = mass[b] * (zcm[b].powi(2) - (zcm[b] - 0.1524).powi(2));
        assert!(
            (knob[b] - knob6[b] - steiner).abs() < 1e-9 * knob[b],
            "bat {b}"
        );
    }
    // The sweet zone: where the stored scan, read linearly between its points, is 0.01 below
    // the peak (the trade's "sweet-zone length"), around the peak.
    let (peak, at) = (
        bat_floats(out, "bbcor_max"),
        bat_floats(out, "bbcor_max_position"),
    );
    let (start, end) = (
        bat_floats(out, "sweet_zone_start"),
        bat_floats(out, "sweet_zone_end"),
    );
    let (scan_z, scan) = (bat_floats(out, "bbcor_z"), bat_floats(out, "bbcor"));
    let n = scan_z.len() / 2;
    for b in 0..2 {
        let (z, v) = (&scan_z[b * n..(b + 1) * n], &scan[b * n..(b + 1) * n]);
        let read = |x: f64| {
            let k = z.iter().rposition(|&zk| zk <= x).unwrap().min(z.len() - 2);
            v[k] + (v[k + 1] - v[k]) * (x - z[k]) / (z[k + 1] - z[k])
        };
        assert!(
            start[b] < at[b] && at[b] < end[b],
            "bat {b}: {start:?} {at:?} {end:?}"
        );
        for edge in [start[b], end[b]] {
            assert!(
                (read(edge) - (peak[b] - 0.01)).abs() < 1e-9,
                "bat {b} at {edge}"
            );
        }
        // a real bat's: a few inches (Russell's sweet-zone maps; here 1–6 in)
        assert!((0.025..0.15).contains(&(end[b] - start[b])), "bat {b}");
    }
    // The card's hoop mode is the wall's lowest breathing mode the collisions used; a solid
    // bat has none.
    let hoop = bat_floats(out, "hoop_mode_frequency");
    let used = {
        let _g = no_spawns();
        let f = hdf5::File::open(out).unwrap();
        f.dataset("summary/hoop_mode_frequency")
            .unwrap()
            .read_raw::<f64>()
            .unwrap()
    };
    assert!(hoop[0].is_nan() && used[0].is_nan(), "{hoop:?} {used:?}");
    assert_eq!(hoop[1], used[1]);
}

/// The best lab-frame exit speed of each curve is stored beside the bat-frame sweet spot
/// (`/sweet_spot/exit_speed_lab`) and shown: it is what a batted ball leaves at, and a design
/// search's objective; the bat-frame exit speed of a bat met at rest by a fast ball is a
/// different number. The refined maximum lies between the best sample and the most a
/// parabola through it and its neighbours can add (a quarter of the larger step to them).
#[test]
fn the_best_lab_exit_speed_is_stored_and_shown() {
    let (_dir, out) = results_of(
        "name: lab\nmodel: wave\nbase: {bat: {preset: r161}, ball: {preset: mlb, speed: 38}}\n\
         grid:\n  swing.omega: [-40, -50]\n  impact.z: {range: [0.60, 0.80, 0.025]}\n",
    );
    let (lab, best) = {
        let _g = no_spawns();
        let f = hdf5::File::open(&out).unwrap();
        let s: Vec<f64> = f
            .dataset("summary/exit_speed_lab")
            .unwrap()
            .read_raw()
            .unwrap();
        let lab: Vec<f64> = f
            .dataset("sweet_spot/exit_speed_lab")
            .unwrap()
            .read_raw()
            .unwrap();
        // (model?, swing_omega, impact_z): each curve's samples are contiguous, 9 of them
        let best: Vec<Vec<f64>> = s.chunks(9).map(<[f64]>::to_vec).collect();
        (lab, best)
    };
    assert_eq!(lab.len(), best.len());
    for (refined, curve) in lab.iter().zip(&best) {
        let k = (0..curve.len())
            .max_by(|&a, &b| curve[a].total_cmp(&curve[b]))
            .unwrap();
        let steps = [k.checked_sub(1), Some(k + 1).filter(|&j| j < curve.len())]
            .iter()
            .flatten()
            .map(|&j| (curve[k] - curve[j]).abs())
            .fold(0.0, f64::max);
        assert!(
            *refined >= curve[k] - 1e-12 && *refined <= curve[k] + 0.25 * steps + 1e-9,
            "{refined} against {curve:?}"
        );
    }
    let text = inspect(&out);
    assert!(text.contains("lab frame: best"), "{text}");
}

/// A design search's file says its best feasible design and a `sample` study's its answers
/// over the sample, each the number the file stores (`/optimize`'s `best_objective`,
/// `/uncertainty`'s quantiles and probability).
#[test]
fn inspect_shows_a_searchs_best_and_a_samples_answers() {
    let dir = tempfile::tempdir().unwrap();
    let search = dir.path().join("search.yaml");
    std::fs::write(
        &search,
        "name: best_point\nmodel: rigid\nbase: {impact: {z: 0.6}}\ngrid:\n  swing.cm_speed: [0]\n\
         optimize:\n  max_evaluations: 40\n  tolerance: 1.0e-10\n  \
         variables: {impact.z: {min: 0.40, max: 0.83}}\n  objective: {maximize: exit_speed}\n",
    )
    .unwrap();
    let found = dir.path().join("search.h5");
    {
        let _g = spawn_guard();
        batstudy_ok(&[
            "optimize",
            search.to_str().unwrap(),
            "-o",
            found.to_str().unwrap(),
            "-q",
        ]);
    }
    let best = {
        let _g = no_spawns();
        let f = hdf5::File::open(&found).unwrap();
        f.group("optimize")
            .unwrap()
            .attr("best_objective")
            .unwrap()
            .read_raw::<f64>()
            .unwrap()[0]
    };
    let text = inspect(&found);
    assert!(
        text.contains(&format!("best feasible: exit_speed = {best:.6} m/s")),
        "{text}"
    );
    assert!(text.contains("impact.z = 0.56"), "{text}");
    let (_dir, sampled) = results_of(
        "name: s\nmodel: rigid\nbase: {bat: {preset: r161}, ball: {preset: mlb, speed: 60.8}}\n\
         grid:\n  swing.omega: [0]\n  impact.z: {range: [0.62, 0.78, 0.02]}\n\
         sample:\n  n: 16\n  seed: 3\n  params:\n    bat.material.density: {normal: {mean: 649, sd: 40}}\n",
    );
    let p = {
        let _g = no_spawns();
        let f = hdf5::File::open(&sampled).unwrap();
        f.dataset("uncertainty/bbcor_max_above_limit")
            .unwrap()
            .read_raw::<f64>()
            .unwrap()[0]
    };
    let text = inspect(&sampled);
    assert!(text.contains("over the sample"), "{text}");
    assert!(
        text.contains(&format!("P(best BBCOR > 0.50) = {p:.3}")),
        "{text}"
    );
}
