//! The rule sets built in (`rules: ncaa_bbcor`, `rules: mlb_wood`) as constraints, each
//! with its source; and the certification protocol's BBCOR of a candidate bat.
//!
//! - NCAA / NFHS (BBCOR bats, since 2011 / 2012): BBCOR ≤ 0.50 at the barrel's maximum, the
//!   bat at rest pivoted 6 in from the knob (NCAA announcement of 16 Sep 2008, the BBCOR
//!   standard's pass/fail criteria); a length-to-weight difference of at most 3 units ("a bat
//!   may not weigh, numerically, more than three units less than the length", NCAA Rule
//!   1-12(b)(5); NFHS 1-3-2): weight (oz) − length (in) ≥ −3; barrel diameter ≤ 2 5/8 in
//!   (NCAA Rule 1-12, NFHS 1-3-2); a moment of inertia about the 6-in point at least the
//!   minimum of the bat's length class (the BBCOR standard's table, which the study gives:
//!   `moi_min`, kg·m²).
//! - MLB (Official Baseball Rules 3.02(a)): "a smooth, round stick not more than 2.61 inches
//!   in diameter at the thickest part and not more than 42 inches in length", one piece of
//!   solid wood (checked when the study is loaded: no shell, bore or fill).

use super::quantity::{BatQuantity, Quantity};
use crate::model::measures::metrics::{protocol_scan, BbcorShot, ScanPoint};
use crate::model::measures::sweet::find_maximum;
use crate::model::outcome::{BatProperties, RuleCheck, SOLID_WOOD_CHECK};
use crate::model::spec::BatSpec;
use crate::model::spec::CollisionSpec;
use crate::model::Target;
use crate::study::optimize_block::{Aggregate, RuleSet};
use rayon::prelude::*;

pub use crate::model::units::{INCH, OUNCE};

/// A constraint: `quantity` (aggregated by `over`) within [min, max].
#[derive(Debug, Clone, PartialEq)]
pub struct Limit {
    pub quantity: Quantity,
    pub min: Option<f64>,
    pub max: Option<f64>,
    pub over: Aggregate,
    /// Where the limit comes from (a rule book), or `study` for the study's own.
    pub source: String,
}

impl Limit {
    /// A label, e.g. `bat.bbcor <= 0.5`.
    pub fn label(&self) -> String {
        let name = self.quantity.name();
        match (
            self.min.map(bound_text),
            self.max.map(bound_text),
            self.over,
        ) {
            (None, Some(b), Aggregate::Quantile(p)) => return format!("P({name} <= {b}) >= {p}"),
            (Some(a), None, Aggregate::UpperQuantile(p)) => {
                return format!("P({name} >= {a}) >= {p}")
            }
            _ => {}
        }
        match (self.min.map(bound_text), self.max.map(bound_text)) {
            (Some(a), Some(b)) => format!("{a} <= {name} <= {b}"),
            (Some(a), None) => format!("{name} >= {a}"),
            (None, Some(b)) => format!("{name} <= {b}"),
            (None, None) => name.to_string(),
        }
    }

    /// How far inside its bounds a value is, in the quantity's units (negative: outside).
    pub fn margin(&self, value: f64) -> f64 {
        let lo = self.min.map_or(f64::INFINITY, |a| value - a);
        let hi = self.max.map_or(f64::INFINITY, |b| b - value);
        if value.is_nan() {
            return f64::NAN;
        }
        lo.min(hi)
    }

    /// The scale a violation is measured in for the penalty: the bound's magnitude.
    pub fn scale(&self) -> f64 {
        let b = self.max.or(self.min).unwrap_or(1.0).abs();
        if b > 0.0 {
            b
        } else {
            1.0
        }
    }
}

/// The swing law's measured range as two limits on the swing weight (the moment of inertia
/// about the 6-in point within `SWING_LAW_MOI6`): a search whose batter answers to each
/// bat's moment of inertia keeps its candidates where the law was measured, and its report
/// shows how far inside they are.
pub fn swing_law_limits() -> [Limit; 2] {
    let [lo, hi] = crate::model::spec::SWING_LAW_MOI6;
    let source = "the swing law's measured range";
    [
        bat_limit(BatQuantity::MomentOfInertiaKnob6, Some(lo), None, source),
        bat_limit(BatQuantity::MomentOfInertiaKnob6, None, Some(hi), source),
    ]
}

fn bat_limit(q: BatQuantity, min: Option<f64>, max: Option<f64>, source: &str) -> Limit {
    Limit {
        quantity: Quantity::Bat(q),
        min,
        max,
        over: if max.is_some() {
            Aggregate::Max
        } else {
            Aggregate::Min
        },
        source: source.to_string(),
    }
}

/// A bound as a label shows it: to 9 decimals, trailing zeros dropped, so that a bound in
/// inches converted to metres (2.625 in = 0.066675 m) reads as its value, not as the float
/// noise of the conversion (0.06667499999999999).
fn bound_text(x: f64) -> String {
    let s = format!("{x:.9}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    match s {
        "-0" => "0".into(),
        _ => s.into(),
    }
}

