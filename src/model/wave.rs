//! Time integration of the wave model: beam + ball (+ optional hoop mode).
//!
//! Two integrators share the set-up and the bookkeeping:
//! - `Modal` (default): the linear beam is advanced exactly in its modal basis (precomputed in
//!   `PreparedBat`) under a contact force that varies linearly over each step; the force at
//!   the end of the step is found implicitly (one scalar equation: compression is affine in
//!   the new force), so the step is set by the contact (µs), not by the highest beam mode.
//!   For the ball (and hoop) this is the linear-acceleration method, stable for
//!   ω_c·dt < 2√3 and second-order accurate.
//! - `Verlet`: plain explicit velocity Verlet in physical coordinates at a step below the
//!   stability limit of the highest beam mode (the paper's approach; the baseline).
//!
//! Sign conventions (PHYSICS.md): y along the incoming ball's velocity; the ball's front
//! surface is at w, the contact point of the bat at y_c; compression s = w − y_c (or
//! w − x_h with a hoop mass at x_h); the ball pushes the bat (or hoop) with +F and is pushed
//! back with −F. Time 0 = first contact (s = 0).

use super::ball::ContactLaw;
use super::bat::PreparedBat;
use super::error::{out_of_range, ModelError};
use super::history::{Recorder, Sample};
use super::outcome::{EnergyPartition, HistoryRequest, Outcome};
use super::spec::{CollisionSpec, Integrator};

/// Time simulated after the last separation to catch a re-contact, s.
pub const COAST_TIME: f64 = 0.5e-3;
/// Upper bound of the simulated time, s.
pub const MAX_TIME: f64 = 20e-3;
/// Default modal step as a fraction of the contact's time scale 1/ω_c (ω_c from the ball's
/// stiffest tangent, plus the hoop): ≈ 3.4 µs for the base case, exit speed within 4e-5 of
/// the converged value.
pub const MODAL_STEP_FRACTION: f64 = 0.02;
/// Largest modal step accepted, as a fraction of 1/ω_c.
pub const MODAL_MAX_STEP_FRACTION: f64 = 0.2;
/// Modes with ω_n above this multiple of the contact's frequency scale are treated
/// quasi-statically by the modal integrator (their dynamic correction is ~(ω_c/ω_n)²).
pub const MODE_CUTOFF_FACTOR: f64 = 50.0;
/// Fewest modes the modal integrator keeps.
const MIN_MODES: usize = 12;
/// Default Verlet step as a fraction of its stability limit.
pub const VERLET_STEP_FRACTION: f64 = 0.9;

/// Conservation checks of one run (for tests and benchmarks), CM frame, about z_cm.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Diagnostics {
    pub momentum_initial: f64,
    pub momentum_final: f64,
    pub angular_momentum_initial: f64,
    pub angular_momentum_final: f64,
    /// Sum of the final energy partition (must equal `energy.initial`).
    pub energy_final: f64,
    pub dt: f64,
    pub steps: usize,
    pub segments: usize,
    /// Modes time-stepped (modal integrator; all segments for Verlet).
    pub modes: usize,
}

/// The hoop mode: mass and spring constant.
#[derive(Debug, Clone, Copy)]
struct Hoop {
    mass: f64,
    stiffness: f64,
}

/// Everything of one collision that both integrators need.
struct Collision {
    law: ContactLaw,
    ball_mass: f64,
    ball_speed: f64,
    omega: f64,
    hoop: Option<Hoop>,
    /// Impact point: node pair k, k+1 and weight a of node k+1; lever arm z − z_cm.
    k: usize,
    a: f64,
    lever: f64,
    dt: f64,
    /// Modes above this angular frequency are treated quasi-statically (modal integrator).
    mode_cutoff: f64,
}

