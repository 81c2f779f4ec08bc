//! The ball's force–compression laws (docs/physics.md "The ball").
//!
//! Every lossy law unloads along a lower branch chosen so that a ball on a rigid wall
//! gives back exactly e² of the energy stored at maximum compression.
//! Given the largest compression so far `s_max`, each law is one continuous function of the
//! compression that increases monotonically (unloading branch below s_max, loading above),
//! which is what makes the integrators' implicit contact solve well posed.

use crate::spec::ball_law::{BallLaw, BallLawKind, BallPreset, Loading};

/// `speed_dependent`: default reference speed, m/s (85 ft/s, the MLB ball specification's
/// wall-test speed).
pub const DEFAULT_REFERENCE_SPEED: f64 = 25.9;
/// `speed_dependent`: default change of the wall COR per m/s. Nathan (2000) takes e = 0.50
/// for his 71 m/s game-speed case; the rule-book ball has 0.546 at 25.9 m/s: a line
/// through both falls by 0.001 per m/s (docs/physics.md, "The ball").
pub const DEFAULT_COR_SLOPE: f64 = -0.001;
/// `speed_dependent`: the COR line is clamped to this range (below 0.05 the unloading
/// exponent exceeds 800; above 1 the ball would gain energy).
pub const COR_RANGE: (f64, f64) = (0.05, 1.0);

/// The ball-alone measurements the `mlb` preset is calibrated on (docs/physics.md, "The
/// calibrated ball"): the rule book's wall COR, the middle of 0.514–0.578 at 85 ft/s
/// (Nathan 2000, footnote 13, quoting the MLB specification), and Cross's COR of a baseball
/// dropped on a hard floor at 1 m/s (measured; Nathan 2000, Sec. III.B).
pub const MLB_SPEC_COR: f64 = 0.546;
pub const MLB_SPEC_SPEED: f64 = 25.9;
pub const CROSS_LOW_SPEED_COR: f64 = 0.64;
pub const CROSS_LOW_SPEED: f64 = 1.0;
/// 36 MLB game balls of 2014–16 fired at 120 mph into a steel cylinder at the Washington
/// State University Sports Science Laboratory (data/mlb_balls_cylinder_2014_2016.csv): the
/// speed (m/s), the mean cylindrical COR, and the mean dynamic stiffness (N/m, 12,768 lbf/in
/// as ASTM F2845 reports it, taken as (F_peak / v)² / m).
pub const CYLINDER_SPEED: f64 = 120.0 * 0.44704;
pub const CYLINDER_COR: f64 = 0.4920;
pub const CYLINDER_DYNAMIC_STIFFNESS: f64 = 2.236e6;
/// The spread of the cylinder test's balls about their mean COR (the sample SD over the 36
/// balls, the three lots included; the lots' means differ by up to 0.006): what one ball,
/// or one lot, may be off the `mlb` curve (`ball.law.cor_shift`).
pub const MLB_COR_SD: f64 = 0.0050;
/// The spread of the 36 balls' dynamic stiffness, the SD of its logarithm (3.2 %; ball to
/// ball, the lots included), and of the three lots' means (1.0 %).
pub const MLB_DS_LOG_SD: f64 = 0.0317;
pub const MLB_LOT_DS_LOG_SD: f64 = 0.0104;
/// The spread of the three lots' mean COR (17, 9 and 10 balls: 0.4892, 0.4951, 0.4941), SD.
pub const MLB_LOT_COR_SD: f64 = 0.0032;
/// The correlation of COR and ln DS over the 36 balls (0.35): livelier balls are stiffer.
pub const MLB_COR_DS_RHO: f64 = 0.35;

/// How far real balls stray from a preset, as measured: the SD of a shift of the COR curve
/// (`ball.law.cor_shift`), the SD of ln k₁, and the correlation of the two.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeasuredSpread {
    pub cor_sd: f64,
    pub k1_log_sd: f64,
    pub rho: f64,
}

