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
//! Sign conventions (docs/physics.md): y along the incoming ball's velocity; the ball's front
//! surface is at w, the contact point of the bat at y_c; compression s = w − y_c (or
//! w − x_h with a hoop mass at x_h); the ball pushes the bat (or hoop) with +F and is pushed
//! back with −F. Time 0 = first contact (s = 0).

use super::ball::ContactLaw;
use super::bat::PreparedBat;
use super::error::{out_of_range, ModelError};
use super::history::{Recorder, Sample};
use super::metrics::{grip_recoil_speed, grip_vibration_amplitude, modal_coordinates, KNOB6};
use super::outcome::{EnergyPartition, HistoryRequest, Outcome};
use super::spec::{BeamTheory, CollisionSpec, Integrator};

/// Time simulated after the last separation to catch a re-contact, s.
pub const COAST_TIME: f64 = 0.5e-3;
/// Upper bound of the simulated time, s.
pub const MAX_TIME: f64 = 20e-3;
/// Default step budget of one collision (`numerics.max_steps`): a few seconds of computing
/// for the explicit baseline, thousands of times what a default collision takes.
pub const DEFAULT_MAX_STEPS: u64 = 10_000_000;
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

/// Conservation checks of one run (for tests and benchmarks). Without a grip: bat-CM frame,
/// angular momentum about z_cm. With a grip: the frame of the hands, angular momentum about
/// the grip point (conserved: the grip force has no moment about it), and linear momentum
/// is not conserved (the hands push).
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
pub struct Hoop {
    /// Effective mass, kg.
    pub mass: f64,
    /// Spring constant, N/m.
    pub stiffness: f64,
}

impl Hoop {
    /// Frequency, Hz.
    pub fn frequency(&self) -> f64 {
        (self.stiffness / self.mass).sqrt() / (2.0 * std::f64::consts::PI)
    }
}

/// Circumferential wave number of the hoop mode derived from geometry (ovalling).
pub const HOOP_WAVE_NUMBER: f64 = 2.0;

/// The hoop mode of a collision: given, or derived from the shell at the impact point.
///
/// Geometry (Love/Rayleigh inextensional ring, Graff 1975 §4.x; Soedel, "Vibrations of
/// shells and plates", ring modes): a shell of wall h, mid-surface radius a, in the
/// n-th ovalling mode w = W cos nθ, v = −(W/n) sin nθ, has
/// ω² = Y h² / (12 ρ (1 − ν²) a⁴) · n²(n² − 1)²/(n² + 1) — the free ring per unit length
/// with the plate modulus Y/(1 − ν²). This is also the lowest mode of a cylinder with free
/// ends (Rayleigh's inextensional mode); a held or capped end only raises it. Its kinetic
/// energy ½ ρ h a ℓ Ẇ² π (1 + 1/n²) gives the mass referred to the radial displacement at
/// the impact point, m = (1 + 1/n²) π ρ h a ℓ, over an axial length ℓ (`hoop.length`).
pub fn resolve_hoop(spec: &CollisionSpec, bat: &PreparedBat) -> Result<Option<Hoop>, ModelError> {
    let Some(h) = &spec.hoop else {
        return Ok(None);
    };
    let two_pi = 2.0 * std::f64::consts::PI;
    if !h.from_geometry {
        let (Some(f), Some(m)) = (h.frequency, h.mass) else {
            return Err(ModelError::Unsupported(
                "hoop needs frequency and mass, or from_geometry: true",
            ));
        };
        return Ok(Some(Hoop {
            mass: m,
            stiffness: m * (two_pi * f).powi(2),
        }));
    }
    if h.frequency.is_some() || h.mass.is_some() {
        return Err(ModelError::Unsupported(
            "hoop.from_geometry derives frequency and mass: leave them unset",
        ));
    }
    let g = &bat.geometry;
    let z = spec.impact.z;
    let (outer, inner) = (g.outer_radius(z), g.inner_radius(z));
    let wall = outer - inner;
    if inner <= 0.0 {
        return Err(out_of_range(
            "impact.z",
            z,
            "on the hollow part of the bat (hoop.from_geometry needs a shell there)",
        ));
    }
    let a = outer - 0.5 * wall;
    let nu = g.poisson_ratio;
    let n = HOOP_WAVE_NUMBER;
    let n2 = n * n;
    let omega2 = g.youngs_modulus * wall * wall / (12.0 * g.density * (1.0 - nu * nu) * a.powi(4))
        * n2
        * (n2 - 1.0).powi(2)
        / (n2 + 1.0);
    let length = match h.length {
        Some(l) => l,
        None => default_hoop_length(a, wall, nu),
    };
    let mass = (1.0 + 1.0 / n2) * std::f64::consts::PI * g.density * wall * a * length;
    Ok(Some(Hoop {
        mass,
        stiffness: mass * omega2,
    }))
}

