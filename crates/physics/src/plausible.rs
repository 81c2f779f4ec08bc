//! Plausible ranges: the values a real bat, ball and swing can have.
//!
//! `validate_spec` refuses what the model cannot compute (a negative mass, a shell thicker
//! than the bat); this table refuses what it can compute but no bat or ball has (a ball at
//! 1e6 m/s, wood at 1e30 kg/m³), because such numbers are almost always typing errors and
//! would be stored without a word. A study that wants to go beyond on purpose (a what-if
//! study) sets `allow_implausible: true`; the study layer then skips this check and the
//! results file records it. The same table feeds the JSON schema (`minimum`/`maximum`) and
//! docs/study-files.md, where each bound's reason is given.

use crate::error::ModelError;
use crate::spec::CollisionSpec;

/// One plausible range of a parameter.
#[derive(Debug, Clone, Copy)]
pub struct Range {
    /// Dotted path of the parameter.
    pub path: &'static str,
    pub min: f64,
    pub max: f64,
    /// Unit of `min` and `max` (SI).
    pub unit: &'static str,
    /// Why these bounds.
    pub reason: &'static str,
    /// The value in a spec, when set (a preset's own values are inside every range).
    pub get: fn(&CollisionSpec) -> Option<f64>,
}

/// Every plausible range, in the order of the study-file reference.
pub const RANGES: &[Range] = &[
    Range {
        path: "bat.length",
        min: 0.4,
        max: 1.5,
        unit: "m",
        reason: "youth bats are about 0.6 m, adult bats 0.8-0.9 m; the paper's longest bat is 1.10 m",
        get: |s| s.bat.length,
    },
    Range {
        path: "bat.radius",
        min: 0.01,
        max: 0.1,
        unit: "m",
        reason: "the cylinder stands for a bat's barrel (radii of 2.5-3.5 cm); a flat target is bat.preset wall",
        get: |s| s.bat.radius,
    },
    Range {
        path: "bat.material.density",
        min: 100.0,
        max: 10000.0,
        unit: "kg/m^3",
        reason: "from balsa (about 150) through woods (400-900), composites (about 1600) and aluminium (2700) to steel (7850)",
        get: |s| s.bat.material.density,
    },
    Range {
        path: "bat.material.youngs_modulus",
        min: 1.0e8,
        max: 5.0e11,
        unit: "Pa",
        reason: "from soft plastics (about 1e9) through wood (1-2e10) and aluminium (6.9e10) to steel and carbon fibre (2-4e11)",
        get: |s| s.bat.material.youngs_modulus,
    },
    Range {
        path: "bat.material.poisson_ratio",
        min: 0.0,
        max: 0.5,
        unit: "1",
        reason: "isotropic materials lie between 0 and 0.5",
        get: |s| s.bat.material.poisson_ratio,
    },
    Range {
        path: "bat.material.shear_modulus",
        min: 1.0e7,
        max: 2.0e11,
        unit: "Pa",
        reason: "wood's longitudinal-radial shear modulus is about 1e9, aluminium's 2.6e10, steel's 8e10",
        get: |s| s.bat.material.shear_modulus,
    },
    Range {
        path: "bat.material.shear_coefficient",
        min: 0.1,
        max: 1.0,
        unit: "1",
        reason: "Cowper's coefficient is about 0.5 for a thin tube and 0.9 for a solid circle",
        get: |s| s.bat.material.shear_coefficient,
    },
    Range {
        path: "bat.material.quality_factor",
        min: 2.0,
        max: 1.0e6,
        unit: "1",
        reason: "wood's Q is tens to a few hundred, metals' thousands; below 2 the modes are barely oscillatory",
        get: |s| s.bat.material.quality_factor,
    },
    Range {
        path: "bat.shell.thickness",
        min: 5.0e-4,
        max: 0.05,
        unit: "m",
        reason: "aluminium bat walls are 2-3.5 mm thick, a corked barrel's wall about 1 cm; below 0.5 mm no wall survives an impact",
        get: |s| s.bat.shell.as_ref().and_then(|x| x.thickness),
    },
    Range {
        path: "bat.fill.density",
        min: 0.0,
        max: 2000.0,
        unit: "kg/m^3",
        reason: "0 is hollow; cork is about 240, rubber and resins up to about 1500",
        get: |s| s.bat.fill.as_ref().map(|f| f.density),
    },
    Range {
        path: "bat.bore.diameter",
        min: 0.005,
        max: 0.05,
        unit: "m",
        reason: "corked bats are drilled 7/8 to 1 1/4 in (2.2-3.2 cm) wide; barrels are about 6.6 cm across",
        get: |s| s.bat.bore.as_ref().map(|b| b.diameter),
    },
    Range {
        path: "bat.bore.depth",
        min: 0.02,
        max: 0.6,
        unit: "m",
        reason: "corked bats are drilled about 10 in (0.25 m) deep; deeper than 0.6 m reaches the handle",
        get: |s| s.bat.bore.as_ref().map(|b| b.depth),
    },
    Range {
        path: "bat.bore.fill_density",
        min: 0.0,
        max: 2000.0,
        unit: "kg/m^3",
        reason: "0 is an empty bore; cork is about 240, rubber balls and resins up to about 1500",
        get: |s| s.bat.bore.as_ref().map(|b| b.fill_density),
    },
    Range {
        path: "bat.handle.radius_scale",
        min: 0.3,
        max: 3.0,
        unit: "1",
        reason: "the paper's handle variants are 0.8 and 1.25; beyond a factor of 3 the handle is no handle",
        get: |s| Some(s.bat.handle.radius_scale),
    },
    Range {
        path: "bat.grip.stiffness",
        min: 1.0e2,
        max: 1.0e9,
        unit: "N/m",
        reason: "hands measured as a few 1e3-1e5 N/m; a clamp is about 1e8",
        get: |s| s.bat.grip.as_ref().and_then(|g| g.stiffness),
    },
    Range {
        path: "bat.grip.damping",
        min: 0.0,
        max: 1.0e5,
        unit: "N s/m",
        reason: "hands damp with tens to hundreds of N s/m",
        get: |s| s.bat.grip.as_ref().map(|g| g.damping),
    },
    Range {
        path: "ball.mass",
        min: 0.1,
        max: 0.25,
        unit: "kg",
        reason: "baseballs weigh 0.142-0.149 kg, softballs 0.17-0.20 kg",
        get: |s| Some(s.ball.mass),
    },
    Range {
        path: "ball.speed",
        min: 0.5,
        max: 100.0,
        unit: "m/s",
        reason: "from slow laboratory impacts (1 m/s) to beyond the fastest pitch (47 m/s) meeting the fastest barrel (about 40 m/s)",
        get: |s| Some(s.ball.speed),
    },
    Range {
        path: "ball.law.stiffness",
        min: 1.0e4,
        max: 1.0e8,
        unit: "N/m",
        reason: "baseballs' dynamic stiffness is about 0.5-2e6 N/m (the paper uses 7e5); two decades either side",
        get: |s| Some(s.ball.law.stiffness),
    },
    Range {
        path: "ball.law.cor",
        min: 0.2,
        max: 1.0,
        unit: "1",
        reason: "balls in play have a wall COR of 0.4-0.6; 1 is lossless",
        get: |s| Some(s.ball.law.cor),
    },
    Range {
        path: "ball.law.k1",
        min: 1.0e5,
        max: 1.0e10,
        unit: "N/m^alpha",
        reason: "Nathan (2000) fits 6.53e7 N/m^1.84 to a baseball",
        get: |s| Some(s.ball.law.k1),
    },
    Range {
        path: "ball.law.alpha",
        min: 1.0,
        max: 3.0,
        unit: "1",
        reason: "1 is a linear spring, 1.5 Hertz contact, 1.84 Nathan's baseball",
        get: |s| Some(s.ball.law.alpha),
    },
    Range {
        path: "ball.law.reference_speed",
        min: 1.0,
        max: 100.0,
        unit: "m/s",
        reason: "balls are certified at 25.9 m/s (85 ft/s); bat tests run up to about 70 m/s",
        get: |s| s.ball.law.reference_speed,
    },
    Range {
        path: "ball.law.cor_slope",
        min: -0.02,
        max: 0.02,
        unit: "1/(m/s)",
        reason: "measured baseballs lose a few thousandths of COR per m/s; 0.02 would halve a COR over 25 m/s",
        get: |s| s.ball.law.cor_slope,
    },
    Range {
        path: "ball.law.cor_exponent",
        min: 0.0,
        max: 0.2,
        unit: "1",
        reason: "the mlb ball's 0.049 takes the COR from 0.64 at 1 m/s to 0.546 at 25.9 m/s; 0.2 would halve it from 1 to 32 m/s",
        get: |s| s.ball.law.cor_exponent,
    },
    Range {
        path: "ball.law.cor_at_rest",
        min: 0.3,
        max: 0.9,
        unit: "1",
        reason: "a baseball dropped on a hard floor rebounds with a COR of about 0.64",
        get: |s| s.ball.law.cor_at_rest,
    },
    Range {
        path: "ball.law.cor_shift",
        min: -0.1,
        max: 0.1,
        unit: "1",
        reason: "game balls on the same cylinder spread by 0.005 (SD) about their mean COR; the rule book's window is 0.064 wide",
        get: |s| s.ball.law.cor_shift,
    },
    Range {
        path: "ball.law.cor_power",
        min: 0.1,
        max: 2.0,
        unit: "1",
        reason: "the mlb ball's COR falls from its value at rest about as the square root of the speed (0.53)",
        get: |s| s.ball.law.cor_power,
    },
    Range {
        path: "swing.omega",
        min: -200.0,
        max: 200.0,
        unit: "rad/s",
        reason: "the fastest measured swings turn the bat at about 50-60 rad/s at impact",
        get: |s| Some(s.swing.omega),
    },
    Range {
        path: "swing.cm_speed",
        min: -60.0,
        max: 60.0,
        unit: "m/s",
        reason: "a bat's centre of mass moves at up to about 25 m/s in a swing",
        get: |s| Some(s.swing.cm_speed),
    },
    Range {
        path: "hoop.frequency",
        min: 100.0,
        max: 20000.0,
        unit: "Hz",
        reason: "hollow bats' hoop modes are measured at about 1-2.5 kHz; the paper explores 300-2000 Hz",
        get: |s| s.hoop.as_ref().and_then(|h| h.frequency),
    },
    Range {
        path: "hoop.mass",
        min: 1.0e-3,
        max: 0.5,
        unit: "kg",
        reason: "the shell that moves in a hoop mode weighs grams to tens of grams",
        get: |s| s.hoop.as_ref().and_then(|h| h.mass),
    },
    Range {
        path: "hoop.patch_radius",
        min: 0.005,
        max: 0.04,
        unit: "m",
        reason: "a baseball's contact patch on a barrel spans one to three centimetres",
        get: |s| s.hoop.as_ref().and_then(|h| h.patch_radius),
    },
    Range {
        path: "hoop.footprint_ratio",
        min: 0.5,
        max: 1.0,
        unit: "1",
        reason: "from Hertz's elastic contact (0.5 of the bodies' overlap) to a ball flattened over all of it (1)",
        get: |s| s.hoop.as_ref().and_then(|h| h.footprint_ratio),
    },
    Range {
        path: "impact.offset",
        min: -0.08,
        max: 0.08,
        unit: "m",
        reason: "a ball meets the bat only within a bat radius plus a ball radius (about 7 cm) of its axis",
        get: |s| Some(s.impact.offset),
    },
    Range {
        path: "ball.spin",
        min: -500.0,
        max: 500.0,
        unit: "rad/s",
        reason: "pitches spin at up to about 3500 rpm (370 rad/s)",
        get: |s| Some(s.ball.spin),
    },
    Range {
        path: "ball.radius",
        min: 0.03,
        max: 0.06,
        unit: "m",
        reason: "baseballs are 3.63-3.68 cm in radius, softballs up to 4.9 cm",
        get: |s| s.ball.radius,
    },
    Range {
        path: "ball.law.friction",
        min: 0.0,
        max: 2.0,
        unit: "1",
        reason: "ball on bat: about 0.15-0.5; above 1 only for tacky surfaces",
        get: |s| s.ball.law.friction,
    },
    Range {
        path: "ball.law.tangential_ratio",
        min: 0.01,
        max: 2.0,
        unit: "1",
        reason: "a rubber contact's tangential stiffness is 0.67-1 of its normal one (Mindlin); baseballs' about 0.27",
        get: |s| s.ball.law.tangential_ratio,
    },
    Range {
        path: "swing.attack_angle",
        min: -0.7,
        max: 0.7,
        unit: "rad",
        reason: "measured attack angles lie between about -10 and +30 degrees (0.5 rad)",
        get: |s| Some(s.swing.attack_angle),
    },
    Range {
        path: "swing.attack_direction",
        min: -0.8,
        max: 0.8,
        unit: "rad",
        reason: "measured attack directions lie within about 45 degrees either side of centre field",
        get: |s| Some(s.swing.attack_direction),
    },
    Range {
        path: "swing.tilt",
        min: -1.2,
        max: 0.5,
        unit: "rad",
        reason: "measured vertical bat angles lie between about -60 and +10 degrees (barrel below the hands, negative)",
        get: |s| Some(s.swing.tilt),
    },
    Range {
        path: "pitch.speed",
        min: 0.0,
        max: 50.0,
        unit: "m/s",
        reason: "from a ball on a tee (0) to the fastest pitches (about 47 m/s, 105 mph)",
        get: |s| s.pitch.as_ref().map(|p| p.speed),
    },
    Range {
        path: "pitch.descent_angle",
        min: -0.1,
        max: 0.35,
        unit: "rad",
        reason: "pitches reach the plate falling at about 4-12 degrees (fastballs) to 15 degrees (curveballs); an underhand softball pitch may rise",
        get: |s| s.pitch.as_ref().map(|p| p.descent_angle),
    },
    Range {
        path: "pitch.horizontal_angle",
        min: -0.2,
        max: 0.2,
        unit: "rad",
        reason: "pitches cross the plate within about 6 degrees of straight toward the catcher",
        get: |s| s.pitch.as_ref().map(|p| p.horizontal_angle),
    },
    Range {
        path: "batter.pitch_speed",
        min: 0.0,
        max: 50.0,
        unit: "m/s",
        reason: "from a ball on a tee (0) to the fastest pitches (about 47 m/s, 105 mph)",
        get: |s| s.batter.as_ref().and_then(|b| b.pitch_speed),
    },
    Range {
        path: "batter.bat_speed",
        min: 5.0,
        max: 50.0,
        unit: "m/s",
        reason: "youth swings are about 20 m/s, the fastest major-league swings about 38 m/s (85 mph) at the sweet spot",
        get: |s| s.batter.as_ref().map(|b| b.bat_speed),
    },
    Range {
        path: "batter.bat_speed_at",
        min: 0.3,
        max: 1.2,
        unit: "m",
        reason: "swing speeds are quoted at a point of the barrel, about 0.5-0.8 m from the knob (28 in is 0.71 m)",
        get: |s| s.batter.as_ref().map(|b| b.bat_speed_at),
    },
    Range {
        path: "batter.pivot",
        min: 0.0,
        max: 0.5,
        unit: "m",
        reason: "the swing turns about a point near the knob at contact (Nathan et al. 2011), well inside the handle",
        get: |s| s.batter.as_ref().map(|b| b.pivot),
    },
    Range {
        path: "batter.reference_moi",
        min: 0.05,
        max: 1.0,
        unit: "kg m^2",
        reason: "bats have 0.15-0.45 kg m^2 about the knob (youth to heavy wood)",
        get: |s| s.batter.as_ref().map(|b| b.reference_moi),
    },
    Range {
        path: "batter.exponent",
        min: 0.0,
        max: 0.5,
        unit: "1",
        reason: "measured players' exponents lie between 0.08 and 0.37 (pooled 0.25-0.29)",
        get: |s| s.batter.as_ref().map(|b| b.exponent),
    },
    Range {
        path: "flight.elevation",
        min: -100.0,
        max: 4000.0,
        unit: "m",
        reason: "ballparks lie between sea level and about 2250 m (Mexico City)",
        get: |s| s.flight.as_ref().map(|f| f.elevation),
    },
    Range {
        path: "flight.temperature",
        min: 240.0,
        max: 330.0,
        unit: "K",
        reason: "games are played between about -10 and +45 degrees Celsius",
        get: |s| s.flight.as_ref().map(|f| f.temperature),
    },
    Range {
        path: "flight.pressure",
        min: 85000.0,
        max: 110000.0,
        unit: "Pa",
        reason: "barometric pressures reduced to sea level on record lie between 870 and 1084 hPa; weather reports give 980-1040",
        get: |s| s.flight.as_ref().map(|f| f.pressure),
    },
    Range {
        path: "flight.wind_speed",
        min: -30.0,
        max: 30.0,
        unit: "m/s",
        reason: "game winds rarely exceed 15 m/s; 30 is a gale",
        get: |s| s.flight.as_ref().map(|f| f.wind_speed),
    },
    Range {
        path: "flight.humidity",
        min: 0.0,
        max: 1.0,
        unit: "1",
        reason: "relative humidity is a fraction, 0 dry to 1 saturated",
        get: |s| s.flight.as_ref().map(|f| f.humidity),
    },
];