/// The `mlb` ball's measured spread: of one ball (`lot == false`: ball to ball, the lots
/// included) or of a lot's mean (`lot == true`: the three lots' means; a certification
/// averages several hits, so its ball is nearer a lot's mean than one ball). k₁ ∝ DS^((α+1)/2)
/// ([`mlb_k1`]), so ln k₁ spreads (α+1)/2 times as far as ln DS. The lots' correlation is
/// taken to be the balls' (three means cannot measure one).
pub fn mlb_spread(lot: bool) -> MeasuredSpread {
    let (cor_sd, ds_log_sd) = match lot {
        false => (MLB_COR_SD, MLB_DS_LOG_SD),
        true => (MLB_LOT_COR_SD, MLB_LOT_DS_LOG_SD),
    };
    MeasuredSpread {
        cor_sd,
        k1_log_sd: ds_log_sd * (MLB_ALPHA + 1.0) / 2.0,
        rho: MLB_COR_DS_RHO,
    }
}

/// The loading's exponent α of the `mlb` ball: Nathan's (2000), shaped to Adair's
/// force–time curves (one speed's dynamic stiffness cannot pin it).
pub const MLB_ALPHA: f64 = 1.84;
/// The mass the calibration takes the ball to have, kg (the rule book's 5–5.25 oz; the
/// cylinder test's balls weighed 145.2 ± 1.0 g).
pub const MLB_MASS: f64 = 0.145;

/// The radius of the cylinder the 36 balls were fired at, m. Not stated in anything this
/// project could read (data/mlb_balls_cylinder_2014_2016.md; WSU calls the surface
/// "intended to approximate the bat"): taken as 3.0 cm, the middle of barrel radii
/// (2 1/4-in softball barrels 2.86 cm, 2 5/8-in BBCOR barrels 3.33 cm), with 2.5–3.5 cm as
/// its uncertainty (docs/physics.md, "The calibrated ball").
pub const TEST_CYLINDER_RADIUS: f64 = 0.030;
/// The range [`TEST_CYLINDER_RADIUS`]'s uncertainty spans, m.
pub const TEST_CYLINDER_RADIUS_RANGE: (f64, f64) = (0.025, 0.035);

/// Hertz's factor on a loading's stiffness for a target whose surface has radius
/// `target_radius` across the ball's path (`None`: a flat wall), against a flat wall at the
/// same compression: √(R_e / R_b), where R_e = √(R′ R″) is the effective radius of a sphere
/// (R_b) on a cylinder (R) with crossed axes, 1/R′ = 1/R_b + 1/R and R″ = R_b (Johnson,
/// "Contact Mechanics", §4.2): (R / (R_b + R))^(1/4).
pub fn curvature_factor(ball_radius: f64, target_radius: Option<f64>) -> f64 {
    match target_radius {
        Some(r) if r > 0.0 && r.is_finite() => (r / (ball_radius + r)).powf(0.25),
        _ => 1.0,
    }
}

/// The law a ball meets a target with, and the speed its COR curve is read at: for a law
/// that sees curvature (`ball.law.curvature`), the loading scaled by [`curvature_factor`] g
/// and the flat-wall speed of the same peak contact strain. On a rigid target the loading's
/// work at the largest compression is the ball's energy, s_max ∝ (v² / (k g))^(1/(α+1)),
/// and Hertz's mean strain is √(s_max / R_e) with R_e = R_b g²: equal strains need
/// v_flat = v g^(−(α + 1.5)). Any other law unchanged, at `v`.
pub fn on_target(
    law: &BallLaw,
    v: f64,
    ball_radius: f64,
    target_radius: Option<f64>,
) -> (BallLaw, f64) {
    if law.kind != BallLawKind::SpeedDependent || law.curvature != Some(true) {
        return (law.clone(), v);
    }
    let g = curvature_factor(ball_radius, target_radius);
    let alpha = match law.loading.unwrap_or_default() {
        Loading::Power => law.alpha,
        Loading::Linear => 1.0,
    };
    let mut on = law.clone();
    on.k1 *= g;
    on.stiffness *= g;
    (on, v * g.powf(-(alpha + 1.5)))
}

