//! The air a batted ball flies through: density from temperature, pressure, elevation and
//! humidity (the formula of Nathan's trajectory calculator), and the wind.

use super::error::{check_range, FlightError};

/// Density of dry air at 0 °C and 760 mmHg, kg/m³ (the calculator's ρ₀).
const DRY_AIR_DENSITY_STP: f64 = 1.2929;
/// 0 °C in kelvin.
const ZERO_CELSIUS_K: f64 = 273.15;
/// Standard sea-level pressure, Pa (760 mmHg = 29.92 inHg, the calculator's default).
pub const STANDARD_PRESSURE_PA: f64 = 101_325.0;
/// The calculator's barometric decay with elevation, 1/m: p(h) = p_sea·exp(−βh), an isothermal
/// atmosphere with an 8.2 km scale height.
pub const PRESSURE_DECAY_PER_M: f64 = 1.217e-4;
/// Water vapour is lighter than air: its partial pressure e removes (1 − 0.622)·e from the
/// "dry-air equivalent" pressure (0.622 = M_water / M_air).
const VAPOUR_DEFICIT: f64 = 0.3783;

/// Kelvin from degrees Fahrenheit (the calculator's input unit).
pub fn fahrenheit_to_kelvin(f: f64) -> f64 {
    (f - 32.0) * 5.0 / 9.0 + ZERO_CELSIUS_K
}

/// Kelvin from degrees Celsius.
pub fn celsius_to_kelvin(c: f64) -> f64 {
    c + ZERO_CELSIUS_K
}

/// The atmosphere of a ballpark. Defaults are those of Nathan's trajectory calculator (sea
/// level, 70 °F, 50 % relative humidity, 29.92 inHg, no wind), the conditions its aerodynamic
/// constants were quoted for, so a default flight is the calculator's default flight.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Atmosphere {
    /// Air temperature, K. Default 294.26 K (70 °F = 21.1 °C).
    pub temperature_k: f64,
    /// Barometric pressure reduced to sea level, Pa, as weather reports give it; the
    /// elevation lowers it to the field's pressure. Default 101 325 Pa (29.92 inHg).
    pub sea_level_pressure_pa: f64,
    /// Elevation of the field above sea level, m. Default 0 (Coors Field: about 1 580 m).
    pub elevation_m: f64,
    /// Relative humidity, 0–1. Default 0.5.
    pub relative_humidity: f64,
    /// The air's velocity over the ground, m/s, uniform at all heights, in the flight frame:
    /// x horizontal toward the first-base (right-field) side, y horizontal toward centre
    /// field, z up. A tail wind to centre field is `[0, +w, 0]`. Default: no wind.
    pub wind_m_s: [f64; 3],
}

impl Default for Atmosphere {
    fn default() -> Self {
        Atmosphere {
            temperature_k: fahrenheit_to_kelvin(70.0),
            sea_level_pressure_pa: STANDARD_PRESSURE_PA,
            elevation_m: 0.0,
            relative_humidity: 0.5,
            wind_m_s: [0.0; 3],
        }
    }
}

/// Saturation vapour pressure of water over liquid water, Pa, at `celsius`: Buck's
/// equation (A. L. Buck, J. Appl. Meteorol. 20, 1527 (1981), as revised in 1996):
/// 611.21·exp((18.678 − T/234.5)·T/(257.14 + T)). The calculator writes the same equation in
/// mmHg with 4.5841 and 18.687 (a transposition of Buck's 18.678); at 21 °C that changes
/// the density by 4 parts in a million.
pub fn saturation_vapour_pressure_pa(celsius: f64) -> f64 {
    611.21 * ((18.678 - celsius / 234.5) * celsius / (257.14 + celsius)).exp()
}

impl Atmosphere {
    /// Checks every field: temperature 150–400 K, pressure 0–200 kPa, elevation −500 to
    /// 10 000 m, relative humidity 0–1, every wind component finite and within ±100 m/s.
    pub fn validate(&self) -> Result<(), FlightError> {
        check_range(
            "atmosphere.temperature_k",
            self.temperature_k,
            150.0,
            400.0,
            "[150, 400] K",
        )?;
        check_range(
            "atmosphere.sea_level_pressure_pa",
            self.sea_level_pressure_pa,
            0.0,
            200_000.0,
            "[0, 200000] Pa",
        )?;
        check_range(
            "atmosphere.elevation_m",
            self.elevation_m,
            -500.0,
            10_000.0,
            "[-500, 10000] m",
        )?;
        check_range(
            "atmosphere.relative_humidity",
            self.relative_humidity,
            0.0,
            1.0,
            "[0, 1]",
        )?;
        for w in self.wind_m_s {
            check_range("atmosphere.wind_m_s", w, -100.0, 100.0, "[-100, 100] m/s")?;
        }
        Ok(())
    }

