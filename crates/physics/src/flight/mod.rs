//! The batted ball's flight: from the launch (speed, angles, spin, contact height) to where
//! it comes back to the ground, through air with Nathan's Statcast-fitted drag and lift
//! (docs/physics.md "Flight"). Pure physics: no I/O, no threads, no allocation unless the
//! trajectory is requested.
//!
//! The frame is that of Nathan's trajectory calculator: origin on the ground below the
//! contact point, x horizontal toward the first-base (right-field) side, y horizontal toward
//! centre field, z up.
//!
//! Rooms, each importing only the ones above it: `error`, `air` (the atmosphere and its
//! density), `aero` (the ball, the drag and lift coefficients, the equations of motion),
//! `integrate` (RK4 and the apex and landing events).

pub mod aero;
pub mod air;
pub mod error;
mod integrate;

pub use aero::{BallProperties, NathanAero, FOOT, GRAVITY, MPH, RPM};
pub use air::{celsius_to_kelvin, fahrenheit_to_kelvin, Atmosphere};
pub use error::FlightError;

use aero::Forces;
use error::check_range;
use integrate::{integrate, rk4, State};

/// The calculator's contact height, m (3 ft).
pub const DEFAULT_CONTACT_HEIGHT_M: f64 = 3.0 * FOOT;
/// Default RK4 step, s. The convergence test (tests/physics_flight.rs) shows the carry
/// error falling as h⁴ (16-fold per halving); at 0.1 s it is at most 8 µm over 90–115 mph,
/// 10–60° and 0–3000 rpm (0.13 mm at 0.2 s), far below the 16-ft (5 m) natural spread of
/// fly-ball distances, in 20–80 steps a flight.
pub const DEFAULT_STEP_S: f64 = 0.1;

/// The stored trajectory's time step, s: the integrator's default, so that a flight of
/// 16 steps or more is stored at its own states.
pub const TRAJECTORY_STEP_S: f64 = DEFAULT_STEP_S;
/// The stored trajectory's samples: 0 to 12 s (the longest pop-ups hang about 7 s).
pub const TRAJECTORY_SAMPLES: usize = 121;

/// A flight's recorded states on the stored trajectory's time axis: (x, y, z) at
/// k·[`TRAJECTORY_STEP_S`], k < [`TRAJECTORY_SAMPLES`], NaN after the landing. Between two
/// recorded states the position is the cubic Hermite through their positions and
/// velocities (exact at the states themselves; a shortened step puts them off the axis).
pub fn trajectory_on_grid(samples: &[Sample]) -> [Vec<f64>; 3] {
    let mut pair = 0;
    let positions: Vec<[f64; 3]> = (0..TRAJECTORY_SAMPLES)
        .map_while(|k| position_at(samples, k as f64 * TRAJECTORY_STEP_S, &mut pair))
        .collect();
    let mut out = [(); 3].map(|_| vec![f64::NAN; TRAJECTORY_SAMPLES]);
    for (c, column) in out.iter_mut().enumerate() {
        for (v, p) in column.iter_mut().zip(&positions) {
            *v = p[c];
        }
    }
    out
}

/// The position at `t` on the recorded states, `None` after the last; `pair` is the index
/// of the state at or before `t`, advanced as `t` grows.
fn position_at(samples: &[Sample], t: f64, pair: &mut usize) -> Option<[f64; 3]> {
    while *pair + 1 < samples.len() && samples[*pair + 1].t_s < t {
        *pair += 1;
    }
    let a = samples.get(*pair)?;
    match samples.get(*pair + 1) {
        Some(b) if t <= b.t_s => Some(hermite(a, b, t)),
        None if t == a.t_s => Some([a.x_m, a.y_m, a.z_m]),
        _ => None,
    }
}

