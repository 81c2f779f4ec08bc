//! `batstudy fly`: one batted ball's flight on its own (`model::flight::fly`), given as
//! Nathan's trajectory calculator takes it (exit speed, launch angle, spin, the air): the
//! carry, apex and hang time printed, the trajectory written as a CSV when asked.
//!
//! Every value is SI unless it carries a unit: `100mph`, `28deg`, `2500rpm`, `3ft`, `70F`,
//! `21C`, `29.92inHg`.

use super::{EXIT_BAD_INPUT, EXIT_OK};
use crate::model::flight::{self, Atmosphere, FlightError, FlightOptions, Launch};
use crate::model::plausible;
use crate::model::units::{meant_of, split_quantity, suffixes, units_of, Unit, FOOT};
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

/// A number with an optional unit suffix, in SI (`model::units`), inside the plausible range
/// of `range` (`model::plausible`), whose SI unit gives the units allowed (`units`, when
/// given, instead). A bare number outside the range that one of the trade's units would put
/// inside it is refused with that unit named (`--exit-speed 100` is 100 mph, not 100 m/s).
fn with_units(s: &str, units: Option<&[Unit]>, what: &str, range: &str) -> Result<f64, String> {
    let r = plausible::range_of(range).expect("every flag has a plausible range");
    let units = units.unwrap_or_else(|| units_of(r.unit));
    let t = s.trim();
    let parsed = match split_quantity(t) {
        Some((x, suffix)) => units
            .iter()
            .find(|u| u.suffix == suffix)
            .map(|u| (x, x * u.factor + u.offset, true)),
        None => t.parse::<f64>().ok().map(|x| (x, x, false)),
    };
    let Some((x, v, suffixed)) = parsed.filter(|p| p.1.is_finite()) else {
        return Err(format!(
            "`{s}` is not {what}: a number in SI units{}, or with one of {}",
            Some(units[0].suffix)
                .filter(|n| !n.is_empty())
                .map(|n| format!(" ({n})"))
                .unwrap_or_default(),
            suffixes(&units[1..])
        ));
    };
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
    let meant = meant_of(units, x, r.min, r.max)
        .filter(|_| !suffixed)
        .map(|u| format!("; if {x} {} is meant, write `{x}{}`", u.suffix, u.suffix))
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

/// A flag's value parser: `with_units` held to the plausible range `range`, in its units.
macro_rules! parser {
    ($name:ident, $what:literal, $range:literal) => {
        fn $name(s: &str) -> Result<f64, String> {
            with_units(s, None, $what, $range)
        }
    };
}

parser!(exit_speed, "a speed", "launch.exit_speed");
parser!(wind, "a speed", "flight.wind_speed");
parser!(launch_angle, "an angle", "launch.launch_angle");
parser!(spray_angle, "an angle", "launch.spray_angle");
parser!(spin, "a spin", "launch.spin");
parser!(height, "a length", "launch.height");
parser!(elevation, "a length", "flight.elevation");
parser!(temperature, "a temperature", "flight.temperature");
parser!(pressure, "a pressure", "flight.pressure");

fn humidity(s: &str) -> Result<f64, String> {
    const FRACTION: &[Unit] = &[
        Unit {
            suffix: "",
            factor: 1.0,
            offset: 0.0,
        },
        Unit {
            suffix: "%",
            factor: 0.01,
            offset: 0.0,
        },
    ];
    with_units(s, Some(FRACTION), "a fraction", "flight.humidity")
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
