//! The calibrated ball (`ball.preset: mlb`) against the ball-alone measurements of
//! data/ball_tests.csv, and the drilled corking (`bat.bore`) against its closed form and the
//! measured mass of Nathan's 2003 test bat.
//!
//! Sources (docs/measurements.md): the MLB rule book's wall COR 0.514–0.578 at 85 ft/s
//! (quoted in Nathan, Am. J. Phys. 68, 979 (2000), note 13); Cross's COR 0.64 at 1 m/s on a
//! hard floor (same paper, Sec. III.B); 36 MLB game balls fired at 120 mph into a steel
//! cylinder at the WSU Sports Science Laboratory (data/mlb_balls_cylinder_2014_2016.md); Woo, Wensberg, Avagyan & Duarte's 28 shots at
//! 8.6–30.4 m/s (student report, appendix Tables 4–6), held out of the fit; Nathan, "Some
//! remarks on corked bats" (2003): a 34-in, 30.5-oz bat drilled 1 in × 10 in weighs 27.6 oz.

use batstudy::model::ball::{cor_at_speed, preset_law, wall_rebound_speed, ContactLaw};
use batstudy::model::bat::section::{BatGeometry, WOOD_DENSITY};
use batstudy::model::measures::metrics::bbcor_scan;
use batstudy::model::spec::{BallPreset, BallSpec, BatPreset, BatSpec, BoreSpec, CollisionSpec};
use batstudy::model::{prepare_bat, simulate_target, Target};
use batstudy::study::{load_str, LoadOptions};
use std::path::Path;

const BALL_MASS: f64 = 0.145;

/// The rows of data/ball_tests.csv whose quantity is COR: (speed m/s, COR, ball type).
fn cor_rows() -> Vec<(f64, f64, String)> {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/data/ball_tests.csv"))
        .expect("data/ball_tests.csv");
    let mut rows = Vec::new();
    for line in text.lines().filter(|l| !l.starts_with('#')).skip(1) {
        let fields = split_csv(line);
        if fields[0] == "COR" {
            if let (Ok(v), Ok(e)) = (fields[1].parse(), fields[2].parse()) {
                rows.push((v, e, fields[5].clone()));
            }
        }
    }
    rows
}

/// One CSV line split on commas outside double quotes.
fn split_csv(line: &str) -> Vec<String> {
    let (mut fields, mut field, mut quoted) = (Vec::new(), String::new(), false);
    for c in line.chars() {
        match c {
            '"' => quoted = !quoted,
            ',' if !quoted => fields.push(std::mem::take(&mut field)),
            _ => field.push(c),
        }
    }
    fields.push(field);
    fields
}

/// The mlb ball's COR on a rigid wall at `speed`, from its full force–compression loop.
fn wall_cor(speed: f64) -> f64 {
    let law = ContactLaw::new(&preset_law(BallPreset::Mlb), speed);
    wall_rebound_speed(&law, BALL_MASS, speed) / speed
}

/// The mean over the 36 balls of a column of data/mlb_balls_cylinder_2014_2016.csv.
fn cylinder_mean(column: &str) -> f64 {
    let values = cylinder_column(column);
    values.iter().sum::<f64>() / values.len() as f64
}

/// A column of data/mlb_balls_cylinder_2014_2016.csv, one value a ball, and its lots.
fn cylinder_column_lots(column: &str) -> (Vec<f64>, Vec<String>) {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/data/mlb_balls_cylinder_2014_2016.csv"
    ))
    .expect("data/mlb_balls_cylinder_2014_2016.csv");
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    let header = split_csv(lines.next().unwrap());
    let k = header.iter().position(|h| h == column).unwrap();
    let lot = header.iter().position(|h| h == "lot").unwrap();
    lines
        .map(|l| {
            let f = split_csv(l);
            (f[k].parse::<f64>().unwrap(), f[lot].clone())
        })
        .unzip()
}

fn cylinder_column(column: &str) -> Vec<f64> {
    let values = cylinder_column_lots(column).0;
    assert_eq!(values.len(), 36);
    values
}

fn mean(x: &[f64]) -> f64 {
    x.iter().sum::<f64>() / x.len() as f64
}

/// Sample standard deviation.
fn sd(x: &[f64]) -> f64 {
    let m = mean(x);
    (x.iter().map(|v| (v - m).powi(2)).sum::<f64>() / (x.len() - 1) as f64).sqrt()
}

