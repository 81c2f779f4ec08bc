//! The batted ball in the lab: its launch from the collision's plane and the swing's
//! geometry, and its flight (docs/physics.md, "Launch" and "Flight").
//!
//! The lab frame is the flight's (Nathan's trajectory calculator): x horizontal toward the
//! first-base side, y toward centre field, z up. The bat's path at the impact point (the
//! direction its impact point moves, toward the pitcher) is û = (0, cos ψ, sin ψ), ψ the
//! attack angle, and the pitch arrives along −û (an "on plane" swing). The bat's axis from
//! knob to barrel, a right-handed batter's, is a = (cos φ, −sin ψ sin φ, cos ψ sin φ), φ the
//! vertical bat angle (tilted about the path; negative with the barrel down). The
//! collision's plane is spanned by ŷ = −û and x̂ = (a × û)/|a × û| (up for a level bat),
//! and its spin axis is b̂ = ŷ × x̂ = −a. A left-handed batter's launch is the mirror image
//! (x → −x).

use crate::collision::oblique::BallContact;
use crate::error::ModelError;
use crate::flight::{fly, Atmosphere, BallProperties, FlightOptions, Launch};
use crate::outcome::{BallExit, BattedBall};
use crate::spec::{CollisionSpec, FlightSpec};

type Vec3 = [f64; 3];

fn scaled(v: Vec3, k: f64) -> Vec3 {
    [v[0] * k, v[1] * k, v[2] * k]
}

fn added(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn dot(a: Vec3, b: Vec3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The swing's directions in the lab: the bat's path û, the plane's x̂ and spin axis b̂.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SwingFrame {
    pub path: Vec3,
    pub across: Vec3,
    pub spin_axis: Vec3,
}

impl SwingFrame {
    /// The frame of attack angle `attack` and vertical bat angle `tilt`, rad.
    pub fn new(attack: f64, tilt: f64) -> SwingFrame {
        let (sa, ca) = attack.sin_cos();
        let (st, ct) = tilt.sin_cos();
        // a × û with a = (ct, −sa st, ca st), û = (0, ca, sa): a unit vector already
        let across = [-st, -ct * sa, ct * ca];
        SwingFrame {
            path: [0.0, ca, sa],
            across,
            spin_axis: [-ct, sa * st, -ca * st],
        }
    }

    /// The ball's lab velocity after the collision: the bat's CM moves at `cm_speed` along
    /// the path; `exit` is in the bat-CM frame (ŷ = −û).
    pub fn velocity(&self, cm_speed: f64, exit: &BallExit) -> Vec3 {
        added(
            scaled(self.path, cm_speed - exit.along),
            scaled(self.across, exit.across),
        )
    }
}

/// Launch angle, spray angle, backspin and sidespin of a lab velocity `v` and spin vector
/// `spin` (the flight's conventions, `flight::Launch`; the spin about the ball's path, which
/// neither lifts nor drags in the calculator, is left out).
pub fn launch_of(v: Vec3, spin: Vec3) -> (f64, f64, f64, f64) {
    let launch = v[2].atan2(v[0].hypot(v[1]));
    let spray = v[0].atan2(v[1]);
    let (sl, cl) = launch.sin_cos();
    let (sp, cp) = spray.sin_cos();
    let backspin = dot(spin, [cp, -sp, 0.0]);
    let sidespin = dot(spin, [-sl * sp, -sl * cp, cl]);
    (launch, spray, backspin, sidespin)
}

/// Fill the batted ball of `outcome` (a bat's collision): bat speed, launch, and the flight
/// when `spec.flight` asks for one. Returns the ball's lab speed, signed positive when it
/// goes toward the pitcher's side of the bat's path.
pub fn complete(
    spec: &CollisionSpec,
    lever_arm: f64,
    exit: &BallExit,
    batted: &mut BattedBall,
) -> Result<f64, ModelError> {
    let frame = SwingFrame::new(spec.swing.attack_angle, spec.swing.vertical_angle);
    let v = frame.velocity(spec.swing.cm_speed, exit);
    let lab_speed = dot(v, v).sqrt().copysign(dot(v, frame.path));
    let spin = scaled(frame.spin_axis, exit.spin);
    let (launch_angle, spray_angle, backspin, sidespin) = launch_of(v, spin);
    *batted = BattedBall {
        bat_speed: spec.swing.cm_speed - spec.swing.omega * lever_arm,
        launch_angle,
        spray_angle,
        backspin,
        sidespin,
        ..BattedBall::default()
    };
    if let Some(flight) = &spec.flight {
        fly_batted(spec, flight, v, batted)?;
    }
    Ok(lab_speed)
}

/// Most spin the flight accepts, rad/s (about 9 500 rpm; Nathan's lift and drag were fitted
/// to batted balls of up to about 4 500 rpm).
const FLIGHT_SPIN_LIMIT: f64 = 1000.0;

/// The flight of a ball launched as `batted` says with lab velocity `v`; a ball that goes
/// back past the batter (toward the catcher), or spins beyond what the flight model covers
/// (an extreme pop-up), has no carry (NaN).
fn fly_batted(
    spec: &CollisionSpec,
    flight: &FlightSpec,
    v: Vec3,
    batted: &mut BattedBall,
) -> Result<(), ModelError> {
    let spin = batted.backspin.hypot(batted.sidespin);
    if v[1].is_nan() || v[1] <= 0.0 || spin.is_nan() || spin > FLIGHT_SPIN_LIMIT {
        return Ok(());
    }
    let speed = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    let launch = Launch {
        speed_m_s: speed,
        launch_angle_rad: batted.launch_angle,
        spray_angle_rad: batted.spray_angle,
        backspin_rad_s: batted.backspin,
        sidespin_rad_s: batted.sidespin,
        height_m: flight.height,
    };
    let (sw, cw) = flight.wind_direction.sin_cos();
    let atmosphere = Atmosphere {
        temperature_k: flight.temperature,
        sea_level_pressure_pa: flight.pressure,
        elevation_m: flight.elevation,
        relative_humidity: flight.humidity,
        wind_m_s: [flight.wind_speed * sw, flight.wind_speed * cw, 0.0],
    };
    let ball = BallContact::of(&spec.ball);
    let options = FlightOptions {
        ball: BallProperties {
            mass_kg: spec.ball.mass,
            circumference_m: std::f64::consts::TAU * ball.radius,
        },
        ..FlightOptions::default()
    };
    let f = fly(launch, &atmosphere, &options).map_err(|e| ModelError::Flight(e.to_string()))?;
    (batted.carry, batted.apex, batted.hang_time) = (f.carry_m, f.apex_m, f.hang_time_s);
    Ok(())
}
