//! Fields a study sets that no point uses: `ball.law.stiffness` with a power-law ball,
//! `bat.grip.damping` with a pinned grip, … A kind or option that ignores a field would
//! otherwise run with the defaults, and nothing would tell the user that the number they
//! typed had no effect.
//!
//! A field is reported only when no point of the study both sets it and uses it: a study
//! that sweeps `ball.law.kind` may well set `stiffness` for its linear points.

use super::paths::get_path;
use yaml_serde::Value;

/// A field that only some options use.
pub struct Rule {
    /// Dotted path of the field.
    pub field: &'static str,
    /// When it is used, in words (for the message).
    pub used_when: &'static str,
    /// Whether a point's parameter tree uses it.
    pub uses: fn(&Value) -> bool,
}

/// The text at `path`, or `default` when the tree leaves it out.
fn text<'a>(tree: &'a Value, path: &str, default: &'a str) -> &'a str {
    get_path(tree, path)
        .and_then(Value::as_str)
        .unwrap_or(default)
}

fn wave(t: &Value) -> bool {
    text(t, "model", "wave") == "wave"
}

/// Whether the point uses a built-in ball (whose law is `speed_dependent`, loading `power`).
fn preset_ball(t: &Value) -> bool {
    get_path(t, "ball.preset").and_then(Value::as_str).is_some()
}

fn law(t: &Value) -> &str {
    let default = if preset_ball(t) {
        "speed_dependent"
    } else {
        "linear_hysteresis"
    };
    text(t, "ball.law.kind", default)
}

fn loading(t: &Value) -> &str {
    text(
        t,
        "ball.law.loading",
        if preset_ball(t) { "power" } else { "linear" },
    )
}

fn speed_dependent(t: &Value) -> bool {
    law(t) == "speed_dependent"
}

/// Whether the point has a batter (whose pitch and swing set the ball's speed).
fn batter(t: &Value) -> bool {
    get_path(t, "batter").is_some_and(|b| !b.is_null())
}

/// Whether the target is a bat (not the rigid wall or cylinder, which have no geometry or
/// material).
fn a_bat(t: &Value) -> bool {
    !matches!(text(t, "bat.preset", "r161"), "wall" | "cylinder")
}

/// Whether the bat has a wall that can breathe: a shell, a bore, or a hollow preset.
fn hollow(t: &Value) -> bool {
    let set = |p: &str| get_path(t, p).is_some_and(|v| !v.is_null());
    set("bat.shell")
        || set("bat.bore")
        || matches!(
            text(t, "bat.preset", "r161"),
            "aluminum" | "corked" | "alloy_bbcor" | "composite_bbcor"
        )
}

/// Whether the bat's wall breathes in this point: a hoop from the geometry of a hollow bat.
fn breathes(t: &Value) -> bool {
    get_path(t, "hoop.from_geometry").and_then(Value::as_bool) == Some(true) && hollow(t)
}

/// A bat field the wall ignores.
macro_rules! bat_field {
    ($field:literal) => {
        Rule {
            field: $field,
            used_when:
                "with a bat (bat.preset other than wall or cylinder: a rigid target has no geometry or material)",
            uses: a_bat,
        }
    };
}