/// The contact's angular frequency scale: the stiffest ball tangent on the ball (and hoop).
fn contact_omega(spec: &CollisionSpec, law: &ContactLaw, approach: f64) -> f64 {
    let kt = law.max_tangent(spec.ball.mass, approach);
    let mut w2 = kt / spec.ball.mass;
    if let Some(h) = &spec.hoop {
        let kh = h.mass * (2.0 * std::f64::consts::PI * h.frequency).powi(2);
        w2 += kt / h.mass + kh / h.mass;
    }
    w2.sqrt()
}

/// Largest step accepted for this collision, s: Verlet's stability limit (beam + contact
/// springs, bounded by λ_max(A + B) ≤ λ_max(A) + λ_max(B)); for the modal integrator a
/// resolution limit well inside its stability limit (see `MODAL_MAX_STEP_FRACTION`).
pub fn stability_limit(spec: &CollisionSpec, bat: &PreparedBat) -> f64 {
    let law = ContactLaw::from_spec(&spec.ball.law);
    let approach = approach_speed(spec, bat);
    let wc = contact_omega(spec, &law, approach.abs());
    match spec.numerics.integrator {
        // The scheme is stable up to ω_c·dt = 2√3 (linear-acceleration method), but steps
        // that coarse silently give wrong exit speeds (10 % off at 1/3 of it): refuse
        // anything coarser than MODAL_MAX_STEP_FRACTION/ω_c (≈ 1 % error in exit speed).
        Integrator::Modal => MODAL_MAX_STEP_FRACTION / wc,
        Integrator::Verlet => {
            // λ_max(A + B) ≤ λ_max(A) + λ_max(B): beam + each spring's mass-weighted bound
            let beam = &bat.beam;
            let (k, a) = beam.interpolation(spec.impact.z);
            let node = (1.0 - a).powi(2) / beam.mass[k] + a * a / beam.mass[k + 1];
            let kt = law.max_tangent(spec.ball.mass, approach.abs());
            let w_beam = bat.modes.omega.last().copied().unwrap_or(0.0);
            let mut w2 = w_beam * w_beam;
            match &spec.hoop {
                None => w2 += kt * (1.0 / spec.ball.mass + node),
                Some(h) => {
                    let kh = h.mass * (2.0 * std::f64::consts::PI * h.frequency).powi(2);
                    w2 += kt * (1.0 / spec.ball.mass + 1.0 / h.mass) + kh * (1.0 / h.mass + node);
                }
            }
            2.0 / w2.sqrt()
        }
    }
}

/// The step used for this collision: the user's (checked) or the default.
pub fn time_step(spec: &CollisionSpec, bat: &PreparedBat) -> Result<f64, ModelError> {
    let limit = stability_limit(spec, bat);
    let name = match spec.numerics.integrator {
        Integrator::Modal => "modal",
        Integrator::Verlet => "verlet",
    };
    match spec.numerics.dt {
        Some(dt) if !(dt > 0.0 && dt.is_finite()) => {
            Err(out_of_range("numerics.dt", dt, "(0, stability limit] s"))
        }
        Some(dt) if dt > limit => Err(ModelError::TimeStepTooLarge {
            dt,
            limit,
            integrator: name,
        }),
        Some(dt) => Ok(dt),
        None => Ok(match spec.numerics.integrator {
            Integrator::Modal => MODAL_STEP_FRACTION / MODAL_MAX_STEP_FRACTION * limit,
            Integrator::Verlet => VERLET_STEP_FRACTION * limit,
        }),
    }
}

/// Relative approach speed at the impact point, m/s.
pub fn approach_speed(spec: &CollisionSpec, bat: &PreparedBat) -> f64 {
    spec.ball.speed - spec.swing.omega * (spec.impact.z - bat.z_cm)
}

/// Contact bookkeeping shared by the integrators.
#[derive(Default)]
struct Contact {
    in_contact: bool,
    separations: usize,
    start: f64,
    first_duration: f64,
    last_separation: f64,
    peak_force: f64,
    max_compression: f64,
    ball_loss: f64,
    recontact: bool,
    s_max: f64,
}

