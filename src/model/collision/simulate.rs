//! One collision: check the spec, dispatch on the model.

use crate::model::ball::wall_cor;
use crate::model::bat::PreparedBat;
use crate::model::collision::rigid::rigid_collision;
use crate::model::collision::target::Target;
use crate::model::collision::validate::validate_spec;
use crate::model::collision::wave::{simulate_wall, simulate_wave, Diagnostics};
use crate::model::error::ModelError;
use crate::model::outcome::EnergyPartition;
use crate::model::outcome::{HistoryRequest, Outcome};
use crate::model::protocol::{
    bbcor_from_efficiency, besr_from_efficiency, free_effective_mass, moment_of_inertia_about,
    pivoted_effective_mass,
};
use crate::model::spec::{CollisionSpec, GripKind, ModelKind};

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
    let (mut outcome, diagnostics) = match spec.model {
        ModelKind::Wave => simulate_wave(spec, bat, history)?,
        ModelKind::Rigid => (simulate_rigid(spec, bat), Diagnostics::default()),
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
                crate::model::collision::validate::validate_history(request)?;
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

/// Brody's model against an immovable wall: the ball comes back at e(v)·v.
fn rigid_wall(spec: &CollisionSpec) -> Outcome {
    let (m, v) = (spec.ball.mass, spec.ball.speed);
    let e = crate::model::ball::cor_at_speed(&spec.ball.law, v);
    Outcome {
        exit_speed: e * v,
        exit_speed_lab: e * v,
        collision_efficiency: e,
        approach_speed: v,
        contact_time: f64::NAN,
        impulse_time_99: f64::NAN,
        peak_force: f64::NAN,
        max_compression: f64::NAN,
        impulse: m * (1.0 + e) * v,
        hoop_frequency: f64::NAN,
        hoop_mass: f64::NAN,
        energy: EnergyPartition {
            initial: 0.5 * m * v * v,
            ball_final: 0.5 * m * (e * v).powi(2),
            ball_loss: 0.5 * m * v * v * (1.0 - e * e),
            ..EnergyPartition::default()
        },
        ..Outcome::default()
    }
}

/// Brody's rigid-body model with e = `ball.law.cor` (its value at the approach speed for
/// `speed_dependent`), on the prepared bat's mass properties.
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
        // The COR at the relative normal speed of ball and bat surface at the impact point.
        crate::model::ball::cor_at_speed(
            &spec.ball.law,
            spec.ball.speed - spec.swing.omega * lever_arm,
        ),
    );
    Outcome {
        exit_speed: r.exit_speed,
        exit_speed_lab: r.exit_speed + spec.swing.cm_speed,
        collision_efficiency: r.collision_efficiency,
        approach_speed: r.approach_speed,
        contact_time: f64::NAN,
        impulse_time_99: f64::NAN,
        peak_force: f64::NAN,
        max_compression: f64::NAN,
        hoop_frequency: f64::NAN,
        hoop_mass: f64::NAN,
        bbcor: f64::NAN,
        besr: f64::NAN,
        bpf: f64::NAN,
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
