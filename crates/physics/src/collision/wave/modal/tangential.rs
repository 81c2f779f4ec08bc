//! The oblique contact's part of a modal step (`collision::oblique`): the ball and the bat
//! across the swing plane, their spins, and the end forces (normal N, tangential T) found
//! implicitly with the beam's response along ŷ.
//!
//! Over a step every force varies linearly, so the end displacements are affine in the end
//! forces: the compression s = Δ·n̂ and the contact points' tangential displacement
//! u = Δ·t̂ + r φ_ball + R φ_roll (Δ the ball's centre minus the bat's contact point) are
//! s₁ = S₀ − b_nn N₁ − b_nt T₁ and u₁ = U₀ + b_nt N₁ + b_tt T₁. While the patch grips,
//! T₁ = T₀ − k (u₁ − u₀) (k the patch's stiffness at the step's start) makes T₁ affine in
//! N₁, and the ball's law gives N₁ from one scalar equation, as head-on; if then
//! |T₁| > μ N₁ the ball slides instead, T₁ = ±μ N₁ (a return mapping). The tangential force
//! itself is the patch's state.

use crate::ball::ContactLaw;
use crate::collision::oblique::Oblique;

/// What the oblique contact adds to the modal integrator's state.
#[derive(Debug, Clone, Copy, Default)]
pub(in crate::collision::wave) struct Tangential {
    /// Normal force N and tangential force T on the ball (along −n̂ and t̂) at the step's
    /// start, N.
    pub(in crate::collision::wave) normal: f64,
    pub(in crate::collision::wave) shear: f64,
    /// The normal force on the bat at the step's start, N: the ball's, or with a hoop mode
    /// its spring's.
    pub(in crate::collision::wave) bat_normal: f64,
    /// The ball's centre and the bat's impact point across the swing plane (along x̂):
    /// displacement (m) and velocity (m/s).
    pub(in crate::collision::wave) ball_x: f64,
    pub(in crate::collision::wave) ball_vx: f64,
    pub(in crate::collision::wave) bat_x: f64,
    pub(in crate::collision::wave) bat_vx: f64,
    /// The ball's turn (rad) and spin (rad/s) about b̂; the bat's roll (rad) and roll rate.
    pub(in crate::collision::wave) ball_turn: f64,
    pub(in crate::collision::wave) ball_spin: f64,
    pub(in crate::collision::wave) roll: f64,
    pub(in crate::collision::wave) roll_rate: f64,
    /// Energy the tangential contact has taken so far (sliding, and the shear a shrinking
    /// patch lets go), J.
    pub(in crate::collision::wave) slip_loss: f64,
    /// The patch's tangential stiffness over the last step, N/m.
    pub(in crate::collision::wave) patch_stiffness: f64,
}

impl Tangential {
    /// At first contact: the pitch's motion across the plane, its spin.
    pub(in crate::collision::wave) fn first_contact(o: &Oblique) -> Tangential {
        Tangential {
            ball_vx: o.across_speed,
            ball_spin: o.spin,
            ..Tangential::default()
        }
    }

    /// The force on the bat along ŷ (what bends the beam): N cos θ + T sin θ.
    pub(in crate::collision::wave) fn bat_force_y(o: &Oblique, n: f64, t: f64) -> f64 {
        n * o.cos + t * o.sin
    }

    /// The force on the bat along x̂: N sin θ − T cos θ.
    fn bat_force_x(o: &Oblique, n: f64, t: f64) -> f64 {
        n * o.sin - t * o.cos
    }

    /// The compression now, from the relative displacement along ŷ, `dy` (ball − bat).
    pub(in crate::collision::wave) fn compression(&self, o: &Oblique, dy: f64) -> f64 {
        o.cos * dy + o.sin * (self.ball_x - self.bat_x)
    }

    /// The compression now with a hoop mass at `xh` along n̂: the ball's centre (front at
    /// `w` along ŷ) less the hoop mass, along n̂.
    pub(in crate::collision::wave) fn hoop_compression(&self, o: &Oblique, w: f64, xh: f64) -> f64 {
        o.cos * w + o.sin * self.ball_x - xh
    }