/// Ranges of a batted ball's launch as `batstudy fly` and the Python package take it (the
/// flight block's air is in [`RANGES`]); no collision spec holds these, so `get` is empty.
pub const LAUNCH_RANGES: &[Range] = &[
    Range {
        path: "launch.exit_speed",
        min: 0.0,
        max: 60.0,
        unit: "m/s",
        reason: "the hardest-hit balls on record leave at about 54 m/s (122 mph)",
        get: |_| None,
    },
    Range {
        path: "launch.launch_angle",
        min: -std::f64::consts::FRAC_PI_2,
        max: std::f64::consts::FRAC_PI_2,
        unit: "rad",
        reason: "a batted ball leaves between straight down and straight up (±90 degrees)",
        get: |_| None,
    },
    Range {
        path: "launch.spray_angle",
        min: -std::f64::consts::FRAC_PI_2,
        max: std::f64::consts::FRAC_PI_2,
        unit: "rad",
        reason: "fair territory is ±45 degrees; ±90 degrees reaches the backstop's line",
        get: |_| None,
    },
    Range {
        path: "launch.spin_axis",
        min: -std::f64::consts::PI,
        max: std::f64::consts::PI,
        unit: "rad",
        reason: "the spin axis's tilt from pure backspin: ±90 degrees is sidespin, ±180 topspin",
        get: |_| None,
    },
    Range {
        path: "launch.spin",
        min: -1000.0,
        max: 1000.0,
        unit: "rad/s",
        reason: "batted balls spin up to about 6000 rpm (630 rad/s)",
        get: |_| None,
    },
    Range {
        path: "launch.height",
        min: 0.0,
        max: 2.5,
        unit: "m",
        reason: "balls are met between the ground and a batter's reach, about 0.3-1.5 m up",
        get: |_| None,
    },
];

