//! One collision: check the spec, dispatch on the model.

use super::bat::PreparedBat;
use super::error::ModelError;
use super::outcome::{HistoryRequest, Outcome};
use super::spec::{CollisionSpec, ModelKind};
use super::validate::validate_spec;
use super::wave::{simulate_wave, Diagnostics};

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
        super::validate::validate_history(request)?;
    }
    if !(spec.impact.z > 0.0 && spec.impact.z < bat.length()) {
        return Err(super::error::out_of_range(
            "impact.z",
            spec.impact.z,
            &format!("(0, {}) m (the bat's length)", bat.length()),
        ));
    }
    match spec.model {
        ModelKind::Wave => simulate_wave(spec, bat, history),
        // RIGID: wired by the integrator with rigid::rigid_collision (another module).
        ModelKind::Rigid => Err(ModelError::Unsupported("rigid model not wired yet")),
    }
}