    /// The contact points' tangential displacement now, with `dy` as above.
    pub(in crate::collision::wave) fn tangential_displacement(&self, o: &Oblique, dy: f64) -> f64 {
        -o.sin * dy
            + o.cos * (self.ball_x - self.bat_x)
            + o.ball.radius * self.ball_turn
            + o.bat_radius * self.roll
    }

    /// Take the patch's stiffness for the next step. A shrinking patch lets go of its shear:
    /// when the stiffness falls, the tangential force the patch holds falls in proportion,
    /// its elastic shear displacement kept (the unloading rule of Mindlin's contact, as in
    /// Thornton, Cummins & Cleary 2013 and LAMMPS's `mindlin_rescale/force`). A growing
    /// patch keeps its force and is stiffer only for what comes next. Without the rule a
    /// vanishing patch would still hold its shear, and the ball would be made to slide at
    /// the end of every contact (docs/physics.md, "Oblique impacts and spin"). Returns
    /// whether the force changed.
    pub(in crate::collision::wave) fn shrink_patch(&mut self, stiffness: f64) -> bool {
        let before = self.patch_stiffness;
        self.patch_stiffness = stiffness;
        if stiffness < before && before > 0.0 {
            self.shear *= stiffness / before;
            return true;
        }
        false
    }
}

/// The ball's mass, the step and the law: what every part of the solve shares.
pub(in crate::collision::wave) struct StepInputs<'a> {
    pub(in crate::collision::wave) law: &'a ContactLaw,
    pub(in crate::collision::wave) mass: f64,
    pub(in crate::collision::wave) h: f64,
    pub(in crate::collision::wave) s_max: f64,
    pub(in crate::collision::wave) guess: f64,
}

/// The contact patch's tangential stiffness over this step, N/m: the ball's tangential ratio
/// times the normal law's tangent dN/ds at the compression at the step's start (Mindlin: a
/// patch's tangential stiffness grows with its radius as its normal stiffness does); 0 out
/// of contact.
pub(in crate::collision::wave) fn patch_stiffness(
    o: &Oblique,
    law: &ContactLaw,
    s_now: f64,
    s_max: f64,
) -> f64 {
    if s_now <= 0.0 {
        return 0.0;
    }
    let (_, tangent) = law.force_and_tangent(s_now, s_max.max(s_now));
    o.ball.tangential_ratio * tangent
}

/// The step's end forces (N₁, T₁) and compression s₁. `y_part`: the relative displacement
/// along ŷ at the step's end without the end force, and its compliance to the bat's end
/// force along ŷ (the head-on solve's s₀ and c); `dy_now`: the relative displacement along
/// ŷ now; the shell's part: its contact point's motion along n̂ without the end force, and
/// its compliance to N₁ (zeros without a shell).
pub(in crate::collision::wave) fn end_forces(
    o: &Oblique,
    t: &Tangential,
    inp: &StepInputs,
    (a_y, c_y): (f64, f64),
    dy_now: f64,
    (r_free, g_r): (f64, f64),
) -> (f64, f64, f64) {
    let (c, s) = (o.cos, o.sin);
    let (a_x, c_x) = cross_part(o, t, inp);
    let (u_free, c_rot) = turn_part(o, t, inp.h);
    // the shell's breathing moves the surface along n̂ only, under N
    let s0 = c * a_y + s * a_x - r_free;
    let u0 = -s * a_y + c * a_x + u_free;
    let b_nn = c * c * c_y + s * s * c_x + g_r;
    let b_nt = c * s * (c_y - c_x);
    let b_tt = s * s * c_y + c * c * c_x + c_rot;
    let k = t.patch_stiffness;
    // gripping: T₁ = T₀ − k (u₁ − u_now)
    let den = 1.0 + k * b_tt;
    let alpha = (t.shear - k * (u0 - t.tangential_displacement(o, dy_now))) / den;
    let beta = -k * b_nt / den;
    let (n1, s1) =
        inp.law
            .solve_implicit(s0 - b_nt * alpha, b_nn + b_nt * beta, inp.s_max, inp.guess);
    let t1 = alpha + beta * n1;
    let mu = o.ball.friction;
    if t1.abs() <= mu * n1 {
        return (n1, t1, s1);
    }
    // sliding, against the direction the grip would have pushed
    let sign = t1.signum();
    let (n1, s1) = inp
        .law
        .solve_implicit(s0, b_nn + b_nt * sign * mu, inp.s_max, inp.guess);
    (n1, sign * mu * n1, s1)
}

