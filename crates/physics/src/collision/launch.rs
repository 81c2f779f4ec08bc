//! The batted ball in the lab: its launch from the collision's plane and the swing's
//! geometry (`frame`), and its flight (docs/physics.md, "Launch" and "Flight").

use crate::collision::frame::{dot, scaled, SwingFrame, Vec3};
use crate::collision::oblique::BallContact;
use crate::error::ModelError;
use crate::flight::{fly, Atmosphere, BallProperties, FlightOptions, Launch};
use crate::outcome::{BallExit, BattedBall, HistoryField, HistoryRequest, Outcome};
use crate::spec::{CollisionSpec, FlightSpec};

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
    trajectory: Option<&mut [Vec<f64>; 3]>,
) -> Result<f64, ModelError> {
    let frame = SwingFrame::of(spec);
    // the pitch's motion along the bat's axis passes through the contact (its friction
    // acts across the bat only)
    let axial = spec.pitch.as_ref().map_or(0.0, |p| frame.pitch(p).axial);
    let v = frame.velocity(spec.swing.cm_speed, (exit.along, exit.across, axial));
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
        let samples = fly_batted(spec, flight, v, batted, trajectory.is_some())?;
        if let Some(out) = trajectory {
            *out = crate::flight::trajectory_on_grid(&samples);
        }
    }
    Ok(lab_speed)
}

/// [`complete`] on a collision's outcome, with the flight's trajectory in its history when
/// `history` asks for it (NaN without a flight, or for a ball that does not fly).
pub fn complete_outcome(
    spec: &CollisionSpec,
    lever_arm: f64,
    history: Option<&HistoryRequest>,
    outcome: &mut Outcome,
) -> Result<f64, ModelError> {
    // the trajectory's room only when it is asked for: most collisions do not store one
    let wants = history.is_some_and(|h| h.fields.contains(&HistoryField::Trajectory));
    let mut trajectory =
        wants.then(|| [(); 3].map(|_| vec![f64::NAN; crate::flight::TRAJECTORY_SAMPLES]));
    let lab_speed = complete(
        spec,
        lever_arm,
        &outcome.ball_exit,
        &mut outcome.batted,
        trajectory.as_mut(),
    )?;
    if let (Some(t), Some(h)) = (trajectory, outcome.history.as_mut()) {
        [h.trajectory_x, h.trajectory_y, h.trajectory_z] = t;
    }
    Ok(lab_speed)
}

/// Most spin the flight accepts, rad/s (about 9 500 rpm; Nathan's lift and drag were fitted
/// to batted balls of up to about 4 500 rpm).
const FLIGHT_SPIN_LIMIT: f64 = 1000.0;

/// The flight of a ball launched as `batted` says with lab velocity `v`, and its recorded
/// states when `record` asks for them; a ball that goes back past the batter (toward the
/// catcher), or spins beyond what the flight model covers (an extreme pop-up), has no carry
/// (NaN) and no states.
fn fly_batted(
    spec: &CollisionSpec,
    flight: &FlightSpec,
    v: Vec3,
    batted: &mut BattedBall,
    record: bool,
) -> Result<Vec<crate::flight::Sample>, ModelError> {
    let spin = batted.backspin.hypot(batted.sidespin);
    if v[1].is_nan() || v[1] <= 0.0 || spin.is_nan() || spin > FLIGHT_SPIN_LIMIT {
        return Ok(Vec::new());
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
        record_trajectory: record,
        ..FlightOptions::default()
    };
    let f = fly(launch, &atmosphere, &options).map_err(|e| ModelError::Flight(e.to_string()))?;
    (batted.carry, batted.apex, batted.hang_time) = (f.carry_m, f.apex_m, f.hang_time_s);
    Ok(f.trajectory)
}
