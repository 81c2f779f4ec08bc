//! Oblique impacts and spin: the ball meets the bat off its axis, or spinning.
//!
//! The collision is solved in the plane across the bat at the impact point, spanned by the
//! ball's incoming path ŷ (the beam's bending direction, as in the head-on model) and x̂,
//! perpendicular to ŷ and to the bat's axis b̂ (x̂ = b̂ × ŷ; "up" for a level bat). The
//! ball's centre line runs at x = −`impact.offset` from the bat's axis. At first touch the
//! line of centres from the ball's centre to the bat's axis is n̂ = (cos θ, sin θ) in
//! (ŷ, x̂), sin θ = offset / (R_bat + r_ball); it is held fixed during the ~1 ms contact
//! (the compression is a few per cent of the radii), as in the rigid-body analyses of
//! Sawicki, Hubbard & Stronge (2003) and Cross & Nathan (2006). The tangent is
//! t̂ = (−sin θ, cos θ).
//!
//! Forces (Cross's model of a ball with tangential compliance, R. Cross, Am. J. Phys. 70,
//! 482 (2002); 73, 914 (2005)): the normal force N ≥ 0 from the ball's law of compression
//! along n̂ pushes the ball by −N n̂ and the bat by +N n̂; the tangential force T on the
//! ball (−T on the bat) comes from the contact patch, which shears with the contact points'
//! relative tangential displacement while the ball grips, dT = −k_t du, with a stiffness
//! that grows with the patch as the normal one does (k_t = κ dN/ds, Mindlin), and slides
//! with |T| = μ N when that would exceed friction.
//!
//! The bat bends in the swing plane (along ŷ) as in the head-on model; across it (along x̂)
//! and in roll about its axis it moves as a rigid body: its impact point has the effective
//! mass of the free (or pivoted) rigid bat, and its roll the moment of inertia of its cross
//! sections about the axis.

use crate::ball::{
    DEFAULT_BALL_RADIUS, DEFAULT_FRICTION, DEFAULT_INERTIA_FACTOR, DEFAULT_TANGENTIAL_RATIO,
};
use crate::bat::PreparedBat;
use crate::collision::frame::pitch_components;
use crate::error::ModelError;
use crate::protocol::{free_effective_mass, pivoted_effective_mass};
use crate::spec::{BallSpec, CollisionSpec};

/// The ball's radius, moment of inertia factor, friction and tangential stiffness, with the
/// defaults filled in.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BallContact {
    /// Radius, m.
    pub radius: f64,
    /// Moment of inertia about a diameter, kg·m².
    pub inertia: f64,
    /// Coefficient of friction μ.
    pub friction: f64,
    /// Tangential stiffness over the normal (secant) one.
    pub tangential_ratio: f64,
}

impl BallContact {
    pub fn of(ball: &BallSpec) -> BallContact {
        let radius = ball.radius.unwrap_or(DEFAULT_BALL_RADIUS);
        let factor = ball.inertia_factor.unwrap_or(DEFAULT_INERTIA_FACTOR);
        BallContact {
            radius,
            inertia: factor * ball.mass * radius * radius,
            friction: ball.law.friction.unwrap_or(DEFAULT_FRICTION),
            tangential_ratio: ball
                .law
                .tangential_ratio
                .unwrap_or(DEFAULT_TANGENTIAL_RATIO),
        }
    }
}

/// Everything an oblique (or spinning) collision needs beyond the head-on one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Oblique {
    /// cos θ and sin θ of the line of centres against the ball's path.
    pub cos: f64,
    pub sin: f64,
    pub ball: BallContact,
    /// The pitch's spin about the bat's axis b̂, rad/s (ω_b; + is the pitch's backspin).
    pub spin: f64,
    /// The ball's velocity across the swing plane (along x̂) before contact, bat-CM frame,
    /// m/s: a pitch off the bat's path (`pitch`); 0 on plane.
    pub across_speed: f64,
    /// The bat's outer radius at the impact point, m.
    pub bat_radius: f64,
    /// The bat's moment of inertia about its long axis, kg·m².
    pub roll_inertia: f64,
    /// The rigid bat's effective mass at the impact point across the swing plane, kg.
    pub cross_mass: f64,
}

