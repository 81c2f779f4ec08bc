//! The study's own physical sanity checks of one resolved `CollisionSpec` (positive
//! quantities, shell thinner than the bat, impact on the bat, hoop in range). Each
//! violation names the dotted path, the value and the allowed range.
//!
//! TODO(integration): also call `crate::model::validate_spec` once the physics lands;
//! these checks stay (they run without preparing a bat).

use super::profile::r161_knots;
use crate::model::spec::{BatPreset, BatSpec, CollisionSpec, ProfileSpec};

/// One failed check.
#[derive(Debug, Clone, PartialEq)]
pub struct Violation {
    pub path: String,
    pub value: String,
    pub allowed: String,
}

/// Allowed hoop-mode frequencies, Hz (measured hoop modes: ~700 Hz to above 5500 Hz).
pub const HOOP_FREQUENCY_RANGE: (f64, f64) = (10.0, 100_000.0);
/// Allowed hoop-mode masses, kg (a fraction of the ball's to a fraction of the bat's).
pub const HOOP_MASS_RANGE: (f64, f64) = (1e-6, 1.0);

struct Checker(Vec<Violation>);

impl Checker {
    fn fail(&mut self, path: &str, value: impl ToString, allowed: impl Into<String>) {
        self.0.push(Violation {
            path: path.into(),
            value: value.to_string(),
            allowed: allowed.into(),
        });
    }
    fn positive(&mut self, path: &str, x: f64) {
        if !(x > 0.0 && x.is_finite()) {
            self.fail(path, x, "a finite number > 0");
        }
    }
    fn finite(&mut self, path: &str, x: f64) {
        if !x.is_finite() {
            self.fail(path, x, "a finite number");
        }
    }
    fn within(&mut self, path: &str, x: f64, lo: f64, hi: f64, unit: &str) {
        if !(x >= lo && x <= hi) {
            self.fail(path, x, format!("{lo} to {hi} {unit}"));
        }
    }
}

fn radius_at(k: &[[f64; 2]], z: f64) -> f64 {
    if z <= k[0][0] {
        return k[0][1];
    }
    for w in k.windows(2) {
        if z <= w[1][0] {
            let t = (z - w[0][0]) / (w[1][0] - w[0][0]);
            return w[0][1] + t * (w[1][1] - w[0][1]);
        }
    }
    k.last().unwrap()[1]
}

/// Length of the bat in m as the model will build it (profile, or `bat.length` when set).
pub fn bat_length(bat: &BatSpec) -> f64 {
    let k = knots(bat);
    bat.length.unwrap_or(k.last().unwrap()[0])
}

fn knots(bat: &BatSpec) -> &[[f64; 2]] {
    match &bat.profile {
        Some(ProfileSpec::Knots(k)) if k.len() >= 2 => k,
        _ => r161_knots(),
    }
}

