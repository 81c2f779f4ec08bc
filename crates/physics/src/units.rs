//! The trade's units, in SI: rule books and bat makers state lengths in inches, weights in
//! ounces and swing weights in ounce-square-inches; tracking states speeds in mph and spins
//! in rpm. Each SI unit's others (`units_of`), and a value written with one (`to_si`).

/// One mile per hour, m/s.
pub const MPH: f64 = 0.447_04;
/// One inch, m.
pub const INCH: f64 = 0.0254;
/// One ounce (avoirdupois), kg.
pub const OUNCE: f64 = 0.028349523125;
/// One ounce-square-inch, kg·m² (a swing weight's unit in the trade).
pub const OUNCE_SQUARE_INCH: f64 = OUNCE * INCH * INCH;
/// One foot, m.
pub const FOOT: f64 = 0.3048;
/// One pound (avoirdupois), kg.
pub const POUND: f64 = 0.453_592_37;
/// One pound-force, N (the standard gravity's pound: 0.45359237 kg × 9.80665 m/s²).
pub const POUND_FORCE: f64 = POUND * 9.806_65;
/// One degree of angle, rad.
pub const DEGREE: f64 = std::f64::consts::PI / 180.0;
/// One revolution per minute, rad/s.
pub const RPM: f64 = std::f64::consts::PI / 30.0;
/// One inch of mercury, Pa (NIST SP 811, at 0 °C).
pub const INCH_OF_MERCURY: f64 = 3386.389;

/// A unit a value may be written in: `SI = x · factor + offset`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Unit {
    /// The suffix that names it (`in`, `mph`, `rpm`, `F`).
    pub suffix: &'static str,
    pub factor: f64,
    pub offset: f64,
}

const fn unit(suffix: &'static str, factor: f64) -> Unit {
    Unit {
        suffix,
        factor,
        offset: 0.0,
    }
}

/// The units a quantity of SI unit `si` (UDUNITS spelling, as the study's parameter table
/// gives it) may be written in, SI's own first; empty for a unit the trade writes no other way.
pub fn units_of(si: &str) -> &'static [Unit] {
    const LENGTH: &[Unit] = &[
        unit("m", 1.0),
        unit("ft", FOOT),
        unit("in", INCH),
        unit("mm", 1e-3),
        unit("cm", 1e-2),
    ];
    const MASS: &[Unit] = &[
        unit("kg", 1.0),
        unit("oz", OUNCE),
        unit("lb", POUND),
        unit("g", 1e-3),
    ];
    const SPEED: &[Unit] = &[
        unit("m/s", 1.0),
        unit("mph", MPH),
        unit("ft/s", FOOT),
        unit("km/h", 1.0 / 3.6),
    ];
    const ANGLE: &[Unit] = &[unit("rad", 1.0), unit("deg", DEGREE)];
    const ANGULAR_SPEED: &[Unit] = &[unit("rad/s", 1.0), unit("rpm", RPM)];
    const PRESSURE: &[Unit] = &[unit("Pa", 1.0), unit("inHg", INCH_OF_MERCURY)];
    const TEMPERATURE: &[Unit] = &[
        unit("K", 1.0),
        Unit {
            suffix: "F",
            factor: 5.0 / 9.0,
            offset: 459.67 * 5.0 / 9.0,
        },
        Unit {
            suffix: "C",
            factor: 1.0,
            offset: 273.15,
        },
    ];
    const MOMENT_OF_INERTIA: &[Unit] = &[unit("kg m^2", 1.0), unit("oz in^2", OUNCE_SQUARE_INCH)];
    match si {
        "m" => LENGTH,
        "kg" => MASS,
        "m/s" => SPEED,
        "rad" => ANGLE,
        "rad/s" => ANGULAR_SPEED,
        "Pa" => PRESSURE,
        "K" => TEMPERATURE,
        "kg m^2" => MOMENT_OF_INERTIA,
        _ => &[],
    }
}

/// Every SI unit [`units_of`] gives others for.
pub const SI_UNITS: &[&str] = &["m", "kg", "m/s", "rad", "rad/s", "Pa", "K", "kg m^2"];

/// Whether `suffix` names a unit of some quantity (`in`, `mph`), not a word of text.
pub fn is_unit_suffix(suffix: &str) -> bool {
    SI_UNITS
        .iter()
        .any(|si| units_of(si).iter().any(|u| u.suffix == suffix))
}

