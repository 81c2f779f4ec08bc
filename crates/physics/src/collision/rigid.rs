//! Brody's rigid-body recoil model (the paper's section 2, with docs/physics.md's conventions).
//!
//! Three equations fix the collision of a ball (mass m, velocity v_i along +y) with a free
//! rigid bat (mass M, moment of inertia I about its CM, initial angular velocity ω_i)
//! hit at lever arm l = z_imp − z_cm:
//!
//! - momentum: `M V_f = m (v_i − v_f)`
//! - angular momentum about the CM: `I (ω_f − ω_i) = m l (v_i − v_f)`
//! - restitution: `e (v_i − ω_i l) = −v_f + V_f + ω_f l`
//!
//! With the impulse J = m (v_i − v_f) on the bat these give
//! `J = (1 + e)(v_i − ω_i l) / (1/m + 1/M*)`, `1/M* = 1/M + l²/I` — the effective mass
//! `M* = M / (1 + M l²/I)` (the paper prints `Ml²/2`, a typo).

/// Result of a rigid-body collision; velocities in the frame where the bat's CM is
/// initially at rest.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidOutcome {
    /// Ball speed back toward the pitcher after the collision, m/s (= −v_f).
    pub exit_speed: f64,
    /// Collision efficiency e_A = (e − m/M*) / (1 + m/M*).
    pub collision_efficiency: f64,
    /// Relative approach speed at the impact point, v_i − ω_i l, m/s.
    pub approach_speed: f64,
    /// Impulse on the ball (= on the bat), N·s.
    pub impulse: f64,
    /// Effective mass of the bat at the impact point, kg.
    pub effective_mass: f64,
    /// Bat CM velocity after the collision (along +y), m/s.
    pub bat_velocity: f64,
    /// Bat angular velocity after the collision, rad/s.
    pub bat_omega: f64,
    /// Kinetic energy before, J.
    pub energy_initial: f64,
    /// Kinetic energy of the ball after, J.
    pub energy_ball_final: f64,
    /// Kinetic energy of the bat after (translation + rotation), J.
    pub energy_bat_final: f64,
    /// Energy lost in the collision, J (the ball's hysteresis when e is the ball's COR).
    pub energy_lost: f64,
}

/// Solve Brody's three equations. `ball_speed` is the ball's speed toward the bat (v_i),
/// `lever_arm` = z_imp − z_cm (m), `omega` = ω_i (rad/s, negative = toward the ball),
/// `cor` = e.
pub fn rigid_collision(
    ball_mass: f64,
    ball_speed: f64,
    bat_mass: f64,
    bat_inertia_cm: f64,
    lever_arm: f64,
    omega: f64,
    cor: f64,
) -> RigidOutcome {
    let inverse_effective_mass = 1.0 / bat_mass + lever_arm * lever_arm / bat_inertia_cm;
    let approach_speed = ball_speed - omega * lever_arm;
    let impulse = (1.0 + cor) * approach_speed / (1.0 / ball_mass + inverse_effective_mass);
    let ball_final_velocity = ball_speed - impulse / ball_mass;
    let bat_velocity = impulse / bat_mass;
    let bat_omega = omega + impulse * lever_arm / bat_inertia_cm;
    let mass_ratio = ball_mass * inverse_effective_mass;

    let kinetic_bat = |v: f64, w: f64| 0.5 * bat_mass * v * v + 0.5 * bat_inertia_cm * w * w;
    let energy_initial = 0.5 * ball_mass * ball_speed * ball_speed + kinetic_bat(0.0, omega);
    let energy_ball_final = 0.5 * ball_mass * ball_final_velocity * ball_final_velocity;
    let energy_bat_final = kinetic_bat(bat_velocity, bat_omega);
    RigidOutcome {
        exit_speed: -ball_final_velocity,
        collision_efficiency: (cor - mass_ratio) / (1.0 + mass_ratio),
        approach_speed,
        impulse,
        effective_mass: 1.0 / inverse_effective_mass,
        bat_velocity,
        bat_omega,
        energy_initial,
        energy_ball_final,
        energy_bat_final,
        energy_lost: energy_initial - energy_ball_final - energy_bat_final,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // Typical wood bat (docs/physics.md, seed paper): M 0.831 kg, I_cm 0.039 kg m², ball 0.145 kg.
    const M: f64 = 0.831;
    const I: f64 = 0.039;
    const M_BALL: f64 = 0.145;

    #[test]
    fn conserves_momentum_and_angular_momentum() {
        let o = rigid_collision(M_BALL, 40.0, M, I, 0.12, -30.0, 0.5);
        // Linear momentum: m v_i = m v_f + M V_f (bat CM at rest initially).
        let p_before = M_BALL * 40.0;
        let p_after = M_BALL * (-o.exit_speed) + M * o.bat_velocity;
        assert!((p_before - p_after).abs() < 1e-12);
        // Angular momentum about the initial CM: I ω_i + m l v_i.
        let l_before = I * -30.0 + M_BALL * 0.12 * 40.0;
        let l_after = I * o.bat_omega + M_BALL * 0.12 * (-o.exit_speed);
        assert!((l_before - l_after).abs() < 1e-12);
    }

    #[test]
    fn restitution_holds_and_elastic_conserves_energy() {
        let o = rigid_collision(M_BALL, 40.0, M, I, 0.1, -20.0, 0.5);
        let separation = -(-o.exit_speed) + o.bat_velocity + o.bat_omega * 0.1;
        assert!((separation - 0.5 * o.approach_speed).abs() < 1e-12);
        let elastic = rigid_collision(M_BALL, 40.0, M, I, 0.1, -20.0, 1.0);
        assert!(elastic.energy_lost.abs() < 1e-9 * elastic.energy_initial);
    }

    #[test]
    fn massive_bat_returns_cor_times_speed() {
        // A wall: exit speed = e v (docs/physics.md, the ball on a rigid wall).
        let o = rigid_collision(M_BALL, 40.0, 1e12, 1e12, 0.1, 0.0, 0.55);
        assert!((o.exit_speed - 0.55 * 40.0).abs() < 1e-9);
    }
}