/// The COR a ball meeting a target of radius `target_radius` at normal speed `v` returns
/// with ([`on_target`], then [`cor_at_speed`]): the rigid model's e.
pub fn cor_on_target(law: &BallLaw, v: f64, ball_radius: f64, target_radius: Option<f64>) -> f64 {
    let (on, v) = on_target(law, v, ball_radius, target_radius);
    cor_at_speed(&on, v)
}

/// The contact law of a ball (`law`, its radius `ball_radius`) that meets a target of
/// surface radius `target_radius` (`None`: flat) at normal speed `v` ([`on_target`]).
pub fn contact_law_on(
    law: &BallLaw,
    v: f64,
    ball_radius: f64,
    target_radius: Option<f64>,
) -> ContactLaw {
    let (on, v) = on_target(law, v, ball_radius, target_radius);
    ContactLaw::new(&on, v)
}

/// The cylinder anchor's flat-wall speed for the `mlb` ball (the 53.6-m/s test on a
/// cylinder of radius `cylinder_radius` strains the ball as a flat wall at this speed).
fn cylinder_anchor_speed(cylinder_radius: f64) -> f64 {
    let g = curvature_factor(DEFAULT_BALL_RADIUS, Some(cylinder_radius));
    CYLINDER_SPEED * g.powf(-(MLB_ALPHA + 1.5))
}

/// The `mlb` ball's COR curve e(v) = e₀ − (e₀ − e_spec) (v / v_spec)^q on a flat wall
/// through its three anchors (Cross's 1 m/s and the specification's 25.9 m/s, both flat;
/// the cylinder's 53.6 m/s at its flat-wall speed of equal strain, [`on_target`]): (e₀, q).
/// Three anchors, three parameters: the curve meets each exactly.
pub fn mlb_cor_curve() -> (f64, f64) {
    static CURVE: std::sync::OnceLock<(f64, f64)> = std::sync::OnceLock::new();
    *CURVE.get_or_init(|| cor_curve_through(TEST_CYLINDER_RADIUS))
}

/// [`mlb_cor_curve`] for a test cylinder of radius `cylinder_radius` (its uncertainty).
pub fn cor_curve_through(cylinder_radius: f64) -> (f64, f64) {
    let (low, high) = (
        CROSS_LOW_SPEED / MLB_SPEC_SPEED,
        cylinder_anchor_speed(cylinder_radius) / MLB_SPEC_SPEED,
    );
    // e₀ − e_spec as each outer anchor asks it at power q; they agree at the answer
    let from_low = |q: f64| (CROSS_LOW_SPEED_COR - MLB_SPEC_COR) / (1.0 - low.powf(q));
    let from_high = |q: f64| (MLB_SPEC_COR - CYLINDER_COR) / (high.powf(q) - 1.0);
    let gap = |q: f64| from_low(q) - from_high(q);
    let (mut a, mut b) = (0.01, 4.0);
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        if (gap(m) > 0.0) == (gap(a) > 0.0) {
            a = m;
        } else {
            b = m;
        }
    }
    let q = 0.5 * (a + b);
    (MLB_SPEC_COR + from_high(q), q)
}

/// The `mlb` ball's k₁ (N/m^α): a power-law loading F = k₁ s^α that gives the cylinder
/// test's dynamic stiffness. On a rigid target the peak force is the loading's at the
/// largest compression, where the loading work is the ball's kinetic energy, so
/// (F_peak / v)² / m = DS solves in closed form: k₁ = (DS m v²)^((α+1)/2) / C^α with
/// C = (α + 1) m v² / 2.
///
/// That is the k₁ the ball shows on the test cylinder; the law keeps a flat wall's, the
/// cylinder's over its [`curvature_factor`].
pub fn mlb_k1() -> f64 {
    let (m, v, a) = (MLB_MASS, CYLINDER_SPEED, MLB_ALPHA);
    let c = (a + 1.0) * m * v * v / 2.0;
    let on_cylinder = (CYLINDER_DYNAMIC_STIFFNESS * m * v * v).powf((a + 1.0) / 2.0) / c.powf(a);
    on_cylinder / curvature_factor(DEFAULT_BALL_RADIUS, Some(TEST_CYLINDER_RADIUS))
}

