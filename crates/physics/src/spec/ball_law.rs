//! The ball's force law as a study writes it (`ball.law`), and the built-in balls' names:
//! the types `ball` computes with. Their field names are the public interface of study files.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Built-in balls: force laws calibrated on tests of the ball alone (docs/physics.md,
/// "The calibrated ball").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum BallPreset {
    /// An MLB baseball: `speed_dependent` and seeing the target's curvature, its COR falling
    /// with the ball's strain from its value at rest through Cross's 0.64 at 1 m/s and the
    /// rule book's 0.546 at 25.9 m/s (flat) and 36 game balls' 0.492 on a cylinder at
    /// 53.6 m/s; a power-law loading with Nathan's (2000) α 1.84 and the k₁ that gives those
    /// balls' dynamic stiffness (docs/physics.md, "The calibrated ball").
    Mlb,
}

/// Kinds of ball force law.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum BallLawKind {
    /// The paper's: loading F = k s; unloading F = k s_max (s/s_max)^p, p = 2/e² − 1.
    #[default]
    LinearHysteresis,
    /// Nathan (2000): loading F = k₁ s^α, unloading k₂ s^β, β = (1 + α)/e² − 1.
    PowerLaw,
    /// Linear spring F = k s without loss (the paper's Fig. 7b).
    Elastic,
    /// A ball whose wall COR falls with speed, as measured baseballs' does:
    /// e(v) = cor + cor_slope (v − reference_speed), clamped to [0.05, 1], at the normal
    /// speed v the ball meets at first contact; loading `linear` (stiffness) or `power`
    /// (k1, alpha), unloading as `linear_hysteresis` or `power_law` with that e.
    SpeedDependent,
}

/// Loading branch of the `speed_dependent` law.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Loading {
    /// F = k s with k = `stiffness` (the paper's loading).
    #[default]
    Linear,
    /// F = k₁ s^α with `k1`, `alpha` (Nathan 2000's).
    Power,
}

/// The ball's force law. One flat record so that any field can be swept whatever the kind;
/// fields a kind does not use are ignored by it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct BallLaw {
    /// Which law. Default `linear_hysteresis`.
    #[serde(default)]
    pub kind: BallLawKind,
    /// Loading stiffness k in N/m (`linear_hysteresis`, `elastic`). Default 7e5 (the paper).
    #[serde(default = "default_stiffness")]
    pub stiffness: f64,
    /// Coefficient of restitution on a rigid wall, 0 < e ≤ 1 (`linear_hysteresis`,
    /// `power_law`; also the rigid model's e). Default 0.5 (docs/physics.md: baseball e₀ ≈ 0.5).
    #[serde(default = "default_cor")]
    pub cor: f64,
    /// Loading coefficient k₁ in N/m^α (`power_law`). Default 6.53e7 (Nathan 2000).
    #[serde(default = "default_k1")]
    pub k1: f64,
    /// Loading exponent α (`power_law`). Default 1.84 (Nathan 2000).
    #[serde(default = "default_alpha")]
    pub alpha: f64,
    /// `speed_dependent`: the normal impact speed in m/s at which the wall COR is `cor`.
    /// Default 25.9 (85 ft/s, the speed of the MLB ball specification's wall test).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reference_speed: Option<f64>,
    /// `speed_dependent`: change of the wall COR per m/s of normal impact speed, 1/(m/s),
    /// usually negative. Default −0.001 (docs/physics.md, "The ball").
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cor_slope: Option<f64>,
    /// `speed_dependent`: `linear` (uses `stiffness`) or `power` (uses `k1`, `alpha`).
    /// Default `linear`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub loading: Option<Loading>,
    /// `speed_dependent`: the COR as a power of the speed instead of a line,
    /// e(v) = cor (v / reference_speed)^(−cor_exponent), so that it rises toward low speed
    /// as measured balls' does. Exclusive with `cor_slope`. Default none (the line).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cor_exponent: Option<f64>,
    /// `speed_dependent`: the COR as v → 0 of a curve that falls from it as a power of the
    /// speed, e(v) = cor_at_rest − (cor_at_rest − cor) (v / reference_speed)^cor_power: flat
    /// at low speed, falling faster at high speed, as measured balls' does. Set with
    /// `cor_power`; exclusive with `cor_slope` and `cor_exponent`. Default none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cor_at_rest: Option<f64>,
    /// `speed_dependent`: the power of that curve (> 0). Default none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cor_power: Option<f64>,
    /// `speed_dependent`: whether the law sees the curvature of what the ball meets (the
    /// `mlb` ball does). Then `k1` (or `stiffness`) is a flat wall's, scaled on a target of
    /// radius R across the ball's path (a cylinder, a bat's barrel) by Hertz's
    /// (R / (R_b + R))^(1/4), and the COR curve is read at the flat-wall speed that strains
    /// the ball as much (the peak contact strain √(s_max / R_e) of a rigid target):
    /// v (R / (R_b + R))^(−(α + 1.5)/4). Default false (one law for every target).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub curvature: Option<bool>,
    /// `speed_dependent`: a shift added to the COR at every speed: one ball (or lot) livelier
    /// or deader than the curve's, the whole curve moved in parallel. Default 0. The `mlb`
    /// ball's measured ball-to-ball SD is `ball::MLB_COR_SD` (0.005).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cor_shift: Option<f64>,
    /// Coefficient of friction between ball and bat (oblique impacts and spin). Default:
    /// docs/physics.md, "Oblique impacts".
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub friction: Option<f64>,
    /// Tangential stiffness of the contact patch (Cross's tangential compliance: how far the
    /// patch shears before it slides) over the ball's normal tangent stiffness dN/ds at the
    /// same compression (Mindlin: both grow with the patch). Default: docs/physics.md,
    /// "Oblique impacts".
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tangential_ratio: Option<f64>,
}

impl Default for BallLaw {
    fn default() -> Self {
        Self {
            kind: BallLawKind::default(),
            stiffness: default_stiffness(),
            cor: default_cor(),
            k1: default_k1(),
            alpha: default_alpha(),
            reference_speed: None,
            cor_slope: None,
            loading: None,
            cor_exponent: None,
            cor_at_rest: None,
            cor_power: None,
            cor_shift: None,
            curvature: None,
            friction: None,
            tangential_ratio: None,
        }
    }
}

fn default_stiffness() -> f64 {
    7.0e5
}
fn default_cor() -> f64 {
    0.5
}
fn default_k1() -> f64 {
    6.53e7
}
fn default_alpha() -> f64 {
    1.84
}
