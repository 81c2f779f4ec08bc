//! The default integrator: the beam advanced exactly in its modal basis under a contact
//! force linear over each step; the end force found implicitly (one scalar equation).
//!
//! One step, as the functions below take it: the contact point's free motion
//! ([`state::free_contact_point`]), the end forces from the ball's law
//! ([`state::solve_contact`]), the damping losses over the step, the modes' exact update
//! ([`state::advance_modes`]), the ball's update and the contact's bookkeeping
//! ([`ball_and_contact`]), then the sample ([`record`]) and the stop test.

mod coast;
mod propagator;
mod record;
mod setup;
mod shell;
mod state;
pub(super) mod tangential;

use super::contact::Contact;
use super::{displacement_points, spec_history, Collision, FinalState};
use crate::bat::motion::grip_vibration_amplitude;
use crate::bat::PreparedBat;
use crate::collision::history::Recorder;
use crate::collision::oblique::Oblique;
use crate::error::ModelError;
use crate::protocol::KNOB6;
use setup::Setup;
use state::State;
use tangential::{StepInputs, Tangential};

pub(super) fn run_modal(
    c: &Collision,
    bat: &PreparedBat,
    contact: &mut Contact,
    recorder: &mut Option<Recorder>,
) -> Result<FinalState, ModelError> {
    let setup = Setup::new(c, bat);
    let mut state = State::first_contact(c, bat, setup.n);
    let points = displacement_points(bat, spec_history(recorder));
    if let Some(rec) = recorder.as_mut().filter(|r| r.modal_form()) {
        record::install_modal(rec, &setup, bat, (c.k, c.a))?;
    } else if let Some(rec) = recorder
        .as_mut()
        .filter(|r| r.wants_displacement && !points.is_empty())
    {
        record::install_projector(rec, &setup, bat, &points);
    }
    let modal = recorder.as_ref().is_some_and(|r| r.wants_modal);
    if let Some(rec) = recorder.as_mut() {
        record::record_now(rec, c, bat, &state, modal);
    }
    loop {
        step(c, &setup, &mut state, contact);
        if let Some(rec) = recorder.as_mut().filter(|r| r.wants(state.t, setup.h)) {
            record::record_now(rec, c, bat, &state, modal);
        }
        let may_return = || coast::may_return(c, &setup, &state);
        if contact.stop_after(state.t, state.steps, setup.h, c.budget, may_return)? {
            break;
        }
    }
    let fin = final_state(c, bat, &setup, &state);
    if let Some(rec) = recorder.as_mut() {
        coast::coast(c, &setup, bat, (&mut state, contact), rec, modal)?;
    }
    Ok(fin)
}

/// One step of length h.
fn step(c: &Collision, s: &Setup, state: &mut State, contact: &mut Contact) {
    if let Some(o) = &c.oblique {
        release_shear(c, o, state, contact);
    }
    let (y_free, g_end, alpha_d) = state::free_contact_point(c, s, state);
    let h2 = s.h * s.h;
    let w_free = state.w + s.h * state.v - h2 * state.force / (3.0 * c.ball_mass);
    let n0 = state.contact_force();
    if let Some(sh) = &c.shell {
        // the footprint this step loads: the contact's at the step's start
        state.shell.follow(sh, state.s);
    }
    let shell_part = s
        .shell
        .as_ref()
        .map_or((0.0, 0.0), |sh| shell::free(sh, &state.shell, n0));
    let (new_force, new_hoop_force, new_s, oblique_forces) = match &c.oblique {
        Some(o) => {
            let free = (w_free, y_free, g_end);
            oblique_end_forces(c, o, s, state, contact, free, shell_part)
        }
        None => {
            let (y_all, g_all) = (y_free + shell_part.0, g_end + shell_part.1);
            let (f1, fh1, s1) =
                state::solve_contact(c, state, contact, w_free, y_all, s.g_start, g_all);
            (f1, fh1, s1, None)
        }
    };
    if let Some(sh) = &s.shell {
        let n1 = oblique_forces.map_or(new_force, |f| f.0);
        shell::advance(sh, &mut state.shell, (n0, n1));
    }
    // the bat is pushed by the ball (no hoop) or by the hoop spring
    let (p0, p1) = match c.hoop {
        Some(_) => (state.hoop_force, new_hoop_force),
        None => (state.force, new_force),
    };
    state::material_losses_before(s, state, p0, p1);
    let d = match &s.grip {
        Some(g) => (state.d_force, alpha_d + g.beta * p1),
        None => (0.0, 0.0),
    };
    if let Some(g) = &s.grip {
        state::grip_losses_before(s, g, state, (p0, p1), d);
    }
    state::advance_modes(s, state, (p0, p1), d);
    state::losses_after(s, state, d.1);
    let dy_before = state.w - state.y_c;
    state.y_c = y_free + s.g_start * p0 + g_end * p1;
    state.w = w_free - h2 * new_force / (6.0 * c.ball_mass);
    if let (Some(o), Some(forces)) = (&c.oblique, oblique_forces) {
        advance_oblique(c, o, s.h, state, dy_before, forces);
    }
    ball_and_contact(c, s, state, contact, (new_force, new_hoop_force, new_s));
    if let Some(sh) = &c.shell {
        let force = state.contact_force();
        state.shell.watch(sh, force, state.s);
    }
}