/// Default axial length of the hoop mode, m: twice the decay length of an n = 2 load on a
/// long shell in semi-membrane theory, a (12(1 − ν²))^¼ √(a/h) / (n √(n² − 1)) (an
/// order-of-magnitude estimate; the mass it gives is a modelling choice, stored with the
/// results as `hoop.length` may be swept).
pub fn default_hoop_length(a: f64, wall: f64, nu: f64) -> f64 {
    let n = HOOP_WAVE_NUMBER;
    2.0 * a * (12.0 * (1.0 - nu * nu)).powf(0.25) * (a / wall).sqrt() / (n * (n * n - 1.0).sqrt())
}

/// Everything of one collision that both integrators need.
struct Collision {
    law: ContactLaw,
    ball_mass: f64,
    /// Ball velocity toward the bat in the collision's frame (the hands' with a grip).
    ball_speed: f64,
    omega: f64,
    /// Velocity of the frame (the hands) in the bat-CM frame: ω (z_grip − z_cm), or 0.
    frame_velocity: f64,
    hoop: Option<Hoop>,
    /// Impact point: node pair k, k+1 and weight a of node k+1; lever arm z − z_cm.
    k: usize,
    a: f64,
    lever: f64,
    dt: f64,
    /// Most steps this collision may take.
    budget: u64,
    /// Modes above this angular frequency are treated quasi-statically (modal integrator).
    mode_cutoff: f64,
}

/// The contact's angular frequency scale: the stiffest ball tangent on the ball (and hoop).
fn contact_omega(spec: &CollisionSpec, hoop: Option<Hoop>, law: &ContactLaw, approach: f64) -> f64 {
    let kt = law.max_tangent(spec.ball.mass, approach);
    let mut w2 = kt / spec.ball.mass;
    if let Some(h) = hoop {
        w2 += kt / h.mass + h.stiffness / h.mass;
    }
    w2.sqrt()
}

