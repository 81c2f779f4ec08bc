//! The batter and the batted ball's flight: the parts of a study that go beyond one
//! collision. Field names are public interface; units SI.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// A batter whose swing answers to the bat: the bat turns about `pivot` with an angular
/// speed that scales as the bat's moment of inertia about that point to the power −n,
/// Ω = Ω_ref (I_ref / I)^n, Ω_ref = `bat_speed` / (`bat_speed_at` − `pivot`). Measured
/// exponents: 0.27 (Cross & Bower 2006), 0.25 pooled over players from 0.08 to 0.37
/// (Smith, Broker & Nathan 2003), 0.29 ± 0.04 (Nathan, Crisco, Greenwald, Russell &
/// Smith 2011, about the knob). With a batter the collision's `ball.speed`,
/// `swing.omega` and `swing.cm_speed` follow from it (docs/physics.md, "The batter"), and
/// a study may not set `swing.omega` or `swing.cm_speed` itself.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct BatterSpec {
    /// Lab-frame speed of the pitch toward the batter at contact, m/s, arriving along the
    /// bat's path (an "on plane" swing). Required unless a `pitch` block gives the pitch
    /// (then it must be left out).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pitch_speed: Option<f64>,
    /// The batter's swing speed with the reference bat: the lab speed of the point
    /// `bat_speed_at` of that bat at contact, m/s.
    pub bat_speed: f64,
    /// Where on the reference bat `bat_speed` is measured, m from the knob. Default 0.7112
    /// (28 in: Crisco et al. 2002 quote swing speeds at 28 in; bat sensors and Statcast
    /// measure about 6 in from the tip of a 34-in bat, the same point).
    #[serde(default = "default_bat_speed_at")]
    pub bat_speed_at: f64,
    /// The reference bat's moment of inertia about `pivot`, kg·m² (a results file's
    /// `/bat/moment_of_inertia_knob` gives a bat's about its knob; docs/study-files.md
    /// lists the presets').
    pub reference_moi: f64,
    /// Exponent n of Ω ∝ I^(−n). Default 0.27 (Cross & Bower 2006; 0 = every bat swung at
    /// the same Ω).
    #[serde(default = "default_exponent")]
    pub exponent: f64,
    /// The point the swing turns about at contact, m from the knob. Default 0 (the knob:
    /// Nathan et al. 2011 found the instantaneous axis of rotation at impact near it).
    #[serde(default)]
    pub pivot: f64,
}

/// The swing weights the swing law was measured near: moments of inertia about the point
/// 6 in from the knob, kg·m², of the bats real batters swing, 5 000–11 000 oz·in²: adult
/// baseball bats 8 000–10 000 oz·in², light fast-pitch bats down to about 5 000 (Washington
/// State University's Sports Science Laboratory, read), a 34-in BBCOR bat 11 000 (a bat
/// maker's figure, second-hand). The measurements' own spans were not found in a primary
/// source (docs/physics.md, "The batter"); outside this span the law is extrapolated.
pub const SWING_LAW_MOI6: [f64; 2] = [
    5000.0 * crate::units::OUNCE_SQUARE_INCH,
    11000.0 * crate::units::OUNCE_SQUARE_INCH,
];

/// Why the swing law is extrapolated for a bat of this moment of inertia about the 6-in
/// point (kg·m²), or `None` within [`SWING_LAW_MOI6`].
pub fn swing_law_extrapolated(moment_of_inertia_knob6: f64) -> Option<String> {
    let [lo, hi] = SWING_LAW_MOI6;
    let oz_in2 = |i: f64| i / crate::units::OUNCE_SQUARE_INCH;
    (moment_of_inertia_knob6.is_finite() && !(lo..=hi).contains(&moment_of_inertia_knob6)).then(
        || {
            format!(
                "its swing weight, {:.3} kg m^2 ({:.0} oz in^2) about the 6-in point, lies outside \
                 the {:.0}-{:.0} oz in^2 of the bats the swing-speed law was measured with: its \
                 swing speed is extrapolated",
                moment_of_inertia_knob6,
                oz_in2(moment_of_inertia_knob6),
                oz_in2(lo),
                oz_in2(hi)
            )
        },
    )
}