/// The ball must meet the bat: |offset| below the bat's radius at the impact point plus the
/// ball's (checked here so that a study that misses is refused before it runs).
pub(crate) fn check_reach(
    spec: &CollisionSpec,
    g: &crate::bat::section::BatGeometry,
) -> Result<(), ModelError> {
    let z = spec.impact.z;
    if spec.impact.offset == 0.0 || !(0.0..=g.length).contains(&z) {
        return Ok(());
    }
    let ball = BallContact::of(&spec.ball);
    let reach = g.outer_radius(z) + ball.radius;
    if spec.impact.offset.abs() < reach {
        return Ok(());
    }
    Err(crate::error::out_of_range(
        "impact.offset",
        spec.impact.offset,
        &format!("|offset| < bat radius + ball radius = {reach:.4} m at impact.z = {z} m (else the ball misses)"),
    ))
}

impl Oblique {
    /// The oblique part of `spec` on `bat`, whose impact point the ball approaches at
    /// `approach` along ŷ (m/s): `None` for a head-on ball without spin on the bat's path
    /// (the paper's collision, computed exactly as before).
    pub fn resolve(
        spec: &CollisionSpec,
        bat: &PreparedBat,
        approach: f64,
    ) -> Result<Option<Oblique>, ModelError> {
        let across_speed = pitch_components(spec).map_or(0.0, |p| p.across);
        if spec.impact.offset == 0.0 && spec.ball.spin == 0.0 && across_speed == 0.0 {
            return Ok(None);
        }
        let ball = BallContact::of(&spec.ball);
        let bat_radius = bat.geometry.outer_radius(spec.impact.z);
        // the same check the study layer makes when it loads (a miss is refused)
        check_reach(spec, &bat.geometry)?;
        let (cos, sin) = line_of_centres(
            spec.impact.offset / (bat_radius + ball.radius),
            (approach, across_speed),
        );
        Ok(Some(Oblique {
            cos,
            sin,
            ball,
            spin: spec.ball.spin,
            across_speed,
            bat_radius,
            roll_inertia: bat.roll_inertia,
            cross_mass: cross_mass(bat, spec.impact.z),
        }))
    }

    /// The normal speed at first contact (the compression's rate), m/s, of a ball that
    /// meets the bat's impact point at `approach` along ŷ.
    pub fn normal_speed(&self, approach: f64) -> f64 {
        approach * self.cos + self.across_speed * self.sin
    }

    /// The tangential velocity of the ball's contact point relative to the bat's surface
    /// point (the slip velocity), m/s, from the relative velocity (ball − bat contact
    /// point) in (ŷ, x̂) and the spins about b̂.
    pub fn slip_velocity(&self, relative: (f64, f64), ball_spin: f64, roll_rate: f64) -> f64 {
        -self.sin * relative.0
            + self.cos * relative.1
            + self.ball.radius * ball_spin
            + self.bat_radius * roll_rate
    }
}

/// cos θ and sin θ of the line of centres at first touch, from the offset's sine
/// (`offset` / (R + r), the offset measured across the ball's path relative to the bat's
/// impact point) and that relative velocity in (ŷ, x̂): θ is the offset's angle turned by
/// the path's, δ = atan2(v_x, v_y). On the bat's path (v_x = 0) it is the offset's alone.
fn line_of_centres(offset_sin: f64, (along, across): (f64, f64)) -> (f64, f64) {
    let offset_cos = (1.0 - offset_sin * offset_sin).sqrt();
    if across == 0.0 {
        return (offset_cos, offset_sin);
    }
    let (sd, cd) = across.atan2(along).sin_cos();
    (
        offset_cos * cd - offset_sin * sd,
        offset_sin * cd + offset_cos * sd,
    )
}