fn correlation(x: &[f64], y: &[f64]) -> f64 {
    let (mx, my) = (mean(x), mean(y));
    let sxy: f64 = x.iter().zip(y).map(|(a, b)| (a - mx) * (b - my)).sum();
    sxy / ((x.len() - 1) as f64 * sd(x) * sd(y))
}

/// The cylinder test run on balls that `sample.ball_spread` draws: (COR, ln DS) a ball.
fn drawn_cylinder_balls(spread: &str) -> (Vec<f64>, Vec<f64>) {
    let text = format!(
        "name: spread\nmodel: wave\nbase:\n  bat: {{preset: cylinder, radius: 0.03}}\n  \
         ball: {{preset: mlb, speed: {}}}\n  impact: {{z: 0.0}}\n\
         sample: {{n: 256, seed: 11, ball_spread: {spread}}}\n",
        120.0 * 0.44704
    );
    let s = load_str(&text, Path::new("spread.yaml"), &LoadOptions::default()).unwrap();
    let (mut cor, mut ds) = (Vec::new(), Vec::new());
    for i in 0..s.plan.n_points() {
        let p = s.plan.point(i).unwrap();
        let target = Target::prepare(&p.spec.bat, &p.spec.numerics).unwrap();
        let o = simulate_target(&p.spec, &target, None).unwrap();
        let v = o.approach_speed;
        cor.push(o.exit_speed / v);
        ds.push(((o.peak_force / v).powi(2) / p.spec.ball.mass).ln());
    }
    (cor, ds)
}

