//! The displacement's modal form (`history.displacement: modal`) describes the
//! same y(z, t) as the grid form computed by the same collision.
//!
//! - The reference is independent of the modal form's code: the grid form, projected while
//!   the collision runs. The reconstruction is the one docs/layout.md gives an h5py user:
//!   y = Σ_j φ_j q_j + s p at the bat's shape points, linear in z between them. Every value
//!   is within one f32 ulp of the grid's, or, where y is zero but for round-off (a pinned
//!   grip's pivot), within 1e-14 of the history's largest |y|: the reference's own round-off.
//! - Every kind of bat the integrator treats apart: free (rigid modes), swung, a pinned grip
//!   (one rigid mode), a spring grip with a damper (every mode stepped), material damping, a
//!   hoop mode (the bat loaded by the hoop spring), Timoshenko (rotations among the degrees of
//!   freedom), a fixed end (no rigid mode), a longer bat.
//! - Closed forms: a free bat's scaled translation mode is 1 everywhere and its coordinate
//!   the recorded rigid translation; its rotation mode is a straight line whose slope times
//!   the coordinate is the recorded rigid rotation; nothing moves at first contact.

use batstudy::model::bat::shapes::{n_modes, scaled_shapes, shape_points};
use batstudy::model::outcome::{History, HistoryDisplacement, HistoryPrecision, HistoryRequest};
use batstudy::model::{prepare_bat, simulate, PreparedBat};
use batstudy::study::{load_str, LoadOptions};
use std::path::Path;

const STUDY: &str = "name: modal_forms
base:
  bat: {preset: r161}
  ball: {speed: 40}
  impact: {z: 0.7}
points:
  name: case
  sets:
    - {}
    - {swing.omega: -40}
    - {bat.grip: {kind: pinned, z: 0.15}}
    - {bat.grip: {kind: spring, z: 0.15, stiffness: 2.0e5, damping: 50}}
    - {bat.material.quality_factor: 30}
    - {bat.preset: aluminum, hoop.frequency: 1250, hoop.mass: 0.03}
    - {bat.beam: timoshenko}
    - {bat.ends.barrel: fixed}
    - {bat.length: 1.10, impact.z: 0.95}
history: {fields: [force, displacement, rigid_motion], interval: 1.0e-5, duration: 2.0e-3,
          z_step: 0.005}
";

/// The cases of `STUDY`: (label, spec, prepared bat).
fn cases() -> Vec<(String, batstudy::model::spec::CollisionSpec, PreparedBat)> {
    let study = load_str(
        STUDY,
        Path::new("modal_forms.yaml"),
        &LoadOptions::default(),
    )
    .unwrap();
    (0..study.plan.n_points())
        .map(|i| {
            let p = study.plan.point(i).unwrap();
            let bat = prepare_bat(&p.spec.bat, &p.spec.numerics).unwrap();
            (study.plan.describe(i), p.spec, bat)
        })
        .collect()
}

fn request(form: HistoryDisplacement) -> HistoryRequest {
    request_in(form, HistoryPrecision::F64)
}

fn request_in(form: HistoryDisplacement, precision: HistoryPrecision) -> HistoryRequest {
    let study = load_str(
        STUDY,
        Path::new("modal_forms.yaml"),
        &LoadOptions::default(),
    )
    .unwrap();
    let mut r = study.history_request(1.10).unwrap();
    r.precision = precision;
    r.displacement = form;
    r
}

/// docs/layout.md's reconstruction: at the shape points y = Σ_j φ_j q_j + s p, then linear
/// in z between them; NaN beyond the bat. (time, z) row-major.
fn reconstruct(bat: &PreparedBat, h: &History, z: &[f64], n_samples: usize) -> Vec<f64> {
    let m = &h.modal;
    let zp = shape_points(bat);
    let phi = scaled_shapes(bat, 0..m.modes);
    let np = zp.len();
    let mut out = Vec::with_capacity(n_samples * z.len());
    for t in 0..n_samples {
        let y: Vec<f64> = (0..np)
            .map(|p| {
                let modal: f64 = (0..m.modes)
                    .map(|j| phi[j * np + p] * m.coordinate[t * m.modes + j])
                    .sum();
                modal + m.static_shape[p] * m.bat_load[t]
            })
            .collect();
        for &zz in z {
            if !(zp[0]..=zp[np - 1]).contains(&zz) {
                out.push(f64::NAN);
                continue;
            }
            let k = zp.partition_point(|&x| x <= zz).clamp(1, np - 1) - 1;
            let a = (zz - zp[k]) / (zp[k + 1] - zp[k]);
            out.push((1.0 - a) * y[k] + a * y[k + 1]);
        }
    }
    out
}

/// The largest |value| of a history, NaN skipped.
fn largest(v: &[f64]) -> f64 {
    v.iter()
        .filter(|x| x.is_finite())
        .fold(0.0, |a, x| a.max(x.abs()))
}