/// The ball's radius, m: a 9.125-in circumference, the middle of the rule book's 9–9.25 in
/// (the same ball as the flight's, `flight::BallProperties`).
pub const DEFAULT_BALL_RADIUS: f64 = 9.125 * 0.0254 / std::f64::consts::TAU;
/// The ball's moment of inertia over m r²: a uniform sphere's 2/5 (a baseball's layers,
/// cork and rubber inside wool and leather, are close to uniform in density).
pub const DEFAULT_INERTIA_FACTOR: f64 = 0.4;
/// Coefficient of friction between ball and bat (docs/physics.md, "Oblique impacts").
pub const DEFAULT_FRICTION: f64 = 0.2;
/// The contact patch's tangential stiffness over the ball's normal tangent stiffness dN/ds
/// (docs/physics.md, "Oblique impacts").
pub const DEFAULT_TANGENTIAL_RATIO: f64 = 0.27;

/// The law of a built-in ball.
pub fn preset_law(preset: BallPreset) -> BallLaw {
    match preset {
        BallPreset::Mlb => {
            let (at_rest, power) = mlb_cor_curve();
            BallLaw {
                kind: BallLawKind::SpeedDependent,
                cor: MLB_SPEC_COR,
                reference_speed: Some(MLB_SPEC_SPEED),
                cor_at_rest: Some(at_rest),
                cor_power: Some(power),
                loading: Some(Loading::Power),
                k1: mlb_k1(),
                alpha: MLB_ALPHA,
                curvature: Some(true),
                ..BallLaw::default()
            }
        }
    }
}

/// The wall COR the law gives a ball that meets the target at normal speed `v`, m/s:
/// `cor` for the fixed laws (the rigid model's e, also for `elastic`), the clamped line or
/// power curve for `speed_dependent`.
pub fn cor_at_speed(law: &BallLaw, v: f64) -> f64 {
    match law.kind {
        BallLawKind::SpeedDependent => {
            let reference = law.reference_speed.unwrap_or(DEFAULT_REFERENCE_SPEED);
            let x = v.max(0.0) / reference;
            let e = match (law.cor_exponent, law.cor_at_rest.zip(law.cor_power)) {
                (Some(gamma), _) => law.cor * x.powf(-gamma),
                (None, Some((at_rest, q))) => at_rest - (at_rest - law.cor) * x.powf(q),
                (None, None) => {
                    let slope = law.cor_slope.unwrap_or(DEFAULT_COR_SLOPE);
                    law.cor + slope * (v - reference)
                }
            };
            (e + law.cor_shift.unwrap_or(0.0)).clamp(COR_RANGE.0, COR_RANGE.1)
        }
        _ => law.cor,
    }
}

/// The ball's COR on a rigid wall at normal speed `v`: 1 for the elastic ball, else
/// [`cor_at_speed`].
pub fn wall_cor(law: &BallLaw, v: f64) -> f64 {
    match law.kind {
        BallLawKind::Elastic => 1.0,
        _ => cor_at_speed(law, v),
    }
}

/// Most integer exponents taken by multiplication (see [`power`]).
const MAX_INTEGER_EXPONENT: f64 = 64.0;

/// `x^e` for the laws' branches. An integer exponent (the paper's ball, e = 0.5, unloads with
/// p = 2/e² − 1 = 7; Nathan's with β = 9) is taken by repeated squaring: four times faster than
/// `powf`, which was a sixth of a collision's time, and the same bits on every CPU
/// (libm picks an FMA or a plain `pow` at run time). Accurate to a few ulp either way.
#[inline]
pub fn power(x: f64, e: f64) -> f64 {
    if e == e.trunc() && e.abs() <= MAX_INTEGER_EXPONENT {
        x.powi(e as i32)
    } else {
        x.powf(e)
    }
}

