//! The default integrator: the beam advanced exactly in its modal basis under a contact
//! force linear over each step; the end force found implicitly (one scalar equation).

use super::contact::Contact;
use super::project::project;
use super::{displacement_points, spec_history, Collision, FinalState, MIN_MODES};
use crate::model::bat::motion::grip_vibration_amplitude;
use crate::model::bat::PreparedBat;
use crate::model::collision::history::Recorder;
use crate::model::collision::history::Sample;
use crate::model::error::ModelError;
use crate::model::protocol::KNOB6;

/// Per-mode constants of one exact step of length h under a force linear in time.
struct ModalStep {
    /// Free propagator [[cos, sin_over_omega], [minus_omega_sin, a22]] (damped if ζ > 0).
    cos: Vec<f64>,
    sin_over_omega: Vec<f64>,
    minus_omega_sin: Vec<f64>,
    a22: Vec<f64>,
    /// Position and velocity responses to the start/end force, times φ_n(z_impact).
    q_start: Vec<f64>,
    q_end: Vec<f64>,
    v_start: Vec<f64>,
    v_end: Vec<f64>,
}

/// (1 − cos ωh)/ω² and (h − sin(ωh)/ω)/(hω²), with series where ωh is small.
fn ramp_terms(omega: f64, h: f64) -> (f64, f64) {
    let x = omega * h;
    if x < 1e-2 {
        let x2 = x * x;
        (
            h * h * (0.5 - x2 / 24.0 + x2 * x2 / 720.0 - x2 * x2 * x2 / 40320.0),
            h * h * (1.0 / 6.0 - x2 / 120.0 + x2 * x2 / 5040.0 - x2 * x2 * x2 / 362880.0),
        )
    } else {
        (
            (1.0 - x.cos()) / (omega * omega),
            (h - x.sin() / omega) / (h * omega * omega),
        )
    }
}

impl ModalStep {
    /// Exact step of q̈ + 2ζωq̇ + ω²q = φ f(t), f linear over the step; ζ applies to the
    /// flexible modes (ω > 0) only.
    fn new(omega: &[f64], zeta: f64, phi: &[f64], h: f64) -> Self {
        let n = omega.len();
        let mut s = Self {
            cos: Vec::with_capacity(n),
            sin_over_omega: Vec::with_capacity(n),
            minus_omega_sin: Vec::with_capacity(n),
            a22: Vec::with_capacity(n),
            q_start: Vec::with_capacity(n),
            q_end: Vec::with_capacity(n),
            v_start: Vec::with_capacity(n),
            v_end: Vec::with_capacity(n),
        };
        for (&w, &p) in omega.iter().zip(phi) {
            if zeta > 0.0 && w > 0.0 {
                // homogeneous: e^{−ζωt}(cos ω_d t, sin ω_d t); particular solution of the
                // ramp f0 + (f1 − f0) t/h: q_p = f(t)/ω² − 2ζ (f1 − f0)/(h ω³)
                let wd = w * (1.0 - zeta * zeta).sqrt();
                let e = (-zeta * w * h).exp();
                let (sn, cs) = (wd * h).sin_cos();
                let r = zeta * w / wd;
                let (a11, a12, a21, a22) = (
                    e * (cs + r * sn),
                    e * sn / wd,
                    -e * w * w / wd * sn,
                    e * (cs - r * sn),
                );
                let response = |qp0: f64, qph: f64, vp: f64| {
                    (qph - a11 * qp0 - a12 * vp, vp - a21 * qp0 - a22 * vp)
                };
                let c = 2.0 * zeta / (h * w * w * w);
                let (qs, vs) = response(1.0 / (w * w) + c, c, -1.0 / (h * w * w));
                let (qe, ve) = response(-c, 1.0 / (w * w) - c, 1.0 / (h * w * w));
                s.cos.push(a11);
                s.sin_over_omega.push(a12);
                s.minus_omega_sin.push(a21);
                s.a22.push(a22);
                s.q_start.push(qs * p);
                s.q_end.push(qe * p);
                s.v_start.push(vs * p);
                s.v_end.push(ve * p);
                continue;
            }
            let x = w * h;
            let sin_over_omega = if x < 1e-2 {
                let x2 = x * x;
                h * (1.0 - x2 / 6.0 + x2 * x2 / 120.0 - x2 * x2 * x2 / 5040.0)
            } else {
                x.sin() / w
            };
            let (a, b) = ramp_terms(w, h);
            s.cos.push(x.cos());
            s.a22.push(x.cos());
            s.sin_over_omega.push(sin_over_omega);
            s.minus_omega_sin.push(-w * x.sin());
            s.q_start.push((a - b) * p);
            s.q_end.push(b * p);
            s.v_start.push((sin_over_omega - a / h) * p);
            s.v_end.push(a / h * p);
        }
        s
    }
}

