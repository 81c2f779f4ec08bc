//! `batstudy fly`: one batted ball's flight on its own (`model::flight::fly`), given as
//! Nathan's trajectory calculator takes it (exit speed, launch angle, spin, the air): the
//! carry, apex and hang time printed, the trajectory written as a CSV when asked.
//!
//! Every value is SI unless it carries a unit: `100mph`, `28deg`, `2500rpm`, `3ft`, `70F`,
//! `21C`, `29.92inHg`.

use super::{EXIT_BAD_INPUT, EXIT_OK};
use crate::model::flight::{self, Atmosphere, FlightError, FlightOptions, Launch, FOOT};
use crate::model::plausible;
use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub struct FlyArgs {
    /// Exit speed: m/s, or `mph`.
    #[arg(long, value_parser = exit_speed, allow_hyphen_values = true)]
    pub exit_speed: f64,
    /// Launch angle above the horizontal: rad, or `deg`.
    #[arg(long, value_parser = launch_angle, allow_hyphen_values = true)]
    pub launch_angle: f64,
    /// Backspin (negative: topspin): rad/s, or `rpm`. Required: a batted ball without spin
    /// is a knuckleball that carries tens of feet less (give `0` for one); line drives and
    /// fly balls leave with about 1,000–3,000 rpm.
    #[arg(long, value_parser = spin, allow_hyphen_values = true)]
    pub backspin: f64,
    /// Sidespin, positive curving toward the left-field side: rad/s, or `rpm`.
    #[arg(long, value_parser = spin, default_value = "0", allow_hyphen_values = true)]
    pub sidespin: f64,
    /// Spray angle from straight-away centre field, positive toward right field: rad, or
    /// `deg`.
    #[arg(long, value_parser = spray_angle, default_value = "0", allow_hyphen_values = true)]
    pub spray_angle: f64,
    /// Height of the contact point: m, or `ft`. Default 3 ft.
    #[arg(long, value_parser = height, default_value = "0.9144")]
    pub height: f64,
    /// Air temperature: K, or `F`, `C`. Default 70 F.
    #[arg(long, value_parser = temperature, allow_hyphen_values = true)]
    pub temperature: Option<f64>,
    /// Elevation of the field above sea level: m, or `ft`.
    #[arg(long, value_parser = elevation, default_value = "0", allow_hyphen_values = true)]
    pub elevation: f64,
    /// Relative humidity, 0 to 1, or `%`.
    #[arg(long, value_parser = humidity, default_value = "0.5")]
    pub humidity: f64,
    /// Barometric pressure reduced to sea level: Pa, or `inHg`. Default 29.92 inHg.
    #[arg(long, value_parser = pressure)]
    pub pressure: Option<f64>,
    /// Wind toward centre field (a tail wind; negative: in the batter's face): m/s, or `mph`.
    #[arg(long, value_parser = wind, default_value = "0", allow_hyphen_values = true)]
    pub tail_wind: f64,
    /// Write the trajectory to this CSV: time, position and velocity at every step, SI.
    #[arg(long)]
    pub trajectory: Option<PathBuf>,
}

