//! The baseline integrator: explicit velocity Verlet in physical coordinates, at a step
//! below the highest beam mode's stability limit (the paper's approach).
//!
//! One step: half a kick and a drift ([`State::kick_and_drift`]), the contact and hoop
//! forces at the new positions ([`State::forces`]), the accelerations, the second half
//! kick; then the contact's bookkeeping, the sample and the stop test.

use super::contact::{steps_on_for_history, Contact};
use super::{displacement_points, spec_history, Collision, FinalState};
use crate::bat::motion::grip_vibration_amplitude;
use crate::bat::motion::modal_coordinates;
use crate::bat::PreparedBat;
use crate::collision::history::Recorder;
use crate::collision::history::Sample;
use crate::error::ModelError;
use crate::protocol::KNOB6;

/// Everything that changes from step to step.
struct State {
    /// Node displacements, velocities and accelerations; the stiffness force K·y.
    y: Vec<f64>,
    yd: Vec<f64>,
    acc: Vec<f64>,
    ky: Vec<f64>,
    /// Ball front position, velocity and acceleration (toward the bat).
    w: f64,
    v: f64,
    ball_acc: f64,
    /// Hoop mass position, velocity and acceleration.
    xh: f64,
    vh: f64,
    hoop_acc: f64,
    /// Compression and the contact point now.
    s: f64,
    y_c: f64,
    t: f64,
    steps: usize,
}

impl State {
    /// At first contact: the bat's rigid rotation about its CM seen from the collision's
    /// frame, the ball at its speed, the hoop moving with the contact point.
    fn first_contact(c: &Collision, bat: &PreparedBat) -> Self {
        let n = bat.beam.len();
        State {
            y: vec![0.0; n],
            yd: bat
                .beam
                .z
                .iter()
                .map(|z| c.omega * (z - bat.z_cm) - c.frame_velocity)
                .collect(),
            acc: vec![0.0; n],
            ky: vec![0.0; n],
            w: 0.0,
            v: c.ball_speed,
            ball_acc: 0.0,
            xh: 0.0,
            vh: c.omega * c.lever - c.frame_velocity,
            hoop_acc: 0.0,
            s: 0.0,
            y_c: 0.0,
            t: 0.0,
            steps: 0,
        }
    }

    /// Half a kick with the last accelerations, then a drift of the whole step.
    fn kick_and_drift(&mut self, c: &Collision) {
        let h = c.dt;
        for i in 0..self.y.len() {
            self.yd[i] += 0.5 * h * self.acc[i];
            self.y[i] += h * self.yd[i];
        }
        self.v += 0.5 * h * self.ball_acc;
        self.w += h * self.v;
        if c.hoop.is_some() {
            self.vh += 0.5 * h * self.hoop_acc;
            self.xh += h * self.vh;
        }
    }

    /// The contact force at the new positions, and the force on the bat (the ball's, or the
    /// hoop spring's); sets the compression, the contact point and the ball's (and hoop's)
    /// acceleration.
    fn forces(&mut self, c: &Collision, contact: &Contact) -> (f64, f64) {
        self.y_c = (1.0 - c.a) * self.y[c.k] + c.a * self.y[c.k + 1];
        self.s = if c.hoop.is_some() {
            self.w - self.xh
        } else {
            self.w - self.y_c
        };
        let force = c.law.force(self.s, contact.s_max);
        let on_bat = match c.hoop {
            None => force,
            Some(hp) => {
                let hoop_force = hp.stiffness * (self.xh - self.y_c);
                self.hoop_acc = (force - hoop_force) / hp.mass;
                hoop_force
            }
        };
        self.ball_acc = -force / c.ball_mass;
        (force, on_bat)
    }

    /// The nodes' accelerations: stiffness, plus the force on the bat shared between the
    /// two nodes around the impact point.
    fn accelerate(&mut self, c: &Collision, bat: &PreparedBat, inv_mass: &[f64], on_bat: f64) {
        bat.beam.apply_stiffness(&self.y, &mut self.ky);
        for ((a, ky), inv) in self.acc.iter_mut().zip(&self.ky).zip(inv_mass) {
            *a = -ky * inv;
        }
        self.acc[c.k] += (1.0 - c.a) * on_bat * inv_mass[c.k];
        self.acc[c.k + 1] += c.a * on_bat * inv_mass[c.k + 1];
    }

    /// The second half kick with the new accelerations.
    fn kick(&mut self, c: &Collision) {
        let h = c.dt;
        for i in 0..self.y.len() {
            self.yd[i] += 0.5 * h * self.acc[i];
        }
        self.v += 0.5 * h * self.ball_acc;
        if c.hoop.is_some() {
            self.vh += 0.5 * h * self.hoop_acc;
        }
    }
}