/// Check one resolved collision.
pub fn check_spec(spec: &CollisionSpec) -> Vec<Violation> {
    let mut c = Checker(Vec::new());
    let bat = &spec.bat;
    if let Some(ProfileSpec::Knots(k)) = &bat.profile {
        if let Err(e) = super::profile::check_knots(k) {
            c.fail("bat.profile.knots", format!("{} knots", k.len()), e);
        }
    }
    let k = knots(bat);
    let profile_len = k.last().unwrap()[0];
    if let Some(l) = bat.length {
        if !(l >= profile_len - 1e-12 && l.is_finite()) {
            c.fail(
                "bat.length",
                l,
                format!(">= the profile's length, {profile_len} m"),
            );
        }
    }
    let len = bat.length.unwrap_or(profile_len);
    if let Some(d) = bat.material.density {
        c.positive("bat.material.density", d);
    }
    if let Some(y) = bat.material.youngs_modulus {
        c.positive("bat.material.youngs_modulus", y);
    }
    if let Some(f) = &bat.fill {
        if !(f.density >= 0.0 && f.density.is_finite()) {
            c.fail("bat.fill.density", f.density, "a finite number >= 0");
        }
    }
    let h = &bat.handle;
    c.within("bat.handle.radius_scale", h.radius_scale, 0.1, 10.0, "");
    c.within("bat.handle.end", h.end, 0.0, len, "m (on the bat)");
    if !(h.blend >= 0.0 && h.blend.is_finite()) {
        c.fail("bat.handle.blend", h.blend, "a finite number >= 0 m");
    }
    let outer = |z: f64| {
        let w = if z <= h.end {
            1.0
        } else if h.blend > 0.0 && z < h.end + h.blend {
            1.0 - (z - h.end) / h.blend
        } else {
            0.0
        };
        radius_at(k, z) * (1.0 + (h.radius_scale - 1.0) * w)
    };
    let shell = bat.shell.clone().or(match bat.preset {
        BatPreset::R161 => None,
        BatPreset::Aluminum => Some(crate::model::spec::ShellSpec {
            thickness: 0.003,
            from: 0.0,
        }),
        BatPreset::Corked => Some(crate::model::spec::ShellSpec {
            thickness: 0.01,
            from: 0.55,
        }),
    });
    if let Some(s) = &shell {
        c.positive("bat.shell.thickness", s.thickness);
        if !(s.from >= 0.0 && s.from < len) {
            c.fail(
                "bat.shell.from",
                s.from,
                format!("0 <= from < bat length {len} m"),
            );
        } else if s.thickness > 0.0 {
            let n = 400;
            let (zmin, rmin) = (0..=n)
                .map(|i| s.from + (len - s.from) * i as f64 / n as f64)
                .map(|z| (z, outer(z)))
                .fold((0.0, f64::INFINITY), |a, b| if b.1 < a.1 { b } else { a });
            if s.thickness >= rmin {
                c.fail(
                    "bat.shell.thickness",
                    s.thickness,
                    format!(
                        "< the bat's outer radius over the shell, min {rmin:.4} m (at z = {zmin:.3} m)"
                    ),
                );
            }
        }
    }
    let ball = &spec.ball;
    c.positive("ball.mass", ball.mass);
    if !(ball.speed >= 0.0 && ball.speed.is_finite()) {
        c.fail("ball.speed", ball.speed, "a finite number >= 0 m/s");
    } else if ball.speed == 0.0 && spec.swing.omega == 0.0 {
        c.fail("ball.speed", ball.speed, "> 0 m/s (or a swing.omega != 0)");
    }
    c.positive("ball.law.stiffness", ball.law.stiffness);
    if !(ball.law.cor > 0.0 && ball.law.cor <= 1.0) {
        c.fail("ball.law.cor", ball.law.cor, "0 < cor <= 1");
    }
    c.positive("ball.law.k1", ball.law.k1);
    c.positive("ball.law.alpha", ball.law.alpha);
    c.finite("swing.omega", spec.swing.omega);
    c.finite("swing.cm_speed", spec.swing.cm_speed);
    if let Some(hoop) = spec.hoop.as_ref().filter(|h| !h.from_geometry) {
        let (lo, hi) = HOOP_FREQUENCY_RANGE;
        match hoop.frequency {
            Some(f) => c.within("hoop.frequency", f, lo, hi, "Hz"),
            None => c.fail(
                "hoop.frequency",
                f64::NAN,
                "this field is required (missing field `frequency`; unless hoop.from_geometry: true)",
            ),
        }
        let (lo, hi) = HOOP_MASS_RANGE;
        match hoop.mass {
            Some(m) => c.within("hoop.mass", m, lo, hi, "kg"),
            None => c.fail(
                "hoop.mass",
                f64::NAN,
                "this field is required (missing field `mass`; unless hoop.from_geometry: true)",
            ),
        }
    }
    let z = spec.impact.z;
    if !(0.0..=len).contains(&z) {
        c.fail(
            "impact.z",
            z,
            format!("on the bat: 0 <= z <= {len} m (the bat's length)"),
        );
    }
    if let Some(n) = spec.numerics.segments {
        if !(10..=100_000).contains(&n) {
            c.fail("numerics.segments", n, "10 to 100000");
        }
    }
    if let Some(dt) = spec.numerics.dt {
        if !(dt > 0.0 && dt < 1e-3) {
            c.fail("numerics.dt", dt, "0 < dt < 1e-3 s");
        }
    }
    c.0
}
