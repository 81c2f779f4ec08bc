//! `batstudy card`: what each bat of a results file *is*, as the trade states it: length,
//! weight and drop, balance point, swing weights, BBCOR with the ball that made it, the sweet
//! zone, the lowest bending and hoop frequencies, and the margin to each rule. Read from
//! `/bat`; strings made safe for a terminal.

use super::error::{H5Ctx, StoreError};
use super::inspect::shot_name;
use super::layout as l;
use super::read::{open_checked, shown};
use crate::results::printable;
use batstudy_physics::outcome::SOLID_WOOD_CHECK;
use batstudy_physics::units::{INCH, OUNCE, OUNCE_SQUARE_INCH, POUND_FORCE};
use hdf5::types::VarLenUnicode;
use std::fmt::Write as _;
use std::path::Path;

/// One limit of a rule set, applied to one bat.
#[derive(Debug, Clone, PartialEq)]
pub struct CardRule {
    pub label: String,
    pub units: String,
    pub value: f64,
    pub margin: f64,
}

impl CardRule {
    /// The rule set it belongs to (`ncaa_bbcor`, `mlb_wood`).
    pub fn rule_set(&self) -> &str {
        self.label.split(':').next().unwrap_or("")
    }

    /// The value in the trade's unit beside SI (`0.066660 m` is 2.624 in), or nothing.
    fn trade_value(&self) -> String {
        match self.units.as_str() {
            "m" => format!(" ({:.3} in)", self.value / INCH),
            "kg m^2" | "kg m2" => format!(" ({:.0} oz in^2)", self.value / OUNCE_SQUARE_INCH),
            "kg" => format!(" ({:.2} oz)", self.value / OUNCE),
            _ => String::new(),
        }
    }
}

impl BatCard {
    /// Whether a rule set is for this bat: a rule set for wood bats alone (one with the
    /// solid-wood check) is not for a bat that fails that check; every other rule set is.
    pub fn rule_set_applies(&self, rule_set: &str) -> bool {
        !self.rules.iter().any(|r| {
            r.rule_set() == rule_set && r.label.ends_with(SOLID_WOOD_CHECK) && r.value != 1.0
        })
    }

    /// The limits of the rule sets that are for this bat.
    pub fn applicable_rules(&self) -> impl Iterator<Item = &CardRule> {
        self.rules
            .iter()
            .filter(|r| self.rule_set_applies(r.rule_set()))
    }

    /// The rule sets that are not for this bat, once each.
    pub fn rule_sets_not_for(&self) -> Vec<&str> {
        let mut sets: Vec<&str> = self
            .rules
            .iter()
            .map(CardRule::rule_set)
            .filter(|set| !self.rule_set_applies(set))
            .collect();
        sets.dedup();
        sets
    }
}

/// A bat's card, SI (as `/bat` stores it).
#[derive(Debug, Clone, PartialEq)]
pub struct BatCard {
    pub label: String,
    pub length: f64,
    pub mass: f64,
    pub drop: f64,
    /// The centre of mass, m from the knob.
    pub balance_point: f64,
    pub moment_of_inertia_knob: f64,
    pub moment_of_inertia_knob6: f64,
    pub barrel_diameter: f64,
    pub bbcor_max: f64,
    pub bbcor_max_position: f64,
    /// The ball and hoop of the BBCOR scan, in a few words.
    pub bbcor_shot: String,
    pub sweet_zone_start: f64,
    pub sweet_zone_end: f64,
    /// The lowest free–free bending mode, Hz.
    pub bending_frequency: f64,
    pub hoop_mode_frequency: f64,
    /// The barrel compression (force at 0.040 in, 6 in from the end), N (NaN without a
    /// shell barrel, or in a file written before it was stored).
    pub barrel_compression: f64,
    /// The wall's largest stress ratio under the BBCOR scan's shots, and where, m (NaN
    /// without a shell barrel, or in a file written before it was stored).
    pub wall_stress_ratio: f64,
    pub wall_stress_ratio_position: f64,
    /// The best collision efficiency in the field's convention at the field's reference
    /// swing, and where, m from the knob (NaN in files before layout 7).
    pub best_q: f64,
    pub best_q_position: f64,
    pub rules: Vec<CardRule>,
}

