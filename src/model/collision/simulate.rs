//! One collision: check the spec, dispatch on the model.

use crate::model::bat::PreparedBat;
use crate::model::collision::rigid::rigid_collision;
use crate::model::collision::validate::validate_spec;
use crate::model::collision::wave::{simulate_wave, Diagnostics};
use crate::model::error::ModelError;
use crate::model::outcome::EnergyPartition;
use crate::model::outcome::{HistoryRequest, Outcome};
use crate::model::spec::{CollisionSpec, ModelKind};

/// Simulate one collision of `spec` with the prepared `bat` (which must have been prepared
/// from `spec.bat` and `spec.numerics`).
pub fn simulate(
    spec: &CollisionSpec,
    bat: &PreparedBat,
    history: Option<&HistoryRequest>,
) -> Result<Outcome, ModelError> {
    simulate_with_diagnostics(spec, bat, history).map(|(outcome, _)| outcome)
}

/// `simulate`, also returning conservation diagnostics (wave model; zeros for rigid).
pub fn simulate_with_diagnostics(
    spec: &CollisionSpec,
    bat: &PreparedBat,
    history: Option<&HistoryRequest>,
) -> Result<(Outcome, Diagnostics), ModelError> {
    validate_spec(spec)?;
    if let Some(request) = history {
        crate::model::collision::validate::validate_history(request)?;
    }
    if !(spec.impact.z >= 0.0 && spec.impact.z <= bat.length()) {
        return Err(crate::model::error::out_of_range(
            "impact.z",
            spec.impact.z,
            &format!("[0, {}] m (on the bat)", bat.length()),
        ));
    }
    match spec.model {
        ModelKind::Wave => simulate_wave(spec, bat, history),
        ModelKind::Rigid => Ok((simulate_rigid(spec, bat), Diagnostics::default())),
    }
}

/// Brody's rigid-body model with e = `ball.law.cor`, on the prepared bat's mass properties.
/// It has no time scale of its own: contact time, peak force and compression are NaN, the
/// hoop mode is ignored, and the energy lost counts as lost in the ball.
fn simulate_rigid(spec: &CollisionSpec, bat: &PreparedBat) -> Outcome {
    let properties = bat.properties();
    let lever_arm = spec.impact.z - properties.z_cm;
    let r = rigid_collision(
        spec.ball.mass,
        spec.ball.speed,
        properties.mass,
        properties.moment_of_inertia,
        lever_arm,
        spec.swing.omega,
        spec.ball.law.cor,
    );
    Outcome {
        exit_speed: r.exit_speed,
        exit_speed_lab: r.exit_speed + spec.swing.cm_speed,
        collision_efficiency: r.collision_efficiency,
        approach_speed: r.approach_speed,
        contact_time: f64::NAN,
        peak_force: f64::NAN,
        max_compression: f64::NAN,
        impulse: r.impulse,
        energy: EnergyPartition {
            initial: r.energy_initial,
            ball_final: r.energy_ball_final,
            ball_loss: r.energy_lost,
            bat_rigid: r.energy_bat_final,
            bat_vibration: 0.0,
            hoop: 0.0,
            bat_damping: 0.0,
            grip_damping: 0.0,
        },
        recontact: false,
        grip_vibration_amplitude: 0.0,
        grip_recoil_speed: crate::model::bat::motion::grip_recoil_speed(
            r.impulse,
            r.impulse * lever_arm,
            properties.mass,
            properties.moment_of_inertia,
            properties.z_cm,
            crate::model::protocol::KNOB6,
        ),
        history: None,
    }
}
