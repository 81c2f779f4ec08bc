//! What the lab shows for a session: every impact position computed as `batstudy run`
//! computes it (`run::driver::compute_point`, the bat prepared once and kept), and the
//! bat's card, as JSON for the page. Numbers are SI; a NaN is `null`.

use super::session;
use crate::optimize::profile_shape::{self, Shape};
use crate::results::BatVariant;
use crate::run::driver::compute_point;
use crate::run::single::bats_of;
use crate::run::ModelSimulator;
use crate::study::{self, LoadOptions};
use rayon::prelude::*;
use serde_json::{json, Value};
use std::path::Path;

/// The name a session's study is loaded under, in its error messages.
pub const SESSION_FILE: &str = "lab-session.yaml";

/// The session evaluated: `{session, study, points, bat}`, or `{study, error}` with the study's
/// positioned message (file, line, field, value and what is allowed) when it is refused.
pub fn evaluate(session: &Value, pool: &rayon::ThreadPool) -> Value {
    // a preset just chosen: its profile as knots, which the answer gives back to the page
    let session = if session["base"]["bat"]["profile"].is_null() {
        match session::with_knots(session.clone()) {
            Ok(s) => s,
            Err(e) => return json!({"error": e}),
        }
    } else {
        session.clone()
    };
    let session = &match turned(session) {
        Ok(s) => s,
        Err(e) => return json!({"error": e}),
    };
    let text = match session::study_text(session) {
        Ok(t) => t,
        Err(e) => return json!({"error": e}),
    };
    let loaded = match study::load_str(&text, Path::new(SESSION_FILE), &LoadOptions::default()) {
        Ok(s) => s,
        Err(e) => return json!({"study": text, "error": e.to_string()}),
    };
    let bats = match bats_of(&loaded, Some(pool)) {
        Ok(b) => b,
        Err(e) => return json!({"study": text, "error": e}),
    };
    if let Some(Err(e)) = bats.handles.first() {
        return json!({"study": text, "error": e});
    }
    let plan = &loaded.plan;
    let records: Vec<_> = pool.install(|| {
        (0..plan.n_points())
            .into_par_iter()
            .map(|i| compute_point(plan, &ModelSimulator, &bats, None, i))
            .collect()
    });
    let points: Vec<Value> = records
        .iter()
        .map(|r| {
            let z = plan.point(r.index).map_or(f64::NAN, |p| p.spec.impact.z);
            match &r.result {
                Ok(o) => json!({
                    "z": z,
                    "exit_speed_lab": o.exit_speed_lab,
                    "exit_speed": o.exit_speed,
                    "bat_speed": o.batted.bat_speed,
                    "launch_angle": o.batted.launch_angle,
                    "backspin": o.batted.backspin,
                    "carry": o.batted.carry,
                    "grip_vibration_amplitude": o.grip_vibration_amplitude,
                    "hoop_mode_frequency": o.hoop_frequency,
                }),
                Err(e) => json!({"z": z, "error": e}),
            }
        })
        .collect();
    json!({
        "session": session,
        "study": text,
        "points": points,
        "bat": card(&bats.variants[0]),
        "modes": bats.handles[0].as_ref().map_or(Value::Null, |t| vibrations(t)),
        "lathe": lathe(&session["base"]["bat"]["profile"]),
    })
}

/// The bat's vibrations to draw: its two lowest bending modes (frequency, Hz, and shape
/// along the bat, largest |value| 1) and its wall's lowest breathing mode (frequency, and
/// its radial shape along the hollow part, largest 1; `null` for a solid bat).
fn vibrations(target: &crate::model::Target) -> Value {
    let Some(bat) = target.bat() else {
        return Value::Null;
    };
    let unit = |v: Vec<f64>| -> Vec<f64> {
        let top = v.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        v.iter()
            .map(|x| if top > 0.0 { x / top } else { 0.0 })
            .collect()
    };
    let z = crate::model::bat::shapes::shape_points(bat);
    let frequencies = &bat.properties().mode_frequency;
    let bending: Vec<Value> = crate::model::bat::shapes::bending_shapes(bat, 2)
        .into_iter()
        .zip(frequencies)
        .map(|(shape, f)| json!({"frequency": f, "z": z, "shape": unit(shape)}))
        .collect();
    let hoop = match bat.shell_modes() {
        Ok(Some(s)) if !s.modes.is_empty() => {
            let w: Vec<f64> = s.nodes.iter().map(|&x| s.radial(0, x)).collect();
            json!({
                "frequency": s.modes[0].omega / std::f64::consts::TAU,
                "wave_number": s.modes[0].wave_number,
                "z": s.nodes,
                "shape": unit(w),
            })
        }
        _ => Value::Null,
    };
    json!({"bending": bending, "hoop": hoop})
}

/// The radii a drag may give a knot, m (the page's own clamp).
const KNOT_RADIUS: (f64, f64) = (0.004, 0.040);