/// A number with an optional unit suffix, times the unit's factor plus its offset, inside
/// the plausible range of `range` (`model::plausible`). The first unit is SI; a bare number
/// outside the range that one of the others would put inside it is refused with that unit
/// named (`--exit-speed 100` is 100 mph, not 100 m/s).
fn with_units(s: &str, units: &[(&str, f64, f64)], what: &str, range: &str) -> Result<f64, String> {
    let t = s.trim();
    let suffixed = units
        .iter()
        .filter(|(u, _, _)| !u.is_empty())
        .find_map(|(u, f, o)| t.strip_suffix(u).map(|n| (n, (*f, *o))));
    let (number, (factor, offset)) = suffixed.unwrap_or((t, (1.0, 0.0)));
    let names: Vec<&str> = units.iter().map(|u| u.0).collect();
    let x = match number.trim().parse::<f64>() {
        Ok(x) if x.is_finite() => x,
        _ => {
            return Err(format!(
                "`{s}` is not {what}: a number in SI units{}, or with one of {}",
                Some(names[0])
                    .filter(|n| !n.is_empty())
                    .map(|n| format!(" ({n})"))
                    .unwrap_or_default(),
                names[1..].join(", ")
            ))
        }
    };
    let r = plausible::range_of(range).expect("every flag has a plausible range");
    let v = x * factor + offset;
    if (r.min..=r.max).contains(&v) {
        return Ok(v);
    }
    let unit = |u: &str| {
        if u == "1" {
            String::new()
        } else {
            format!(" {u}")
        }
    };
    let meant = units[1..]
        .iter()
        .find(|(_, f, o)| suffixed.is_none() && (r.min..=r.max).contains(&(x * f + o)))
        .map(|(u, _, _)| format!("; if {x} {u} is meant, write `{x}{u}`"))
        .unwrap_or_default();
    // four decimals: a bound of ±π/2 reads as 1.5708
    let num = |v: f64| (v * 1e4).round() / 1e4;
    Err(format!(
        "`{s}` is {}{} (SI), outside the plausible {} to {}{} ({}){meant}",
        num(v),
        unit(r.unit),
        num(r.min),
        num(r.max),
        unit(r.unit),
        r.reason
    ))
}

const DEG: f64 = std::f64::consts::PI / 180.0;
const SPEEDS: &[(&str, f64, f64)] = &[("m/s", 1.0, 0.0), ("mph", flight::MPH, 0.0)];
const ANGLES: &[(&str, f64, f64)] = &[("rad", 1.0, 0.0), ("deg", DEG, 0.0)];
const SPINS: &[(&str, f64, f64)] = &[("rad/s", 1.0, 0.0), ("rpm", flight::RPM, 0.0)];
const LENGTHS: &[(&str, f64, f64)] = &[("m", 1.0, 0.0), ("ft", FOOT, 0.0)];

/// A flag's value parser: `with_units` over `units`, held to the plausible range `range`.
macro_rules! parser {
    ($name:ident, $units:expr, $what:literal, $range:literal) => {
        fn $name(s: &str) -> Result<f64, String> {
            with_units(s, $units, $what, $range)
        }
    };
}

parser!(exit_speed, SPEEDS, "a speed", "launch.exit_speed");
parser!(wind, SPEEDS, "a speed", "flight.wind_speed");
parser!(launch_angle, ANGLES, "an angle", "launch.launch_angle");
parser!(spray_angle, ANGLES, "an angle", "launch.spray_angle");
parser!(spin, SPINS, "a spin", "launch.spin");
parser!(height, LENGTHS, "a length", "launch.height");
parser!(elevation, LENGTHS, "a length", "flight.elevation");

fn humidity(s: &str) -> Result<f64, String> {
    with_units(
        s,
        &[("", 1.0, 0.0), ("%", 0.01, 0.0)],
        "a fraction",
        "flight.humidity",
    )
}

fn temperature(s: &str) -> Result<f64, String> {
    let f = flight::fahrenheit_to_kelvin(0.0);
    let c = flight::celsius_to_kelvin(0.0);
    let units = [("K", 1.0, 0.0), ("F", 5.0 / 9.0, f), ("C", 1.0, c)];
    with_units(s, &units, "a temperature", "flight.temperature")
}

fn pressure(s: &str) -> Result<f64, String> {
    // 1 inHg = 3386.389 Pa (NIST SP 811, at 0 °C)
    let units = [("Pa", 1.0, 0.0), ("inHg", 3386.389, 0.0)];
    with_units(s, &units, "a pressure", "flight.pressure")
}