/// The label of a profile's length (its last knot's z) in [`PROFILE_RANGES`].
pub const PROFILE_LENGTH: &str = "bat.profile.length";
/// The label of a profile's knot radii in [`PROFILE_RANGES`].
pub const PROFILE_RADIUS: &str = "bat.profile.radius";

/// The knots of a profile given by value or read from its CSV (the study layer puts a
/// CSV's knots in the spec before it is checked).
fn knots(s: &CollisionSpec) -> Option<&[[f64; 2]]> {
    match &s.bat.profile {
        Some(crate::spec::ProfileSpec::Knots(k)) => Some(k),
        _ => None,
    }
}

/// Of `values`, the first outside [lo, hi], else the largest: the one a range check needs.
fn extreme(values: impl Iterator<Item = f64>, lo: f64, hi: f64) -> Option<f64> {
    let mut largest: Option<f64> = None;
    for v in values {
        if !(lo..=hi).contains(&v) {
            return Some(v);
        }
        largest = Some(largest.map_or(v, |l| l.max(v)));
    }
    largest
}

/// Ranges of what a profile implies rather than of one field: a profile file in the wrong
/// unit (the R161 table read as metres when written in centimetres is an 84 m bat) must
/// meet the same bounds as `bat.length` and a bat's radius.
pub const PROFILE_RANGES: &[Range] = &[
    Range {
        path: PROFILE_LENGTH,
        min: 0.4,
        max: 1.5,
        unit: "m",
        reason: "the last knot is the bat's length: youth bats are about 0.6 m, adult bats 0.8-0.9 m",
        get: |s| knots(s).and_then(|k| k.last()).map(|k| k[0]),
    },
    Range {
        path: PROFILE_RADIUS,
        min: 0.003,
        max: 0.06,
        unit: "m",
        reason: "bat radii lie between about 0.5 cm (the thinnest handles) and 3.5 cm (big-barrel youth bats); a profile in cm or mm is 10-1000 times that",
        get: |s| knots(s).and_then(|k| extreme(k.iter().map(|p| p[1]), 0.003, 0.06)),
    },
];

