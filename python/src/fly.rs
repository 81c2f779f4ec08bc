//! `_native.fly`: one batted ball's flight (`model::flight::fly`), its trajectory as raw
//! little-endian f64 bytes for NumPy.

use batstudy::model::flight::{self, Atmosphere, FlightOptions, Launch};
use batstudy::model::plausible;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// The flight of a ball launched at `exit_speed` (m/s) and `launch_angle` (rad) with
/// `backspin` and `sidespin` (rad/s), toward `spray_angle` (rad) from `height` (m), through
/// the air given (K, Pa at sea level, m, 0-1, m/s in the flight frame). Returns a dict:
/// carry, apex, apex_time, hang_time, landing (x, y) and, with `trajectory`, the columns
/// t, x, y, z, vx, vy, vz as bytes. Raises ValueError naming the input out of its range.
#[pyfunction]
#[pyo3(signature = (exit_speed, launch_angle, backspin, sidespin, spray_angle, height,
                    temperature, pressure, elevation, humidity, wind, trajectory))]
#[allow(clippy::too_many_arguments)]
pub fn fly<'py>(
    py: Python<'py>,
    exit_speed: f64,
    launch_angle: f64,
    backspin: f64,
    sidespin: f64,
    spray_angle: f64,
    height: f64,
    temperature: f64,
    pressure: f64,
    elevation: f64,
    humidity: f64,
    wind: [f64; 3],
    trajectory: bool,
) -> PyResult<Bound<'py, PyDict>> {
    // the same plausible ranges as a study's `flight` block and `batstudy fly`: SI only
    // (`batstudy.units` converts), so 100 meant as mph is refused, not flown
    let checks = [
        ("launch.exit_speed", exit_speed),
        ("launch.launch_angle", launch_angle),
        ("launch.spin", backspin),
        ("launch.spin", sidespin),
        ("launch.spray_angle", spray_angle),
        ("launch.height", height),
        ("flight.temperature", temperature),
        ("flight.pressure", pressure),
        ("flight.elevation", elevation),
        ("flight.humidity", humidity),
    ];
    for (path, value) in checks
        .into_iter()
        .chain(wind.map(|w| ("flight.wind_speed", w)))
    {
        plausible::check_value(path, value).map_err(|e| {
            PyValueError::new_err(format!(
                "{e} (SI: batstudy.units converts mph, deg, rpm, ft)"
            ))
        })?;
    }
    let launch = Launch {
        spray_angle_rad: spray_angle,
        sidespin_rad_s: sidespin,
        height_m: height,
        ..Launch::new(exit_speed, launch_angle, backspin)
    };
    let atm = Atmosphere {
        temperature_k: temperature,
        sea_level_pressure_pa: pressure,
        elevation_m: elevation,
        relative_humidity: humidity,
        wind_m_s: wind,
    };
    let opts = FlightOptions {
        record_trajectory: trajectory,
        ..FlightOptions::default()
    };
    let f = py
        .detach(|| flight::fly(launch, &atm, &opts))
        .map_err(|e| PyValueError::new_err(e.to_string()))?;
    let d = PyDict::new(py);
    d.set_item("carry", f.carry_m)?;
    d.set_item("apex", f.apex_m)?;
    d.set_item("apex_time", f.apex_time_s)?;
    d.set_item("hang_time", f.hang_time_s)?;
    d.set_item("landing", (f.landing_m[0], f.landing_m[1]))?;
    let column =
        |g: &dyn Fn(&flight::Sample) -> f64| -> Vec<f64> { f.trajectory.iter().map(g).collect() };
    let columns: [(&str, Vec<f64>); 7] = [
        ("t", column(&|s| s.t_s)),
        ("x", column(&|s| s.x_m)),
        ("y", column(&|s| s.y_m)),
        ("z", column(&|s| s.z_m)),
        ("vx", column(&|s| s.velocity_m_s[0])),
        ("vy", column(&|s| s.velocity_m_s[1])),
        ("vz", column(&|s| s.velocity_m_s[2])),
    ];
    for (name, values) in columns {
        d.set_item(name, crate::f64_bytes(py, &values))?;
    }
    Ok(d)
}

/// The calculator's standard day, for the Python defaults: (K, Pa).
#[pyfunction]
pub fn standard_air() -> (f64, f64) {
    let a = Atmosphere::default();
    (a.temperature_k, a.sea_level_pressure_pa)
}

/// A value written with a unit (`"100mph"`, `"28deg"`, `"2500rpm"`, `"70F"`) in SI, for the
/// plausible range `path` (`launch.exit_speed`, `flight.temperature`, …), whose unit says
/// which units it takes. Raises ValueError naming the input and the units allowed.
#[pyfunction]
pub fn to_si(text: &str, path: &str) -> PyResult<f64> {
    let range = plausible::range_of(path)
        .ok_or_else(|| PyValueError::new_err(format!("{path}: no such quantity")))?;
    batstudy::model::units::to_si(text, range.unit)
        .map_err(|why| PyValueError::new_err(format!("{path}: {why}")))
}
