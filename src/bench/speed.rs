//! Speed and accuracy on one thread: the two integrators on the base case against a converged
//! reference, and a 45-point exit-speed curve with a shared prepared bat.

use super::cases::{base_spec, curve_positions, Sizes};
use super::measure::{err, median, thread_cpu_seconds, time_per_call};
use crate::model::spec::{CollisionSpec, Integrator};
use crate::model::{prepare_bat, simulate, simulate_with_diagnostics, PreparedBat};
use serde::Serialize;
use std::time::Instant;

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
    /// Median wall seconds per collision.
    pub seconds_per_collision: f64,
    pub collisions_per_second: f64,
    /// Median CPU seconds of the thread per collision (insensitive to other load).
    pub cpu_seconds_per_collision: f64,
    pub collisions_per_cpu_second: f64,
}

#[derive(Debug, Clone, Serialize)]
pub struct IntegratorBench {
    pub reference_exit_speed: f64,
    pub reference_dt: f64,
    pub reference_segments: usize,
    pub modal: IntegratorFigures,
    pub verlet: IntegratorFigures,
    /// Median over repeats of (Verlet time / modal time), wall clock and CPU time.
    pub speedup: f64,
    pub speedup_cpu: f64,
    pub repeats: usize,
}

#[derive(Debug, Clone, Serialize)]
pub struct CurveBench {
    pub points: usize,
    /// Median seconds for the whole curve (bat prepared beforehand, shared): wall, CPU.
    pub curve_seconds: f64,
    pub curve_cpu_seconds: f64,
    /// Median seconds of one `prepare_bat`: wall, CPU.
    pub prepare_seconds: f64,
    pub prepare_cpu_seconds: f64,
    pub exit_speed_min: f64,
    pub exit_speed_max: f64,
    pub repeats: usize,
}

/// Integrator speed and accuracy on the base case.
pub(super) fn bench_integrators(sz: &Sizes) -> Result<IntegratorBench, String> {
    let spec = base_spec(0.70);
    let bat = prepare_bat(&spec.bat, &spec.numerics).map_err(err("prepare the bat"))?;
    let mut verlet_spec = spec.clone();
    verlet_spec.numerics.integrator = Integrator::Verlet;
    let (mo, md) = simulate_with_diagnostics(&spec, &bat, None).map_err(err("modal"))?;
    let (vo, vd) = simulate_with_diagnostics(&verlet_spec, &bat, None).map_err(err("verlet"))?;

    // converged reference: modal, dt/16, twice the segments
    let mut reference = spec.clone();
    reference.numerics.segments = Some(2 * md.segments);
    reference.numerics.dt = Some(md.dt / 16.0);
    let ref_bat = prepare_bat(&reference.bat, &reference.numerics)
        .map_err(err("prepare the reference bat"))?;
    let (ro, rd) =
        simulate_with_diagnostics(&reference, &ref_bat, None).map_err(err("reference"))?;
    let v_ref = ro.exit_speed;

    let (mut tm, mut tv, mut ratio) = (Vec::new(), Vec::new(), Vec::new());
    let (mut cm, mut cv, mut cratio) = (Vec::new(), Vec::new(), Vec::new());
    for _ in 0..sz.repeats {
        let (m, mc) = time_per_call(sz.min_time, || {
            std::hint::black_box(simulate(&spec, &bat, None).ok());
        });
        let (v, vc) = time_per_call(sz.min_time, || {
            std::hint::black_box(simulate(&verlet_spec, &bat, None).ok());
        });
        tm.push(m);
        tv.push(v);
        ratio.push(v / m);
        cm.push(mc);
        cv.push(vc);
        cratio.push(vc / mc);
    }
    let figures = |o: &crate::model::outcome::Outcome,
                   d: &crate::model::collision::wave::Diagnostics,
                   t: f64,
                   c: f64| IntegratorFigures {
        exit_speed: o.exit_speed,
        rel_error: (o.exit_speed / v_ref - 1.0).abs(),
        dt: d.dt,
        steps: d.steps,
        modes: d.modes,
        seconds_per_collision: t,
        collisions_per_second: 1.0 / t,
        cpu_seconds_per_collision: c,
        collisions_per_cpu_second: 1.0 / c,
    };
    Ok(IntegratorBench {
        reference_exit_speed: v_ref,
        reference_dt: rd.dt,
        reference_segments: rd.segments,
        modal: figures(&mo, &md, median(tm), median(cm)),
        verlet: figures(&vo, &vd, median(tv), median(cv)),
        speedup: median(ratio),
        speedup_cpu: median(cratio),
        repeats: sz.repeats,
    })
}

/// The 45-point curve with one prepared bat, and `prepare_bat` on its own.
pub(super) fn bench_curve(sz: &Sizes) -> Result<CurveBench, String> {
    let spec = base_spec(0.70);
    let (mut prep, mut prep_cpu) = (Vec::new(), Vec::new());
    let mut bat: Option<PreparedBat> = None;
    for _ in 0..sz.curve_repeats {
        let c0 = thread_cpu_seconds();
        let t0 = Instant::now();
        let b = prepare_bat(&spec.bat, &spec.numerics).map_err(err("prepare the bat"))?;
        prep.push(t0.elapsed().as_secs_f64());
        prep_cpu.push(thread_cpu_seconds() - c0);
        bat = Some(b);
    }
    let bat = bat.ok_or("no repeats")?;
    let zs = curve_positions();
    let specs: Vec<CollisionSpec> = zs.iter().map(|&z| base_spec(z)).collect();
    let (mut times, mut cpu) = (Vec::new(), Vec::new());
    let mut speeds = Vec::new();
    for _ in 0..sz.curve_repeats {
        let c0 = thread_cpu_seconds();
        let t0 = Instant::now();
        speeds = specs
            .iter()
            .map(|s| simulate(s, &bat, None).map(|o| o.exit_speed))
            .collect::<Result<Vec<f64>, _>>()
            .map_err(err("curve"))?;
        times.push(t0.elapsed().as_secs_f64());
        cpu.push(thread_cpu_seconds() - c0);
    }
    Ok(CurveBench {
        points: zs.len(),
        curve_seconds: median(times),
        curve_cpu_seconds: median(cpu),
        prepare_seconds: median(prep),
        prepare_cpu_seconds: median(prep_cpu),
        exit_speed_min: speeds.iter().copied().fold(f64::INFINITY, f64::min),
        exit_speed_max: speeds.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        repeats: sz.curve_repeats,
    })
}