/// Plausible layers of a wall (`bat.shell.layers`), in m: a ply from the thinnest prepregs
/// (about 0.03 mm) up; each wall between gaps, and the stack, as thick as
/// `bat.shell.thickness` allows; a gap between two walls of a double-wall barrel.
pub const PLY_THICKNESS: (f64, f64) = (2.0e-5, 0.05);
/// A gap's thickness in m: double-wall barrels leave well under a millimetre to a few.
pub const GAP_THICKNESS: (f64, f64) = (1.0e-5, 0.01);
/// A fibre's angle from the bat's axis, rad: ±90° covers every direction; a larger number
/// is an angle in degrees.
pub const FIBRE_ANGLE: f64 = std::f64::consts::FRAC_PI_2;

/// The first implausible layer, wall or stack of `bat.shell.layers`.
fn check_layers(spec: &CollisionSpec) -> Result<(), ModelError> {
    let Some(layers) = spec.bat.shell.as_ref().and_then(|s| s.layers.as_ref()) else {
        return Ok(());
    };
    let out = |path: String, value: f64, allowed: String| ModelError::OutOfRange {
        path,
        value,
        allowed: format!("{allowed}; a what-if study beyond it sets `allow_implausible: true`"),
    };
    let wall = range_of("bat.shell.thickness").expect("the shell's range");
    let mut walls = vec![0.0];
    for (i, l) in layers.iter().enumerate() {
        let gap = l.material == "gap";
        let (lo, hi) = if gap { GAP_THICKNESS } else { PLY_THICKNESS };
        if !(lo..=hi).contains(&l.thickness) {
            let what = if gap {
                "a gap between two walls"
            } else {
                "a ply or a metal layer"
            };
            return Err(out(
                format!("bat.shell.layers[{i}].thickness"),
                l.thickness,
                format!("{lo} to {hi} m ({what})"),
            ));
        }
        // 1e-4 rad of slack: π/2 written as 1.5708
        if l.angle.abs() > FIBRE_ANGLE + 1e-4 {
            let degrees = if l.angle.abs() <= 180.0 {
                format!("; {} degrees is {:.4} rad", l.angle, l.angle.to_radians())
            } else {
                String::new()
            };
            return Err(out(
                format!("bat.shell.layers[{i}].angle"),
                l.angle,
                format!("-{FIBRE_ANGLE:.4} to {FIBRE_ANGLE:.4} rad (±90 degrees from the axis){degrees}"),
            ));
        }
        match gap {
            true => walls.push(0.0),
            false => *walls.last_mut().expect("one wall at least") += l.thickness,
        }
    }
    let total: f64 = layers.iter().map(|l| l.thickness).sum();
    let thinnest = walls.iter().copied().fold(f64::INFINITY, f64::min);
    for (what, v) in [("each wall between gaps", thinnest), ("the stack", total)] {
        if !(wall.min..=wall.max).contains(&v) {
            return Err(out(
                "bat.shell.layers".into(),
                v,
                format!("{what}: {} to {} m ({})", wall.min, wall.max, wall.reason),
            ));
        }
    }
    Ok(())
}

