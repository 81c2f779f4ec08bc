//! The quantities an objective or a constraint names: a `/summary` variable, a sweet-spot
//! quantity along `impact_z` (`sweet_spot.NAME`), or a bat's (`bat.NAME`, including the
//! certification protocol's BBCOR); their units, and how a grid of values becomes one.

use crate::model::outcome::BatProperties;
use crate::store::layout::SUMMARY_FLOATS;
use crate::study::optimize_block::Aggregate;

/// A sweet-spot quantity of each curve along `impact_z`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Sweet {
    Position,
    ExitSpeed,
    /// The largest lab-frame exit speed along the barrel (with a `batter`, the one that
    /// compares bats swung at different speeds).
    ExitSpeedLab,
    Width,
    Carry,
    CarryPosition,
}

/// A bat's quantity.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BatQuantity {
    Mass,
    Length,
    CentreOfMass,
    MomentOfInertia,
    MomentOfInertiaKnob6,
    MomentOfInertiaKnob,
    /// Twice the largest outer radius, m.
    BarrelDiameter,
    /// Weight in ounces minus length in inches (the rule book's "drop").
    Drop,
    /// The BBCOR protocol's BBCOR: the study's ball at 136 mph on the bat at rest, the
    /// maximum along the barrel (`crate::optimize::rules`).
    Bbcor,
    /// The wall's largest stress ratio under the BBCOR protocol's shots
    /// (`metrics::protocol_scan`): 1 where it would dent or crack.
    WallStressRatio,
}

/// A quantity by name.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Quantity {
    /// Index into `store::layout::SUMMARY_FLOATS`.
    Summary(usize),
    Sweet(Sweet),
    Bat(BatQuantity),
}

impl BatQuantity {
    /// Its value for a bat (the BBCOR: the protocol's maximum `/bat` stores, NaN before the
    /// scan has run).
    pub fn of(self, p: &BatProperties) -> f64 {
        match self {
            BatQuantity::Mass => p.mass,
            BatQuantity::Length => p.length,
            BatQuantity::CentreOfMass => p.z_cm,
            BatQuantity::MomentOfInertia => p.moment_of_inertia,
            BatQuantity::MomentOfInertiaKnob6 => p.moment_of_inertia_knob6,
            BatQuantity::MomentOfInertiaKnob => p.moment_of_inertia_knob(),
            BatQuantity::BarrelDiameter => p.barrel_diameter(),
            BatQuantity::Drop => p.drop(),
            BatQuantity::Bbcor => p.metrics.bbcor_max,
            BatQuantity::WallStressRatio => p.metrics.wall_stress_ratio,
        }
    }
}

const SWEET: &[(&str, Sweet, &str)] = &[
    ("sweet_spot.position", Sweet::Position, "m"),
    ("sweet_spot.exit_speed", Sweet::ExitSpeed, "m/s"),
    ("sweet_spot.exit_speed_lab", Sweet::ExitSpeedLab, "m/s"),
    ("sweet_spot.width", Sweet::Width, "m"),
    ("sweet_spot.carry", Sweet::Carry, "m"),
    ("sweet_spot.carry_position", Sweet::CarryPosition, "m"),
];

const BAT: &[(&str, BatQuantity, &str)] = &[
    ("bat.mass", BatQuantity::Mass, "kg"),
    ("bat.length", BatQuantity::Length, "m"),
    ("bat.z_cm", BatQuantity::CentreOfMass, "m"),
    (
        "bat.moment_of_inertia",
        BatQuantity::MomentOfInertia,
        "kg m^2",
    ),
    (
        "bat.moment_of_inertia_knob6",
        BatQuantity::MomentOfInertiaKnob6,
        "kg m^2",
    ),
    (
        "bat.moment_of_inertia_knob",
        BatQuantity::MomentOfInertiaKnob,
        "kg m^2",
    ),
    ("bat.barrel_diameter", BatQuantity::BarrelDiameter, "m"),
    ("bat.drop", BatQuantity::Drop, "1"),
    ("bat.bbcor", BatQuantity::Bbcor, "1"),
    ("bat.wall_stress_ratio", BatQuantity::WallStressRatio, "1"),
];

impl Quantity {
    /// The quantity a name means, if any.
    pub fn parse(name: &str) -> Option<Quantity> {
        if let Some(k) = SUMMARY_FLOATS.iter().position(|d| d.name == name) {
            return Some(Quantity::Summary(k));
        }
        let sweet = SWEET
            .iter()
            .find(|s| s.0 == name)
            .map(|s| Quantity::Sweet(s.1));
        sweet.or_else(|| BAT.iter().find(|b| b.0 == name).map(|b| Quantity::Bat(b.1)))
    }

