//! The state the modal integrator advances, and the parts of one step: the contact point's
//! free motion, the implicit contact (and hoop) force, the damping losses, the modes' exact
//! update and the ball's.

use super::super::contact::Contact;
use super::super::Collision;
use super::propagator::ModalStep;
use super::setup::{dot_n, GripDamper, Setup};
use super::shell::ShellState;
use super::tangential::Tangential;
use crate::bat::PreparedBat;

/// Everything that changes from step to step.
pub(super) struct State {
    /// Modal coordinates and velocities of the stepped modes.
    pub(super) q: Vec<f64>,
    pub(super) qd: Vec<f64>,
    /// Ball front position and velocity (toward the bat).
    pub(super) w: f64,
    pub(super) v: f64,
    /// Hoop mass position and velocity.
    pub(super) xh: f64,
    pub(super) vh: f64,
    /// Contact force (ball on bat or hoop) and hoop spring force at the step's start.
    pub(super) force: f64,
    pub(super) hoop_force: f64,
    /// Compression now and one step before.
    pub(super) s: f64,
    pub(super) s_before: f64,
    /// The bat's contact point.
    pub(super) y_c: f64,
    pub(super) t: f64,
    pub(super) steps: usize,
    /// Grip damper force at the step's start.
    pub(super) d_force: f64,
    /// Energy dissipated by material damping and by the grip damper.
    pub(super) bat_damping: f64,
    pub(super) grip_loss: f64,
    /// The oblique contact's state (`None` head-on without spin).
    pub(super) tangential: Option<Tangential>,
    /// The barrel's breathing modes (empty without them).
    pub(super) shell: ShellState,
}

impl State {
    /// At first contact: the bat's rigid rotation about its CM seen from the collision's
    /// frame, the ball at its speed, the hoop moving with the contact point.
    pub(super) fn first_contact(c: &Collision, bat: &PreparedBat, n: usize) -> Self {
        let qd = bat.angular_weight[..n]
            .iter()
            .zip(&bat.momentum_weight[..n])
            .map(|(l, p)| c.omega * l - c.frame_velocity * p)
            .collect();
        State {
            q: vec![0.0; n],
            qd,
            w: 0.0,
            v: c.ball_speed,
            xh: 0.0,
            // the surface's velocity along the line of centres
            vh: (c.omega * c.lever - c.frame_velocity) * c.oblique.map_or(1.0, |o| o.cos),
            force: 0.0,
            hoop_force: 0.0,
            s: 0.0,
            s_before: 0.0,
            y_c: 0.0,
            t: 0.0,
            steps: 0,
            d_force: 0.0,
            bat_damping: 0.0,
            grip_loss: 0.0,
            tangential: c.oblique.as_ref().map(Tangential::first_contact),
            shell: ShellState::at_rest(c.shell.as_ref().map_or(0, |s| s.omega.len())),
        }
    }

    /// The hoop spring's stretch: the hoop mass's displacement less the bat's surface point's,
    /// along ŷ head-on, along the line of centres n̂ in an oblique contact.
    pub(super) fn hoop_stretch(&self, c: &Collision) -> f64 {
        if let Some(sh) = &c.shell {
            return self.shell.r + sh.residual * self.contact_force();
        }
        match (&c.oblique, &self.tangential) {
            (Some(o), Some(t)) => self.xh - (o.cos * self.y_c + o.sin * t.bat_x),
            _ => self.xh - self.y_c,
        }
    }

    /// The contact force between ball and bat: the normal force of an oblique contact,
    /// else the force along the ball's path.
    pub(super) fn contact_force(&self) -> f64 {
        self.tangential.map_or(self.force, |t| t.normal)
    }

    /// The force on the bat at the step's start: the ball's, or the hoop spring's.
    pub(super) fn bat_force(&self, c: &Collision) -> f64 {
        match c.hoop {
            Some(_) => self.hoop_force,
            None => self.force,
        }
    }
}

/// Where the contact point goes in one step without the step's end forces: its free
/// motion plus the start forces' (and the grip damper's) response; and the compliance to
/// the end force. Returns (y_free, g_end, alpha_d: the grip end force's part that does not
/// depend on the bat's end force).
pub(super) fn free_contact_point(c: &Collision, s: &Setup, state: &State) -> (f64, f64, f64) {
    let st = &s.st;
    let y_free: f64 = s
        .phi()
        .iter()
        .zip(&st.cos)
        .zip(&st.sin_over_omega)
        .zip(state.q.iter().zip(&state.qd))
        .map(|(((p, c), so), (qj, qdj))| p * (c * qj + so * qdj))
        .sum();
    let Some(g) = &s.grip else {
        return (y_free, s.g_end, 0.0);
    };
    let p_start = state.bat_force(c);
    let a_g: f64 = (0..s.n)
        .map(|j| {
            g.psi[j]
                * (st.minus_omega_sin[j] * state.q[j]
                    + st.a22[j] * state.qd[j]
                    + st.v_start[j] * p_start
                    + g.st.v_start[j] * state.d_force)
        })
        .sum();
    let alpha_d = -g.c * a_g / (1.0 + g.c * g.b_gg);
    (
        y_free + g.c_start * state.d_force + g.c_end * alpha_d,
        s.g_end + g.c_end * g.beta,
        alpha_d,
    )
}

