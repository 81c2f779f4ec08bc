//! The bat's displacement basis for the modal form of its histories: its shape
//! points (the knob end, every node, the barrel end) and the mode shapes there, scaled to be
//! dimensionless. The model's displacement is linear between nodes and extrapolated over the
//! half segment at each end (`Beam::interpolation`), so a displacement known at the shape
//! points is known at every z of the bat by linear interpolation between them.

use super::PreparedBat;
use std::ops::Range;

/// Mode `m`'s shape between nodes `k` and `k + 1` at weight `a` of node `k + 1`: the
/// formula of the integrator's contact point and grid, and of the stored shapes.
pub fn shape_at(bat: &PreparedBat, k: usize, a: f64, m: usize) -> f64 {
    let shapes = &bat.modes.shapes;
    (1.0 - a) * shapes[(k, m)] + a * shapes[(k + 1, m)]
}

/// (node pair, weight) of each shape point: the knob end and the barrel end as
/// `Beam::interpolation` gives them, and node i as (i, 0) (the last one (N − 2, 1)).
pub fn shape_point_weights(bat: &PreparedBat) -> Vec<(usize, f64)> {
    let beam = &bat.beam;
    let nodes = beam.len();
    let mut w = Vec::with_capacity(nodes + 2);
    w.push(beam.interpolation(0.0));
    w.extend((0..nodes).map(|i| match i + 1 < nodes {
        true => (i, 0.0),
        false => (nodes - 2, 1.0),
    }));
    w.push(beam.interpolation(bat.length()));
    w
}

/// z of the shape points, m from the knob: 0, every node, the bat's length.
pub fn shape_points(bat: &PreparedBat) -> Vec<f64> {
    let mut z = Vec::with_capacity(bat.beam.len() + 2);
    z.push(0.0);
    z.extend_from_slice(&bat.beam.z);
    z.push(bat.length());
    z
}

/// The factor √M (M the bat's mass, kg) that makes the mass-normalised mode shapes
/// (kg^-½) dimensionless; the stored modal coordinates are divided by it (then in m).
pub fn modal_scale(bat: &PreparedBat) -> f64 {
    bat.total_mass.sqrt()
}

/// Number of modes of the bat (one per degree of freedom).
pub fn n_modes(bat: &PreparedBat) -> usize {
    bat.modes.omega.len()
}

/// Each mode's largest |φ_m √M| over the shape points (between them the displacement is
/// linear, so nowhere on the bat larger): what the modal form's stored precision needs
/// (`collision::modal_precision`). Computed once per bat, for every mode.
pub fn shape_maxima(bat: &PreparedBat) -> &[f64] {
    bat.shape_max.get_or_init(|| {
        let points = shape_point_weights(bat).len();
        scaled_shapes(bat, 0..n_modes(bat))
            .chunks_exact(points.max(1))
            .map(|phi| phi.iter().fold(0.0_f64, |m, x| m.max(x.abs())))
            .collect()
    })
}

/// The scaled shapes φ_m √M of modes `modes` at the shape points, mode-major
/// (`[m][point]`), dimensionless.
pub fn scaled_shapes(bat: &PreparedBat, modes: Range<usize>) -> Vec<f64> {
    let scale = modal_scale(bat);
    let points = shape_point_weights(bat);
    let mut out = Vec::with_capacity(modes.len() * points.len());
    for m in modes {
        out.extend(points.iter().map(|&(k, a)| shape_at(bat, k, a, m) * scale));
    }
    out
}

/// The lowest `count` flexible (bending) modes' scaled shapes at the shape points, one
/// `[point]` vector per mode (fewer for a bat with fewer modes), dimensionless.
pub fn bending_shapes(bat: &PreparedBat, count: usize) -> Vec<Vec<f64>> {
    let first = bat.modes.n_rigid;
    let last = (first + count).min(n_modes(bat));
    let points = shape_point_weights(bat).len().max(1);
    scaled_shapes(bat, first..last)
        .chunks_exact(points)
        .map(<[f64]>::to_vec)
        .collect()
}