#[test]
fn the_modal_form_reconstructs_the_grid_form() {
    let (grid, modal) = (
        request(HistoryDisplacement::Grid),
        request(HistoryDisplacement::Modal),
    );
    for (label, spec, bat) in cases() {
        let g = simulate(&spec, &bat, Some(&grid)).unwrap().history.unwrap();
        let o = simulate(&spec, &bat, Some(&modal)).unwrap();
        let m = o.history.unwrap();
        assert!(
            m.displacement.is_empty(),
            "{label}: no grid in the modal form"
        );
        assert_eq!(m.modal.coordinate.len(), grid.n_samples * m.modal.modes);
        assert_eq!(m.modal.static_shape.len(), shape_points(&bat).len());
        assert!(m.modal.modes <= n_modes(&bat));
        let y = reconstruct(&bat, &m, &grid.z, grid.n_samples);
        let scale = largest(&g.displacement);
        let (mut worst, mut off_ulp) = (0.0f64, 0);
        for (a, b) in y.iter().zip(&g.displacement) {
            assert_eq!(a.is_nan(), b.is_nan(), "{label}: NaN at different places");
            if b.is_nan() {
                continue;
            }
            worst = worst.max((a - b).abs() / scale);
            // within one f32 ulp of the grid's value; or, where y is zero but for round-off
            // (the pinned point: both forms hold round-off there), within that round-off
            let (a32, b32) = (*a as f32, *b as f32);
            let ulp = f32::from_bits(b32.abs().to_bits() + 1) - b32.abs();
            let round_off = (a - b).abs() <= 1e-14 * scale;
            off_ulp += usize::from((a32 - b32).abs() > ulp && !round_off);
        }
        eprintln!(
            "{label}: {} modes stepped of {}, largest |y| {scale:.2e} m, worst difference {worst:.1e} of it, {off_ulp} f32 values more than one ulp apart",
            m.modal.modes,
            n_modes(&bat)
        );
        assert!(
            worst < 1e-12,
            "{label}: worst difference {worst:e} of the largest |y|"
        );
        assert_eq!(off_ulp, 0, "{label}: values more than one f32 ulp apart");
        // the other series do not depend on the form
        assert_eq!(m.force, g.force, "{label}");
        assert_eq!(m.rigid_translation, g.rigid_translation, "{label}");
    }
}

/// The spacing of f32 values at `y` (> 0).
fn f32_ulp(y: f64) -> f64 {
    let y = y as f32;
    f64::from(f32::from_bits(y.to_bits() + 1) - y)
}

// With `history.precision: f32` the modal form is kept to the precision that gives y to f32
// rounding (`collision::modal_precision`): the bound is analytic (each coordinate within
// half its step, the steps chosen so that the terms' errors add up to at most half an f32
// ulp of the history's largest |y|), and checked here against the grid form in f64, on
// every kind of bat. The coordinates were rounded (some have zero low bits), and a study
// that asks for f64 gets them as computed (the test above).
#[test]
fn at_f32_precision_the_modal_form_is_within_half_an_ulp_of_the_largest() {
    let grid = request_in(HistoryDisplacement::Grid, HistoryPrecision::F32);
    let modal = request_in(HistoryDisplacement::Modal, HistoryPrecision::F32);
    let exact = request(HistoryDisplacement::Modal);
    for (label, spec, bat) in cases() {
        let g = simulate(&spec, &bat, Some(&grid)).unwrap().history.unwrap();
        let m = simulate(&spec, &bat, Some(&modal))
            .unwrap()
            .history
            .unwrap();
        let e = simulate(&spec, &bat, Some(&exact))
            .unwrap()
            .history
            .unwrap();
        let y = reconstruct(&bat, &m, &grid.z, grid.n_samples);
        let scale = largest(&g.displacement);
        let mut worst = 0.0f64;
        for (a, b) in y.iter().zip(&g.displacement) {
            assert_eq!(a.is_nan(), b.is_nan(), "{label}: NaN at different places");
            if !b.is_nan() {
                worst = worst.max((a - b).abs());
            }
        }
        let bound = 0.5 * f32_ulp(scale);
        eprintln!(
            "{label}: worst {:.3} of half an f32 ulp of the largest |y| ({scale:.2e} m)",
            worst / bound
        );
        // the grid's own round-off (1e-14 of the largest, the test above) on top
        assert!(
            worst <= bound + 1e-14 * scale,
            "{label}: {worst:e} > {bound:e}"
        );
        let rounded = m.modal.coordinate.iter().zip(&e.modal.coordinate);
        assert!(
            rounded.clone().any(|(a, b)| a != b),
            "{label}: the coordinates are rounded"
        );
        let low_zero = m
            .modal
            .coordinate
            .iter()
            .filter(|q| q.to_bits() & 0xFFFF == 0);
        assert!(
            low_zero.count() * 2 > m.modal.coordinate.len(),
            "{label}: most coordinates end in 16 zero bits"
        );
    }
}