/// The first layout version whose `/bat` holds every quantity of a card.
const CARD_LAYOUT: u32 = 6;

/// Every bat's card, in the file's order.
pub fn bat_cards(path: &Path) -> Result<Vec<BatCard>, StoreError> {
    let (f, _, version) = open_checked(path)?;
    if version < CARD_LAYOUT {
        return Err(StoreError::BadFile {
            path: path.to_path_buf(),
            what: format!(
                "it has layout version {version}: a bat card needs version {CARD_LAYOUT} or later \
                 (run the study again with this batstudy)"
            ),
        });
    }
    let g = f.group(l::GROUP_BAT).ctx(path, "open group bat")?;
    let floats = |name: &str| -> Result<Vec<f64>, StoreError> {
        g.dataset(name)
            .and_then(|d| d.read_raw::<f64>())
            .ctx(path, &format!("read /bat/{name}"))
    };
    let texts = |name: &str| -> Result<Vec<String>, StoreError> {
        g.dataset(name)
            .and_then(|d| d.read_raw::<VarLenUnicode>())
            .map(|v| v.iter().map(shown).collect())
            .ctx(path, &format!("read /bat/{name}"))
    };
    let labels = texts(l::BAT_DIM.name)?;
    let n = labels.len();
    let column = |name: &str| -> Result<Vec<f64>, StoreError> {
        let mut v = floats(name)?;
        v.resize(n, f64::NAN);
        Ok(v)
    };
    let [length, mass, drop, zcm, moi6, diameter, bbcor, bbcor_z, start, end, hoop] = [
        l::BAT_LENGTH.name,
        l::BAT_MASS.name,
        l::BAT_DROP.name,
        l::BAT_Z_CM.name,
        l::BAT_MOI6.name,
        l::BAT_BARREL_DIAMETER.name,
        l::BAT_BBCOR_MAX.name,
        l::BAT_BBCOR_MAX_POS.name,
        l::BAT_SWEET_ZONE_START.name,
        l::BAT_SWEET_ZONE_END.name,
        l::BAT_HOOP_MODE_FREQ.name,
    ]
    .map(column);
    let moi_knob = column(l::BAT_MOI_KNOB.name)?;
    // layout 7 added the best q: an older file's card shows it unknown
    let optional = |name: &str| {
        column(name)
            .ok()
            .filter(|_| version >= 7)
            .unwrap_or_else(|| vec![f64::NAN; n])
    };
    let (best_q, best_q_z) = (
        optional(l::BAT_BEST_Q.name),
        optional(l::BAT_BEST_Q_POS.name),
    );
    let compression = optional(l::BAT_BARREL_COMPRESSION.name);
    let stress = optional(l::BAT_WALL_STRESS_RATIO.name);
    let stress_z = optional(l::BAT_WALL_STRESS_POS.name);
    let modes = floats(l::BAT_MODE_FREQ.name)?;
    let per = modes.len().checked_div(n).unwrap_or(0);
    let shots = texts(l::BAT_BBCOR_SHOT.name)?;
    let rule_labels = texts(l::RULE_CHECK_DIM.name)?;
    let rule_units = texts(l::BAT_RULE_UNITS.name)?;
    let (values, margins) = (
        floats(l::BAT_RULE_VALUE.name)?,
        floats(l::BAT_RULE_MARGIN.name)?,
    );
    let (length, mass, drop, zcm, moi6, diameter) = (length?, mass?, drop?, zcm?, moi6?, diameter?);
    let (bbcor, bbcor_z, start, end, hoop) = (bbcor?, bbcor_z?, start?, end?, hoop?);
    let nr = rule_labels.len();
    Ok((0..n)
        .map(|i| BatCard {
            label: labels[i].clone(),
            length: length[i],
            mass: mass[i],
            drop: drop[i],
            balance_point: zcm[i],
            moment_of_inertia_knob: moi_knob[i],
            moment_of_inertia_knob6: moi6[i],
            barrel_diameter: diameter[i],
            bbcor_max: bbcor[i],
            bbcor_max_position: bbcor_z[i],
            bbcor_shot: shots.get(i).map_or(String::new(), |j| shot_name(j)),
            sweet_zone_start: start[i],
            sweet_zone_end: end[i],
            bending_frequency: if per > 0 { modes[i * per] } else { f64::NAN },
            hoop_mode_frequency: hoop[i],
            barrel_compression: compression[i],
            wall_stress_ratio: stress[i],
            wall_stress_ratio_position: stress_z[i],
            best_q: best_q[i],
            best_q_position: best_q_z[i],
            rules: (0..nr)
                .map(|k| CardRule {
                    label: rule_labels[k].clone(),
                    units: rule_units.get(k).cloned().unwrap_or_default(),
                    value: values.get(i * nr + k).copied().unwrap_or(f64::NAN),
                    margin: margins.get(i * nr + k).copied().unwrap_or(f64::NAN),
                })
                .collect(),
        })
        .collect())
}