pub(super) fn run_verlet(
    c: &Collision,
    bat: &PreparedBat,
    contact: &mut Contact,
    recorder: &mut Option<Recorder>,
) -> Result<FinalState, ModelError> {
    let h = c.dt;
    let mut state = State::first_contact(c, bat);
    let inv_mass: Vec<f64> = bat.beam.mass.iter().map(|m| 1.0 / m).collect();
    let points = displacement_points(bat, spec_history(recorder));
    if let Some(rec) = recorder.as_mut() {
        let smp = sample(rec, bat, &points, &state.y, (0.0, 0.0, state.v, 0.0));
        rec.push(0.0, smp);
    }
    loop {
        verlet_step(c, bat, &inv_mass, &mut state, contact, recorder, &points);
        if contact.stop_after(state.t, state.steps, h, c.budget, || false)? {
            break;
        }
    }
    let fin = final_state(c, bat, &mut state);
    // the history past the collision's end: the same steps, the contact's bookkeeping on a
    // copy (a point's summary is the same with or without histories, `Contact::stop_after`)
    let mut watch = contact.clone();
    let history_done = |r: &Option<Recorder>| r.as_ref().is_none_or(|r| r.done());
    while steps_on_for_history(history_done(recorder), (state.steps, state.t), h, c.budget)? {
        verlet_step(c, bat, &inv_mass, &mut state, &mut watch, recorder, &points);
    }
    Ok(fin)
}

/// One step, its contact's bookkeeping, and the sample the recorder wants of it.
fn verlet_step(
    c: &Collision,
    bat: &PreparedBat,
    inv_mass: &[f64],
    state: &mut State,
    contact: &mut Contact,
    recorder: &mut Option<Recorder>,
    points: &[(usize, f64, bool)],
) {
    state.kick_and_drift(c);
    let s_prev = state.s;
    let (force, on_bat) = state.forces(c, contact);
    state.accelerate(c, bat, inv_mass, on_bat);
    state.kick(c);
    let t_prev = state.t;
    state.steps += 1;
    state.t = state.steps as f64 * c.dt;
    contact.update(&c.law, t_prev, s_prev, state.t, state.s, force);
    if let Some(rec) = recorder.as_mut().filter(|r| r.wants(state.t, c.dt)) {
        let now = (force, state.s.max(0.0), state.v, state.xh - state.y_c);
        let smp = sample(rec, bat, points, &state.y, now);
        rec.push(state.t, smp);
    }
}

/// The sample of displacements `y` with (force, compression, ball velocity, hoop
/// displacement) `now`. The rigid motion is computed only when asked, as in the modal
/// integrator: it is O(N) per sample.
fn sample(
    rec: &Recorder,
    bat: &PreparedBat,
    points: &[(usize, f64, bool)],
    y: &[f64],
    (force, s, v, hoop_rel): (f64, f64, f64, f64),
) -> Sample {
    let beam = &bat.beam;
    let rigid_translation =
        || beam.mass.iter().zip(y).map(|(m, y)| m * y).sum::<f64>() / beam.total_mass();
    let rigid_rotation = || {
        beam.mass
            .iter()
            .zip(y)
            .zip(&beam.z)
            .map(|((m, y), z)| m * y * (z - bat.z_cm))
            .sum::<f64>()
            / bat.inertia_cm
    };
    let at = |&(k, a, inside): &(usize, f64, bool)| match inside {
        true => (1.0 - a) * y[k] + a * y[k + 1],
        false => f64::NAN,
    };
    Sample {
        force,
        compression: s,
        ball_velocity: v,
        hoop_displacement: hoop_rel,
        rigid_translation: if rec.wants_rigid {
            rigid_translation()
        } else {
            0.0
        },
        rigid_rotation: if rec.wants_rigid {
            rigid_rotation()
        } else {
            0.0
        },
        displacement: if rec.wants_displacement {
            points.iter().map(at).collect()
        } else {
            Vec::new()
        },
        ..Sample::default()
    }
}

/// What the run hands back: the ball's velocity, the bat's energies and momenta.
fn final_state(c: &Collision, bat: &PreparedBat, state: &mut State) -> FinalState {
    let beam = &bat.beam;
    let (y, yd) = (&state.y, &state.yd);
    beam.apply_stiffness(y, &mut state.ky);
    let mut bat_energy = 0.0;
    let (mut momentum, mut angular) = (0.0, 0.0);
    for i in 0..y.len() {
        bat_energy += 0.5 * beam.mass[i] * yd[i] * yd[i] + 0.5 * y[i] * state.ky[i];
        momentum += beam.mass[i] * yd[i];
        angular += beam.mass[i] * (beam.z[i] - bat.z_cm) * yd[i];
    }
    let y_c = (1.0 - c.a) * y[c.k] + c.a * y[c.k + 1];
    let hoop_energy = c.hoop.map_or(0.0, |hp| {
        0.5 * hp.mass * state.vh * state.vh + 0.5 * hp.stiffness * (state.xh - y_c).powi(2)
    });
    // with a (spring) grip: the rotation about the grip point
    let bat_rigid_energy = beam.grip_z.map_or(0.0, |zg| {
        let (mut l, mut i) = (0.0, 0.0);
        for ((m, z), v) in beam.mass.iter().zip(&beam.z).zip(yd) {
            l += m * (z - zg) * v;
            i += m * (z - zg).powi(2);
        }
        0.5 * l * l / i
    });
    FinalState {
        ball_velocity: state.v,
        bat_energy,
        bat_rigid_energy,
        bat_damping: 0.0,
        grip_loss: 0.0,
        bat_momentum: momentum,
        bat_angular_momentum: angular,
        hoop_energy,
        hoop_velocity: if c.hoop.is_some() { state.vh } else { 0.0 },
        grip_amplitude: grip_vibration_amplitude(
            bat,
            &modal_coordinates(bat, y),
            &modal_coordinates(bat, yd),
            KNOB6,
        ),
        steps: state.steps,
        modes: y.len(),
        tangential: None,
        wall: Vec::new(),
    }
}