/// The step's end forces (N₁, T₁, N_h₁) and compression s₁ with a hoop mode: a mass m_h on
/// a spring k_h along n̂ between the ball and the bat's surface (the barrel wall's radial
/// mode, as head-on), pushed by N and pushing the bat with N_h; the tangential force acts on
/// the bat's surface directly. `hoop_state`: the hoop, its mass's displacement and
/// velocity along n̂; `free`: the ball's front along ŷ at the step's end without the end
/// force, the bat's contact point likewise without the bat's end force, and its compliance
/// to that force.
pub(in crate::collision::wave) fn end_forces_hoop(
    o: &Oblique,
    t: &Tangential,
    inp: &StepInputs,
    (hoop, xh, vh): (crate::collision::wave::Hoop, f64, f64),
    (w_free, y0, g): (f64, f64, f64),
    dy_now: f64,
) -> (f64, f64, f64, f64) {
    let (c, s, h) = (o.cos, o.sin, inp.h);
    let h2 = h * h;
    let (a_w, a_x, a_h) = (
        h2 / (6.0 * inp.mass),
        h2 / (6.0 * o.cross_mass),
        h2 / (6.0 * hoop.mass),
    );
    let (xb0, xc0) = cross_free(o, t, inp);
    let xh0 = xh + h * vh + h2 * (t.normal - t.bat_normal) / (3.0 * hoop.mass);
    // the spring: N_h₁ = η₀ + η_N N₁ + η_T T₁
    let k = hoop.stiffness;
    let den = 1.0 + k * (a_h + c * c * g + s * s * a_x);
    let (eta0, eta_n, eta_t) = (
        k * (xh0 - c * y0 - s * xc0) / den,
        k * a_h / den,
        -k * c * s * (g - a_x) / den,
    );
    // s₁ = S − B_nn N₁ − B_nt T₁ and u₁ = U + D_n N₁ + D_t T₁
    let (u_free, c_rot) = turn_part(o, t, h);
    let b_nn = a_w + a_h * (1.0 - eta_n);
    let b_nt = -a_h * eta_t;
    let lever = c * s * (g - a_x);
    let d_n = lever * eta_n;
    let d_t = a_w + s * s * g + c * c * a_x + c_rot + lever * eta_t;
    let s_free = c * w_free + s * xb0 - xh0 + a_h * eta0;
    let u_now = t.tangential_displacement(o, dy_now);
    let u_free = -s * (w_free - y0) + c * (xb0 - xc0) + u_free + lever * eta0 - u_now;
    let kt = t.patch_stiffness;
    let den_t = 1.0 + kt * d_t;
    let (alpha, beta) = ((t.shear - kt * u_free) / den_t, -kt * d_n / den_t);
    let (n1, s1) = inp.law.solve_implicit(
        s_free - b_nt * alpha,
        b_nn + b_nt * beta,
        inp.s_max,
        inp.guess,
    );
    let mut t1 = alpha + beta * n1;
    let mu = o.ball.friction;
    let (n1, s1) = if t1.abs() <= mu * n1 {
        (n1, s1)
    } else {
        let sign = t1.signum();
        let (n1, s1) =
            inp.law
                .solve_implicit(s_free, b_nn + b_nt * sign * mu, inp.s_max, inp.guess);
        t1 = sign * mu * n1;
        (n1, s1)
    };
    (n1, t1, eta0 + eta_n * n1 + eta_t * t1, s1)
}

/// The relative displacement along x̂ at the step's end without the end forces, and its
/// compliance to the bat's end force along x̂.
fn cross_part(o: &Oblique, t: &Tangential, inp: &StepInputs) -> (f64, f64) {
    let (ball, bat) = cross_free(o, t, inp);
    let h2 = inp.h * inp.h;
    (ball - bat, h2 / 6.0 * (1.0 / inp.mass + 1.0 / o.cross_mass))
}