/// The cards as text for a terminal: SI first, the trade's units beside.
pub fn render(cards: &[BatCard]) -> String {
    let mut s = String::new();
    for (i, c) in cards.iter().enumerate() {
        if i > 0 {
            s.push('\n');
        }
        render_one(c, &mut s);
    }
    s
}

fn render_one(c: &BatCard, s: &mut String) {
    let inch = |m: f64| m / INCH;
    let _ = writeln!(s, "{}", printable(&c.label, false));
    let mut row = |name: &str, text: String| {
        let _ = writeln!(s, "  {name:<19}{text}");
    };
    row(
        "length",
        format!("{:.4} m  ({:.2} in)", c.length, inch(c.length)),
    );
    row(
        "mass",
        format!(
            "{:.4} kg  ({:.2} oz, drop {:+.2})",
            c.mass,
            c.mass / OUNCE,
            c.drop
        ),
    );
    row(
        "balance point",
        format!(
            "{:.4} m  ({:.2} in) from the knob",
            c.balance_point,
            inch(c.balance_point)
        ),
    );
    for (name, moi) in [
        ("MOI about knob", c.moment_of_inertia_knob),
        ("MOI about 6 in", c.moment_of_inertia_knob6),
    ] {
        row(
            name,
            format!("{moi:.4} kg m^2  ({:.0} oz in^2)", moi / OUNCE_SQUARE_INCH),
        );
    }
    row(
        "barrel diameter",
        format!(
            "{:.5} m  ({:.3} in)",
            c.barrel_diameter,
            inch(c.barrel_diameter)
        ),
    );
    row(
        "BBCOR",
        format!(
            "{:.4} at {:.4} m ({:.2} in), {}",
            c.bbcor_max,
            c.bbcor_max_position,
            inch(c.bbcor_max_position),
            printable(&c.bbcor_shot, false)
        ),
    );
    let zone = c.sweet_zone_end - c.sweet_zone_start;
    row(
        "sweet zone",
        format!(
            "{:.4} m ({:.2} in), {:.4}-{:.4} m from the knob: BBCOR within 0.01 of its peak",
            zone,
            inch(zone),
            c.sweet_zone_start,
            c.sweet_zone_end
        ),
    );
    row(
        "bending mode 1",
        format!("{:.0} Hz (free-free)", c.bending_frequency),
    );
    let hoop = if c.hoop_mode_frequency.is_finite() {
        format!(
            "{:.0} Hz (the barrel wall's lowest breathing mode)",
            c.hoop_mode_frequency
        )
    } else {
        "none (a solid bat)".to_string()
    };
    row("hoop mode", hoop);
    if c.barrel_compression.is_finite() {
        row(
            "barrel compression",
            format!(
                "{:.0} lbf at 0.040 in ({:.0} N; {:.0} lbf per 0.050 in), 6 in from the end: the static squeeze of the trade's testers",
                c.barrel_compression / POUND_FORCE,
                c.barrel_compression,
                c.barrel_compression * 1.25 / POUND_FORCE
            ),
        );
    }
    if c.wall_stress_ratio.is_finite() {
        row(
            "wall stress",
            format!(
                "{:.2} of its strength at {:.3} m ({:.1} in) under the BBCOR shot: {}",
                c.wall_stress_ratio,
                c.wall_stress_ratio_position,
                c.wall_stress_ratio_position / INCH,
                if c.wall_stress_ratio > 1.0 {
                    "the certification's impact would dent or crack it there"
                } else {
                    "within it everywhere along the barrel"
                }
            ),
        );
    }
    row(
        "best q",
        format!(
            "{:.4} at {:.4} m ({:.2} in): exit = q pitch + (1 + q) bat speed 6 in from the end, 70-mph swing, 82-mph pitch",
            c.best_q,
            c.best_q_position,
            inch(c.best_q_position)
        ),
    );
    render_rules(c, s);
}