/// The mlb ball on a rigid target at `speed`: (COR, dynamic stiffness (F_peak / v)² / m)
/// from the wave model's full loop (the ball rig's own numbers).
fn rig(speed: f64, preset: BatPreset) -> (f64, f64) {
    let mut spec = CollisionSpec::base_case(0.0);
    spec.bat = BatSpec {
        preset,
        radius: (preset == BatPreset::Cylinder).then_some(0.03),
        ..BatSpec::default()
    };
    spec.ball = serde_json::from_str(&format!(r#"{{"preset": "mlb", "speed": {speed}}}"#)).unwrap();
    let target = Target::prepare(&spec.bat, &spec.numerics).unwrap();
    let o = simulate_target(&spec, &target, None).unwrap();
    let v = o.approach_speed;
    (
        o.exit_speed / v,
        (o.peak_force / v).powi(2) / spec.ball.mass,
    )
}

#[test]
fn the_fit_meets_the_ball_data_it_was_fitted_to() {
    // Consistency, not validation: the three anchors the fit goes through, from the data
    // files (the rule book's window at 25.9 m/s and Cross's 0.64 at 1 m/s on flat targets;
    // the 36 balls' mean cylindrical COR and dynamic stiffness at 120 mph).
    let rows = cor_rows();
    let datum = |v: f64| rows.iter().find(|r| r.0 == v).map(|r| r.1).unwrap();
    let at_rule = wall_cor(25.9);
    assert!((0.514..=0.578).contains(&at_rule), "{at_rule}");
    assert!((at_rule - datum(25.9)).abs() < 0.003, "{at_rule}");
    let at_cross = wall_cor(1.0);
    assert!((at_cross - datum(1.0)).abs() < 0.005, "{at_cross}");
    let (cor, ds) = rig(120.0 * 0.44704, BatPreset::Cylinder);
    // the mean's standard error: 0.005 over sqrt(36) balls
    assert!((cor - cylinder_mean("cor_cylinder")).abs() < 0.001, "{cor}");
    let measured = cylinder_mean("dynamic_stiffness_N_per_m");
    assert!(
        (ds / measured - 1.0).abs() < 0.005,
        "{ds} against {measured}"
    );
}

/// The ball sees the target's curvature. Independent references:
/// - Hertz (Johnson, "Contact Mechanics" §4.2): a sphere (R_b) on a cylinder (R_c) with
///   crossed axes has the effective radius R_e = √(R′R″), 1/R′ = 1/R_b + 1/R_c, R″ = R_b,
///   and its stiffness at equal compression scales as √R_e: the dynamic stiffness
///   (F_peak/v)²/m of a power-law loading then scales as g^(2/(α+1)), g = √(R_e/R_b),
///   at the same speed;
/// - WSU's Sports Science Laboratory: a ball's COR on the cylinder "is lower than the
///   standard ball COR ... due to the higher impact speed and the cylindrical impact
///   surface" (ssl.wsu.edu glossary, "Ball dynamic stiffness"; read): at one speed, the
///   cylinder alone must take COR off.
#[test]
fn the_cylinder_strains_the_ball_more_than_the_wall() {
    let v = 53.6;
    let (wall, wall_ds) = rig(v, BatPreset::Wall);
    let (cylinder, cylinder_ds) = rig(v, BatPreset::Cylinder);
    eprintln!("at {v} m/s: wall COR {wall:.4}, cylinder {cylinder:.4}; DS {wall_ds:.4e}, {cylinder_ds:.4e}");
    assert!(cylinder < wall - 0.01, "{cylinder} against {wall}");
    let (rb, rc) = (0.0369_f64, 0.03_f64);
    let r1 = 1.0 / (1.0 / rb + 1.0 / rc);
    let g = ((r1 * rb).sqrt() / rb).sqrt();
    let alpha = 1.84;
    let expected = g.powf(2.0 / (alpha + 1.0));
    // to the loop's own resolution (the peak force is sampled at the step)
    assert!(
        (cylinder_ds / wall_ds / expected - 1.0).abs() < 2e-3,
        "{} against Hertz's {expected}",
        cylinder_ds / wall_ds
    );
}

/// What the unknown radius of the test cylinder (2.5–3.5 cm: data/mlb_balls_cylinder_2014_2016.md)
/// does to a bat's answer: the R161's BBCOR with the ball calibrated on each end of the range
/// moves by less than 0.005, a certification measurement's uncertainty. The curve's shape
/// is solved from the anchors for each radius, and k₁ follows it, so this is the whole
/// calibration's dependence on the one dimension no source gave.
#[test]
fn the_test_cylinders_unknown_radius_moves_bbcor_by_less_than_a_measurement() {
    use batstudy::model::ball::{
        cor_curve_through, curvature_factor, DEFAULT_BALL_RADIUS, TEST_CYLINDER_RADIUS,
        TEST_CYLINDER_RADIUS_RANGE,
    };
    let spec = CollisionSpec::base_case(0.7);
    let bat = prepare_bat(&spec.bat, &spec.numerics).unwrap();
    let best = |radius: f64| {
        let mut ball: BallSpec = serde_json::from_str(r#"{"preset": "mlb"}"#).unwrap();
        let (at_rest, power) = cor_curve_through(radius);
        ball.law.cor_at_rest = Some(at_rest);
        ball.law.cor_power = Some(power);
        ball.law.k1 *= curvature_factor(DEFAULT_BALL_RADIUS, Some(TEST_CYLINDER_RADIUS))
            / curvature_factor(DEFAULT_BALL_RADIUS, Some(radius));
        let (_, bbcor) = bbcor_scan(&bat, &spec.bat, &spec.numerics, &ball).unwrap();
        bbcor.iter().cloned().fold(f64::NEG_INFINITY, f64::max)
    };
    let at = best(TEST_CYLINDER_RADIUS);
    for r in [TEST_CYLINDER_RADIUS_RANGE.0, TEST_CYLINDER_RADIUS_RANGE.1] {
        let moved = best(r) - at;
        eprintln!(
            "test cylinder {r} m: the R161's BBCOR {:.4} ({moved:+.4})",
            at + moved
        );
        assert!(
            moved.abs() < 0.005,
            "radius {r}: BBCOR {at} moves by {moved}"
        );
    }
}

/// Consistency through the full loop: balls drawn by `sample.ball_spread: ball` and fired at
/// the cylinder spread as the 36 game balls did (their COR's SD, their dynamic stiffness's,
/// and the correlation of the two, computed here from the data file); with `lot`, the COR
/// spreads as the three lots' means. It fails if the spread's k₁ is not carried to the peak
/// force as DS ∝ k₁^(2/(α+1)) says, or the COR shift does not reach the cylinder. Tolerances:
/// 256 quasi-random points and the 3-SD truncation (−1.5 % of an SD).
#[test]
fn drawn_balls_spread_on_the_cylinder_as_the_game_balls_did() {
    let cor = cylinder_column("cor_cylinder");
    let ds: Vec<f64> = cylinder_column("dynamic_stiffness_N_per_m")
        .iter()
        .map(|d| d.ln())
        .collect();
    let (model_cor, model_ds) = drawn_cylinder_balls("ball");
    let near = |model: f64, data: f64, what: &str| {
        assert!(
            (model / data - 1.0).abs() < 0.06,
            "{what}: drawn {model}, measured {data}"
        )
    };
    near(sd(&model_cor), sd(&cor), "SD of the COR");
    near(sd(&model_ds), sd(&ds), "SD of ln DS");
    let (r_model, r_data) = (correlation(&model_cor, &model_ds), correlation(&cor, &ds));
    assert!(
        (r_model - r_data).abs() < 0.05,
        "{r_model} against {r_data}"
    );
    let (cor, lots) = cylinder_column_lots("cor_cylinder");
    let lot_means: Vec<f64> = ["A", "B", "C"]
        .iter()
        .map(|l| {
            let of: Vec<f64> = cor
                .iter()
                .zip(&lots)
                .filter(|(_, lot)| lot.starts_with(l))
                .map(|(c, _)| *c)
                .collect();
            mean(&of)
        })
        .collect();
    near(
        sd(&drawn_cylinder_balls("lot").0),
        sd(&lot_means),
        "SD of the lots' COR",
    );
}

#[test]
fn the_loop_returns_the_curve_at_every_speed() {
    // Verification: the unloading branch built from e(v) gives back e(v)² of the stored
    // energy (docs/physics.md, "The ball"), so the wall rebound is e(v) v.
    let law = preset_law(BallPreset::Mlb);
    for v in [1.0, 8.6, 25.9, 49.2, 60.8] {
        let (simulated, curve) = (wall_cor(v), cor_at_speed(&law, v));
        assert!(
            (simulated / curve - 1.0).abs() < 5e-3,
            "{v}: {simulated} against {curve}"
        );
    }
}

/// Verification: `cor_shift` moves the wall COR the full loading–unloading loop returns by
/// exactly the shift at every speed (the unloading branch is rebuilt from the shifted COR),
/// so a sample over it draws balls off the curve by what it says.
#[test]
fn a_shifted_ball_comes_back_off_the_curve_by_its_shift() {
    let mut law = preset_law(BallPreset::Mlb);
    law.cor_shift = Some(-0.005);
    for v in [1.0, 25.9, 49.2, 60.8] {
        let shifted = wall_rebound_speed(&ContactLaw::new(&law, v), BALL_MASS, v) / v;
        let moved = shifted - wall_cor(v);
        assert!((moved + 0.005).abs() < 2e-4, "{v} m/s: moved by {moved}");
    }
}

#[test]
fn the_held_out_student_data_fall_as_the_curve_predicts() {
    // Woo et al.'s 28 shots, fitted with one exponent γ (e ∝ v^−γ) and a level per ball by least
    // squares in log–log; the curve's γ between the ends of their range must lie within two
    // standard errors of theirs (0.070 ± 0.012).
    let shots: Vec<(f64, f64, usize)> = cor_rows()
        .into_iter()
        .filter(|r| r.2.contains("used baseball no."))
        .map(|(v, e, ball)| {
            (
                v,
                e,
                ball.split("no. ").nth(1).unwrap()[..1].parse().unwrap(),
            )
        })
        .collect();
    assert_eq!(shots.len(), 28);
    let (gamma, se) = pooled_exponent(&shots);
    let curve = -(wall_cor(30.4) / wall_cor(8.6)).ln() / (30.4f64 / 8.6).ln();
    assert!(
        (curve - gamma).abs() <= 2.0 * se,
        "curve {curve}, data {gamma} ± {se}"
    );
}

/// −slope of ln e against ln v with one intercept per ball (the within-ball regression), and
/// its standard error.
fn pooled_exponent(shots: &[(f64, f64, usize)]) -> (f64, f64) {
    let mean = |ball: usize, f: &dyn Fn(&(f64, f64, usize)) -> f64| {
        let of: Vec<f64> = shots.iter().filter(|s| s.2 == ball).map(f).collect();
        of.iter().sum::<f64>() / of.len() as f64
    };
    let centred: Vec<(f64, f64)> = shots
        .iter()
        .map(|s| {
            let (x, y) = (s.0.ln(), s.1.ln());
            (x - mean(s.2, &|t| t.0.ln()), y - mean(s.2, &|t| t.1.ln()))
        })
        .collect();
    let sxx: f64 = centred.iter().map(|c| c.0 * c.0).sum();
    let slope = centred.iter().map(|c| c.0 * c.1).sum::<f64>() / sxx;
    let balls = 3.0;
    let rss: f64 = centred.iter().map(|c| (c.1 - slope * c.0).powi(2)).sum();
    let se = (rss / (centred.len() as f64 - balls - 1.0) / sxx).sqrt();
    (-slope, se)
}

#[test]
fn a_preset_fills_what_the_study_leaves_out_and_the_study_wins() {
    let ball: BallSpec = serde_json::from_str(r#"{"preset": "mlb", "speed": 49.2}"#).unwrap();
    assert_eq!(ball.law, preset_law(BallPreset::Mlb));
    let ball: BallSpec =
        serde_json::from_str(r#"{"preset": "mlb", "law": {"cor": 0.514}}"#).unwrap();
    assert_eq!(ball.law.cor, 0.514);
    assert_eq!(ball.law.k1, preset_law(BallPreset::Mlb).k1);
    // a slope asks for the line: the preset's curve gives way
    let ball: BallSpec =
        serde_json::from_str(r#"{"preset": "mlb", "law": {"cor_slope": -0.002}}"#).unwrap();
    assert_eq!(ball.law.cor_exponent, None);
    assert_eq!((ball.law.cor_at_rest, ball.law.cor_power), (None, None));
    // null: the preset's value (a points set over a base that gives a law)
    let ball: BallSpec =
        serde_json::from_str(r#"{"preset": "mlb", "law": {"cor": null, "kind": null}}"#).unwrap();
    assert_eq!(ball.law, preset_law(BallPreset::Mlb));
    let ball: BallSpec = serde_json::from_str(r#"{"preset": "mlb", "law": null}"#).unwrap();
    assert_eq!(ball.law, preset_law(BallPreset::Mlb));
    let unknown = serde_json::from_str::<BallSpec>(r#"{"preset": "mlb", "law": {"cr": 1}}"#);
    assert!(unknown.is_err());
}

fn drilled(diameter: f64, depth: f64, fill_density: f64) -> BatSpec {
    BatSpec {
        bore: Some(BoreSpec {
            diameter,
            depth,
            fill_density,
        }),
        ..BatSpec::default()
    }
}

fn mass(g: &BatGeometry) -> f64 {
    g.integrate(0.0, g.length, |z| g.mass_per_length(z))
}

#[test]
fn a_bore_removes_its_cylinder_of_wood() {
    // Closed form: an empty bore of diameter d and depth h removes ρ π d²/4 h; a filled one
    // adds back ρ_fill π d²/4 h. Nathan's 2003 bat lost 30.5 − 27.6 oz = 82 ± 3 g to the same
    // bore (±0.1 oz per weighing); the R161's wood density gives 83.5 g.
    let (d, h) = (0.0254, 0.254);
    let solid = mass(&BatGeometry::resolve(&BatSpec::default()).unwrap());
    let empty = mass(&BatGeometry::resolve(&drilled(d, h, 0.0)).unwrap());
    let corked = mass(&BatGeometry::resolve(&drilled(d, h, 240.0)).unwrap());
    let volume = std::f64::consts::PI * d * d / 4.0 * h;
    assert!(((solid - empty) / (WOOD_DENSITY * volume) - 1.0).abs() < 1e-9);
    assert!(((corked - empty) / (240.0 * volume) - 1.0).abs() < 1e-9);
    let measured = (30.5 - 27.6) * 0.028_349_5;
    assert!(
        (solid - empty - measured).abs() < 0.003,
        "{}",
        solid - empty
    );
}

#[test]
fn an_impossible_bore_is_refused() {
    for (spec, field) in [
        (drilled(0.08, 0.254, 0.0), "bat.bore.diameter"),
        (drilled(0.0254, 0.9, 0.0), "bat.bore.depth"),
        (drilled(-0.01, 0.254, 0.0), "bat.bore.diameter"),
    ] {
        let err = BatGeometry::resolve(&spec).unwrap_err().to_string();
        assert!(err.contains(field), "{err}");
    }
    let hollow = BatSpec {
        preset: batstudy::model::spec::BatPreset::Aluminum,
        ..drilled(0.0254, 0.254, 0.0)
    };
    assert!(BatGeometry::resolve(&hollow).is_err());
}