/// A force law F(s; s_max) ≥ 0 for compression s (> 0 in contact).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ContactLaw {
    /// Loading F = k s; unloading F = k s_max (s/s_max)^p, p = 2/e² − 1 (the paper's, with
    /// the unloading branch fixed by the COR).
    LinearHysteresis { stiffness: f64, exponent: f64 },
    /// Nathan (2000): loading F = k₁ s^α, unloading F = k₂ s^β, β = (1 + α)/e² − 1,
    /// k₂ = k₁ s_max^(α−β) by continuity at s_max.
    PowerLaw {
        k1: f64,
        alpha: f64,
        beta: f64,
        cor: f64,
    },
    /// F = k s both ways (no loss).
    Elastic { stiffness: f64 },
}

impl ContactLaw {
    /// The law a spec asks for, for a ball that meets the target at normal speed
    /// `approach` (m/s; only `speed_dependent` uses it: its loop is set once, at first
    /// contact, from the COR at that speed).
    pub fn new(law: &BallLaw, approach: f64) -> Self {
        let linear = |e: f64| Self::LinearHysteresis {
            stiffness: law.stiffness,
            exponent: 2.0 / (e * e) - 1.0,
        };
        let power = |e: f64| Self::PowerLaw {
            k1: law.k1,
            alpha: law.alpha,
            beta: (1.0 + law.alpha) / (e * e) - 1.0,
            cor: e,
        };
        match law.kind {
            BallLawKind::LinearHysteresis => linear(law.cor),
            BallLawKind::PowerLaw => power(law.cor),
            BallLawKind::Elastic => Self::Elastic {
                stiffness: law.stiffness,
            },
            BallLawKind::SpeedDependent => {
                let e = cor_at_speed(law, approach);
                match law.loading.unwrap_or_default() {
                    Loading::Linear => linear(e),
                    Loading::Power => power(e),
                }
            }
        }
    }

    /// Force at compression `s` after a largest compression `s_max` (0 when unloaded).
    pub fn force(&self, s: f64, s_max: f64) -> f64 {
        if s <= 0.0 {
            return 0.0;
        }
        match *self {
            Self::Elastic { stiffness } => stiffness * s,
            Self::LinearHysteresis {
                stiffness,
                exponent,
            } => {
                if s >= s_max {
                    stiffness * s
                } else {
                    stiffness * s_max * power(s / s_max, exponent)
                }
            }
            Self::PowerLaw {
                k1, alpha, beta, ..
            } => {
                if s >= s_max {
                    k1 * power(s, alpha)
                } else {
                    k1 * power(s_max, alpha) * power(s / s_max, beta)
                }
            }
        }
    }

    /// dF/ds at compression `s` (the branch that applies at s).
    pub fn tangent(&self, s: f64, s_max: f64) -> f64 {
        if s <= 0.0 {
            return 0.0;
        }
        match *self {
            Self::Elastic { stiffness } => stiffness,
            Self::LinearHysteresis {
                stiffness,
                exponent,
            } => {
                if s >= s_max {
                    stiffness
                } else {
                    stiffness * exponent * power(s / s_max, exponent - 1.0)
                }
            }
            Self::PowerLaw {
                k1, alpha, beta, ..
            } => {
                if s >= s_max {
                    k1 * alpha * power(s, alpha - 1.0)
                } else {
                    k1 * power(s_max, alpha - 1.0) * beta * power(s / s_max, beta - 1.0)
                }
            }
        }
    }

    /// Work done compressing the ball from 0 to `s` along the loading branch, J.
    pub fn loading_work(&self, s: f64) -> f64 {
        match *self {
            Self::Elastic { stiffness } | Self::LinearHysteresis { stiffness, .. } => {
                0.5 * stiffness * s * s
            }
            Self::PowerLaw { k1, alpha, .. } => k1 * power(s, alpha + 1.0) / (alpha + 1.0),
        }
    }

    /// Energy lost in one full loop that reached `s_max`, J: (1 − e²) of the loading work.
    pub fn loop_loss(&self, s_max: f64) -> f64 {
        let e2 = match *self {
            Self::Elastic { .. } => 1.0,
            Self::LinearHysteresis { exponent, .. } => 2.0 / (exponent + 1.0),
            Self::PowerLaw { cor, .. } => cor * cor,
        };
        (1.0 - e2) * self.loading_work(s_max)
    }