/// The rigid bat's effective mass at `z` for a push across the swing plane: about the
/// pivot for a pinned grip, of the free bat otherwise (a spring grip is soft on the
/// collision's time scale).
fn cross_mass(bat: &PreparedBat, z: f64) -> f64 {
    let (mass, z_cm, inertia) = (bat.beam.total_mass(), bat.z_cm, bat.inertia_cm);
    match (bat.beam.pin, bat.beam.grip_z) {
        (Some(_), Some(zg)) => pivoted_effective_mass(inertia + mass * (z_cm - zg).powi(2), zg, z),
        _ => free_effective_mass(mass, z_cm, inertia, z),
    }
}

/// The ball after a rigid oblique collision, in the bat-CM frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidOblique {
    /// Ball velocity along ŷ and x̂, m/s.
    pub velocity: (f64, f64),
    /// Ball spin about b̂, rad/s.
    pub spin: f64,
    /// The bat's roll rate, rad/s.
    pub roll_rate: f64,
    /// Normal and tangential impulses on the ball (along −n̂ and t̂), N·s.
    pub normal_impulse: f64,
    pub tangential_impulse: f64,
    /// Slip velocity before and after, m/s.
    pub slip_before: f64,
    pub slip_after: f64,
    /// The impulse on the ball along ŷ and x̂, N·s (the bat takes the opposite).
    pub impulse: (f64, f64),
}

/// The rigid-body oblique collision with Coulomb friction in closed form (Stronge's impact
/// mechanics as applied to bat and ball by Sawicki, Hubbard & Stronge, Am. J. Phys. 71,
/// 1152 (2003), and Cross & Nathan, Am. J. Phys. 74, 896 (2006)): a rigid bat has the same
/// effective mass M* = 1/(1/M + l²/I) in every direction across its axis, so the normal
/// and tangential impulses decouple. The normal impulse gives the normal COR `cor`; the
/// tangential impulse stops the slip (the ball rolls off, e_T = 0) when friction can,
/// μ J_n ≥ |v_t| / w_t, and is μ J_n against the slip otherwise (gross slip).
/// `ball_speed` and `bat_speed`: the ball's and the bat's impact point's velocities along
/// ŷ before contact, m/s.
pub fn rigid_oblique(
    o: &Oblique,
    ball_mass: f64,
    bat_effective_mass: f64,
    (ball_speed, bat_speed): (f64, f64),
    cor: f64,
) -> RigidOblique {
    let approach = ball_speed - bat_speed;
    let inverse_bat = 1.0 / bat_effective_mass;
    let w_n = 1.0 / ball_mass + inverse_bat;
    let r = o.ball.radius;
    let w_t = w_n + r * r / o.ball.inertia + o.bat_radius.powi(2) / o.roll_inertia;
    let v_n = o.normal_speed(approach);
    let slip_before = o.slip_velocity((approach, o.across_speed), o.spin, 0.0);
    let normal_impulse = (1.0 + cor) * v_n / w_n;
    let stop = slip_before / w_t;
    let tangential_impulse = if o.ball.friction * normal_impulse >= stop.abs() {
        -stop
    } else {
        -o.ball.friction * normal_impulse * slip_before.signum()
    };
    // on the ball: −J_n n̂ + J_t t̂, n̂ = (c, s), t̂ = (−s, c)
    let (jn, jt) = (normal_impulse, tangential_impulse);
    let impulse = (-jn * o.cos - jt * o.sin, -jn * o.sin + jt * o.cos);
    let velocity = (
        ball_speed + impulse.0 / ball_mass,
        o.across_speed + impulse.1 / ball_mass,
    );
    RigidOblique {
        velocity,
        spin: o.spin + r * jt / o.ball.inertia,
        roll_rate: o.bat_radius * jt / o.roll_inertia,
        normal_impulse: jn,
        tangential_impulse: jt,
        slip_before,
        slip_after: slip_before + jt * w_t,
        impulse,
    }
}