/// Every field that an option can make irrelevant.
pub const RULES: &[Rule] = &[
    Rule {
        field: "ball.speed",
        used_when: "without a batter block (a batter's pitch_speed and bat_speed set the approach)",
        uses: |t| !batter(t),
    },
    bat_field!("bat.length"),
    bat_field!("bat.material"),
    bat_field!("bat.shell"),
    bat_field!("bat.fill"),
    bat_field!("bat.bore"),
    bat_field!("bat.profile"),
    bat_field!("bat.handle"),
    bat_field!("bat.ends"),
    Rule {
        field: "bat.radius",
        used_when: "with bat.preset cylinder (a bat's radius comes from its profile)",
        uses: |t| text(t, "bat.preset", "r161") == "cylinder",
    },
    Rule {
        field: "ball.law.stiffness",
        used_when: "by the wave model with ball.law.kind linear_hysteresis or elastic, or speed_dependent with loading linear",
        uses: |t| {
            wave(t)
                && (matches!(law(t), "linear_hysteresis" | "elastic")
                    || speed_dependent(t) && loading(t) == "linear")
        },
    },
    Rule {
        field: "ball.law.cor",
        used_when: "by ball.law.kind linear_hysteresis, power_law or speed_dependent, and by the rigid model",
        uses: |t| !wave(t) || matches!(law(t), "linear_hysteresis" | "power_law" | "speed_dependent"),
    },
    Rule {
        field: "ball.law.k1",
        used_when: "by the wave model with ball.law.kind power_law, or speed_dependent with loading power",
        uses: |t| wave(t) && (law(t) == "power_law" || speed_dependent(t) && loading(t) == "power"),
    },
    Rule {
        field: "ball.law.alpha",
        used_when: "by the wave model with ball.law.kind power_law, or speed_dependent with loading power",
        uses: |t| wave(t) && (law(t) == "power_law" || speed_dependent(t) && loading(t) == "power"),
    },
    Rule {
        field: "ball.law.reference_speed",
        used_when: "by ball.law.kind speed_dependent",
        uses: speed_dependent,
    },
    Rule {
        field: "ball.law.cor_slope",
        used_when: "by ball.law.kind speed_dependent",
        uses: speed_dependent,
    },
    Rule {
        field: "ball.law.cor_exponent",
        used_when: "by ball.law.kind speed_dependent",
        uses: speed_dependent,
    },
    Rule {
        field: "ball.law.cor_at_rest",
        used_when: "by ball.law.kind speed_dependent",
        uses: speed_dependent,
    },
    Rule {
        field: "ball.law.cor_power",
        used_when: "by ball.law.kind speed_dependent",
        uses: speed_dependent,
    },
    Rule {
        field: "ball.law.curvature",
        used_when: "by ball.law.kind speed_dependent",
        uses: speed_dependent,
    },
    Rule {
        field: "ball.law.cor_shift",
        used_when: "by ball.law.kind speed_dependent",
        uses: speed_dependent,
    },
    Rule {
        field: "ball.law.loading",
        used_when: "by the wave model with ball.law.kind speed_dependent",
        uses: |t| wave(t) && speed_dependent(t),
    },
    Rule {
        field: "hoop.patch_radius",
        used_when: "with hoop.from_geometry: true on a hollow bat (a shell, a bore or a hollow preset)",
        uses: breathes,
    },
    Rule {
        field: "hoop.footprint_ratio",
        used_when: "with hoop.from_geometry: true on a hollow bat (a shell, a bore or a hollow preset)",
        uses: breathes,
    },
    Rule {
        field: "bat.shell.break_in",
        used_when: "by the wave model (the rigid model sees a wall's mass, not its stiffness)",
        uses: wave,
    },
    Rule {
        field: "bat.grip.stiffness",
        used_when: "with bat.grip.kind: spring",
        uses: |t| text(t, "bat.grip.kind", "pinned") == "spring",
    },
    Rule {
        field: "bat.grip.damping",
        used_when: "with bat.grip.kind: spring",
        uses: |t| text(t, "bat.grip.kind", "pinned") == "spring",
    },
    Rule {
        field: "bat.material.shear_modulus",
        used_when: "by the wave model with bat.beam: timoshenko",
        uses: |t| wave(t) && text(t, "bat.beam", "euler_bernoulli") == "timoshenko",
    },
    Rule {
        field: "bat.material.shear_coefficient",
        used_when: "by the wave model with bat.beam: timoshenko",
        uses: |t| wave(t) && text(t, "bat.beam", "euler_bernoulli") == "timoshenko",
    },
];

/// Tallies, over the parameter trees of a study's points, which rule fields are set and
/// whether any point that sets one uses it.
#[derive(Debug, Default)]
pub struct Tally {
    set: Vec<bool>,
    used: Vec<bool>,
    /// Whether any point flies its batted ball (a `flight` block).
    pub flies: bool,
}

impl Tally {
    pub fn new() -> Self {
        Tally {
            set: vec![false; RULES.len()],
            used: vec![false; RULES.len()],
            flies: false,
        }
    }

    /// Count one point's parameter tree (as written: base plus the blocks' values).
    pub fn add(&mut self, tree: &Value) {
        self.flies |= get_path(tree, "flight").is_some_and(|v| !v.is_null());
        for (i, r) in RULES.iter().enumerate() {
            if get_path(tree, r.field).is_some_and(|v| !v.is_null()) {
                self.set[i] = true;
                if !self.used[i] && (r.uses)(tree) {
                    self.used[i] = true;
                }
            }
        }
    }

    /// The first rule whose field is set somewhere and used nowhere.
    pub fn unused(&self) -> Option<&'static Rule> {
        (0..RULES.len())
            .find(|&i| self.set[i] && !self.used[i])
            .map(|i| &RULES[i])
    }
}
