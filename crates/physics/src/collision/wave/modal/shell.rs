//! The barrel's breathing modes in a modal step: stepped exactly, as the beam's modes are,
//! under the contact's normal force (linear over the step), beside the beam.

use super::super::ShellContact;
use super::propagator::damping_rate_each;
use super::setup::ShellStep;
use crate::bat::wall_stress::WallInstant;

/// The shell's coordinates and velocities, the footprint's shape this step (φ of each
/// mode), its displacement at the contact (inward, along the contact normal: the work
/// conjugate of the contact force, the footprint's displacement summed step by step) and
/// what its damping has taken.
#[derive(Debug, Clone, Default)]
pub(super) struct ShellState {
    pub(super) q: Vec<f64>,
    pub(super) qd: Vec<f64>,
    pub(super) phi: Vec<f64>,
    pub(super) r: f64,
    pub(super) damping: f64,
    /// The wall at its largest contact force and at its largest displacement under the
    /// ball (`bat::wall_stress`), with those largest values.
    pub(super) at_force: (f64, WallInstant),
    pub(super) at_deflection: (f64, WallInstant),
}

impl ShellState {
    /// At rest: the wall is round when the ball arrives.
    pub(super) fn at_rest(modes: usize) -> Self {
        let instant = WallInstant {
            q: vec![0.0; modes],
            phi: vec![0.0; modes],
            ..WallInstant::default()
        };
        ShellState {
            q: vec![0.0; modes],
            qd: vec![0.0; modes],
            phi: vec![0.0; modes],
            at_force: (0.0, instant.clone()),
            at_deflection: (0.0, instant),
            ..Self::default()
        }
    }

    /// Energy in the modes (unit modal masses), J.
    pub(super) fn energy(&self, sh: &ShellStep) -> f64 {
        (0..self.q.len())
            .map(|j| 0.5 * (self.qd[j].powi(2) + (sh.omega[j] * self.q[j]).powi(2)))
            .sum()
    }

    /// After a step that ends with contact force `force` at compression `s`: keep the
    /// wall's state if the force or the displacement under the ball (the kept modes' and
    /// the left-out modes' static share) is the largest yet.
    pub(super) fn watch(&mut self, contact: &ShellContact, force: f64, s: f64) {
        let deflection = self.r + contact.residual * force;
        // in place: a new largest value comes at most every step of the loading
        let keep = |(peak, kept): &mut (f64, WallInstant), value: f64, q: &[f64], phi: &[f64]| {
            *peak = value;
            kept.force = force;
            kept.axes = contact.size.axes(s);
            kept.q.clone_from_slice(q);
            kept.phi.clone_from_slice(phi);
        };
        if force > self.at_force.0 {
            keep(&mut self.at_force, force, &self.q, &self.phi);
        }
        if deflection > self.at_deflection.0 {
            keep(&mut self.at_deflection, deflection, &self.q, &self.phi);
        }
    }

    /// The instants kept by [`Self::watch`] (none if the ball never pressed the wall).
    pub(super) fn instants(&self) -> Vec<WallInstant> {
        [&self.at_force, &self.at_deflection]
            .into_iter()
            .filter(|(peak, _)| *peak > 0.0)
            .map(|(_, i)| i.clone())
            .collect()
    }

    /// The footprint for a step that starts at compression `s`.
    pub(super) fn follow(&mut self, contact: &ShellContact, s: f64) {
        contact.phi_at(s, &mut self.phi);
    }
}

/// Where the shell's contact point goes over the step without the end force (free motion
/// and the start force `n0`), and its compliance to the end force (the kept modes' and the
/// left-out modes' static one).
pub(super) fn free(sh: &ShellStep, shell: &ShellState, n0: f64) -> (f64, f64) {
    let st = &sh.st;
    let moved: f64 = (0..shell.q.len())
        .map(|j| {
            let q_free = st.cos[j] * shell.q[j] + st.sin_over_omega[j] * shell.qd[j];
            shell.phi[j] * (q_free - shell.q[j])
        })
        .sum();
    let (g_start, g_end) = sh.compliances(&shell.phi);
    // the left-out modes follow the end force at once
    (shell.r + moved + g_start * n0, g_end + sh.residual)
}

/// The modes' exact update under the normal force (n0 → n1) over the footprint, and their
/// damping's losses over the step (Simpson's rule, the mid-step velocities from an exact
/// half step).
pub(super) fn advance(sh: &ShellStep, shell: &mut ShellState, (n0, n1): (f64, f64)) {
    let rate = |qd: &[f64]| damping_rate_each(&sh.omega, &sh.zeta, qd);
    if let Some(hs) = &sh.half {
        let nm = 0.5 * (n0 + n1);
        let mid: Vec<f64> = (0..shell.q.len())
            .map(|j| {
                let p = shell.phi[j];
                hs.advance(j, (shell.q[j], shell.qd[j]), (p * n0, p * nm)).1
            })
            .collect();
        shell.damping += sh.h / 6.0 * (rate(&shell.qd) + 4.0 * rate(&mid));
    }
    for j in 0..shell.q.len() {
        let p = shell.phi[j];
        let before = shell.q[j];
        (shell.q[j], shell.qd[j]) = sh
            .st
            .advance(j, (shell.q[j], shell.qd[j]), (p * n0, p * n1));
        shell.r += p * (shell.q[j] - before);
    }
    if sh.half.is_some() {
        shell.damping += sh.h / 6.0 * rate(&shell.qd);
    }
}