pub(super) fn run_modal(
    c: &Collision,
    bat: &PreparedBat,
    contact: &mut Contact,
    recorder: &mut Option<Recorder>,
) -> Result<FinalState, ModelError> {
    let modes = &bat.modes;
    let n_all = modes.omega.len();
    let shapes = &modes.shapes;
    let phi_all: Vec<f64> = (0..n_all)
        .map(|m| (1.0 - c.a) * shapes[(c.k, m)] + c.a * shapes[(c.k + 1, m)])
        .collect();
    // Modes far above the contact's frequency respond quasi-statically: keep them out of the
    // time stepping and add their static compliance at the contact point instead (the
    // mode-acceleration method). Dropping them is exact for the initial state only when they
    // carry none of it: always for a free–free bat (the rigid rotation is two rigid modes).
    let initial_is_rigid = c.omega == 0.0
        || bat.modes.n_rigid == 2
        || (bat.beam.grip_z.is_some() && bat.modes.n_rigid == 1);
    // a grip damper couples the modes (non-proportional damping): step them all
    let grip_damping = bat.grip_damping;
    let n = if initial_is_rigid && grip_damping == 0.0 {
        modes
            .omega
            .partition_point(|&w| w <= c.mode_cutoff)
            .max(MIN_MODES.min(n_all))
    } else {
        n_all
    };
    let static_weight: Vec<f64> = (n..n_all)
        .map(|j| phi_all[j] / modes.omega[j].powi(2))
        .collect();
    let g_static: f64 = static_weight
        .iter()
        .zip(&phi_all[n..])
        .map(|(w, p)| w * p)
        .sum();
    let phi = &phi_all[..n];
    let h = c.dt;
    let zeta = bat.damping_ratio;
    let st = ModalStep::new(&modes.omega[..n], zeta, phi, h);
    // material damping: dissipation rate Σ 2ζω q̇², integrated by Simpson's rule with the
    // mid-step velocities from an exact half step
    let half = (zeta > 0.0).then(|| ModalStep::new(&modes.omega[..n], zeta, phi, 0.5 * h));
    let damping_rate = |qd: &[f64]| -> f64 {
        qd.iter()
            .zip(&modes.omega[..n])
            .map(|(v, w)| 2.0 * zeta * w * v * v)
            .sum()
    };
    let mut bat_damping = 0.0;
    // grip damper: force d = −c v_grip at the grip point, linear over the step like the
    // contact force and solved implicitly with it (d₁ is affine in the bat's end force p₁)
    let grip_psi: Vec<f64> = bat.beam.grip_z.map_or(vec![0.0; n], |zg| {
        let (kg, ag) = bat.beam.interpolation(zg);
        (0..n)
            .map(|j| (1.0 - ag) * shapes[(kg, j)] + ag * shapes[(kg + 1, j)])
            .collect()
    });
    let damper = grip_damping > 0.0;
    let st_g = ModalStep::new(&modes.omega[..n], zeta, &grip_psi, h);
    let half_g = ModalStep::new(&modes.omega[..n], zeta, &grip_psi, 0.5 * h);
    let half_p = ModalStep::new(&modes.omega[..n], zeta, phi, 0.5 * h);
    let dot_n = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    // contact displacement per unit grip force (start/end of the step), grip velocity per
    // unit contact / grip end force
    let c_start = dot_n(phi, &st_g.q_start);
    let c_end = dot_n(phi, &st_g.q_end);
    let b_gp = dot_n(&grip_psi, &st.v_end);
    let b_gg = dot_n(&grip_psi, &st_g.v_end);
    let beta_d = -grip_damping * b_gp / (1.0 + grip_damping * b_gg);
    let mut d_force = 0.0;
    let mut grip_loss = 0.0;
    // contact-point compliance to the start/end force over one step (high modes: static)
    let g_start: f64 = st.q_start.iter().zip(phi).map(|(x, p)| x * p).sum();
    let g_end: f64 = st.q_end.iter().zip(phi).map(|(x, p)| x * p).sum::<f64>() + g_static;

    let mut q = vec![0.0; n];
    // initial rigid rotation about the CM, seen from the collision's frame
    let mut qd: Vec<f64> = bat.angular_weight[..n]
        .iter()
        .zip(&bat.momentum_weight[..n])
        .map(|(l, p)| c.omega * l - c.frame_velocity * p)
        .collect();
    let m = c.ball_mass;
    let (mut w, mut v) = (0.0, c.ball_speed);
    let v_contact0 = c.omega * c.lever - c.frame_velocity;
    let (mut xh, mut vh) = (0.0, v_contact0);
    let (mut force, mut hoop_force) = (0.0, 0.0);
    let mut y_c;
    let mut s = 0.0;
    let mut s_before = 0.0;
    let mut t = 0.0;
    let mut steps = 0usize;

    let points = displacement_points(bat, spec_history(recorder));
    // The mode shapes at the requested z, mode by mode (`shape_by_mode[j * nz + i]`): a
    // sample's displacements are summed over the modes for every z at once (`project`).
    let nz = points.len();
    let mut shape_by_mode = vec![0.0; n * nz];
    for (i, &(k, a, _)) in points.iter().enumerate() {
        for j in 0..n {
            shape_by_mode[j * nz + i] = (1.0 - a) * shapes[(k, j)] + a * shapes[(k + 1, j)];
        }
    }
    // where `Iterator::sum` starts (-0.0 or 0.0, by toolchain): the same bits as a sum
    let sum_start: f64 = std::iter::empty::<f64>().sum();
    // static displacement of the dropped modes at each requested z per unit contact force
    let static_at: Vec<f64> = points
        .iter()
        .map(|&(k, a, _)| {
            (n..n_all)
                .map(|j| {
                    ((1.0 - a) * shapes[(k, j)] + a * shapes[(k + 1, j)]) * static_weight[j - n]
                })
                .sum()
        })
        .collect();
    if let Some(rec) = recorder.as_mut().filter(|r| r.wants_displacement && nz > 0) {
        let inside: Vec<bool> = points.iter().map(|&(_, _, inside)| inside).collect();
        rec.project_with(Box::new(
            move |q: &[f64], p_bat: f64, out: &mut Vec<f64>| {
                let start = out.len();
                out.resize(start + nz, sum_start);
                let y = &mut out[start..];
                project(q, &shape_by_mode, y, sum_start);
                for (yi, (&inside, st)) in y.iter_mut().zip(inside.iter().zip(&static_at)) {
                    *yi = if inside { *yi + st * p_bat } else { f64::NAN };
                }
            },
        ));
    }
    let total_mass = bat.beam.total_mass();
    let sample =
        |q: &[f64], rec: &Recorder, force: f64, p_bat: f64, s: f64, v: f64, hoop_rel: f64| {
            let dot = |x: &[f64]| x.iter().zip(q).map(|(a, b)| a * b).sum::<f64>();
            Sample {
                force,
                compression: s,
                ball_velocity: v,
                hoop_displacement: hoop_rel,
                rigid_translation: if rec.wants_rigid {
                    dot(&bat.momentum_weight) / total_mass
                } else {
                    0.0
                },
                rigid_rotation: if rec.wants_rigid {
                    dot(&bat.angular_weight) / bat.inertia_cm
                } else {
                    0.0
                },
                modal: if rec.wants_displacement && nz > 0 {
                    q[..n.min(q.len())].to_vec()
                } else {
                    Vec::new()
                },
                modal_force: p_bat,
                displacement: Vec::new(),
            }
        };
    if let Some(rec) = recorder.as_mut() {
        let smp = sample(&q, rec, 0.0, 0.0, 0.0, v, 0.0);
        rec.push(0.0, smp);
    }

    let h2 = h * h;
    loop {
        // free propagation of the contact point
        let y_free: f64 = phi
            .iter()
            .zip(&st.cos)
            .zip(&st.sin_over_omega)
            .zip(q.iter().zip(&qd))
            .map(|(((p, c), so), (qj, qdj))| p * (c * qj + so * qdj))
            .sum();
        let p_start = if c.hoop.is_some() { hoop_force } else { force };
        let (y_free, g_end, alpha_d) = if damper {
            let a_g: f64 = (0..n)
                .map(|j| {
                    grip_psi[j]
                        * (st.minus_omega_sin[j] * q[j]
                            + st.a22[j] * qd[j]
                            + st.v_start[j] * p_start
                            + st_g.v_start[j] * d_force)
                })
                .sum();
            let alpha_d = -grip_damping * a_g / (1.0 + grip_damping * b_gg);
            (
                y_free + c_start * d_force + c_end * alpha_d,
                g_end + c_end * beta_d,
                alpha_d,
            )
        } else {
            (y_free, g_end, 0.0)
        };
        let w_free = w + h * v - h2 * force / (3.0 * m);
        let (new_force, new_hoop_force, new_s);
        match c.hoop {
            None => {
                let s0 = w_free - y_free - g_start * force;
                let cc = h2 / (6.0 * m) + g_end;
                let (f1, s1) = c
                    .law
                    .solve_implicit(s0, cc, contact.s_max, 2.0 * s - s_before);
                new_force = f1;
                new_hoop_force = 0.0;
                new_s = s1;
            }
            Some(hoop) => {
                let mh = hoop.mass;
                let x0 = xh + h * vh + h2 * (force - hoop_force) / (3.0 * mh);
                let y0 = y_free + g_start * hoop_force;
                let r = h2 / (6.0 * mh);
                let denom = 1.0 + hoop.stiffness * (r + g_end);
                let (ah, bh) = (
                    hoop.stiffness * (x0 - y0) / denom,
                    hoop.stiffness * r / denom,
                );
                let s0 = w_free - x0 + ah * r;
                let cc = h2 / (6.0 * m) + r * (1.0 - bh);
                let (f1, s1) = c
                    .law
                    .solve_implicit(s0, cc, contact.s_max, 2.0 * s - s_before);
                new_force = f1;
                new_hoop_force = ah + bh * f1;
                new_s = s1;
                let x1 = x0 + (f1 - new_hoop_force) * r;
                vh += h * ((force - hoop_force) + (f1 - new_hoop_force)) / (2.0 * mh);
                xh = x1;
            }
        }
        // the bat is pushed by the ball (no hoop) or by the hoop spring
        let (p0, p1) = if c.hoop.is_some() {
            (hoop_force, new_hoop_force)
        } else {
            (force, new_force)
        };
        if let Some(hs) = &half {
            let pm = 0.5 * (p0 + p1);
            let mid: f64 = (0..n)
                .map(|j| {
                    let vm = hs.minus_omega_sin[j] * q[j]
                        + hs.a22[j] * qd[j]
                        + hs.v_start[j] * p0
                        + hs.v_end[j] * pm;
                    2.0 * zeta * modes.omega[j] * vm * vm
                })
                .sum();
            bat_damping += h / 6.0 * (damping_rate(&qd) + 4.0 * mid);
        }
        let (d0, d1) = (d_force, alpha_d + beta_d * p1);
        if damper {
            // damper power c v² by Simpson's rule (mid-step velocity from an exact half step)
            let (pm, dm) = (0.5 * (p0 + p1), 0.5 * (d0 + d1));
            let vg0 = dot_n(&grip_psi, &qd);
            let vgm: f64 = (0..n)
                .map(|j| {
                    grip_psi[j]
                        * (half_p.minus_omega_sin[j] * q[j]
                            + half_p.a22[j] * qd[j]
                            + half_p.v_start[j] * p0
                            + half_p.v_end[j] * pm
                            + half_g.v_start[j] * d0
                            + half_g.v_end[j] * dm)
                })
                .sum();
            grip_loss += h / 6.0 * grip_damping * (vg0 * vg0 + 4.0 * vgm * vgm);
            if let Some(hs) = &half {
                // material damping's mid-step rate with the grip force included
                let mid_extra: f64 = (0..n)
                    .map(|j| {
                        let base = hs.minus_omega_sin[j] * q[j]
                            + hs.a22[j] * qd[j]
                            + hs.v_start[j] * p0
                            + hs.v_end[j] * pm;
                        let vm = base + half_g.v_start[j] * d0 + half_g.v_end[j] * dm;
                        2.0 * zeta * modes.omega[j] * (vm * vm - base * base)
                    })
                    .sum();
                bat_damping += h / 6.0 * 4.0 * mid_extra;
            }
        }
        for (j, (qj, qdj)) in q.iter_mut().zip(qd.iter_mut()).enumerate().take(n) {
            let (x, xd) = (*qj, *qdj);
            *qj = st.cos[j] * x + st.sin_over_omega[j] * xd + st.q_start[j] * p0 + st.q_end[j] * p1;
            *qdj =
                st.minus_omega_sin[j] * x + st.a22[j] * xd + st.v_start[j] * p0 + st.v_end[j] * p1;
            if damper {
                *qj += st_g.q_start[j] * d0 + st_g.q_end[j] * d1;
                *qdj += st_g.v_start[j] * d0 + st_g.v_end[j] * d1;
            }
        }
        if damper {
            let vg1 = dot_n(&grip_psi, &qd);
            grip_loss += h / 6.0 * grip_damping * vg1 * vg1;
            d_force = d1;
        }
        if half.is_some() {
            bat_damping += h / 6.0 * damping_rate(&qd);
        }
        y_c = y_free + g_start * p0 + g_end * p1;
        w = w_free - h2 * new_force / (6.0 * m);
        v -= h * (force + new_force) / (2.0 * m);
        let s_prev = s;
        s_before = s;
        s = if c.hoop.is_some() { w - xh } else { w - y_c };
        // s from the solve and from the states agree to round-off; use the solve's in-contact
        let s_track = if new_force > 0.0 { new_s } else { s };
        force = new_force;
        hoop_force = new_hoop_force;
        let t_prev = t;
        steps += 1;
        t = steps as f64 * h;
        contact.update(&c.law, t_prev, s_prev, t, s_track, force);
        s = s_track;
        if let Some(rec) = recorder.as_mut().filter(|r| r.wants(t, h)) {
            let p_bat = if c.hoop.is_some() { hoop_force } else { force };
            let smp = sample(&q, rec, force, p_bat, s.max(0.0), v, xh - y_c);
            rec.push(t, smp);
        }
        if contact.stop_after(t, steps, h, c.budget, recorder)? {
            break;
        }
    }
    let mut bat_energy = 0.0;
    for j in 0..n {
        bat_energy += 0.5 * (qd[j] * qd[j] + (modes.omega[j] * q[j]).powi(2));
    }
    // strain energy of the dropped modes under the final contact load (zero once separated)
    let p_final = if c.hoop.is_some() { hoop_force } else { force };
    bat_energy += 0.5 * g_static * p_final * p_final;
    let dot = |x: &[f64]| x.iter().zip(&qd).map(|(a, b)| a * b).sum::<f64>();
    let hoop_energy = c.hoop.map_or(0.0, |hp| {
        0.5 * hp.mass * vh * vh + 0.5 * hp.stiffness * (xh - y_c).powi(2)
    });
    let bat_rigid_energy = qd[..modes.n_rigid].iter().map(|x| 0.5 * x * x).sum();
    Ok(FinalState {
        ball_velocity: v,
        bat_energy,
        bat_rigid_energy,
        bat_damping,
        grip_loss,
        bat_momentum: dot(&bat.momentum_weight),
        bat_angular_momentum: dot(&bat.angular_weight),
        hoop_energy,
        hoop_velocity: if c.hoop.is_some() { vh } else { 0.0 },
        grip_amplitude: grip_vibration_amplitude(bat, &q, &qd, KNOB6),
        steps,
        modes: n,
    })
}
