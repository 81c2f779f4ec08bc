//! What one collision keeps fixed while the modal integrator steps: the modes it steps, their
//! step constants, the contact point's compliances and the grip damper's.

use super::super::{Collision, ShellContact, MIN_MODES};
use super::propagator::ModalStep;
use crate::bat::shapes::shape_at;
use crate::bat::PreparedBat;

/// The grip damper (a force −c·v_grip at the grip point), linear over the step like the
/// contact force and solved implicitly with it: its end force is affine in the bat's.
pub(super) struct GripDamper {
    /// Damping coefficient c, N·s/m.
    pub(super) c: f64,
    /// Mode shapes at the grip point.
    pub(super) psi: Vec<f64>,
    /// Steps (full and half) of the modes under the grip force, and a half step under the
    /// bat's end force.
    pub(super) st: ModalStep,
    pub(super) half: ModalStep,
    pub(super) half_p: ModalStep,
    /// Contact displacement per unit grip force at the start and end of the step.
    pub(super) c_start: f64,
    pub(super) c_end: f64,
    /// Grip velocity per unit grip end force, and the end force's slope in the bat's force.
    pub(super) b_gg: f64,
    pub(super) beta: f64,
}

/// The integrator's fixed part.
pub(super) struct Setup<'b> {
    /// Modes stepped in time (the rest respond quasi-statically).
    pub(super) n: usize,
    /// Angular frequencies of the stepped modes, rad/s.
    pub(super) omega: &'b [f64],
    /// Mode shapes of every mode at the contact point.
    pub(super) phi_all: Vec<f64>,
    /// Static compliance of the dropped modes at the contact point, and their weights
    /// φ_j/ω_j² (for the displacement elsewhere).
    pub(super) g_static: f64,
    pub(super) static_weight: Vec<f64>,
    pub(super) h: f64,
    pub(super) zeta: f64,
    pub(super) st: ModalStep,
    /// A half step, for the mid-step velocities of the material damping (ζ > 0).
    pub(super) half: Option<ModalStep>,
    /// Contact-point compliance to the start and end force over one step.
    pub(super) g_start: f64,
    pub(super) g_end: f64,
    pub(super) grip: Option<GripDamper>,
    /// The barrel's breathing modes, stepped beside the beam's.
    pub(super) shell: Option<ShellStep>,
}

/// The shell's modes over one step: their propagators under a unit generalised force (the
/// footprint's shape φ, which follows the contact, is applied at each step).
pub(super) struct ShellStep {
    /// The left-out modes' static compliance at the footprint, m/N (`ShellContact::residual`).
    pub(super) residual: f64,
    pub(super) omega: Vec<f64>,
    pub(super) zeta: Vec<f64>,
    pub(super) h: f64,
    pub(super) st: ModalStep,
    pub(super) half: Option<ModalStep>,
}

impl ShellStep {
    fn new(shell: &ShellContact, h: f64) -> Self {
        let (omega, zeta) = (&shell.omega, &shell.zeta);
        let unit = vec![1.0; omega.len()];
        let st = ModalStep::each(omega, zeta, &unit, h);
        let damped = zeta.iter().any(|&z| z > 0.0);
        let half = damped.then(|| ModalStep::each(omega, zeta, &unit, 0.5 * h));
        ShellStep {
            residual: shell.residual,
            omega: omega.clone(),
            zeta: zeta.clone(),
            h,
            st,
            half,
        }
    }

    /// The footprint's displacement under a start and an end force of one newton over the
    /// step, for the footprint shape `phi`.
    pub(super) fn compliances(&self, phi: &[f64]) -> (f64, f64) {
        let weighted = |r: &[f64]| r.iter().zip(phi).map(|(r, p)| r * p * p).sum::<f64>();
        (weighted(&self.st.q_start), weighted(&self.st.q_end))
    }
}

pub(super) fn dot_n(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>()
}