    /// Energy stored in the ball at compression `s` after largest compression `s_max`, J:
    /// the loading work up to s_max less what the unloading branch gives back down to s.
    pub fn stored_energy(&self, s: f64, s_max: f64) -> f64 {
        if s <= 0.0 {
            return 0.0;
        }
        if s >= s_max {
            return self.loading_work(s);
        }
        let given_back = match *self {
            Self::Elastic { stiffness } => 0.5 * stiffness * (s_max * s_max - s * s),
            Self::LinearHysteresis {
                stiffness,
                exponent,
            } => {
                stiffness * s_max * s_max / (exponent + 1.0)
                    * (1.0 - power(s / s_max, exponent + 1.0))
            }
            Self::PowerLaw {
                k1, alpha, beta, ..
            } => {
                k1 * power(s_max, alpha + 1.0) / (beta + 1.0) * (1.0 - power(s / s_max, beta + 1.0))
            }
        };
        self.loading_work(s_max) - given_back
    }

    /// Upper bound of the largest compression for an approach speed `v` and ball mass `m`:
    /// all the ball's kinetic energy stored on a rigid wall.
    pub fn wall_compression(&self, mass: f64, v: f64) -> f64 {
        let energy = 0.5 * mass * v * v;
        match *self {
            Self::Elastic { stiffness } | Self::LinearHysteresis { stiffness, .. } => {
                (2.0 * energy / stiffness).sqrt()
            }
            Self::PowerLaw { k1, alpha, .. } => {
                (energy * (alpha + 1.0) / k1).powf(1.0 / (alpha + 1.0))
            }
        }
    }

    /// Largest tangent stiffness met in a collision at approach speed `v` (bounded by the
    /// rigid-wall compression), N/m: sets the contact's time scale and stability limits.
    pub fn max_tangent(&self, mass: f64, v: f64) -> f64 {
        let s = self.wall_compression(mass, v);
        // just below s_max on the unloading branch, and at s_max on the loading one
        self.tangent(s, s * (1.0 + 1e-12)).max(self.tangent(s, 0.0))
    }

    /// Force and its tangent dF/ds together (one `powf`).
    pub fn force_and_tangent(&self, s: f64, s_max: f64) -> (f64, f64) {
        if s <= 0.0 {
            return (0.0, 0.0);
        }
        match *self {
            Self::Elastic { stiffness } => (stiffness * s, stiffness),
            Self::LinearHysteresis {
                stiffness,
                exponent,
            } => {
                if s >= s_max {
                    (stiffness * s, stiffness)
                } else {
                    let x = s / s_max;
                    let r = power(x, exponent - 1.0);
                    (stiffness * s_max * r * x, stiffness * exponent * r)
                }
            }
            Self::PowerLaw {
                k1, alpha, beta, ..
            } => {
                let (base, exponent, x, scale) = if s >= s_max {
                    (k1, alpha, s, 1.0)
                } else {
                    (k1 * power(s_max, alpha), beta, s / s_max, 1.0 / s_max)
                };
                let r = power(x, exponent - 1.0);
                (base * r * x, base * exponent * r * scale)
            }
        }
    }