/// The ball's centre and the bat's impact point across the plane at the step's end without
/// the end forces.
fn cross_free(o: &Oblique, t: &Tangential, inp: &StepInputs) -> (f64, f64) {
    let (h, m) = (inp.h, inp.mass);
    let h2 = h * h;
    let on_ball = Tangential::bat_force_x(o, t.normal, t.shear);
    let on_bat = Tangential::bat_force_x(o, t.bat_normal, t.shear);
    (
        t.ball_x + h * t.ball_vx - h2 * on_ball / (3.0 * m),
        t.bat_x + h * t.bat_vx + h2 * on_bat / (3.0 * o.cross_mass),
    )
}

/// The spins' part of the tangential displacement at the step's end without the end force,
/// and its compliance to the end force T₁.
fn turn_part(o: &Oblique, t: &Tangential, h: f64) -> (f64, f64) {
    let (r, rb) = (o.ball.radius, o.bat_radius);
    let lever2 = r * r / o.ball.inertia + rb * rb / o.roll_inertia;
    let h2 = h * h;
    let free = r * (t.ball_turn + h * t.ball_spin)
        + rb * (t.roll + h * t.roll_rate)
        + h2 * lever2 * t.shear / 3.0;
    (free, h2 / 6.0 * lever2)
}

/// Move the ball and the bat across the plane and turn them under the step's forces
/// (linear in time: exact for free masses), then take the end forces as the next start.
pub(in crate::collision::wave) fn advance(
    o: &Oblique,
    t: &mut Tangential,
    (m, h): (f64, f64),
    (n1, t1, nb1): (f64, f64, f64),
) {
    let h2 = h * h;
    let (q0, q1) = (
        Tangential::bat_force_x(o, t.normal, t.shear),
        Tangential::bat_force_x(o, n1, t1),
    );
    t.ball_x += h * t.ball_vx - h2 * (2.0 * q0 + q1) / (6.0 * m);
    t.ball_vx -= h * (q0 + q1) / (2.0 * m);
    let (b0, b1) = (
        Tangential::bat_force_x(o, t.bat_normal, t.shear),
        Tangential::bat_force_x(o, nb1, t1),
    );
    let inv_x = 1.0 / o.cross_mass;
    t.bat_x += h * t.bat_vx + h2 * (2.0 * b0 + b1) * inv_x / 6.0;
    t.bat_vx += h * (b0 + b1) * inv_x / 2.0;
    let (t0, r, rb) = (t.shear, o.ball.radius, o.bat_radius);
    let (ball_turn, spin) = turned(t.ball_turn, t.ball_spin, r / o.ball.inertia, h, (t0, t1));
    let (roll, roll_rate) = turned(t.roll, t.roll_rate, rb / o.roll_inertia, h, (t0, t1));
    (t.ball_turn, t.ball_spin, t.roll, t.roll_rate) = (ball_turn, spin, roll, roll_rate);
    (t.normal, t.shear, t.bat_normal) = (n1, t1, nb1);
}

/// A body's angle and rate after a step under a torque `lever_over_inertia`·T, T linear.
fn turned(
    angle: f64,
    rate: f64,
    lever_over_inertia: f64,
    h: f64,
    (t0, t1): (f64, f64),
) -> (f64, f64) {
    (
        angle + h * rate + h * h * lever_over_inertia * (2.0 * t0 + t1) / 6.0,
        rate + h * lever_over_inertia * (t0 + t1) / 2.0,
    )
}

/// The tangential force's work against the contact points' relative motion over a step
/// (trapezoid): what the patch takes from the bodies. Summed over a contact it is what the
/// tangential contact dissipated (the patch holds no force once the ball has left);
/// within a contact it includes what the patch holds for the moment.
pub(in crate::collision::wave) fn slip_loss((t0, t1): (f64, f64), slip: f64) -> f64 {
    -0.5 * (t0 + t1) * slip
}
