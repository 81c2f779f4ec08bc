//! The baseline integrator: explicit velocity Verlet in physical coordinates, at a step
//! below the highest beam mode's stability limit (the paper's approach).

use super::contact::Contact;
use super::{displacement_points, spec_history, Collision, FinalState};
use crate::model::bat::motion::grip_vibration_amplitude;
use crate::model::bat::motion::modal_coordinates;
use crate::model::bat::PreparedBat;
use crate::model::collision::history::Recorder;
use crate::model::collision::history::Sample;
use crate::model::error::ModelError;
use crate::model::protocol::KNOB6;

pub(super) fn run_verlet(
    c: &Collision,
    bat: &PreparedBat,
    contact: &mut Contact,
    recorder: &mut Option<Recorder>,
) -> Result<FinalState, ModelError> {
    let beam = &bat.beam;
    let n = beam.len();
    let (k, a) = (c.k, c.a);
    let h = c.dt;
    let m = c.ball_mass;
    let mut y = vec![0.0; n];
    let mut yd: Vec<f64> = beam
        .z
        .iter()
        .map(|z| c.omega * (z - bat.z_cm) - c.frame_velocity)
        .collect();
    let mut acc = vec![0.0; n];
    let mut ky = vec![0.0; n];
    let (mut w, mut v) = (0.0, c.ball_speed);
    let (mut xh, mut vh) = (0.0, c.omega * c.lever - c.frame_velocity);
    let (mut force, mut hoop_force);
    let (mut ball_acc, mut hoop_acc) = (0.0, 0.0);
    let mut s = 0.0;
    let mut t = 0.0;
    let mut steps = 0usize;
    let inv_mass: Vec<f64> = beam.mass.iter().map(|m| 1.0 / m).collect();
    let points = displacement_points(bat, spec_history(recorder));
    let total_mass = beam.total_mass();
    let sample = |y: &[f64], rec: &Recorder, force: f64, s: f64, v: f64, hoop_rel: f64| Sample {
        force,
        compression: s,
        ball_velocity: v,
        hoop_displacement: hoop_rel,
        // Only when asked, as in the modal integrator: these are O(N) per sample.
        rigid_translation: if rec.wants_rigid {
            beam.mass.iter().zip(y).map(|(m, y)| m * y).sum::<f64>() / total_mass
        } else {
            0.0
        },
        rigid_rotation: if rec.wants_rigid {
            beam.mass
                .iter()
                .zip(y)
                .zip(&beam.z)
                .map(|((m, y), z)| m * y * (z - bat.z_cm))
                .sum::<f64>()
                / bat.inertia_cm
        } else {
            0.0
        },
        displacement: if rec.wants_displacement {
            points
                .iter()
                .map(|&(kk, aa, inside)| {
                    if inside {
                        (1.0 - aa) * y[kk] + aa * y[kk + 1]
                    } else {
                        f64::NAN
                    }
                })
                .collect()
        } else {
            Vec::new()
        },
        ..Sample::default()
    };
    if let Some(rec) = recorder.as_mut() {
        let smp = sample(&y, rec, 0.0, 0.0, v, 0.0);
        rec.push(0.0, smp);
    }
    loop {
        for i in 0..n {
            yd[i] += 0.5 * h * acc[i];
            y[i] += h * yd[i];
        }
        v += 0.5 * h * ball_acc;
        w += h * v;
        if c.hoop.is_some() {
            vh += 0.5 * h * hoop_acc;
            xh += h * vh;
        }
        let y_c = (1.0 - a) * y[k] + a * y[k + 1];
        let s_prev = s;
        s = if c.hoop.is_some() { w - xh } else { w - y_c };
        force = c.law.force(s, contact.s_max);
        let on_bat = match c.hoop {
            None => force,
            Some(hp) => {
                hoop_force = hp.stiffness * (xh - y_c);
                hoop_acc = (force - hoop_force) / hp.mass;
                hoop_force
            }
        };
        ball_acc = -force / m;
        beam.apply_stiffness(&y, &mut ky);
        for i in 0..n {
            acc[i] = -ky[i] * inv_mass[i];
        }
        acc[k] += (1.0 - a) * on_bat * inv_mass[k];
        acc[k + 1] += a * on_bat * inv_mass[k + 1];
        for i in 0..n {
            yd[i] += 0.5 * h * acc[i];
        }
        v += 0.5 * h * ball_acc;
        if c.hoop.is_some() {
            vh += 0.5 * h * hoop_acc;
        }
        let t_prev = t;
        steps += 1;
        t = steps as f64 * h;
        contact.update(&c.law, t_prev, s_prev, t, s, force);
        if let Some(rec) = recorder.as_mut().filter(|r| r.wants(t, h)) {
            let smp = sample(&y, rec, force, s.max(0.0), v, xh - y_c);
            rec.push(t, smp);
        }
        if contact.stop_after(t, steps, h, c.budget, recorder)? {
            break;
        }
    }
    let _ = hoop_force;
    beam.apply_stiffness(&y, &mut ky);
    let mut bat_energy = 0.0;
    let (mut momentum, mut angular) = (0.0, 0.0);
    for i in 0..n {
        bat_energy += 0.5 * beam.mass[i] * yd[i] * yd[i] + 0.5 * y[i] * ky[i];
        momentum += beam.mass[i] * yd[i];
        angular += beam.mass[i] * (beam.z[i] - bat.z_cm) * yd[i];
    }
    let y_c = (1.0 - a) * y[k] + a * y[k + 1];
    let hoop_energy = c.hoop.map_or(0.0, |hp| {
        0.5 * hp.mass * vh * vh + 0.5 * hp.stiffness * (xh - y_c).powi(2)
    });
    // with a (spring) grip: the rotation about the grip point
    let bat_rigid_energy = beam.grip_z.map_or(0.0, |zg| {
        let (mut l, mut i) = (0.0, 0.0);
        for ((m, z), v) in beam.mass.iter().zip(&beam.z).zip(&yd) {
            l += m * (z - zg) * v;
            i += m * (z - zg).powi(2);
        }
        0.5 * l * l / i
    });
    Ok(FinalState {
        ball_velocity: v,
        bat_energy,
        bat_rigid_energy,
        bat_damping: 0.0,
        grip_loss: 0.0,
        bat_momentum: momentum,
        bat_angular_momentum: angular,
        hoop_energy,
        hoop_velocity: if c.hoop.is_some() { vh } else { 0.0 },
        grip_amplitude: grip_vibration_amplitude(
            bat,
            &modal_coordinates(bat, &y),
            &modal_coordinates(bat, &yd),
            KNOB6,
        ),
        steps,
        modes: n,
    })
}
