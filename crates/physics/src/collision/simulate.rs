//! One collision: check the spec, dispatch on the model.

use crate::ball::wall_cor;
use crate::bat::PreparedBat;
use crate::collision::batter::swung;
use crate::collision::launch;
use crate::collision::rigid_model::{rigid_wall, simulate_rigid};
use crate::collision::target::Target;
use crate::collision::validate::validate_spec;
use crate::collision::wave::{simulate_wall, simulate_wave, Diagnostics};
use crate::error::ModelError;
use crate::outcome::{HistoryRequest, Outcome};
use crate::protocol::{
    bbcor_from_efficiency, besr_from_efficiency, free_effective_mass, moment_of_inertia_about,
    pivoted_effective_mass,
};
use crate::spec::{CollisionSpec, GripKind, ModelKind};

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
        crate::collision::validate::validate_history(request)?;
    }
    // with a batter, the swing this bat gets
    let swung = swung(spec, bat)?;
    let spec = swung.as_ref();
    if !crate::bat::on_bat(spec.impact.z, bat.length()) {
        return Err(crate::error::out_of_range(
            "impact.z",
            spec.impact.z,
            &format!("[0, {}] m (on the bat)", bat.length()),
        ));
    }
    let (mut outcome, diagnostics) = match spec.model {
        ModelKind::Wave => simulate_wave(spec, bat, history)?,
        ModelKind::Rigid => (simulate_rigid(spec, bat)?, Diagnostics::default()),
    };
    let p = bat.properties();
    let effective_mass = match spec.bat.grip.as_ref() {
        Some(g) if g.kind == GripKind::Pinned => pivoted_effective_mass(
            moment_of_inertia_about(p.mass, p.z_cm, p.moment_of_inertia, g.z),
            g.z,
            spec.impact.z,
        ),
        _ => free_effective_mass(p.mass, p.z_cm, p.moment_of_inertia, spec.impact.z),
    };
    certify(spec, spec.swing.omega == 0.0, effective_mass, &mut outcome);
    let lever_arm = spec.impact.z - p.z_cm;
    let lab_speed = launch::complete_outcome(spec, lever_arm, history, &mut outcome)?;
    // off the bat's path the lab speed is no longer the CM frame's plus the CM's
    if outcome.ball_exit.across != 0.0 || spec.pitch.is_some() {
        outcome.exit_speed_lab = lab_speed;
    }
    crate::field::fill(spec, bat, &mut outcome);
    Ok((outcome, diagnostics))
}

/// The protocols' numbers of a collision with a target at rest: BBCOR, BESR, BPF
/// (`protocol`); NaN for a swung bat. `effective_mass`: the target's at the impact point,
/// kg (∞ for the wall).
fn certify(spec: &CollisionSpec, at_rest: bool, effective_mass: f64, o: &mut Outcome) {
    if !at_rest {
        (o.bbcor, o.besr, o.bpf) = (f64::NAN, f64::NAN, f64::NAN);
        return;
    }
    let e_a = o.collision_efficiency;
    o.bbcor = bbcor_from_efficiency(e_a, spec.ball.mass, effective_mass);
    o.besr = besr_from_efficiency(e_a);
    o.bpf = o.bbcor / wall_cor(&spec.ball.law, o.approach_speed);
}

/// Simulate one collision of `spec` with a prepared target: a bat (as [`simulate`]) or the
/// rigid wall, where the wave model's ball bounces off an immovable target and the rigid
/// model gives back e(v)·v.
pub fn simulate_target(
    spec: &CollisionSpec,
    target: &Target,
    history: Option<&HistoryRequest>,
) -> Result<Outcome, ModelError> {
    match target {
        Target::Bat(bat) => simulate(spec, bat, history),
        Target::Wall => {
            validate_spec(spec)?;
            if let Some(request) = history {
                crate::collision::validate::validate_history(request)?;
            }
            let mut outcome = match spec.model {
                ModelKind::Wave => simulate_wall(spec, history)?.0,
                ModelKind::Rigid => rigid_wall(spec),
            };
            // the wall ignores the swing: it is always at rest
            certify(spec, true, f64::INFINITY, &mut outcome);
            Ok(outcome)
        }
    }
}