/// The patch's stiffness for this step; a shrinking patch lets go of its shear, and the
/// forces at the step's start follow.
fn release_shear(c: &Collision, o: &Oblique, state: &mut State, contact: &Contact) {
    let s_now = state.s;
    let Some(t) = state.tangential.as_mut() else {
        return;
    };
    let k = tangential::patch_stiffness(o, &c.law, s_now, contact.s_max);
    if t.shrink_patch(k) {
        state.force = Tangential::bat_force_y(o, t.normal, t.shear);
        if c.hoop.is_some() {
            state.hoop_force = Tangential::bat_force_y(o, t.bat_normal, t.shear);
        }
    }
}

/// The oblique contact's end forces: (the ball's force along ŷ, the bat's along ŷ, the
/// compression, and (N₁, T₁, the normal force on the bat: N₁, or the hoop spring's)).
type ObliqueEnd = (f64, f64, f64, Option<(f64, f64, f64)>);

fn oblique_end_forces(
    c: &Collision,
    o: &Oblique,
    s: &Setup,
    state: &mut State,
    contact: &Contact,
    (w_free, y_free, g_end): (f64, f64, f64),
    shell_part: (f64, f64),
) -> ObliqueEnd {
    let Some(t) = state.tangential else {
        return (0.0, 0.0, state.s, None);
    };
    let inputs = StepInputs {
        law: &c.law,
        mass: c.ball_mass,
        h: s.h,
        s_max: contact.s_max,
        guess: 2.0 * state.s - state.s_before,
    };
    let dy_now = state.w - state.y_c;
    let y0 = y_free + s.g_start * state.bat_force(c);
    let Some(hoop) = c.hoop else {
        let y_part = (w_free - y0, s.h * s.h / (6.0 * c.ball_mass) + g_end);
        let (n1, t1, s1) = tangential::end_forces(o, &t, &inputs, y_part, dy_now, shell_part);
        let fy = Tangential::bat_force_y(o, n1, t1);
        return (fy, 0.0, s1, Some((n1, t1, n1)));
    };
    let hoop_state = (hoop, state.xh, state.vh);
    let (n1, t1, nh1, s1) =
        tangential::end_forces_hoop(o, &t, &inputs, hoop_state, (w_free, y0, g_end), dy_now);
    let (fy, hy) = (
        Tangential::bat_force_y(o, n1, t1),
        Tangential::bat_force_y(o, nh1, t1),
    );
    (fy, hy, s1, Some((n1, t1, nh1)))
}

