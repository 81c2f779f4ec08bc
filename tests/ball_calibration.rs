//! The calibrated ball (`ball.preset: mlb`) against the ball-alone measurements of
//! data/ball_tests.csv, and the drilled corking (`bat.bore`) against its closed form and the
//! measured mass of Nathan's 2003 test bat.
//!
//! Sources (docs/measurements.md): the MLB rule book's wall COR 0.514–0.578 at 85 ft/s
//! (quoted in Nathan, Am. J. Phys. 68, 979 (2000), note 13); Cross's COR 0.64 at 1 m/s on a
//! hard floor (same paper, Sec. III.B); Woo, Wensberg, Avagyan & Duarte's 28 shots at
//! 8.6–30.4 m/s (student report, appendix Tables 4–6), held out of the fit; Nathan, "Some
//! remarks on corked bats" (2003): a 34-in, 30.5-oz bat drilled 1 in × 10 in weighs 27.6 oz.

use batstudy::model::ball::{cor_at_speed, preset_law, wall_rebound_speed, ContactLaw};
use batstudy::model::bat::section::{BatGeometry, WOOD_DENSITY};
use batstudy::model::spec::{BallPreset, BallSpec, BatSpec, BoreSpec};

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

#[test]
fn the_fit_meets_the_ball_data_it_was_fitted_to() {
    // The fit's own data: the rule book's window at 25.9 m/s and Cross's 0.64 at 1 m/s.
    let rows = cor_rows();
    let datum = |v: f64| rows.iter().find(|r| r.0 == v).map(|r| r.1).unwrap();
    let at_rule = wall_cor(25.9);
    assert!((0.514..=0.578).contains(&at_rule), "{at_rule}");
    assert!((at_rule - datum(25.9)).abs() < 0.003, "{at_rule}");
    let at_cross = wall_cor(1.0);
    assert!((at_cross - datum(1.0)).abs() < 0.005, "{at_cross}");
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