/// The cubic Hermite position at `t` between states `a` and `b` (a.t ≤ t ≤ b.t).
fn hermite(a: &Sample, b: &Sample, t: f64) -> [f64; 3] {
    let h = b.t_s - a.t_s;
    if h <= 0.0 {
        return [a.x_m, a.y_m, a.z_m];
    }
    let tau = (t - a.t_s) / h;
    let (pa, pb) = ([a.x_m, a.y_m, a.z_m], [b.x_m, b.y_m, b.z_m]);
    std::array::from_fn(|i| {
        let [c0, c1, c2, c3] =
            integrate::hermite_cubic(pa[i], pb[i], h * a.velocity_m_s[i], h * b.velocity_m_s[i]);
        c0 + tau * (c1 + tau * (c2 + tau * c3))
    })
}
/// Fewest steps a flight is cut into: a very short flight gets a smaller step.
const MIN_STEPS_PER_FLIGHT: f64 = 16.0;

/// The ball as it leaves the bat.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Launch {
    /// Exit speed, m/s (≥ 0, ≤ 100).
    pub speed_m_s: f64,
    /// Vertical launch angle above the horizontal, rad (−π/2 to π/2).
    pub launch_angle_rad: f64,
    /// Horizontal (spray) angle from straight-away centre field, rad, positive toward the
    /// first-base (right-field) side, +x (−π/2 to π/2). The calculator's convention.
    pub spray_angle_rad: f64,
    /// Backspin, rad/s; positive is backspin (lift upward), negative topspin. Its axis is
    /// horizontal and perpendicular to the launch direction.
    pub backspin_rad_s: f64,
    /// Sidespin, rad/s, about the axis perpendicular to the launch velocity in its vertical
    /// plane (vertical for a level launch); positive curves the ball toward the left-field
    /// side (−x), as the calculator's sidespin does. 0 unless given.
    pub sidespin_rad_s: f64,
    /// Height of the contact point above the ground, m (0–10). Default 0.9144 m (3 ft).
    pub height_m: f64,
}

impl Launch {
    /// A ball hit to centre field without sidespin from the default contact height.
    pub fn new(speed_m_s: f64, launch_angle_rad: f64, backspin_rad_s: f64) -> Launch {
        Launch {
            speed_m_s,
            launch_angle_rad,
            spray_angle_rad: 0.0,
            backspin_rad_s,
            sidespin_rad_s: 0.0,
            height_m: DEFAULT_CONTACT_HEIGHT_M,
        }
    }

    fn validate(&self) -> Result<(), FlightError> {
        use std::f64::consts::FRAC_PI_2;
        check_range(
            "launch.speed_m_s",
            self.speed_m_s,
            0.0,
            100.0,
            "[0, 100] m/s",
        )?;
        let angle = "[-pi/2, pi/2] rad";
        check_range(
            "launch.launch_angle_rad",
            self.launch_angle_rad,
            -FRAC_PI_2,
            FRAC_PI_2,
            angle,
        )?;
        check_range(
            "launch.spray_angle_rad",
            self.spray_angle_rad,
            -FRAC_PI_2,
            FRAC_PI_2,
            angle,
        )?;
        let spin = "[-1000, 1000] rad/s";
        check_range(
            "launch.backspin_rad_s",
            self.backspin_rad_s,
            -1000.0,
            1000.0,
            spin,
        )?;
        check_range(
            "launch.sidespin_rad_s",
            self.sidespin_rad_s,
            -1000.0,
            1000.0,
            spin,
        )?;
        check_range("launch.height_m", self.height_m, 0.0, 10.0, "[0, 10] m")?;
        Ok(())
    }

    /// Initial velocity, m/s, in the flight frame.
    pub fn velocity(&self) -> [f64; 3] {
        let (sin_t, cos_t) = self.launch_angle_rad.sin_cos();
        let (sin_p, cos_p) = self.spray_angle_rad.sin_cos();
        let v = self.speed_m_s;
        [v * cos_t * sin_p, v * cos_t * cos_p, v * sin_t]
    }

