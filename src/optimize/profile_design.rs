//! A design's profile block (`optimize.profile`), checked: its knots and their variables,
//! the wall's knots, and the shape every candidate keeps (`profile.shape`).

#![allow(clippy::result_large_err)] // StudyError: see study/mod.rs

use super::profile_shape::{self, Shape};
use super::variable::{at, bounds_ok, located, Variable};
use crate::study::optimize_block::{Knot, ProfileDesign};
use crate::study::plan::related;
use crate::study::{Study, StudyError};

/// `profile`: knots increasing from 0, one radius each, fixed (> 0) or bounded.
pub(super) type ProfileValues = (Vec<f64>, Vec<f64>, Option<Vec<f64>>);

pub(super) fn profile_variables(
    study: &Study,
    p: &ProfileDesign,
    vars: &mut Vec<Variable>,
) -> Result<ProfileValues, StudyError> {
    let bad = |part: &str, msg: &str, value: String, allowed: &str| {
        located(study, &at(&["profile", part]), msg.to_string())
            .field(format!("optimize.profile.{part}"))
            .value(value)
            .allowed(allowed.to_string())
    };
    let increasing = p.z.first() == Some(&0.0) && p.z.windows(2).all(|w| w[1] > w[0]);
    if p.z.len() < 2 || !increasing {
        return Err(bad(
            "z",
            "bad knot positions",
            format!("{:?}", p.z),
            "at least 2 positions, increasing from 0 (m from the knob)",
        ));
    }
    if p.radius.len() != p.z.len() {
        return Err(bad(
            "radius",
            "one radius per knot position",
            format!("{} radii", p.radius.len()),
            &format!("{} radii", p.z.len()),
        ));
    }
    if let Some(d) = study
        .plan
        .dims()
        .iter()
        .find(|d| d.params.iter().any(|(q, _)| related(q, "bat.profile")))
    {
        return Err(bad(
            "z",
            &format!("the profile is also varied by dimension `{}`", d.name),
            String::new(),
            "a profile no grid, zip or points block sets",
        ));
    }
    let radius = knot_values(&p.radius, false, vars).map_err(|(k, r)| {
        bad(
            "radius",
            &format!("bad radius of knot {k}"),
            r,
            "a radius > 0, or {min, max, start} with 0 < min < max and start within",
        )
    })?;
    let wall = match &p.thickness {
        None => None,
        Some(t) if t.len() != p.z.len() => {
            return Err(bad(
                "thickness",
                "one wall thickness per knot position",
                format!("{} thicknesses", t.len()),
                &format!("{} thicknesses", p.z.len()),
            ))
        }
        Some(t) => Some(knot_values(t, true, vars).map_err(|(k, r)| {
            bad(
                "thickness",
                &format!("bad wall thickness of knot {k}"),
                r,
                "a thickness > 0, or {min, max, start} with 0 < min < max and start within",
            )
        })?),
    };
    Ok((p.z.clone(), radius, wall))
}

/// `profile.shape`, checked: a rising span inside the profile whose knots' bounds allow a
/// rise, a curvature bound > 0.
pub(super) fn shape_of(
    study: &Study,
    p: &ProfileDesign,
    vars: &[Variable],
) -> Result<Option<Shape>, StudyError> {
    let Some(s) = p.shape else { return Ok(None) };
    let bad = |part: &str, msg: String, value: String, allowed: &str| {
        located(study, &at(&["profile", "shape", part]), msg)
            .field(format!("optimize.profile.shape.{part}"))
            .value(value)
            .allowed(allowed.to_string())
    };
    if let Some(k) = s.max_curvature.filter(|k| !(k.is_finite() && *k > 0.0)) {
        return Err(bad(
            "max_curvature",
            "bad curvature bound".into(),
            k.to_string(),
            "a curvature > 0, 1/m",
        ));
    }
    let shape = Shape {
        rising: s.rising,
        max_curvature: s.max_curvature,
        // the wall's gradient (`Shape::for_wall`); the radii's list drops it
        max_slope: s.max_wall_slope,
    };
    check_wall_slope(study, p, vars, s.max_wall_slope)?;
    let Some([a, b]) = s.rising else {
        return Ok(Some(shape));
    };
    let last = p.z.last().copied().unwrap_or(0.0);
    if !(a.is_finite() && b.is_finite() && 0.0 <= a && a < b && b <= last) {
        return Err(bad(
            "rising",
            "bad rising span".into(),
            format!("[{a}, {b}]"),
            &format!("[z_start, z_end] with 0 <= z_start < z_end <= {last} (the last knot), m"),
        ));
    }
    let mut bounds: Vec<(f64, f64)> = p
        .radius
        .iter()
        .map(|k| match k {
            Knot::Fixed(r) => (*r, *r),
            Knot::Free(b) => (b.min, b.max),
        })
        .collect();
    for v in vars.iter().filter(|v| !v.wall) {
        if let Some(k) = v.knot {
            bounds[k] = (v.min, v.max);
        }
    }
    profile_shape::check_rise(&p.z, &bounds, &shape).map_err(|(k, j)| {
        bad(
            "rising",
            format!(
                "the radius cannot rise from knot {k} (z = {} m, at least {} m) to knot {j} (z = {} m, at most {} m)",
                p.z[k], bounds[k].0, p.z[j], bounds[j].1
            ),
            format!("[{a}, {b}]"),
            "a span over which no knot's lower bound exceeds a later knot's upper bound",
        )
    })?;
    Ok(Some(shape))
}

