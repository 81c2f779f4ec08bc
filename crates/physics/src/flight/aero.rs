//! The ball and the forces of the air on it: Nathan's drag and lift fitted to Statcast
//! batted balls, and the spin decay of his trajectory calculator.
//!
//! Accelerations (A. M. Nathan, "Going deep on goin' deep", The Hardball Times, 6 Apr 2016;
//! the coefficients are those of his trajectory calculator):
//! - drag: a_D = −K·C_D·|u|·u, with u = v − wind the velocity through the air and
//!   K = ρA/(2m);
//! - lift (Magnus): a_L = K·C_L·|u|·(ω̂ × u), ω̂ the spin axis, fixed during the flight
//!   (the calculator does not precess it);
//! - C_D = 0.3008 + 0.0292·(ω/1000 rpm), C_L = 1.120·S/(0.583 + 2.333·S), S = Rω/|u|;
//! - spin decay as the calculator applies it: ω = ω₀·exp(−t·|u|/(τ·100 mph)), τ = 30 s.

use super::error::{check_range, FlightError};

/// 1 mph in m/s (exact: 1609.344 m / 3600 s).
pub const MPH: f64 = crate::units::MPH;
/// 1 ft in m (exact).
pub const FOOT: f64 = crate::units::FOOT;
/// 1 rpm in rad/s.
pub const RPM: f64 = crate::units::RPM;
/// Standard gravity, m/s² (the calculator's 32.174 ft/s²).
pub const GRAVITY: f64 = 9.806_65;

/// The ball. Defaults are the calculator's (and the rule book's mid-range): 5.125 oz and a
/// 9.125-in circumference.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BallProperties {
    /// Mass, kg. Default 0.145 295 kg (5.125 oz).
    pub mass_kg: f64,
    /// Circumference, m. Default 0.231 775 m (9.125 in): radius 0.036 888 m.
    pub circumference_m: f64,
}

impl Default for BallProperties {
    fn default() -> Self {
        BallProperties {
            mass_kg: 5.125 * 0.028_349_523_125,
            circumference_m: 9.125 * 0.0254,
        }
    }
}

impl BallProperties {
    /// Radius, m.
    pub fn radius_m(&self) -> f64 {
        self.circumference_m / (2.0 * std::f64::consts::PI)
    }

    /// K = ρA/(2m) per unit air density, m²/kg: the drag and lift accelerations are
    /// K·ρ·C·|u|².
    pub fn area_over_twice_mass(&self) -> f64 {
        let r = self.radius_m();
        std::f64::consts::PI * r * r / (2.0 * self.mass_kg)
    }
}

/// The aerodynamic model: Nathan's Statcast fit, with switches for the tests.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NathanAero {
    /// C_D at zero spin. Default 0.3008.
    pub drag_base: f64,
    /// Rise of C_D per 1000 rpm of spin. Default 0.0292.
    pub drag_per_1000_rpm: f64,
    /// C_L = lift_numerator·S/(lift_offset + lift_slope·S). Defaults 1.120, 0.583, 2.333.
    pub lift_numerator: f64,
    /// See `lift_numerator`.
    pub lift_offset: f64,
    /// See `lift_numerator`.
    pub lift_slope: f64,
    /// Spin-decay time τ, s, at 100 mph through the air: ω = ω₀·exp(−t·|u|/(τ·100 mph)).
    /// Default 30 s, the value in the calculator's own output (TrajectoryCalculator-new-3D,
    /// its S and C_D columns; docs/physics.md "Flight"); `f64::INFINITY` turns decay off.
    pub spin_decay_tau_s: f64,
    /// Multiplies the drag (1 = the fit, 0 = none): the calculator's "drag strength".
    pub drag_scale: f64,
    /// Multiplies the lift (1 = the fit, 0 = none): the calculator's "Magnus strength".
    pub lift_scale: f64,
}

impl Default for NathanAero {
    fn default() -> Self {
        NathanAero {
            drag_base: 0.3008,
            drag_per_1000_rpm: 0.0292,
            lift_numerator: 1.120,
            lift_offset: 0.583,
            lift_slope: 2.333,
            spin_decay_tau_s: 30.0,
            drag_scale: 1.0,
            lift_scale: 1.0,
        }
    }
}

impl NathanAero {
    /// No drag and no lift: the vacuum projectile (for tests of the integrator).
    pub fn vacuum() -> Self {
        NathanAero {
            drag_scale: 0.0,
            lift_scale: 0.0,
            ..NathanAero::default()
        }
    }

    /// Lift coefficient at spin factor `s` (≥ 0).
    pub fn lift_coefficient(&self, s: f64) -> f64 {
        self.lift_numerator * s / (self.lift_offset + self.lift_slope * s)
    }

    /// Drag coefficient at `spin_rpm` (≥ 0).
    pub fn drag_coefficient(&self, spin_rpm: f64) -> f64 {
        self.drag_base + self.drag_per_1000_rpm * spin_rpm / 1000.0
    }