/// The step's end forces (contact, hoop spring) and compression, from the ball's law
/// solved implicitly; with a hoop, also moves the hoop mass.
pub(super) fn solve_contact(
    c: &Collision,
    state: &mut State,
    contact: &Contact,
    w_free: f64,
    y_free: f64,
    g_start: f64,
    g_end: f64,
) -> (f64, f64, f64) {
    let (h, m) = (c.dt, c.ball_mass);
    let h2 = h * h;
    let guess = 2.0 * state.s - state.s_before;
    let Some(hoop) = c.hoop else {
        let s0 = w_free - y_free - g_start * state.force;
        let cc = h2 / (6.0 * m) + g_end;
        let (f1, s1) = c.law.solve_implicit(s0, cc, contact.s_max, guess);
        return (f1, 0.0, s1);
    };
    let mh = hoop.mass;
    let (force, hoop_force) = (state.force, state.hoop_force);
    let x0 = state.xh + h * state.vh + h2 * (force - hoop_force) / (3.0 * mh);
    let y0 = y_free + g_start * hoop_force;
    let r = h2 / (6.0 * mh);
    let denom = 1.0 + hoop.stiffness * (r + g_end);
    let (ah, bh) = (
        hoop.stiffness * (x0 - y0) / denom,
        hoop.stiffness * r / denom,
    );
    let s0 = w_free - x0 + ah * r;
    let cc = h2 / (6.0 * m) + r * (1.0 - bh);
    let (f1, s1) = c.law.solve_implicit(s0, cc, contact.s_max, guess);
    let new_hoop_force = ah + bh * f1;
    let x1 = x0 + (f1 - new_hoop_force) * r;
    state.vh += h * ((force - hoop_force) + (f1 - new_hoop_force)) / (2.0 * mh);
    state.xh = x1;
    (f1, new_hoop_force, s1)
}

/// Dissipation rate of material damping, Σ 2ζω q̇².
fn damping_rate(s: &Setup, qd: &[f64]) -> f64 {
    super::propagator::damping_rate(s.omega, s.zeta, qd)
}

/// Material damping's part of the step before the modes move: Simpson's rule over the
/// step, with the mid-step velocities from an exact half step (the end rate is added after
/// the update, [`losses_after`]).
pub(super) fn material_losses_before(s: &Setup, state: &mut State, p0: f64, p1: f64) {
    let Some(hs) = &s.half else { return };
    let pm = 0.5 * (p0 + p1);
    let mid: f64 = (0..s.n)
        .map(|j| {
            let vm = mid_velocity(hs, state, j, p0, pm);
            2.0 * s.zeta * s.omega[j] * vm * vm
        })
        .sum();
    state.bat_damping += s.h / 6.0 * (damping_rate(s, &state.qd) + 4.0 * mid);
}

/// Mode j's velocity after a half step under the bat's start and mid forces.
fn mid_velocity(hs: &ModalStep, state: &State, j: usize, p0: f64, pm: f64) -> f64 {
    hs.advance(j, (state.q[j], state.qd[j]), (p0, pm)).1
}

/// The grip damper's losses before the modes move: its power c·v² by Simpson's rule (the
/// start and mid-step parts), and the grip force's share of material damping at mid-step.
pub(super) fn grip_losses_before(
    s: &Setup,
    g: &GripDamper,
    state: &mut State,
    (p0, p1): (f64, f64),
    (d0, d1): (f64, f64),
) {
    let (pm, dm) = (0.5 * (p0 + p1), 0.5 * (d0 + d1));
    let vg0 = dot_n(&g.psi, &state.qd);
    let vgm: f64 = (0..s.n)
        .map(|j| {
            g.psi[j]
                * (mid_velocity(&g.half_p, state, j, p0, pm)
                    + g.half.v_start[j] * d0
                    + g.half.v_end[j] * dm)
        })
        .sum();
    state.grip_loss += s.h / 6.0 * g.c * (vg0 * vg0 + 4.0 * vgm * vgm);
    if let Some(hs) = &s.half {
        let mid_extra: f64 = (0..s.n)
            .map(|j| {
                let base = mid_velocity(hs, state, j, p0, pm);
                let vm = base + g.half.v_start[j] * d0 + g.half.v_end[j] * dm;
                2.0 * s.zeta * s.omega[j] * (vm * vm - base * base)
            })
            .sum();
        state.bat_damping += s.h / 6.0 * 4.0 * mid_extra;
    }
}

/// The modes' exact update under the bat's start and end forces (and the grip's).
pub(super) fn advance_modes(
    s: &Setup,
    state: &mut State,
    (p0, p1): (f64, f64),
    (d0, d1): (f64, f64),
) {
    let st = &s.st;
    for (j, (qj, qdj)) in state.q.iter_mut().zip(state.qd.iter_mut()).enumerate() {
        (*qj, *qdj) = st.advance(j, (*qj, *qdj), (p0, p1));
        if let Some(g) = &s.grip {
            *qj += g.st.q_start[j] * d0 + g.st.q_end[j] * d1;
            *qdj += g.st.v_start[j] * d0 + g.st.v_end[j] * d1;
        }
    }
}

/// The losses' end terms, after the modes moved (Simpson's last weight).
pub(super) fn losses_after(s: &Setup, state: &mut State, d1: f64) {
    if let Some(g) = &s.grip {
        let vg1 = dot_n(&g.psi, &state.qd);
        state.grip_loss += s.h / 6.0 * g.c * vg1 * vg1;
        state.d_force = d1;
    }
    if s.half.is_some() {
        state.bat_damping += s.h / 6.0 * damping_rate(s, &state.qd);
    }
}