    /// Spin vector, rad/s: backspin about the horizontal axis (cos φ, −sin φ, 0), sidespin
    /// about (−sin θ sin φ, −sin θ cos φ, cos θ), both perpendicular to the launch velocity.
    pub fn spin(&self) -> [f64; 3] {
        let (sin_t, cos_t) = self.launch_angle_rad.sin_cos();
        let (sin_p, cos_p) = self.spray_angle_rad.sin_cos();
        let (b, s) = (self.backspin_rad_s, self.sidespin_rad_s);
        [
            b * cos_p - s * sin_t * sin_p,
            -b * sin_p - s * sin_t * cos_p,
            s * cos_t,
        ]
    }
}

/// How to compute a flight, and with which ball and aerodynamics.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlightOptions {
    /// The ball (default: 5.125 oz, 9.125 in).
    pub ball: BallProperties,
    /// Drag, lift and spin decay (default: Nathan's Statcast fit, τ = 30 s).
    pub aero: NathanAero,
    /// RK4 step, s (default [`DEFAULT_STEP_S`]); shortened for flights under 16 steps.
    pub step_s: f64,
    /// The ball must land within this time, s (default 60).
    pub max_time_s: f64,
    /// Keep every step's position in `Flight::trajectory` (default false: no allocation).
    pub record_trajectory: bool,
}

impl Default for FlightOptions {
    fn default() -> Self {
        FlightOptions {
            ball: BallProperties::default(),
            aero: NathanAero::default(),
            step_s: DEFAULT_STEP_S,
            max_time_s: 60.0,
            record_trajectory: false,
        }
    }
}

/// One position of the ball on its way.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// Time since contact, s.
    pub t_s: f64,
    /// Position in the flight frame, m.
    pub x_m: f64,
    pub y_m: f64,
    pub z_m: f64,
    /// Velocity over the ground, m/s.
    pub velocity_m_s: [f64; 3],
}

impl Sample {
    fn from_state(s: &State) -> Sample {
        Sample {
            t_s: s.t,
            x_m: s.p[0],
            y_m: s.p[1],
            z_m: s.p[2],
            velocity_m_s: s.v,
        }
    }
}

/// Where and when the ball comes down.
#[derive(Debug, Clone, PartialEq)]
pub struct Flight {
    /// Horizontal distance from the contact point to where the ball is back at z = 0, m.
    /// (Statcast and the calculator measure from home plate, about 2 ft behind contact.)
    pub carry_m: f64,
    /// Greatest height above the ground, m (the contact height for a ball hit downward).
    pub apex_m: f64,
    /// Time of the apex, s (0 for a ball hit downward).
    pub apex_time_s: f64,
    /// Time from contact to landing, s.
    pub hang_time_s: f64,
    /// Landing point (x, y), m.
    pub landing_m: [f64; 2],
    /// Velocity at landing, m/s.
    pub landing_velocity_m_s: [f64; 3],
    /// (t, x, y, z) at every step and at the landing, when `record_trajectory` was set;
    /// empty otherwise.
    pub trajectory: Vec<Sample>,
}

/// The flight of a batted ball through `atm`. Errors name the first input outside its range
/// (NaN included) or report a ball that never lands within `opts.max_time_s`.
pub fn fly(launch: Launch, atm: &Atmosphere, opts: &FlightOptions) -> Result<Flight, FlightError> {
    launch.validate()?;
    opts.aero.validate()?;
    validate_options(opts)?;
    let density = atm.air_density()?;
    let forces = Forces::new(density, atm.wind_m_s, &opts.ball, &opts.aero, launch.spin());
    let start = State {
        t: 0.0,
        p: [0.0, 0.0, launch.height_m],
        v: launch.velocity(),
    };
    let Some(step) = first_step(&forces, &start, opts.step_s) else {
        return Ok(landed_at_once(&start, opts.record_trajectory));
    };
    let mut samples = Vec::new();
    let record = opts.record_trajectory.then_some(&mut samples);
    let events = integrate(&forces, start, step, opts.max_time_s, record)?;
    let land = events.landing;
    Ok(Flight {
        carry_m: land.p[0].hypot(land.p[1]),
        apex_m: events.apex_m,
        apex_time_s: events.apex_time_s,
        hang_time_s: land.t,
        landing_m: [land.p[0], land.p[1]],
        landing_velocity_m_s: land.v,
        trajectory: samples,
    })
}