/// The plausible range of a path, if it has one.
pub fn range_of(path: &str) -> Option<&'static Range> {
    RANGES
        .iter()
        .chain(PROFILE_RANGES)
        .chain(LAUNCH_RANGES)
        .find(|r| r.path == path)
}

/// `value` against the plausible range of `path` (a flag's or an argument's, where no
/// study's `allow_implausible` applies): the error names the path, the value and the range.
pub fn check_value(path: &str, value: f64) -> Result<(), ModelError> {
    let r = range_of(path).expect("a path with a plausible range");
    if value >= r.min && value <= r.max {
        return Ok(());
    }
    Err(ModelError::OutOfRange {
        path: path.to_string(),
        value,
        allowed: format!("{} to {} {} ({})", r.min, r.max, r.unit, r.reason),
    })
}

/// The first value of `spec` outside its plausible range.
pub fn check_plausible(spec: &CollisionSpec) -> Result<(), ModelError> {
    for r in RANGES.iter().chain(PROFILE_RANGES).chain(LAUNCH_RANGES) {
        if let Some(v) = (r.get)(spec) {
            if !(v >= r.min && v <= r.max) {
                return Err(ModelError::OutOfRange {
                    path: r.path.to_string(),
                    value: v,
                    allowed: format!(
                        "{} to {} {} ({}); a what-if study beyond it sets `allow_implausible: true`",
                        r.min, r.max, r.unit, r.reason
                    ),
                });
            }
        }
    }
    check_layers(spec)
}

