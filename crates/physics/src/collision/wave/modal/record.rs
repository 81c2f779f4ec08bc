//! What the modal integrator hands the history recorder: a projector from the modal
//! coordinates to the bat's displacement at every requested z (the grid form) or the
//! static shape of the modes it does not step (the modal form), and one sample per step.

use super::super::project::project;
use super::super::Collision;
use super::setup::{shapes_at, Setup};
use super::state::State;
use crate::bat::shapes::{modal_scale, shape_at, shape_maxima, shape_point_weights};
use crate::bat::PreparedBat;
use crate::collision::history::Recorder;
use crate::collision::modal_precision::ModalRounding;
use crate::error::ModelError;
use crate::outcome::HistoryPrecision;

/// The modal form: the recorder keeps the stepped modes' coordinates and the force on the
/// bat; the modes not stepped respond statically to that force, with the shape
/// [`static_shape`] (m/N at the bat's shape points) of this contact point (`at`: node and
/// weight), which the bat keeps once computed (`bat::static_memo`).
pub(super) fn install_modal(
    rec: &mut Recorder,
    setup: &Setup,
    bat: &PreparedBat,
    at: (usize, f64),
) -> Result<(), ModelError> {
    let n = setup.n;
    let key = (n, at.0, at.1.to_bits());
    let static_shape = bat
        .static_shapes
        .get_or_compute(key, || static_shape(setup, bat));
    let weights = shape_point_weights(bat);
    // stored to f32 rounding of y, not of each coordinate (`modal_precision`)
    let rounding = (rec.request().precision == HistoryPrecision::F32).then(|| {
        let scale = modal_scale(bat);
        ModalRounding::new(&shape_maxima(bat)[..n], &static_shape, |p, j| {
            let (k, a) = weights[p];
            shape_at(bat, k, a, j) * scale
        })
    });
    rec.record_modes(n, modal_scale(bat), static_shape.to_vec(), rounding)
}

/// The static response of the modes not stepped to a unit force at the contact point, m/N
/// at the bat's shape points: Σ_j φ_j w_j over those modes, first at every node, a mode's
/// column at a time (the shapes are stored by mode: one pass in memory order, where a node
/// at a time strides across every column), then linear between nodes.
fn static_shape(setup: &Setup, bat: &PreparedBat) -> Vec<f64> {
    let n = setup.n;
    let nodes = bat.beam.len();
    let mut at_nodes = vec![0.0; nodes];
    // the matrix in memory, column-major: a mode's node values are one contiguous run (a
    // slice loop the compiler vectorises; nalgebra's column iterator was 19 µs a history)
    let (rows, all) = (bat.modes.shapes.nrows(), bat.modes.shapes.as_slice());
    for (j, w) in (n..).zip(&setup.static_weight) {
        let column = &all[j * rows..][..nodes];
        for (u, phi) in at_nodes.iter_mut().zip(column) {
            *u += phi * w;
        }
    }
    shape_point_weights(bat)
        .iter()
        .map(|&(k, a)| (1.0 - a) * at_nodes[k] + a * at_nodes[k + 1])
        .collect()
}

/// Give the recorder the displacement of the bat at its requested positions (`points`:
/// node pair, weight, inside the bat) as a function of the modal coordinates and the force
/// on the bat: the stepped modes' sum plus the dropped modes' static response.
pub(super) fn install_projector(
    rec: &mut Recorder,
    setup: &Setup,
    bat: &PreparedBat,
    points: &[(usize, f64, bool)],
) {
    let (n, n_all, nz) = (setup.n, bat.modes.omega.len(), points.len());
    // The mode shapes at the requested z, mode by mode (`shape_by_mode[j * nz + i]`): a
    // sample's displacements are summed over the modes for every z at once (`project`).
    let mut shape_by_mode = vec![0.0; n * nz];
    for (i, &(k, a, _)) in points.iter().enumerate() {
        for (j, s) in shapes_at(bat, k, a, 0..n).into_iter().enumerate() {
            shape_by_mode[j * nz + i] = s;
        }
    }
    // where `Iterator::sum` starts (-0.0 or 0.0, by toolchain): the same bits as a sum
    let sum_start: f64 = std::iter::empty::<f64>().sum();
    // static displacement of the dropped modes at each requested z per unit contact force
    let static_at: Vec<f64> = points
        .iter()
        .map(|&(k, a, _)| {
            shapes_at(bat, k, a, n..n_all)
                .iter()
                .zip(&setup.static_weight)
                .map(|(s, w)| s * w)
                .sum()
        })
        .collect();
    let inside: Vec<bool> = points.iter().map(|&(_, _, inside)| inside).collect();
    rec.project_with(Box::new(
        move |q: &[f64], p_bat: f64, out: &mut Vec<f64>| {
            let start = out.len();
            out.resize(start + nz, sum_start);
            let y = &mut out[start..];
            project(q, &shape_by_mode, y, sum_start);
            for (yi, (&inside, st)) in y.iter_mut().zip(inside.iter().zip(&static_at)) {
                *yi = if inside { *yi + st * p_bat } else { f64::NAN };
            }
        },
    ));
}

/// Record the state now, at `state.t`: contact force, compression, ball velocity, the
/// hoop's displacement, the rigid motion and the modal coordinates (projected by the
/// recorder, or kept), written into the recorder's own state (`Recorder::state`).
pub(super) fn record_now(
    rec: &mut Recorder,
    c: &Collision,
    bat: &PreparedBat,
    state: &State,
    wants_modal: bool,
) {
    let (force, p_bat, hoop_rel) = (
        state.contact_force(),
        state.bat_force(c),
        state.hoop_stretch(c),
    );
    let q = &state.q;
    let wants_rigid = rec.wants_rigid;
    let rigid = |weight: &[f64], over: f64| match wants_rigid {
        true => dot(weight, q) / over,
        false => 0.0,
    };
    let (translation, rotation) = (
        rigid(&bat.momentum_weight, bat.total_mass),
        rigid(&bat.angular_weight, bat.inertia_cm),
    );
    let s = rec.state();
    s.force = force;
    s.compression = state.s.max(0.0);
    s.ball_velocity = state.v;
    s.hoop_displacement = hoop_rel;
    s.rigid_translation = translation;
    s.rigid_rotation = rotation;
    s.modal.clear();
    if wants_modal {
        s.modal.extend_from_slice(q);
    }
    s.modal_force = p_bat;
    rec.commit(state.t);
}

/// Σ x_j q_j over the shorter of the two, in four interleaved partial sums: a history
/// samples two of these for every state it keeps, and one running sum would make each wait
/// on the addition before it (a twentieth of a modal history point's time).
fn dot(x: &[f64], q: &[f64]) -> f64 {
    let n = x.len().min(q.len());
    let (x, q) = (&x[..n], &q[..n]);
    let mut sums = [0.0_f64; 4];
    let (xs, qs) = (x.chunks_exact(4), q.chunks_exact(4));
    let tail: f64 = xs
        .remainder()
        .iter()
        .zip(qs.remainder())
        .map(|(a, b)| a * b)
        .sum();
    for (a, b) in xs.zip(qs) {
        for k in 0..4 {
            sums[k] += a[k] * b[k];
        }
    }
    (sums[0] + sums[1]) + (sums[2] + sums[3]) + tail
}