    /// Air density, kg/m³, by the calculator's formula
    /// ρ = 1.2929·(273.15/T)·(p_sea·exp(−βh) − 0.3783·RH·SVP(T))/101 325 Pa:
    /// the ideal-gas density of dry air at 0 °C and 760 mmHg, scaled to the temperature and
    /// to the field's pressure, less the lighter water vapour. Sea level, 70 °F, 50 %:
    /// 1.1945 kg/m³.
    pub fn air_density(&self) -> Result<f64, FlightError> {
        self.validate()?;
        let celsius = self.temperature_k - ZERO_CELSIUS_K;
        let field_pressure =
            self.sea_level_pressure_pa * (-PRESSURE_DECAY_PER_M * self.elevation_m).exp();
        let vapour = self.relative_humidity * saturation_vapour_pressure_pa(celsius);
        let density = DRY_AIR_DENSITY_STP
            * (ZERO_CELSIUS_K / self.temperature_k)
            * (field_pressure - VAPOUR_DEFICIT * vapour)
            / STANDARD_PRESSURE_PA;
        if density < 0.0 {
            return Err(FlightError::NegativeDensity { density });
        }
        Ok(density)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The formula's anchor: dry air at 0 °C and 760 mmHg is ρ₀ = 1.2929 kg/m³.
    #[test]
    fn dry_air_at_zero_celsius_and_one_atmosphere_is_rho_zero() {
        let atm = Atmosphere {
            temperature_k: ZERO_CELSIUS_K,
            relative_humidity: 0.0,
            ..Atmosphere::default()
        };
        assert!((atm.air_density().unwrap() - 1.2929).abs() < 1e-12);
    }

    /// Elevation enters only as exp(−βh) on the dry part.
    #[test]
    fn elevation_scales_dry_density_by_the_barometric_factor() {
        let sea = Atmosphere {
            relative_humidity: 0.0,
            ..Atmosphere::default()
        };
        let high = Atmosphere {
            elevation_m: 1600.0,
            ..sea
        };
        let ratio = high.air_density().unwrap() / sea.air_density().unwrap();
        assert!((ratio - (-1.217e-4 * 1600.0f64).exp()).abs() < 1e-12);
    }

    /// Buck's SVP is 611.21 Pa at 0 °C and 3.17 kPa at 25 °C (steam tables: 3.169 kPa).
    #[test]
    fn saturation_vapour_pressure_matches_steam_tables() {
        assert!((saturation_vapour_pressure_pa(0.0) - 611.21).abs() < 1e-9);
        assert!((saturation_vapour_pressure_pa(25.0) - 3169.0).abs() < 5.0);
    }

    /// Humid air is lighter than dry air at the same temperature and pressure.
    #[test]
    fn humidity_lowers_density() {
        let dry = Atmosphere {
            relative_humidity: 0.0,
            ..Atmosphere::default()
        };
        let wet = Atmosphere {
            relative_humidity: 1.0,
            ..dry
        };
        assert!(wet.air_density().unwrap() < dry.air_density().unwrap());
    }

    #[test]
    fn nan_and_out_of_range_inputs_are_errors() {
        let nan = Atmosphere {
            temperature_k: f64::NAN,
            ..Atmosphere::default()
        };
        assert!(matches!(
            nan.air_density(),
            Err(FlightError::OutOfRange {
                name: "atmosphere.temperature_k",
                ..
            })
        ));
        let humid = Atmosphere {
            relative_humidity: 1.5,
            ..Atmosphere::default()
        };
        assert!(humid.air_density().is_err());
        let vacuum_humid = Atmosphere {
            sea_level_pressure_pa: 0.0,
            ..Atmosphere::default()
        };
        assert!(matches!(
            vacuum_humid.air_density(),
            Err(FlightError::NegativeDensity { .. })
        ));
    }
}