#[test]
fn a_free_bats_rigid_modes_are_its_rigid_motion() {
    let modal = request(HistoryDisplacement::Modal);
    // the free Euler–Bernoulli bats: at rest, swung, damped
    for (label, spec, bat) in cases()
        .into_iter()
        .take(5)
        .filter(|c| c.1.bat.grip.is_none())
    {
        let h = simulate(&spec, &bat, Some(&modal))
            .unwrap()
            .history
            .unwrap();
        let m = &h.modal;
        let (zp, np) = (shape_points(&bat), shape_points(&bat).len());
        let phi = scaled_shapes(&bat, 0..2);
        // translation: φ √M = 1 everywhere, so q is the centre of mass's translation
        assert!(
            phi[..np].iter().all(|&x| (x - 1.0).abs() < 1e-12),
            "{label}"
        );
        // rotation: a straight line through the centre of mass
        let slope = (phi[2 * np - 1] - phi[np]) / (zp[np - 1] - zp[0]);
        for p in 0..np {
            let line = phi[np] + slope * (zp[p] - zp[0]);
            assert!((phi[np + p] - line).abs() < 1e-12 * slope.abs(), "{label}");
        }
        let (mut t_scale, mut r_scale) = (0.0f64, 0.0f64);
        for t in 0..modal.n_samples {
            t_scale = t_scale.max(h.rigid_translation[t].abs());
            r_scale = r_scale.max(h.rigid_rotation[t].abs());
        }
        for t in 0..modal.n_samples {
            let (q0, q1) = (m.coordinate[t * m.modes], m.coordinate[t * m.modes + 1]);
            assert!(
                (q0 - h.rigid_translation[t]).abs() <= 1e-12 * t_scale,
                "{label}: t {t}: {q0} against {}",
                h.rigid_translation[t]
            );
            assert!(
                (q1 * slope - h.rigid_rotation[t]).abs() <= 1e-12 * r_scale,
                "{label}: t {t}"
            );
        }
        // first contact: nothing has moved
        assert!(m.coordinate[..m.modes].iter().all(|&q| q == 0.0), "{label}");
        assert_eq!(m.bat_load[0], 0.0);
    }
}

#[test]
fn verlet_records_the_grid_form_only() {
    let (label, mut spec, _) = cases().remove(0);
    spec.numerics.integrator = batstudy::model::spec::Integrator::Verlet;
    let bat = prepare_bat(&spec.bat, &spec.numerics).unwrap();
    let e = simulate(&spec, &bat, Some(&request(HistoryDisplacement::Modal))).unwrap_err();
    assert!(e.to_string().contains("modal integrator"), "{label}: {e}");
    assert!(simulate(&spec, &bat, Some(&request(HistoryDisplacement::Grid))).is_ok());
}

// A bat keeps the static shape of each contact point its histories asked for
// (`bat::static_memo`). A history whose shape came from the memo must be the one the
// computation gives on its own: collisions on one bat at contact points that share a node
// pair but not its weight, at ball speeds, swings and masses (a heavy ball, a slower
// contact: fewer modes stepped) in one
// order and then in the reverse (every shape then from the memo), are each bit for bit the
// history of the same collision on a copy of the bat (a copy starts with an empty memo).
#[test]
fn a_bats_kept_static_shapes_are_those_computed_anew() {
    let (_, base, bat) = cases().remove(0);
    let modal = request_in(HistoryDisplacement::Modal, HistoryPrecision::F32);
    let mut specs = Vec::new();
    for z in [0.55, 0.70, 0.7004, 0.7011, 0.80] {
        for (speed, omega, mass) in [(40.0, 0.0, 0.145), (15.0, 0.0, 0.145), (40.0, -45.0, 2.0)] {
            let mut s = base.clone();
            s.impact.z = z;
            s.ball.speed = speed;
            s.swing.omega = omega;
            s.ball.mass = mass;
            specs.push(s);
        }
    }
    let alone = |s: &batstudy::model::spec::CollisionSpec| {
        simulate(s, &bat.clone(), Some(&modal))
            .unwrap()
            .history
            .unwrap()
    };
    let mut modes = std::collections::BTreeSet::new();
    for pass in [specs.clone(), specs.iter().rev().cloned().collect()] {
        for s in &pass {
            let kept = simulate(s, &bat, Some(&modal)).unwrap().history.unwrap();
            let fresh = alone(s);
            modes.insert(kept.modal.modes);
            let at = format!(
                "z {}, speed {}, ω {}",
                s.impact.z, s.ball.speed, s.swing.omega
            );
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(
                bits(&kept.modal.static_shape),
                bits(&fresh.modal.static_shape),
                "{at}"
            );
            assert_eq!(
                bits(&kept.modal.coordinate),
                bits(&fresh.modal.coordinate),
                "{at}"
            );
            assert_eq!(
                bits(&kept.modal.bat_load),
                bits(&fresh.modal.bat_load),
                "{at}"
            );
        }
    }
    eprintln!("modes stepped: {modes:?}");
    assert!(modes.len() > 1, "the cases step different numbers of modes");
}