    pub(crate) fn validate(&self) -> Result<(), FlightError> {
        let coefficients = [
            ("aero.drag_base", self.drag_base),
            ("aero.drag_per_1000_rpm", self.drag_per_1000_rpm),
            ("aero.lift_numerator", self.lift_numerator),
            ("aero.lift_slope", self.lift_slope),
            ("aero.drag_scale", self.drag_scale),
            ("aero.lift_scale", self.lift_scale),
        ];
        for (name, value) in coefficients {
            check_range(name, value, 0.0, 100.0, "[0, 100]")?;
        }
        // A positive offset keeps C_L finite at S = 0.
        check_range(
            "aero.lift_offset",
            self.lift_offset,
            1e-9,
            100.0,
            "(0, 100]",
        )?;
        // NaN fails the comparison, so it is rejected too.
        if self.spin_decay_tau_s.is_nan() || self.spin_decay_tau_s <= 0.0 {
            return Err(FlightError::OutOfRange {
                name: "aero.spin_decay_tau_s",
                value: self.spin_decay_tau_s,
                allowed: "(0, inf] s",
            });
        }
        Ok(())
    }
}

/// Everything the equations of motion need, computed once per flight.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Forces {
    /// ρA/(2m), 1/m.
    k: f64,
    /// Unit spin axis (zero vector for a ball without spin).
    axis: [f64; 3],
    /// R·ω₀, m/s.
    surface_speed: f64,
    /// Initial spin, rpm.
    spin_rpm: f64,
    /// 1/(τ·100 mph), 1/m: the decay exponent is t·|u| times this (0 = no decay).
    decay_per_m: f64,
    wind: [f64; 3],
    drag_base: f64,
    drag_per_rpm: f64,
    lift: (f64, f64, f64),
    drag_scale: f64,
    lift_scale: f64,
}

impl Forces {
    /// `spin` is the initial spin vector, rad/s.
    pub(crate) fn new(
        density: f64,
        wind: [f64; 3],
        ball: &BallProperties,
        aero: &NathanAero,
        spin: [f64; 3],
    ) -> Forces {
        let omega = norm(spin);
        let axis = if omega > 0.0 {
            spin.map(|c| c / omega)
        } else {
            [0.0; 3]
        };
        Forces {
            k: density * ball.area_over_twice_mass(),
            axis,
            surface_speed: ball.radius_m() * omega,
            spin_rpm: omega / RPM,
            decay_per_m: 1.0 / (aero.spin_decay_tau_s * 100.0 * MPH),
            wind,
            drag_base: aero.drag_base,
            drag_per_rpm: aero.drag_per_1000_rpm / 1000.0,
            lift: (aero.lift_numerator, aero.lift_offset, aero.lift_slope),
            drag_scale: aero.drag_scale,
            lift_scale: aero.lift_scale,
        }
    }

    /// Acceleration at time `t` of a ball moving at `v` (ground frame), m/s².
    #[inline]
    pub(crate) fn acceleration(&self, t: f64, v: [f64; 3]) -> [f64; 3] {
        let u = [
            v[0] - self.wind[0],
            v[1] - self.wind[1],
            v[2] - self.wind[2],
        ];
        let speed = norm(u);
        if speed == 0.0 || self.k == 0.0 {
            return [0.0, 0.0, -GRAVITY];
        }
        // The calculator's decay: elapsed time × current airspeed, not the path length.
        let decay = if self.decay_per_m > 0.0 {
            (-t * speed * self.decay_per_m).exp()
        } else {
            1.0
        };
        let cd = self.drag_base + self.drag_per_rpm * self.spin_rpm * decay;
        let s = self.surface_speed * decay / speed;
        let cl = self.lift.0 * s / (self.lift.1 + self.lift.2 * s);
        let drag = self.drag_scale * self.k * cd * speed;
        let lift = self.lift_scale * self.k * cl * speed;
        let a = self.axis;
        let cross = [
            a[1] * u[2] - a[2] * u[1],
            a[2] * u[0] - a[0] * u[2],
            a[0] * u[1] - a[1] * u[0],
        ];
        [
            -drag * u[0] + lift * cross[0],
            -drag * u[1] + lift * cross[1],
            -drag * u[2] + lift * cross[2] - GRAVITY,
        ]
    }
}

/// Euclidean length.
#[inline]
pub(crate) fn norm(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 9.125 in of circumference is a radius of 1.4523 in = 0.036888 m.
    #[test]
    fn ball_radius_from_circumference() {
        let r = BallProperties::default().radius_m();
        assert!((r - 9.125 / (2.0 * std::f64::consts::PI) * 0.0254).abs() < 1e-15);
        assert!((r - 0.036888).abs() < 1e-6);
    }

    /// C_L saturates at 1.120/2.333 = 0.48 for large S and is linear (1.120/0.583·S) near 0.
    #[test]
    fn lift_coefficient_limits() {
        let aero = NathanAero::default();
        assert!((aero.lift_coefficient(1e9) - 1.120 / 2.333).abs() < 1e-8);
        assert!((aero.lift_coefficient(1e-9) / 1e-9 - 1.120 / 0.583).abs() < 1e-6);
        assert!((aero.drag_coefficient(2500.0) - 0.3738).abs() < 1e-12);
    }

    /// Lift is perpendicular to the velocity and upward for backspin on a ball going to
    /// centre field (+y): ω along +x.
    #[test]
    fn backspin_lifts() {
        let f = Forces::new(
            1.2,
            [0.0; 3],
            &BallProperties::default(),
            &NathanAero {
                drag_scale: 0.0,
                ..NathanAero::default()
            },
            [200.0, 0.0, 0.0],
        );
        let a = f.acceleration(0.0, [0.0, 40.0, 0.0]);
        assert!(a[2] > -GRAVITY && a[0] == 0.0 && a[1].abs() < 1e-15);
    }
}