impl Contact {
    fn started() -> Self {
        Self {
            in_contact: true,
            ..Self::default()
        }
    }

    /// After a step from (t0, s0) to (t1, s1) with end force f1.
    fn update(&mut self, law: &ContactLaw, t0: f64, s0: f64, t1: f64, s1: f64, f1: f64) {
        let crossing = || {
            if s0 != s1 {
                t0 + (t1 - t0) * s0 / (s0 - s1)
            } else {
                t1
            }
        };
        if s1 > 0.0 {
            if !self.in_contact {
                self.in_contact = true;
                self.recontact = true;
                self.start = crossing();
            }
            self.s_max = self.s_max.max(s1);
            self.peak_force = self.peak_force.max(f1);
            self.max_compression = self.max_compression.max(s1);
        } else if self.in_contact {
            let t_sep = crossing();
            if self.separations == 0 {
                self.first_duration = t_sep - self.start;
            }
            self.separations += 1;
            self.last_separation = t_sep;
            self.ball_loss += law.loop_loss(self.s_max);
            self.s_max = 0.0;
            self.in_contact = false;
        }
    }

    fn finished(&self, t: f64, recorder: &Option<Recorder>) -> bool {
        !self.in_contact
            && self.separations > 0
            && t >= self.last_separation + COAST_TIME
            && recorder.as_ref().is_none_or(|r| r.done())
    }
}

/// What an integrator hands back at the end.
struct FinalState {
    ball_velocity: f64,
    bat_energy: f64,
    bat_momentum: f64,
    bat_angular_momentum: f64,
    hoop_energy: f64,
    hoop_velocity: f64,
    steps: usize,
    modes: usize,
}

/// Run one wave-model collision.
pub fn simulate_wave(
    spec: &CollisionSpec,
    bat: &PreparedBat,
    history: Option<&HistoryRequest>,
) -> Result<(Outcome, Diagnostics), ModelError> {
    let approach = approach_speed(spec, bat);
    if approach <= 0.0 {
        return Err(ModelError::NoApproach {
            approach_speed: approach,
        });
    }
    let dt = time_step(spec, bat)?;
    let (k, a) = bat.beam.interpolation(spec.impact.z);
    let collision = Collision {
        law: ContactLaw::from_spec(&spec.ball.law),
        ball_mass: spec.ball.mass,
        ball_speed: spec.ball.speed,
        omega: spec.swing.omega,
        hoop: spec.hoop.as_ref().map(|h| Hoop {
            mass: h.mass,
            stiffness: h.mass * (2.0 * std::f64::consts::PI * h.frequency).powi(2),
        }),
        k,
        a,
        lever: spec.impact.z - bat.z_cm,
        dt,
        mode_cutoff: MODE_CUTOFF_FACTOR
            * contact_omega(spec, &ContactLaw::from_spec(&spec.ball.law), approach),
    };
    let mut recorder = history.map(Recorder::new);
    let mut contact = Contact::started();
    let fin = match spec.numerics.integrator {
        Integrator::Modal => run_modal(&collision, bat, &mut contact, &mut recorder)?,
        Integrator::Verlet => run_verlet(&collision, bat, &mut contact, &mut recorder)?,
    };

    let m = collision.ball_mass;
    let exit_speed = -fin.ball_velocity;
    let bat_rigid = 0.5 * fin.bat_momentum.powi(2) / bat.beam.total_mass()
        + 0.5 * fin.bat_angular_momentum.powi(2) / bat.inertia_cm;
    let hoop_initial_velocity = collision.omega * collision.lever;
    let hoop_mass = collision.hoop.map_or(0.0, |h| h.mass);
    let energy = EnergyPartition {
        initial: 0.5 * m * collision.ball_speed.powi(2)
            + 0.5 * collision.omega.powi(2) * bat.inertia_cm
            + 0.5 * hoop_mass * hoop_initial_velocity.powi(2),
        ball_final: 0.5 * m * fin.ball_velocity.powi(2),
        ball_loss: contact.ball_loss,
        bat_rigid,
        bat_vibration: fin.bat_energy - bat_rigid,
        hoop: fin.hoop_energy,
    };
    let outcome = Outcome {
        exit_speed,
        exit_speed_lab: exit_speed + spec.swing.cm_speed,
        // v_exit = e_A v_pitch + (1 + e_A) v_bat with v_pitch = ball.speed and the bat's
        // impact-point speed toward the pitcher v_bat = −ω l: e_A = (exit + ω l)/approach.
        collision_efficiency: (exit_speed + collision.omega * collision.lever) / approach,
        approach_speed: approach,
        contact_time: contact.first_duration,
        peak_force: contact.peak_force,
        max_compression: contact.max_compression,
        impulse: m * (collision.ball_speed - fin.ball_velocity),
        energy,
        recontact: contact.recontact,
        history: recorder.map(|r| r.finish()),
    };
    let lever = collision.lever;
    let diagnostics = Diagnostics {
        momentum_initial: m * collision.ball_speed + hoop_mass * hoop_initial_velocity,
        momentum_final: m * fin.ball_velocity + fin.bat_momentum + hoop_mass * fin.hoop_velocity,
        angular_momentum_initial: (m * collision.ball_speed + hoop_mass * hoop_initial_velocity)
            * lever
            + collision.omega * bat.inertia_cm,
        angular_momentum_final: (m * fin.ball_velocity + hoop_mass * fin.hoop_velocity) * lever
            + fin.bat_angular_momentum,
        energy_final: energy.ball_final
            + energy.ball_loss
            + energy.bat_rigid
            + energy.bat_vibration
            + energy.hoop,
        dt,
        steps: fin.steps,
        segments: bat.beam.len(),
        modes: fin.modes,
    };
    Ok((outcome, diagnostics))
}