    /// Solve F = f(S0 − C F) for the force (C > 0): the implicit contact equation of one
    /// step. Returns (F, s). h(s) = s + C f(s) − S0 increases in s, with its root in (0, S0];
    /// safeguarded Newton from the guess `s_guess`.
    pub fn solve_implicit(&self, s0: f64, c: f64, s_max: f64, s_guess: f64) -> (f64, f64) {
        if s0 <= 0.0 {
            return (0.0, s0);
        }
        match *self {
            Self::Elastic { stiffness } => {
                let s = s0 / (1.0 + c * stiffness);
                return (stiffness * s, s);
            }
            Self::LinearHysteresis { stiffness, .. } => {
                // on the loading line the equation is linear
                let s = s0 / (1.0 + c * stiffness);
                if s >= s_max {
                    return (stiffness * s, s);
                }
            }
            Self::PowerLaw { .. } => {}
        }
        let (mut lo, mut hi) = (0.0, s0);
        let mut s = if s_guess > 0.0 && s_guess < s0 {
            s_guess
        } else {
            s0
        };
        let mut f = 0.0;
        for _ in 0..100 {
            let (force, tangent) = self.force_and_tangent(s, s_max);
            f = force;
            let h = s + c * force - s0;
            if h > 0.0 {
                hi = s;
            } else {
                lo = s;
            }
            let mut next = s - h / (1.0 + c * tangent);
            if !(next > lo && next < hi) {
                next = 0.5 * (lo + hi);
            }
            if (next - s).abs() <= 1e-14 * s0 {
                break;
            }
            s = next;
        }
        (f, s)
    }
}

/// Exit speed of a ball fired at `speed` into a rigid, immovable wall: the ball's own
/// equation m s̈ = −F(s) integrated with small velocity-Verlet steps (independent of the
/// bat integrators). Returns the rebound speed (positive = away from the wall).
pub fn wall_rebound_speed(law: &ContactLaw, mass: f64, speed: f64) -> f64 {
    let s_peak = law.wall_compression(mass, speed);
    let steps_per_contact = 200_000.0;
    let dt = 4.0 * s_peak / speed / steps_per_contact;
    let (mut s, mut v, mut s_max) = (0.0f64, speed, 0.0f64);
    let mut a = 0.0;
    for _ in 0..(20.0 * steps_per_contact) as usize {
        v += 0.5 * dt * a;
        s += dt * v;
        let f = law.force(s, s_max);
        s_max = s_max.max(s);
        a = -f / mass;
        v += 0.5 * dt * a;
        if s <= 0.0 && v < 0.0 {
            break;
        }
    }
    -v
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn branches_meet_at_s_max() {
        let law = ContactLaw::new(
            &BallLaw {
                kind: BallLawKind::PowerLaw,
                ..BallLaw::default()
            },
            40.0,
        );
        let s_max = 0.01;
        let below = law.force(s_max * (1.0 - 1e-12), s_max);
        assert!((below / law.force(s_max, s_max) - 1.0).abs() < 1e-9);
    }

    #[test]
    fn implicit_solve_satisfies_its_equation() {
        let law = ContactLaw::new(&BallLaw::default(), 40.0);
        let (f, s) = law.solve_implicit(0.01, 1e-8, 0.012, 0.0);
        assert!((s + 1e-8 * f - 0.01).abs() < 1e-15);
        assert!((law.force(s, 0.012) - f).abs() < 1e-9 * f);
    }

    /// `power` against exact rational arithmetic: for x = k/16 (exact in binary) and an
    /// integer n, x^n = kⁿ/16ⁿ is exactly representable when kⁿ < 2⁵³, so the only error is
    /// the algorithm's; repeated squaring must stay within a few ulp of it (IEEE 754 products
    /// are correctly rounded, and n ≤ 15 takes at most 7 of them). Non-integer exponents
    /// must give `powf`'s bits.
    #[test]
    fn power_is_exact_to_a_few_ulp() {
        for k in 1u64..16 {
            let mut tested = 0;
            let x = k as f64 / 16.0;
            for n in 0i32..=15 {
                let Some(kn) = k.checked_pow(n as u32).filter(|&p| p < 1 << 53) else {
                    continue; // kⁿ not exact in f64
                };
                let exact = kn as f64 / 16f64.powi(n); // a power of two: exact
                let got = power(x, n as f64);
                let ulp = exact * f64::EPSILON;
                assert!(
                    (got - exact).abs() <= 4.0 * ulp,
                    "{x}^{n}: {got} vs {exact}"
                );
                tested += 1;
            }
            assert!(tested >= 13, "k = {k}: {tested} exponents");
        }
        for e in [0.5, 1.5, 6.999_999, 8.000_001, 65.0, -0.25] {
            assert_eq!(power(0.37, e).to_bits(), 0.37f64.powf(e).to_bits());
        }
    }
}