/// The limits of a rule set (`moi_min`: the NCAA minimum moment of inertia about the 6-in
/// point, kg·m²).
pub fn rule_limits(rules: RuleSet, moi_min: Option<f64>) -> Vec<Limit> {
    const NCAA: &str = "NCAA BBCOR standard (2011), NCAA Rule 1-12, NFHS Rule 1-3-2";
    const MLB: &str = "Official Baseball Rules 3.02(a)";
    match rules {
        RuleSet::NcaaBbcor => {
            let mut v = vec![
                bat_limit(BatQuantity::Bbcor, None, Some(0.50), NCAA),
                bat_limit(BatQuantity::Drop, Some(-3.0), None, NCAA),
                bat_limit(BatQuantity::BarrelDiameter, None, Some(2.625 * INCH), NCAA),
            ];
            if let Some(m) = moi_min {
                v.push(bat_limit(
                    BatQuantity::MomentOfInertiaKnob6,
                    Some(m),
                    None,
                    NCAA,
                ));
            }
            v
        }
        RuleSet::MlbWood => vec![
            bat_limit(BatQuantity::BarrelDiameter, None, Some(2.61 * INCH), MLB),
            bat_limit(BatQuantity::Length, None, Some(42.0 * INCH), MLB),
        ],
    }
}

/// Every rule set built in, in the order a bat card shows them.
pub const RULE_SETS: [RuleSet; 2] = [RuleSet::NcaaBbcor, RuleSet::MlbWood];

/// A rule set's name in a study file.
pub fn rule_set_name(rules: RuleSet) -> &'static str {
    match rules {
        RuleSet::NcaaBbcor => "ncaa_bbcor",
        RuleSet::MlbWood => "mlb_wood",
    }
}

/// A bat against every limit of every rule set built in (without the study's `moi_min`,
/// which depends on the length class): the bat card's verdicts. MLB's "one piece of solid
/// wood" is a check of its own, valued 1 (yes) or 0 (no). A bat's BBCOR is the maximum of
/// its protocol scan (`properties.metrics`).
pub fn rule_checks(p: &BatProperties, spec: &BatSpec) -> Vec<RuleCheck> {
    let mut out = Vec::new();
    for rules in RULE_SETS {
        let name = rule_set_name(rules);
        for limit in rule_limits(rules, None) {
            let Quantity::Bat(q) = limit.quantity else {
                continue;
            };
            let value = q.of(p);
            out.push(RuleCheck {
                label: format!("{name}: {}", limit.label()),
                units: limit.quantity.units().to_string(),
                value,
                margin: limit.margin(value),
            });
        }
        if rules == RuleSet::MlbWood {
            let value = if spec.is_solid_wood() { 1.0 } else { 0.0 };
            out.push(RuleCheck {
                label: format!("{name}: {SOLID_WOOD_CHECK}"),
                units: "1".into(),
                value,
                margin: value - 1.0,
            });
        }
    }
    out
}

/// A scan's collisions (`metrics::ScanMap`) on every core of the current pool, each value
/// computed alone: the same whatever the threads.
pub fn parallel_scan(z: &[f64], f: &ScanPoint) -> Vec<[f64; 2]> {
    z.par_iter().map(|&z| f(z)).collect()
}

/// The BBCOR protocol on a candidate (`metrics::bbcor_scan_mapped`, the one scan `/bat` stores
/// too): `spec`'s bat, ball (at 136 mph, no spin, head-on) and hoop, the bat at rest and free
/// (Nathan 2000: a pivot does not change barrel impacts, and ASTM F2219 evaluates the bat
/// unconstrained); the largest BBCOR along the barrel, parabola-refined. NaN for a rigid
/// target or if no collision of the scan succeeds.
pub fn protocol_bbcor(spec: &CollisionSpec, target: &Target) -> f64 {
    protocol(spec, target, false)[0]
}

/// [`protocol_bbcor`], and with `with_stress` the wall's largest stress ratio under the
/// scan's shots (`metrics::protocol_scan`; NaN without it).
pub fn protocol(spec: &CollisionSpec, target: &Target, with_stress: bool) -> [f64; 2] {
    let Some(bat) = target.bat() else {
        return [f64::NAN; 2];
    };
    let shot = BbcorShot::of(spec);
    match protocol_scan(
        bat,
        &spec.bat,
        &spec.numerics,
        &shot,
        &parallel_scan,
        with_stress,
    ) {
        Ok(scan) => [
            find_maximum(&scan.z, &scan.bbcor).map_or(f64::NAN, |m| m.1),
            scan.wall_stress_ratio
                .iter()
                .copied()
                .fold(f64::NAN, f64::max),
        ],
        Err(_) => [f64::NAN; 2],
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn labels_show_bounds_without_conversion_noise() {
        let limits = super::rule_limits(crate::study::optimize_block::RuleSet::NcaaBbcor, None);
        let labels: Vec<String> = limits.iter().map(|l| l.label()).collect();
        assert!(
            labels.iter().any(|l| l.ends_with("<= 0.066675")),
            "{labels:?}"
        );
        assert!(labels.iter().any(|l| l.ends_with("<= 0.5")), "{labels:?}");
        assert!(labels.iter().any(|l| l.ends_with(">= -3")), "{labels:?}");
    }

    use super::*;

    #[test]
    fn margins_are_inside_positive() {
        let l = bat_limit(BatQuantity::Bbcor, None, Some(0.5), "x");
        assert!((l.margin(0.48) - 0.02).abs() < 1e-15);
        assert!(l.margin(0.51) < 0.0);
        let l = bat_limit(BatQuantity::Drop, Some(-3.0), None, "x");
        assert_eq!(l.margin(-2.0), 1.0);
        assert_eq!(l.label(), "bat.drop >= -3");
        assert_eq!(rule_limits(RuleSet::MlbWood, None).len(), 2);
        assert_eq!(rule_limits(RuleSet::NcaaBbcor, Some(0.1)).len(), 4);
    }
}