/// Interpolation weights of the requested z (NaN marks points beyond the bat).
fn displacement_points(
    bat: &PreparedBat,
    request: Option<&HistoryRequest>,
) -> Vec<(usize, f64, bool)> {
    request.map_or(Vec::new(), |r| {
        r.z.iter()
            .map(|&z| {
                let (k, a) = bat.beam.interpolation(z);
                (k, a, (0.0..=bat.length()).contains(&z))
            })
            .collect()
    })
}

/// Per-mode constants of one exact step of length h under a force linear in time.
struct ModalStep {
    cos: Vec<f64>,
    sin_over_omega: Vec<f64>,
    minus_omega_sin: Vec<f64>,
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
    fn new(omega: &[f64], phi: &[f64], h: f64) -> Self {
        let n = omega.len();
        let mut s = Self {
            cos: Vec::with_capacity(n),
            sin_over_omega: Vec::with_capacity(n),
            minus_omega_sin: Vec::with_capacity(n),
            q_start: Vec::with_capacity(n),
            q_end: Vec::with_capacity(n),
            v_start: Vec::with_capacity(n),
            v_end: Vec::with_capacity(n),
        };
        for (&w, &p) in omega.iter().zip(phi) {
            let x = w * h;
            let sin_over_omega = if x < 1e-2 {
                let x2 = x * x;
                h * (1.0 - x2 / 6.0 + x2 * x2 / 120.0 - x2 * x2 * x2 / 5040.0)
            } else {
                x.sin() / w
            };
            let (a, b) = ramp_terms(w, h);
            s.cos.push(x.cos());
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

fn run_modal(
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
    let n = if bat.modes.n_rigid == 2 || c.omega == 0.0 {
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
    let st = ModalStep::new(&modes.omega[..n], phi, h);
    // contact-point compliance to the start/end force over one step (high modes: static)
    let g_start: f64 = st.q_start.iter().zip(phi).map(|(x, p)| x * p).sum();
    let g_end: f64 = st.q_end.iter().zip(phi).map(|(x, p)| x * p).sum::<f64>() + g_static;

    let mut q = vec![0.0; n];
    let mut qd: Vec<f64> = bat.angular_weight[..n]
        .iter()
        .map(|l| c.omega * l)
        .collect();
    let m = c.ball_mass;
    let (mut w, mut v) = (0.0, c.ball_speed);
    let v_contact0 = c.omega * c.lever;
    let (mut xh, mut vh) = (0.0, v_contact0);
    let (mut force, mut hoop_force) = (0.0, 0.0);
    let mut y_c;
    let mut s = 0.0;
    let mut s_before = 0.0;
    let mut t = 0.0;
    let mut steps = 0usize;

    let points = displacement_points(bat, spec_history(recorder));
    let shape_at: Vec<Vec<f64>> = points
        .iter()
        .map(|&(k, a, _)| {
            (0..n)
                .map(|j| (1.0 - a) * shapes[(k, j)] + a * shapes[(k + 1, j)])
                .collect()
        })
        .collect();
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
                displacement: if rec.wants_displacement {
                    points
                        .iter()
                        .zip(shape_at.iter().zip(&static_at))
                        .map(|(&(_, _, inside), (psi, st))| {
                            if inside {
                                dot(psi) + st * p_bat
                            } else {
                                f64::NAN
                            }
                        })
                        .collect()
                } else {
                    Vec::new()
                },
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
        for (j, (qj, qdj)) in q.iter_mut().zip(qd.iter_mut()).enumerate().take(n) {
            let (x, xd) = (*qj, *qdj);
            *qj = st.cos[j] * x + st.sin_over_omega[j] * xd + st.q_start[j] * p0 + st.q_end[j] * p1;
            *qdj =
                st.minus_omega_sin[j] * x + st.cos[j] * xd + st.v_start[j] * p0 + st.v_end[j] * p1;
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
        if contact.finished(t, recorder) {
            break;
        }
        if t > MAX_TIME {
            if contact.in_contact {
                return Err(ModelError::NoSeparation { t });
            }
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
    Ok(FinalState {
        ball_velocity: v,
        bat_energy,
        bat_momentum: dot(&bat.momentum_weight),
        bat_angular_momentum: dot(&bat.angular_weight),
        hoop_energy,
        hoop_velocity: if c.hoop.is_some() { vh } else { 0.0 },
        steps,
        modes: n,
    })
}

fn spec_history<'a>(recorder: &'a Option<Recorder>) -> Option<&'a HistoryRequest> {
    recorder.as_ref().map(|r| r.request())
}

fn run_verlet(
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
    let mut yd: Vec<f64> = beam.z.iter().map(|z| c.omega * (z - bat.z_cm)).collect();
    let mut acc = vec![0.0; n];
    let mut ky = vec![0.0; n];
    let (mut w, mut v) = (0.0, c.ball_speed);
    let (mut xh, mut vh) = (0.0, c.omega * c.lever);
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
        rigid_translation: beam.mass.iter().zip(y).map(|(m, y)| m * y).sum::<f64>() / total_mass,
        rigid_rotation: beam
            .mass
            .iter()
            .zip(y)
            .zip(&beam.z)
            .map(|((m, y), z)| m * y * (z - bat.z_cm))
            .sum::<f64>()
            / bat.inertia_cm,
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
        if contact.finished(t, recorder) {
            break;
        }
        if t > MAX_TIME {
            if contact.in_contact {
                return Err(ModelError::NoSeparation { t });
            }
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
    Ok(FinalState {
        ball_velocity: v,
        bat_energy,
        bat_momentum: momentum,
        bat_angular_momentum: angular,
        hoop_energy,
        hoop_velocity: if c.hoop.is_some() { vh } else { 0.0 },
        steps,
        modes: n,
    })
}