/// The session with its knots turned as a lathe would when it asks for it (`lathe:
/// {max_curvature}`, 1/m): each knot from the handle's thinnest on, in order, moved to the
/// nearest radius that keeps the radius from falling from there to the end and the knots'
/// curvature within the bound (`optimize::profile_shape`, the rule the design
/// searches keep); unchanged without `lathe`.
fn turned(session: Value) -> Result<Value, String> {
    let Some(bound) = session.get("lathe").and_then(|l| l.get("max_curvature")) else {
        return Ok(session);
    };
    let kappa = bound
        .as_f64()
        .filter(|k| k.is_finite() && *k > 0.0)
        .ok_or_else(|| {
            format!("session.lathe.max_curvature: {bound} is not a curvature > 0, 1/m")
        })?;
    let mut session = session;
    let profile = &mut session["base"]["bat"]["profile"];
    let knots = if profile.get("knots").is_some() {
        &mut profile["knots"]
    } else {
        profile
    };
    let Some(rows) = knots.as_array() else {
        return Ok(session);
    };
    let k: Vec<(f64, f64)> = rows
        .iter()
        .filter_map(|r| Some((r.get(0)?.as_f64()?, r.get(1)?.as_f64()?)))
        .collect();
    if k.len() < 3 || k.len() != rows.len() {
        return Ok(session);
    }
    let z: Vec<f64> = k.iter().map(|p| p.0).collect();
    let r: Vec<f64> = k.iter().map(|p| p.1).collect();
    let thinnest = r
        .iter()
        .enumerate()
        .min_by(|a, b| a.1.total_cmp(b.1))
        .map_or(0, |m| m.0);
    let shape = Shape {
        rising: Some([z[thinnest], z[z.len() - 1]]),
        max_curvature: Some(kappa),
        max_slope: None,
    };
    // the knob and the handle down to its thinnest knot as they are (a lathe's rules are
    // for the taper and the barrel; the knob's flare bends far more than they allow)
    let bounds: Vec<(f64, f64)> = r
        .iter()
        .enumerate()
        .map(|(i, &ri)| if i < thinnest { (ri, ri) } else { KNOT_RADIUS })
        .collect();
    let t = profile_shape::fractions(&z, &bounds, &r, &shape);
    let placed = profile_shape::place(&z, &bounds, &t, &shape);
    *knots = json!(z
        .iter()
        .zip(&placed)
        .map(|(z, r)| [*z, *r])
        .collect::<Vec<_>>());
    Ok(session)
}

/// A bat's card and its drawing: the profile, the BBCOR scan and the rules.
fn card(v: &BatVariant) -> Value {
    let p = &v.properties;
    let m = &p.metrics;
    let rules: Vec<Value> = p
        .rule_checks
        .iter()
        .map(|r| json!({"label": r.label, "units": r.units, "value": r.value, "margin": r.margin}))
        .collect();
    json!({
        "label": v.label,
        "length": p.length,
        "mass": p.mass,
        "drop": p.drop(),
        "z_cm": p.z_cm,
        "moment_of_inertia_knob6": p.moment_of_inertia_knob6,
        "barrel_diameter": p.barrel_diameter(),
        "bending_frequency": p.mode_frequency.first(),
        "bbcor_max": m.bbcor_max,
        "bbcor_max_position": m.bbcor_max_position,
        "sweet_zone_start": m.sweet_zone_start,
        "sweet_zone_end": m.sweet_zone_end,
        "hoop_mode_frequency": m.hoop_mode_frequency,
        "barrel_compression": m.barrel_compression,
        "wall_stress_ratio": m.wall_stress_ratio,
        "wall_stress_ratio_position": m.wall_stress_ratio_position,
        "best_q": m.best_q,
        "best_q_position": m.best_q_position,
        "bbcor_z": m.bbcor_z,
        "bbcor": m.bbcor,
        "profile_z": p.z,
        "outer_radius": p.outer_radius,
        "inner_radius": p.inner_radius,
        "rules": rules,
    })
}

/// What a lathe holds on a radius, m: 0.01 mm on a diameter (`profile_export`'s rounding).
const LATHE_RADIUS: f64 = 5e-6;

/// What a lathe would say of the profile's knots: whether the radius rises from the
/// handle's thinnest knot to the barrel's thickest (the largest fall between neighbouring
/// knots there that is more than a lathe holds: where, m from the knob, and by how much, m), and the sharpest bend there, 1/m: the curvature of the parabola through three
/// neighbouring knots, 2 |δ₁ − δ₀| / (h₀ + h₁) with δ the secants (the bound
/// `optimize.profile.shape.max_curvature` sets on a design). `null` without knots.
fn lathe(profile: &Value) -> Value {
    let knots = profile.get("knots").unwrap_or(profile);
    let Some(rows) = knots.as_array() else {
        return Value::Null;
    };
    let k: Vec<(f64, f64)> = rows
        .iter()
        .filter_map(|r| Some((r.get(0)?.as_f64()?, r.get(1)?.as_f64()?)))
        .collect();
    if k.len() < 3 {
        return Value::Null;
    }
    let by_radius = |a: &&(f64, f64), b: &&(f64, f64)| a.1.total_cmp(&b.1);
    let thinnest = k
        .iter()
        .enumerate()
        .min_by(|a, b| by_radius(&a.1, &b.1))
        .map_or(0, |m| m.0);
    let thickest = k[thinnest..]
        .iter()
        .enumerate()
        .max_by(|a, b| by_radius(&a.1, &b.1))
        .map_or(thinnest, |m| thinnest + m.0);
    let span = &k[thinnest..=thickest];
    let fall = span
        .windows(2)
        .map(|w| (w[1].0, w[0].1 - w[1].1))
        .filter(|&(_, by)| by > LATHE_RADIUS)
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(at, by)| json!({"at": at, "by": by}));
    let bend = span
        .windows(3)
        .map(|w| {
            let (h0, h1) = (w[1].0 - w[0].0, w[2].0 - w[1].0);
            let (d0, d1) = ((w[1].1 - w[0].1) / h0, (w[2].1 - w[1].1) / h1);
            2.0 * (d1 - d0).abs() / (h0 + h1)
        })
        .fold(0.0, f64::max);
    json!({
        "rises_from": k[thinnest].0,
        "rises_to": k[thickest].0,
        "largest_fall": fall,
        "sharpest_bend": bend,
    })
}