/// The pitch as it reaches the bat, in the lab: its speed and the two angles of its path,
/// independent of the swing's (docs/physics.md, "The geometry of a swing"). Without this
/// block the pitch arrives along the bat's path (`batter.pitch_speed`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PitchSpec {
    /// The pitch's speed at contact, m/s (about 92 % of its release speed: a pitch loses
    /// about 8 % to drag on its way to the plate).
    pub speed: f64,
    /// The angle of the pitch's path below the horizontal at contact, rad, positive for a
    /// falling pitch (measured fastballs about 0.09–0.12, curveballs up to about 0.21).
    /// Default 0.
    #[serde(default, skip_serializing_if = "super::is_zero")]
    pub descent_angle: f64,
    /// The angle of the pitch's path from straight toward the catcher, seen from above,
    /// rad, positive when it moves toward the first-base side. Default 0.
    #[serde(default, skip_serializing_if = "super::is_zero")]
    pub horizontal_angle: f64,
}

fn default_bat_speed_at() -> f64 {
    0.7112
}
fn default_exponent() -> f64 {
    0.27
}

/// The batted ball's flight through the air to the ground, with Nathan's drag, lift and
/// spin decay fitted to Statcast (docs/physics.md, "Flight"). Every field has the default
/// of Nathan's trajectory calculator, so `flight: {}` flies the calculator's standard day.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FlightSpec {
    /// Air temperature, K. Default 294.26 (70 °F).
    #[serde(default = "default_temperature")]
    pub temperature: f64,
    /// Barometric pressure reduced to sea level, Pa, as weather reports give it. Default
    /// 101 325 (29.92 inHg).
    #[serde(default = "default_pressure")]
    pub pressure: f64,
    /// Elevation of the field above sea level, m. Default 0 (Coors Field: about 1 580).
    #[serde(default)]
    pub elevation: f64,
    /// Relative humidity, 0–1. Default 0.5.
    #[serde(default = "default_humidity")]
    pub humidity: f64,
    /// Wind speed over the ground, m/s, horizontal and uniform. Default 0.
    #[serde(default)]
    pub wind_speed: f64,
    /// Where the wind blows to, rad from straight-away centre field, positive toward the
    /// first-base (right-field) side. Default 0 (blowing out to centre field).
    #[serde(default)]
    pub wind_direction: f64,
    /// Height of the contact point above the ground, m. Default 0.9144 (3 ft, the
    /// calculator's).
    #[serde(default = "default_height")]
    pub height: f64,
}

impl Default for FlightSpec {
    fn default() -> Self {
        Self {
            temperature: default_temperature(),
            pressure: default_pressure(),
            elevation: 0.0,
            humidity: default_humidity(),
            wind_speed: 0.0,
            wind_direction: 0.0,
            height: default_height(),
        }
    }
}

fn default_temperature() -> f64 {
    crate::flight::fahrenheit_to_kelvin(70.0)
}
fn default_pressure() -> f64 {
    crate::flight::air::STANDARD_PRESSURE_PA
}
fn default_humidity() -> f64 {
    0.5
}
fn default_height() -> f64 {
    crate::flight::DEFAULT_CONTACT_HEIGHT_M
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_swing_laws_span_is_the_trades_in_si() {
        // 1 oz in^2 = 0.028349523125 kg × 0.0254² m² (the avoirdupois ounce and the inch)
        let oz_in2 = 0.028349523125 * 0.0254 * 0.0254;
        assert!((SWING_LAW_MOI6[0] - 5000.0 * oz_in2).abs() < 1e-15);
        assert!((SWING_LAW_MOI6[1] - 0.2012).abs() < 1e-4);
        // the R161 (0.1905 kg m^2 about 6 in) is inside; a 1 000 kg/m^3 R161 (0.2935) is not
        assert!(swing_law_extrapolated(0.1905).is_none());
        let why = swing_law_extrapolated(0.2935).unwrap();
        assert!(why.contains("(16047 oz in^2)"), "{why}");
        assert!(swing_law_extrapolated(f64::NAN).is_none());
    }
}