/// The oblique contact's states after the step (the hoop mass's too), and what sliding
/// dissipated.
fn advance_oblique(
    c: &Collision,
    o: &Oblique,
    h: f64,
    state: &mut State,
    dy_before: f64,
    (n1, t1, nb1): (f64, f64, f64),
) {
    let dy_after = state.w - state.y_c;
    let Some(t) = state.tangential.as_mut() else {
        return;
    };
    if let Some(hoop) = c.hoop {
        // the hoop mass between the ball's normal force and its spring, along n̂
        let (load0, load1) = (t.normal - t.bat_normal, n1 - nb1);
        state.xh += h * state.vh + h * h * (2.0 * load0 + load1) / (6.0 * hoop.mass);
        state.vh += h * (load0 + load1) / (2.0 * hoop.mass);
    }
    let (u_before, t0) = (t.tangential_displacement(o, dy_before), t.shear);
    tangential::advance(o, t, (c.ball_mass, h), (n1, t1, nb1));
    let slip = t.tangential_displacement(o, dy_after) - u_before;
    t.slip_loss += tangential::slip_loss((t0, t1), slip);
}

/// The ball's velocity, the compression, the forces and the clock after the step, and the
/// contact's bookkeeping (first contact, separation, impulse).
fn ball_and_contact(
    c: &Collision,
    s: &Setup,
    state: &mut State,
    contact: &mut Contact,
    (new_force, new_hoop_force, new_s): (f64, f64, f64),
) {
    state.v -= s.h * (state.force + new_force) / (2.0 * c.ball_mass);
    let s_prev = state.s;
    state.s_before = state.s;
    let s_states = match (c.hoop, &c.oblique, &state.tangential) {
        (Some(_), Some(o), Some(t)) => t.hoop_compression(o, state.w, state.xh),
        (Some(_), _, _) => state.w - state.xh,
        (None, Some(o), Some(t)) => t.compression(o, state.w - state.y_c) - state.shell.r,
        _ => state.w - state.y_c - state.shell.r,
    };
    // s from the solve and from the states agree to round-off; use the solve's in-contact
    let s_track = if new_force > 0.0 { new_s } else { s_states };
    state.force = new_force;
    state.hoop_force = new_hoop_force;
    let t_prev = state.t;
    state.steps += 1;
    state.t = state.steps as f64 * s.h;
    contact.update(
        &c.law,
        t_prev,
        s_prev,
        state.t,
        s_track,
        state.contact_force(),
    );
    state.s = s_track;
}

/// What the run hands back: the ball's velocity, the bat's energies and momenta, the losses.
fn final_state(c: &Collision, bat: &PreparedBat, s: &Setup, state: &State) -> FinalState {
    let (q, qd) = (&state.q, &state.qd);
    let mut bat_energy = 0.0;
    for j in 0..s.n {
        bat_energy += 0.5 * (qd[j] * qd[j] + (s.omega[j] * q[j]).powi(2));
    }
    // strain energy of the dropped modes under the final contact load (zero once separated)
    let p_final = state.bat_force(c);
    bat_energy += 0.5 * s.g_static * p_final * p_final;
    let dot = |x: &[f64]| x.iter().zip(qd).map(|(a, b)| a * b).sum::<f64>();
    let hoop_energy = match (c.hoop, &s.shell) {
        (Some(hp), _) => {
            0.5 * hp.mass * state.vh * state.vh + 0.5 * hp.stiffness * state.hoop_stretch(c).powi(2)
        }
        // with the left-out modes' strain energy under the final load (zero once separated)
        (None, Some(sh)) => {
            state.shell.energy(sh) + 0.5 * sh.residual * state.contact_force().powi(2)
        }
        (None, None) => 0.0,
    };
    let bat_rigid_energy = qd[..bat.modes.n_rigid].iter().map(|x| 0.5 * x * x).sum();
    FinalState {
        ball_velocity: state.v,
        bat_energy,
        bat_rigid_energy,
        bat_damping: state.bat_damping + state.shell.damping,
        grip_loss: state.grip_loss,
        bat_momentum: dot(&bat.momentum_weight),
        bat_angular_momentum: dot(&bat.angular_weight),
        hoop_energy,
        // along ŷ: an oblique contact's hoop mass moves along n̂
        hoop_velocity: match (c.hoop, &c.oblique) {
            (Some(_), Some(o)) => o.cos * state.vh,
            (Some(_), None) => state.vh,
            (None, _) => 0.0,
        },
        grip_amplitude: grip_vibration_amplitude(bat, q, qd, KNOB6),
        steps: state.steps,
        modes: s.n,
        tangential: state.tangential,
        wall: state.shell.instants(),
    }
}