/// Modes far above the contact's frequency respond quasi-statically: keep them out of the
/// time stepping and add their static compliance at the contact point instead (the
/// mode-acceleration method). Dropping them is exact for the initial state only when they
/// carry none of it: always for a free–free bat (the rigid rotation is two rigid modes). A
/// grip damper couples the modes (non-proportional damping): then all are stepped.
fn stepped_modes(c: &Collision, bat: &PreparedBat) -> usize {
    let modes = &bat.modes;
    let n_all = modes.omega.len();
    let initial_is_rigid =
        c.omega == 0.0 || modes.n_rigid == 2 || (bat.beam.grip_z.is_some() && modes.n_rigid == 1);
    if initial_is_rigid && bat.grip_damping == 0.0 {
        modes
            .omega
            .partition_point(|&w| w <= c.mode_cutoff)
            .max(MIN_MODES.min(n_all))
    } else {
        n_all
    }
}

/// The mode shapes at position z of the beam (between nodes k and k+1).
pub(super) fn shapes_at(
    bat: &PreparedBat,
    k: usize,
    a: f64,
    modes: std::ops::Range<usize>,
) -> Vec<f64> {
    modes.map(|m| shape_at(bat, k, a, m)).collect()
}

impl<'b> Setup<'b> {
    pub(super) fn new(c: &Collision, bat: &'b PreparedBat) -> Self {
        let modes = &bat.modes;
        let n_all = modes.omega.len();
        let phi_all = shapes_at(bat, c.k, c.a, 0..n_all);
        let n = stepped_modes(c, bat);
        let static_weight: Vec<f64> = (n..n_all)
            .map(|j| phi_all[j] / modes.omega[j].powi(2))
            .collect();
        let g_static: f64 = static_weight
            .iter()
            .zip(&phi_all[n..])
            .map(|(w, p)| w * p)
            .sum();
        let (h, zeta, omega) = (c.dt, bat.damping_ratio, &modes.omega[..n]);
        let phi = &phi_all[..n];
        let st = ModalStep::new(omega, zeta, phi, h);
        let half = (zeta > 0.0).then(|| ModalStep::new(omega, zeta, phi, 0.5 * h));
        let g_start: f64 = st.q_start.iter().zip(phi).map(|(x, p)| x * p).sum();
        let g_end: f64 = st.q_end.iter().zip(phi).map(|(x, p)| x * p).sum::<f64>() + g_static;
        let grip = (bat.grip_damping > 0.0).then(|| GripDamper::new(bat, omega, zeta, phi, h, &st));
        Setup {
            n,
            omega,
            phi_all,
            g_static,
            static_weight,
            h,
            zeta,
            st,
            half,
            g_start,
            g_end,
            grip,
            shell: c.shell.as_ref().map(|sh| ShellStep::new(sh, h)),
        }
    }

    /// The mode shapes of the stepped modes at the contact point.
    pub(super) fn phi(&self) -> &[f64] {
        &self.phi_all[..self.n]
    }
}

impl GripDamper {
    fn new(
        bat: &PreparedBat,
        omega: &[f64],
        zeta: f64,
        phi: &[f64],
        h: f64,
        st: &ModalStep,
    ) -> Self {
        let n = omega.len();
        let psi: Vec<f64> = bat.beam.grip_z.map_or(vec![0.0; n], |zg| {
            let (kg, ag) = bat.beam.interpolation(zg);
            shapes_at(bat, kg, ag, 0..n)
        });
        let st_g = ModalStep::new(omega, zeta, &psi, h);
        let c = bat.grip_damping;
        let b_gp = dot_n(&psi, &st.v_end);
        let b_gg = dot_n(&psi, &st_g.v_end);
        GripDamper {
            c,
            c_start: dot_n(phi, &st_g.q_start),
            c_end: dot_n(phi, &st_g.q_end),
            b_gg,
            beta: -c * b_gp / (1.0 + c * b_gg),
            half: ModalStep::new(omega, zeta, &psi, 0.5 * h),
            half_p: ModalStep::new(omega, zeta, phi, 0.5 * h),
            st: st_g,
            psi,
        }
    }
}