    /// Every name, for messages.
    pub fn names() -> Vec<&'static str> {
        let mut v: Vec<&str> = SUMMARY_FLOATS.iter().map(|d| d.name).collect();
        v.extend(SWEET.iter().map(|s| s.0));
        v.extend(BAT.iter().map(|b| b.0));
        v
    }

    /// Its name.
    pub fn name(&self) -> &'static str {
        match self {
            Quantity::Summary(k) => SUMMARY_FLOATS[*k].name,
            Quantity::Sweet(s) => SWEET.iter().find(|x| x.1 == *s).expect("listed").0,
            Quantity::Bat(b) => BAT.iter().find(|x| x.1 == *b).expect("listed").0,
        }
    }

    /// Its units (UDUNITS spelling).
    pub fn units(&self) -> &'static str {
        match self {
            Quantity::Summary(k) => SUMMARY_FLOATS[*k].units,
            Quantity::Sweet(s) => SWEET.iter().find(|x| x.1 == *s).expect("listed").2,
            Quantity::Bat(b) => BAT.iter().find(|x| x.1 == *b).expect("listed").2,
        }
    }
}

/// The grid's values as one number: `over` of the finite values (NaN if there are none).
pub fn aggregate(values: &[f64], over: Aggregate) -> f64 {
    let finite = values.iter().copied().filter(|v| v.is_finite());
    let n = finite.clone().count();
    if n == 0 {
        return f64::NAN;
    }
    match over {
        Aggregate::Mean => finite.sum::<f64>() / n as f64,
        Aggregate::Min => finite.fold(f64::INFINITY, f64::min),
        Aggregate::Max => finite.fold(f64::NEG_INFINITY, f64::max),
        Aggregate::Quantile(q) => order_statistic(finite, n, fraction_count(q, n)),
        Aggregate::UpperQuantile(p) => order_statistic(finite, n, n + 1 - fraction_count(p, n)),
    }
}

/// ⌈q n⌉ within 1..=n: how many of n values make at least a fraction q of them. The product
/// is rounded to 12 digits first, so that 0.95 × 20 counts 19, not 20.
fn fraction_count(q: f64, n: usize) -> usize {
    let qn = (q * n as f64 * 1e12).round() / 1e12;
    (qn.ceil() as usize).clamp(1, n)
}

/// The k-th smallest (1-based) of n values.
fn order_statistic(values: impl Iterator<Item = f64>, n: usize, k: usize) -> f64 {
    let mut v: Vec<f64> = values.collect();
    v.sort_by(f64::total_cmp);
    v[k.clamp(1, n) - 1]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip() {
        for n in Quantity::names() {
            assert_eq!(Quantity::parse(n).unwrap().name(), n);
        }
        assert!(Quantity::parse("exit_sped").is_none());
        assert_eq!(aggregate(&[1.0, f64::NAN, 3.0], Aggregate::Mean), 2.0);
        assert_eq!(aggregate(&[1.0, 3.0], Aggregate::Min), 1.0);
        assert!(aggregate(&[f64::NAN], Aggregate::Max).is_nan());
    }

    /// The quantiles by their definitions, counted: Q(q) is the smallest value with at least
    /// a fraction q of the values at or below it, the upper one the largest with at least a
    /// fraction p at or above it; so P(X ≤ b) ≥ p exactly when Q(p) ≤ b, and P(X ≥ a) ≥ p
    /// exactly when the upper quantile is ≥ a.
    #[test]
    fn quantiles_are_what_they_count() {
        let mut seed = 0x2545_F491_u64;
        for n in 1..40usize {
            let values: Vec<f64> = (0..n)
                .map(|_| {
                    seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1);
                    ((seed >> 33) % 17) as f64 // ties on purpose
                })
                .collect();
            for p in [0.05, 0.1, 0.5, 0.9, 0.95, 1.0, 1.0 / 3.0] {
                let share = |f: &dyn Fn(f64) -> bool| {
                    values.iter().filter(|&&x| f(x)).count() as f64 / n as f64
                };
                let q = aggregate(&values, Aggregate::Quantile(p));
                assert!(share(&|x| x <= q) >= p - 1e-12, "n {n} p {p}");
                for &b in values.iter().filter(|&&b| b < q) {
                    assert!(share(&|x| x <= b) < p - 1e-12, "n {n} p {p}: {b} would do");
                }
                let u = aggregate(&values, Aggregate::UpperQuantile(p));
                assert!(share(&|x| x >= u) >= p - 1e-12, "n {n} p {p}");
                for &a in values.iter().filter(|&&a| a > u) {
                    assert!(share(&|x| x >= a) < p - 1e-12, "n {n} p {p}: {a} would do");
                }
            }
        }
    }
}