/// The ranges as a JSON Schema fragment for the `base` block: nested `properties` with
/// `minimum`/`maximum` (numbers only; `null` and absent fields pass).
pub fn schema_overlay() -> serde_json::Value {
    use serde_json::{json, Map, Value};
    let mut root = Map::new();
    for r in RANGES {
        let mut node = &mut root;
        let segs: Vec<&str> = r.path.split('.').collect();
        for seg in &segs[..segs.len() - 1] {
            let child = node
                .entry(seg.to_string())
                .or_insert_with(|| json!({"properties": {}}));
            node = child
                .get_mut("properties")
                .and_then(Value::as_object_mut)
                .expect("overlay nodes have properties");
        }
        node.insert(
            segs[segs.len() - 1].to_string(),
            json!({
                "minimum": r.min,
                "maximum": r.max,
                "description": format!("plausible range, {}: {}", r.unit, r.reason),
            }),
        );
    }
    json!({ "properties": root })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_base_case_and_every_preset_are_plausible() {
        use crate::spec::BatPreset;
        for preset in [BatPreset::R161, BatPreset::Aluminum, BatPreset::Corked] {
            let mut s = CollisionSpec::base_case(0.6);
            s.bat.preset = preset;
            check_plausible(&s).unwrap();
        }
    }

    /// A profile written in other units than metres (the R161 table in centimetres, radii
    /// in millimetres) is refused by the same bounds as a bat's length and radius.
    #[test]
    fn profiles_in_the_wrong_unit_are_refused() {
        use crate::spec::ProfileSpec;
        let metres = vec![[0.0, 0.012], [0.5, 0.016], [0.84, 0.033]];
        let with = |k: Vec<[f64; 2]>| {
            let mut s = CollisionSpec::base_case(0.6);
            s.bat.profile = Some(ProfileSpec::Knots(k));
            check_plausible(&s)
        };
        with(metres.clone()).unwrap();
        let scaled = |fz: f64, fr: f64| metres.iter().map(|p| [p[0] * fz, p[1] * fr]).collect();
        for (k, path) in [
            (scaled(100.0, 100.0), PROFILE_LENGTH),
            (scaled(1.0, 1000.0), PROFILE_RADIUS),
            (scaled(1.0, 0.1), PROFILE_RADIUS),
        ] {
            match with(k) {
                Err(ModelError::OutOfRange { path: p, .. }) => assert_eq!(p, path),
                other => panic!("{path}: {other:?}"),
            }
        }
    }

    #[test]
    fn every_range_is_ordered() {
        for r in RANGES.iter().chain(PROFILE_RANGES) {
            assert!(r.min < r.max, "{}", r.path);
        }
    }

    #[test]
    fn the_issues_implausible_values_are_refused() {
        type Edit = fn(&mut CollisionSpec);
        let cases: [(&str, Edit); 4] = [
            ("ball.speed", |s| s.ball.speed = 1e6),
            ("bat.material.youngs_modulus", |s| {
                s.bat.material.youngs_modulus = Some(1e3)
            }),
            ("bat.material.density", |s| {
                s.bat.material.density = Some(1e30)
            }),
            ("bat.shell.thickness", |s| {
                s.bat.preset = crate::spec::BatPreset::Aluminum;
                s.bat.shell = Some(crate::spec::ShellSpec {
                    thickness: Some(1e-4),
                    from: None,
                    ..Default::default()
                });
            }),
        ];
        for (path, set) in cases {
            let mut s = CollisionSpec::base_case(0.6);
            set(&mut s);
            match check_plausible(&s) {
                Err(ModelError::OutOfRange { path: p, .. }) => assert_eq!(p, path),
                other => panic!("{path}: {other:?}"),
            }
        }
    }
}