fn validate_options(opts: &FlightOptions) -> Result<(), FlightError> {
    check_range(
        "options.ball.mass_kg",
        opts.ball.mass_kg,
        1e-3,
        10.0,
        "[0.001, 10] kg",
    )?;
    let circumference = opts.ball.circumference_m;
    check_range(
        "options.ball.circumference_m",
        circumference,
        1e-3,
        10.0,
        "[0.001, 10] m",
    )?;
    check_range("options.step_s", opts.step_s, 1e-6, 1.0, "[1e-6, 1] s")?;
    check_range(
        "options.max_time_s",
        opts.max_time_s,
        0.0,
        3600.0,
        "[0, 3600] s",
    )?;
    Ok(())
}

/// The step for this flight: `step`, shortened so that the vacuum flight time from the
/// same launch is at least 16 steps, and halved until a ball launched from the ground is
/// still in the air after the first step (the landing search needs z > 0 at a step's
/// start). None when the ball starts on the ground going down or level.
fn first_step(forces: &Forces, start: &State, step: f64) -> Option<f64> {
    let (z0, vz0) = (start.p[2], start.v[2]);
    let vacuum_hang = (vz0 + (vz0 * vz0 + 2.0 * GRAVITY * z0).sqrt()) / GRAVITY;
    if vacuum_hang.is_nan() || vacuum_hang <= 0.0 {
        return None;
    }
    let mut h = step.min(vacuum_hang / MIN_STEPS_PER_FLIGHT);
    if z0 > 0.0 {
        return Some(h);
    }
    for _ in 0..60 {
        if rk4(forces, start, h).p[2] > 0.0 {
            return Some(h);
        }
        h *= 0.5;
    }
    None
}

/// A ball that starts on the ground moving down or level: it lands where it starts.
fn landed_at_once(start: &State, record: bool) -> Flight {
    Flight {
        carry_m: 0.0,
        apex_m: start.p[2],
        apex_time_s: 0.0,
        hang_time_s: 0.0,
        landing_m: [0.0, 0.0],
        landing_velocity_m_s: start.v,
        trajectory: if record {
            vec![Sample::from_state(start)]
        } else {
            Vec::new()
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(t: f64) -> Sample {
        // a cubic path, which the Hermite cubic reproduces exactly
        Sample {
            t_s: t,
            x_m: 0.5 * t,
            y_m: 30.0 * t - t * t * t,
            z_m: 1.0 + 20.0 * t - 4.9 * t * t,
            velocity_m_s: [0.5, 30.0 - 3.0 * t * t, 20.0 - 9.8 * t],
        }
    }

    #[test]
    fn the_grid_holds_the_path_between_uneven_states_and_nothing_after_the_landing() {
        let times = [0.0, 0.07, 0.19, 0.23, 0.41, 0.5, 0.58];
        let samples: Vec<Sample> = times.iter().map(|&t| at(t)).collect();
        let [x, y, z] = trajectory_on_grid(&samples);
        for k in 0..=5 {
            let want = at(k as f64 * TRAJECTORY_STEP_S);
            assert!((x[k] - want.x_m).abs() < 1e-12, "{k}");
            assert!((y[k] - want.y_m).abs() < 1e-12, "{k}");
            assert!((z[k] - want.z_m).abs() < 1e-12, "{k}");
        }
        assert!(x[6..].iter().chain(&z[6..]).all(|v| v.is_nan()));
        assert_eq!(x.len(), TRAJECTORY_SAMPLES);
    }
}
