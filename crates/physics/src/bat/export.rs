//! A bat's outer radius and wall thickness along its length as rows that describe it
//! exactly: linear between rows, as a profile CSV is read (`z, radius, wall`).
//!
//! Rows sit at every breakpoint of the geometry (profile knots, the wall's knots, where the
//! hollow part starts, the ends), where R(z) and the wall are linear in between, and at
//! eight points across the handle's blend, where R(z) is the profile times a linear factor
//! (a parabola; eight pieces put it within 1e-5 of its radius). A wall of 0 is solid; the
//! hollow part starts at the first row with a wall, which is the hollow side of the step.

use super::section::BatGeometry;

/// Pieces the handle's blend is cut into.
const BLEND_PIECES: usize = 8;

/// One row: position from the knob, outer radius and wall thickness (0: solid), m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProfileRow {
    pub z: f64,
    pub radius: f64,
    pub wall: f64,
}

/// The rows of a bat.
pub fn profile_rows(g: &BatGeometry) -> Vec<ProfileRow> {
    let mut z = g.breakpoints();
    let (end, blend) = (g.handle.end, g.handle.blend);
    if g.handle.radius_scale != 1.0 && blend > 0.0 {
        z.extend((1..BLEND_PIECES).map(|i| end + blend * i as f64 / BLEND_PIECES as f64));
        z.retain(|&x| (0.0..=g.length).contains(&x));
        z.sort_by(f64::total_cmp);
        z.dedup_by(|a, b| (*a - *b).abs() < 1e-12);
    }
    z.into_iter()
        .map(|z| {
            let radius = g.outer_radius(z);
            // the wall as given (its knots, or the bore's radius), not R − r's round-off
            let wall = match (g.shell, g.bore) {
                (Some((t, from)), _) if z >= from => g.wall_thickness(z).unwrap_or(t),
                (_, Some((r, from))) if z >= from => radius - r,
                _ => 0.0,
            };
            ProfileRow { z, radius, wall }
        })
        .collect()
}