/// The card's rules: each limit of the rule sets for the bat with its margin and verdict,
/// and the rule sets that are not for it.
fn render_rules(c: &BatCard, s: &mut String) {
    let _ = writeln!(
        s,
        "  rules (margin: how far inside the limit; negative breaks it)"
    );
    for r in c.applicable_rules() {
        let verdict = if r.margin >= 0.0 {
            "passes"
        } else if r.margin < 0.0 {
            "FAILS"
        } else {
            "unknown"
        };
        let _ = writeln!(
            s,
            "    {:<46} {:>12.6} {:<7} margin {:>+12.6}  {verdict}{}",
            printable(&r.label, false),
            r.value,
            printable(&r.units, false),
            r.margin,
            r.trade_value()
        );
    }
    for set in c.rule_sets_not_for() {
        let _ = writeln!(
            s,
            "    {:<46} not for this bat: a rule set for bats of {SOLID_WOOD_CHECK}",
            format!("{}:", printable(set, false))
        );
    }
}

/// The cards as one table, a row per bat, in the trade's units (`batstudy compare`): the bats'
/// numbers side by side, each bat's rules as how many of those for it (a wood-bat rule set is
/// not for a hollow bat) it keeps, and the first it breaks.
pub fn render_table(cards: &[BatCard]) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{:>3} {:>7} {:>6} {:>7} {:>8} {:>8} {:>6} {:>7} {:>6} {:>6} {:>6} {:>6} {:>5}  bat",
        "#",
        "oz",
        "drop",
        "bal.in",
        "knob",
        "6in",
        "diam",
        "BBCOR",
        "best q",
        "zone",
        "bend",
        "hoop",
        "rules"
    );
    let _ = writeln!(
        s,
        "{:>3} {:>7} {:>6} {:>7} {:>8} {:>8} {:>6} {:>7} {:>6} {:>6} {:>6} {:>6} {:>5}",
        "", "", "", "", "oz in^2", "oz in^2", "in", "", "", "in", "Hz", "Hz", "kept"
    );
    for (i, c) in cards.iter().enumerate() {
        let applicable: Vec<&CardRule> = c.applicable_rules().collect();
        let kept = applicable.iter().filter(|r| r.margin >= 0.0).count();
        let broken = applicable.iter().find(|r| r.margin < 0.0);
        let unknown = applicable.iter().find(|r| r.margin.is_nan());
        let _ = writeln!(
            s,
            "{i:>3} {:>7.2} {:>+6.2} {:>7.2} {:>8.0} {:>8.0} {:>6.3} {:>7.4} {:>6.3} {:>6.2} {:>6.0} {:>6.0} {:>5}  {}{}",
            c.mass / OUNCE,
            c.drop,
            c.balance_point / INCH,
            c.moment_of_inertia_knob / OUNCE_SQUARE_INCH,
            c.moment_of_inertia_knob6 / OUNCE_SQUARE_INCH,
            c.barrel_diameter / INCH,
            c.bbcor_max,
            c.best_q,
            (c.sweet_zone_end - c.sweet_zone_start) / INCH,
            c.bending_frequency,
            c.hoop_mode_frequency,
            format!("{kept}/{}", applicable.len()),
            printable(&c.label, false),
            match (broken, unknown) {
                (Some(r), _) => format!(" (breaks {})", printable(&r.label, false)),
                (None, Some(r)) => format!(" (cannot judge {})", printable(&r.label, false)),
                (None, None) => String::new(),
            },
        );
    }
    s
}