/// `profile.shape.max_wall_slope`, checked: > 0, with the wall's knots given, and their
/// fixed values and bounds within its reach of each other.
fn check_wall_slope(
    study: &Study,
    p: &ProfileDesign,
    vars: &[Variable],
    slope: Option<f64>,
) -> Result<(), StudyError> {
    let Some(g) = slope else { return Ok(()) };
    let here = at(&["profile", "shape", "max_wall_slope"]);
    let bad = |msg: String, allowed: &str| {
        located(study, &here, msg)
            .field("optimize.profile.shape.max_wall_slope")
            .value(crate::model::error::number_text(g))
            .allowed(allowed.to_string())
    };
    if !(g.is_finite() && g > 0.0) {
        return Err(bad(
            "bad wall gradient bound".into(),
            "a gradient > 0, m of wall per m along the bat",
        ));
    }
    let Some(thickness) = &p.thickness else {
        return Err(bad(
            "a wall gradient bound without wall knots".into(),
            "`optimize.profile.thickness` beside it",
        ));
    };
    let mut bounds: Vec<(f64, f64)> = thickness
        .iter()
        .map(|k| match k {
            Knot::Fixed(t) => (*t, *t),
            Knot::Free(b) => (b.min, b.max),
        })
        .collect();
    for v in vars.iter().filter(|v| v.wall) {
        if let Some(k) = v.knot {
            bounds[k] = (v.min, v.max);
        }
    }
    profile_shape::check_slope(&p.z, &bounds, g).map_err(|(k, j)| {
        bad(
            format!(
                "the wall cannot pass from knot {k} (z = {} m, {}–{} m) to knot {j} (z = {} m, {}–{} m) within the gradient",
                p.z[k], bounds[k].0, bounds[k].1, p.z[j], bounds[j].0, bounds[j].1
            ),
            "a gradient that lets every pair of wall knots' bounds meet",
        )
    })
}

/// A profile's fixed values (NaN where a variable), its variables pushed to `vars`; the
/// bad knot and its text on error.
fn knot_values(
    list: &[Knot],
    wall: bool,
    vars: &mut Vec<Variable>,
) -> Result<Vec<f64>, (usize, String)> {
    let mut fixed = Vec::new();
    for (k, r) in list.iter().enumerate() {
        match r {
            Knot::Fixed(r) if *r > 0.0 => fixed.push(*r),
            Knot::Free(b) if b.min > 0.0 && bounds_ok(b).is_ok() => {
                fixed.push(f64::NAN);
                let what = if wall {
                    "shell.thickness"
                } else {
                    "profile.radius"
                };
                vars.push(Variable {
                    name: format!("bat.{what}[{k}]"),
                    min: b.min,
                    max: b.max,
                    start: bounds_ok(b).unwrap_or(b.min),
                    units: "m".into(),
                    knot: Some(k),
                    wall,
                });
            }
            _ => return Err((k, format!("{r:?}"))),
        }
    }
    Ok(fixed)
}