/// Largest step accepted for this collision, s: Verlet's stability limit (beam + contact
/// springs, bounded by λ_max(A + B) ≤ λ_max(A) + λ_max(B)); for the modal integrator a
/// resolution limit well inside its stability limit (see `MODAL_MAX_STEP_FRACTION`).
pub fn stability_limit(spec: &CollisionSpec, bat: &PreparedBat) -> f64 {
    let law = ContactLaw::from_spec(&spec.ball.law);
    let approach = approach_speed(spec, bat);
    let hoop = resolve_hoop(spec, bat).ok().flatten();
    let wc = contact_omega(spec, hoop, &law, approach.abs());
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
            if bat.beam.pin.is_some() {
                return 0.0; // not supported by Verlet (refused in simulate_wave)
            }
            match hoop {
                None => w2 += kt * (1.0 / spec.ball.mass + node),
                Some(h) => {
                    let kh = h.stiffness;
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

/// The step budget of this collision (`numerics.max_steps`, default `DEFAULT_MAX_STEPS`).
pub fn step_budget(spec: &CollisionSpec) -> u64 {
    spec.numerics.max_steps.unwrap_or(DEFAULT_MAX_STEPS)
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
    /// Energy of the rigid modes (rotation about the grip) with a grip; unused without.
    bat_rigid_energy: f64,
    /// Dissipated by material damping.
    bat_damping: f64,
    /// Dissipated by the grip damper.
    grip_loss: f64,
    bat_momentum: f64,
    bat_angular_momentum: f64,
    hoop_energy: f64,
    hoop_velocity: f64,
    /// Free-vibration amplitude at the grip at the end (`metrics::grip_vibration_amplitude`).
    grip_amplitude: f64,
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
    if spec.numerics.integrator == Integrator::Verlet {
        if bat.beam.pin.is_some() {
            return Err(ModelError::Unsupported(
                "a pinned grip needs the modal integrator",
            ));
        }
        if bat.damping_ratio > 0.0 || bat.grip_damping > 0.0 {
            return Err(ModelError::Unsupported(
                "material damping needs the modal integrator",
            ));
        }
        if spec.bat.beam == BeamTheory::Timoshenko {
            return Err(ModelError::Unsupported(
                "the Timoshenko beam needs the modal integrator",
            ));
        }
    }
    let hoop = resolve_hoop(spec, bat)?;
    let dt = time_step(spec, bat)?;
    // The run lasts at least the re-contact watch after the ball has left.
    let budget = step_budget(spec);
    let least = (COAST_TIME / dt).ceil();
    if least > budget as f64 {
        return Err(ModelError::StepBudget {
            steps: least,
            dt,
            budget,
            cause: "numerics.max_steps",
            provable: true,
        });
    }
    let (k, a) = bat.beam.interpolation(spec.impact.z);
    let frame_velocity = bat
        .beam
        .grip_z
        .map_or(0.0, |zg| spec.swing.omega * (zg - bat.z_cm));
    let collision = Collision {
        law: ContactLaw::from_spec(&spec.ball.law),
        ball_mass: spec.ball.mass,
        ball_speed: spec.ball.speed - frame_velocity,
        omega: spec.swing.omega,
        frame_velocity,
        hoop,
        k,
        a,
        lever: spec.impact.z - bat.z_cm,
        dt,
        budget,
        mode_cutoff: MODE_CUTOFF_FACTOR
            * contact_omega(spec, hoop, &ContactLaw::from_spec(&spec.ball.law), approach),
    };
    let mut recorder = history.map(Recorder::new);
    let mut contact = Contact::started();
    let fin = match spec.numerics.integrator {
        Integrator::Modal => run_modal(&collision, bat, &mut contact, &mut recorder)?,
        Integrator::Verlet => run_verlet(&collision, bat, &mut contact, &mut recorder)?,
    };

    let m = collision.ball_mass;
    let u = collision.frame_velocity;
    // back to the bat-CM frame
    let exit_speed = -(fin.ball_velocity + u);
    let total_mass = bat.beam.total_mass();
    let bat_rigid = if bat.beam.grip_z.is_some() {
        fin.bat_rigid_energy
    } else {
        0.5 * fin.bat_momentum.powi(2) / total_mass
            + 0.5 * fin.bat_angular_momentum.powi(2) / bat.inertia_cm
    };
    let hoop_initial_velocity = collision.omega * collision.lever - u;
    let hoop_mass = collision.hoop.map_or(0.0, |h| h.mass);
    let energy = EnergyPartition {
        initial: 0.5 * m * collision.ball_speed.powi(2)
            + 0.5 * collision.omega.powi(2) * bat.inertia_cm
            + 0.5 * total_mass * u * u
            + 0.5 * hoop_mass * hoop_initial_velocity.powi(2),
        ball_final: 0.5 * m * fin.ball_velocity.powi(2),
        ball_loss: contact.ball_loss,
        bat_rigid,
        bat_vibration: fin.bat_energy - bat_rigid,
        hoop: fin.hoop_energy,
        bat_damping: fin.bat_damping,
        grip_damping: fin.grip_loss,
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
        grip_vibration_amplitude: fin.grip_amplitude,
        grip_recoil_speed: grip_recoil_speed(
            fin.bat_momentum,
            fin.bat_angular_momentum - collision.omega * bat.inertia_cm,
            bat.beam.total_mass(),
            bat.inertia_cm,
            bat.z_cm,
            KNOB6,
        ),
        history: recorder.map(|r| r.finish()),
    };
    // about the grip (with one) or the CM; bat angular momentum about the CM → about centre
    let centre = bat.beam.grip_z.unwrap_or(bat.z_cm);
    let lever = spec.impact.z - centre;
    let shift = bat.z_cm - centre;
    let bat_momentum_initial = -total_mass * u;
    let diagnostics = Diagnostics {
        momentum_initial: m * collision.ball_speed
            + hoop_mass * hoop_initial_velocity
            + bat_momentum_initial,
        momentum_final: m * fin.ball_velocity + fin.bat_momentum + hoop_mass * fin.hoop_velocity,
        angular_momentum_initial: (m * collision.ball_speed + hoop_mass * hoop_initial_velocity)
            * lever
            + collision.omega * bat.inertia_cm
            + shift * bat_momentum_initial,
        angular_momentum_final: (m * fin.ball_velocity + hoop_mass * fin.hoop_velocity) * lever
            + fin.bat_angular_momentum
            + shift * fin.bat_momentum,
        energy_final: energy.ball_final
            + energy.ball_loss
            + energy.bat_rigid
            + energy.bat_vibration
            + energy.hoop
            + energy.bat_damping
            + energy.grip_damping,
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
        if contact.finished(t, recorder) {
            break;
        }
        if t > MAX_TIME {
            if contact.in_contact {
                return Err(ModelError::NoSeparation { t });
            }
            break;
        }
        if steps as u64 >= c.budget {
            return Err(ModelError::StepBudget {
                steps: steps as f64,
                dt: h,
                budget: c.budget,
                cause: "numerics.max_steps",
                provable: false,
            });
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
        if steps as u64 >= c.budget {
            return Err(ModelError::StepBudget {
                steps: steps as f64,
                dt: h,
                budget: c.budget,
                cause: "numerics.max_steps",
                provable: false,
            });
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
