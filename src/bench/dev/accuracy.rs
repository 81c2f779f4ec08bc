//! The two integrators on the base case against a converged reference (modal, dt/16, twice
//! the segments).

use crate::bench::cases::base_spec;
use crate::bench::measure::err;
use crate::model::collision::wave::Diagnostics;
use crate::model::outcome::Outcome;
use crate::model::spec::{CollisionSpec, Integrator};
use crate::model::{prepare_bat, simulate_with_diagnostics};
use serde::Serialize;

/// One integrator on the base case.
#[derive(Debug, Clone, Serialize)]
pub struct IntegratorFigures {
    pub exit_speed: f64,
    /// |v / v_ref − 1|.
    pub rel_error: f64,
    pub dt: f64,
    pub steps: usize,
    /// Modes time-stepped (modal) or nodes (Verlet).
    pub modes: usize,
}

#[derive(Debug, Clone, Serialize)]
pub struct IntegratorAccuracy {
    pub reference_exit_speed: f64,
    pub reference_dt: f64,
    pub reference_segments: usize,
    pub modal: IntegratorFigures,
    pub verlet: IntegratorFigures,
}

/// `spec` with plain velocity Verlet (at 0.9 × its stability limit, the default step).
pub fn verlet_spec(spec: &CollisionSpec) -> CollisionSpec {
    let mut v = spec.clone();
    v.numerics.integrator = Integrator::Verlet;
    v
}

fn figures(o: &Outcome, d: &Diagnostics, v_ref: f64) -> IntegratorFigures {
    IntegratorFigures {
        exit_speed: o.exit_speed,
        rel_error: (o.exit_speed / v_ref - 1.0).abs(),
        dt: d.dt,
        steps: d.steps,
        modes: d.modes,
    }
}

/// Both integrators on the base case at z = 0.70 m against the converged reference.
pub fn integrator_accuracy() -> Result<IntegratorAccuracy, String> {
    let spec = base_spec(0.70);
    let bat = prepare_bat(&spec.bat, &spec.numerics).map_err(err("prepare the bat"))?;
    let (mo, md) = simulate_with_diagnostics(&spec, &bat, None).map_err(err("modal"))?;
    let (vo, vd) =
        simulate_with_diagnostics(&verlet_spec(&spec), &bat, None).map_err(err("verlet"))?;
    let mut reference = spec.clone();
    reference.numerics.segments = Some(2 * md.segments);
    reference.numerics.dt = Some(md.dt / 16.0);
    let ref_bat = prepare_bat(&reference.bat, &reference.numerics)
        .map_err(err("prepare the reference bat"))?;
    let (ro, rd) =
        simulate_with_diagnostics(&reference, &ref_bat, None).map_err(err("reference"))?;
    Ok(IntegratorAccuracy {
        reference_exit_speed: ro.exit_speed,
        reference_dt: rd.dt,
        reference_segments: rd.segments,
        modal: figures(&mo, &md, ro.exit_speed),
        verlet: figures(&vo, &vd, ro.exit_speed),
    })
}