/// A number followed by a unit's suffix (`34in`, `90 mph`, `-3.5deg`, `70F`): the number and
/// the suffix, or None for text that is not a number with a suffix (a bare number included).
pub fn split_quantity(text: &str) -> Option<(f64, &str)> {
    let t = text.trim();
    let end = t
        .char_indices()
        .find(|&(i, c)| {
            c.is_alphabetic() && !(matches!(c, 'e' | 'E') && exponent_at(t, i))
                || c == '%'
                || c == '°'
        })
        .map(|(i, _)| i)?;
    let number = t[..end].trim().parse::<f64>().ok()?;
    let suffix = t[end..].trim();
    (!suffix.is_empty() && number.is_finite()).then_some((number, suffix))
}

/// Whether an `e` at byte `i` of `t` is a number's exponent (`1e-3`): a digit before it and
/// a digit or sign after it.
fn exponent_at(t: &str, i: usize) -> bool {
    let before = t[..i]
        .chars()
        .last()
        .is_some_and(|c| c.is_ascii_digit() || c == '.');
    let after = t[i + 1..].chars().next();
    before && after.is_some_and(|c| c.is_ascii_digit() || c == '-' || c == '+')
}

/// `text` (a number with a suffix) in SI, for a quantity of SI unit `si`; or why not: the
/// suffixes that quantity takes.
pub fn to_si(text: &str, si: &str) -> Result<f64, String> {
    let (x, suffix) =
        split_quantity(text).ok_or_else(|| format!("`{text}` is not a number with a unit"))?;
    let units = units_of(si);
    units
        .iter()
        .find(|u| u.suffix == suffix)
        .map(|u| x * u.factor + u.offset)
        .ok_or_else(|| match units.is_empty() {
            true => format!("a quantity in {si} takes no unit suffix: write the number in {si}"),
            false => format!(
                "`{suffix}` is not a unit of this quantity ({si}); allowed: {}",
                suffixes(units)
            ),
        })
}

/// The suffixes of `units`, for a message: `m, in, ft, mm, cm`.
pub fn suffixes(units: &[Unit]) -> String {
    units
        .iter()
        .map(|u| u.suffix)
        .collect::<Vec<_>>()
        .join(", ")
}

/// For a bare number `x` outside [min, max] in SI unit `si`: the trade's unit that puts it
/// inside, if one does (34 as a bat's length is 34 in); of several, the first in the table,
/// whose order is the trade's (feet before inches: 5280 as an elevation is feet, 34 as a
/// bat's length too large in feet and so inches).
pub fn meant_unit(x: f64, si: &str, min: f64, max: f64) -> Option<&'static Unit> {
    meant_of(units_of(si), x, min, max)
}

/// [`meant_unit`] among `units` (SI's first).
pub fn meant_of(units: &[Unit], x: f64, min: f64, max: f64) -> Option<&Unit> {
    units
        .iter()
        .skip(1)
        .find(|u| (min..=max).contains(&(x * u.factor + u.offset)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quantities_split_into_a_number_and_a_suffix() {
        assert_eq!(split_quantity("34in"), Some((34.0, "in")));
        assert_eq!(split_quantity(" 90 mph "), Some((90.0, "mph")));
        assert_eq!(split_quantity("-3.5deg"), Some((-3.5, "deg")));
        assert_eq!(split_quantity("1e-3m"), Some((1e-3, "m")));
        assert_eq!(split_quantity("2.5e2 rpm"), Some((250.0, "rpm")));
        assert_eq!(split_quantity("0.75"), None);
        assert_eq!(split_quantity("r161"), None);
        assert_eq!(split_quantity("in"), None);
    }

    #[test]
    fn conversions_are_the_definitions() {
        // NIST SP 811: 1 in = 0.0254 m exactly, 1 oz = 28.349523125 g, 1 mph = 0.44704 m/s
        assert_eq!(to_si("34in", "m").unwrap(), 34.0 * 0.0254);
        assert_eq!(to_si("32oz", "kg").unwrap(), 32.0 * 0.028349523125);
        assert_eq!(to_si("100mph", "m/s").unwrap(), 44.704);
        assert!((to_si("212F", "K").unwrap() - 373.15).abs() < 1e-12);
        assert!((to_si("180deg", "rad").unwrap() - std::f64::consts::PI).abs() < 1e-15);
        assert!(to_si("34oz", "m")
            .unwrap_err()
            .contains("allowed: m, ft, in, mm, cm"));
        assert!(to_si("3in", "Hz")
            .unwrap_err()
            .contains("takes no unit suffix"));
        assert_eq!(
            meant_unit(34.0, "m", 0.4, 1.5).map(|u| u.suffix),
            Some("in")
        );
        assert!(meant_unit(1e6, "m", 0.4, 1.5).is_none());
        assert_eq!(
            meant_unit(5280.0, "m", -100.0, 4000.0).map(|u| u.suffix),
            Some("ft")
        );
        assert_eq!(meant_unit(3.0, "m", 0.0, 2.5).map(|u| u.suffix), Some("ft"));
    }
}