/// The launch and the air the arguments describe.
fn inputs(a: &FlyArgs) -> (Launch, Atmosphere) {
    let launch = Launch {
        spray_angle_rad: a.spray_angle,
        sidespin_rad_s: a.sidespin,
        height_m: a.height,
        ..Launch::new(a.exit_speed, a.launch_angle, a.backspin)
    };
    let standard = Atmosphere::default();
    let atm = Atmosphere {
        temperature_k: a.temperature.unwrap_or(standard.temperature_k),
        sea_level_pressure_pa: a.pressure.unwrap_or(standard.sea_level_pressure_pa),
        elevation_m: a.elevation,
        relative_humidity: a.humidity,
        wind_m_s: [0.0, a.tail_wind, 0.0],
    };
    (launch, atm)
}

pub(super) fn cmd_fly(a: &FlyArgs) -> i32 {
    if let Some(path) = &a.trajectory {
        if let Err(e) = super::common::side_output_ok(path, "--trajectory", &[]) {
            eprintln!("{e}");
            return EXIT_BAD_INPUT;
        }
    }
    let (launch, atm) = inputs(a);
    let opts = FlightOptions {
        record_trajectory: a.trajectory.is_some(),
        ..FlightOptions::default()
    };
    let f = match flight::fly(launch, &atm, &opts) {
        Ok(f) => f,
        Err(e) => {
            eprintln!("error: {}", flag_of(&e));
            return EXIT_BAD_INPUT;
        }
    };
    if let Some(path) = &a.trajectory {
        if let Err(e) = write_trajectory(path, &f.trajectory) {
            eprintln!("error: {}: {e}", path.display());
            return super::EXIT_RUN_FAILED;
        }
    }
    println!(
        "carry {:.2} m ({:.1} ft) from the contact point; apex {:.2} m ({:.1} ft) at {:.3} s; \
         hang time {:.3} s; lands at x = {:.2} m, y = {:.2} m (x toward right field, y to centre)",
        f.carry_m,
        f.carry_m / FOOT,
        f.apex_m,
        f.apex_m / FOOT,
        f.apex_time_s,
        f.hang_time_s,
        f.landing_m[0],
        f.landing_m[1]
    );
    EXIT_OK
}

/// A flight's error in the command's words: the flag of the input out of its range.
fn flag_of(e: &FlightError) -> String {
    const FLAGS: &[(&str, &str)] = &[
        ("launch.speed_m_s", "--exit-speed"),
        ("launch.launch_angle_rad", "--launch-angle"),
        ("launch.spray_angle_rad", "--spray-angle"),
        ("launch.backspin_rad_s", "--backspin"),
        ("launch.sidespin_rad_s", "--sidespin"),
        ("launch.height_m", "--height"),
        ("atmosphere.temperature_k", "--temperature"),
        ("atmosphere.sea_level_pressure_pa", "--pressure"),
        ("atmosphere.elevation_m", "--elevation"),
        ("atmosphere.relative_humidity", "--humidity"),
        ("atmosphere.wind_m_s", "--tail-wind"),
    ];
    match e {
        FlightError::OutOfRange {
            name,
            value,
            allowed,
        } => match FLAGS.iter().find(|(n, _)| n == name) {
            Some((_, flag)) => {
                format!("{flag}: {value} (SI) is outside the allowed range {allowed}")
            }
            None => e.to_string(),
        },
        _ => e.to_string(),
    }
}

/// The trajectory as CSV, written beside `path` and renamed onto it when whole.
fn write_trajectory(path: &std::path::Path, samples: &[flight::Sample]) -> std::io::Result<()> {
    use std::fmt::Write as _;
    let mut text = String::from(
        "# batstudy fly: the ball's flight; x toward right field, y toward centre field, z up, from the ground below the contact point\nt_s,x_m,y_m,z_m,vx_m_s,vy_m_s,vz_m_s\n",
    );
    for s in samples {
        let [vx, vy, vz] = s.velocity_m_s;
        let _ = writeln!(
            text,
            "{},{},{},{},{vx},{vy},{vz}",
            s.t_s, s.x_m, s.y_m, s.z_m
        );
    }
    crate::store::journal::write_whole(path, text.as_bytes())
}
