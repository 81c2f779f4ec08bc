//! `/history`'s (empty) variables and their dimension scales, made with the skeleton.

use super::vars::{new_var_level, study_dims};
use crate::dimscale::{self as h5u, attr_str, Attacher};
use crate::error::{H5Ctx, StoreError};
use crate::header::history_vars;
use crate::layout::{self as l, HistoryDims};
use crate::modal::ModalExtents;
use crate::results::StudyInfo;
use batstudy_physics::flight::{TRAJECTORY_SAMPLES, TRAJECTORY_STEP_S};
use batstudy_physics::outcome::{HistoryField, HistoryPrecision, HistoryRequest};
use hdf5::Dataset;
use std::path::Path;

/// The stored history variables: index into [`l::HISTORY_VARS`], dataset, full shape.
pub type HistoryVars = Vec<(usize, Dataset, Vec<usize>)>;

/// The `/history` group and its (empty) variables.
pub(super) fn create_history(
    f: &hdf5::File,
    h: &HistoryRequest,
    info: &StudyInfo,
    att: &Attacher,
    out: &Path,
) -> Result<HistoryVars, StoreError> {
    let dims = &info.shape.dims;
    let g = f
        .create_group(l::GROUP_HISTORY)
        .ctx(out, "create group history")?;
    let (scales, aux) = study_dims(&g, dims, att, out)?;
    let vars = history_vars(h);
    let tails = Tails::create(&g, h, info, vars.iter().any(|&k| l::is_modal(k)), out)?;
    let level = l::history_deflate_level(h);
    let mut created = Vec::new();
    for &k in &vars {
        let (def, _, tail) = &l::HISTORY_VARS[k];
        let mut s: Vec<usize> = dims.iter().map(|d| d.size).collect();
        let mut c = vec![1; s.len()];
        if let Some(last) = c.last_mut() {
            *last = l::history_groups(info).size(); // a group's points share a chunk
        }
        let mut sc: Vec<&Dataset> = scales.iter().collect();
        for (size, chunk, scale) in tails.of(*tail) {
            s.push(size);
            c.push(chunk.max(1));
            sc.extend(scale);
        }
        // an unwritten block of coordinates is a block of modes the point did not step: 0
        let fill = match tail {
            HistoryDims::ModeTime => 0.0,
            _ => f64::NAN,
        };
        let links = (&sc[..], &aux[..], att);
        let (ds, precision) = match l::history_precision(h, k) {
            HistoryPrecision::F64 => (
                new_var_level(&g, def, (&s, &c), fill, links, level, out)?,
                "f64",
            ),
            HistoryPrecision::F32 => (
                new_var_level(&g, def, (&s, &c), fill as f32, links, level, out)?,
                "f32",
            ),
        };
        attr_str(&ds, "precision", precision).ctx(out, "describe history")?;
        created.push((k, ds, s));
    }
    Ok(created)
}

/// The dimension scales of `/history` after the study's, and their sizes: `time`, `z`, and
/// with the displacement's modal form `bat_mode` and `shape_point` (index coordinates).
struct Tails {
    time: (usize, Dataset),
    z: (usize, Dataset),
    flight_time: Option<Dataset>,
    modal: Option<(ModalExtents, Dataset, Dataset)>,
}

impl Tails {
    fn create(
        g: &hdf5::Group,
        h: &HistoryRequest,
        info: &StudyInfo,
        modal: bool,
        out: &Path,
    ) -> Result<Tails, StoreError> {
        let t: Vec<f64> = (0..h.n_samples).map(|k| k as f64 * h.interval).collect();
        let time = h5u::scale_coord(g, l::TIME.name, &t, &l::TIME).ctx(out, "write time")?;
        let z = h5u::scale_coord(g, l::HIST_Z.name, &h.z, &l::HIST_Z).ctx(out, "write z")?;
        let flight_time = match h.fields.contains(&HistoryField::Trajectory) {
            true => {
                let t: Vec<f64> = (0..TRAJECTORY_SAMPLES)
                    .map(|k| k as f64 * TRAJECTORY_STEP_S)
                    .collect();
                let d = &l::FLIGHT_TIME;
                Some(h5u::scale_coord(g, d.name, &t, d).ctx(out, "write flight_time")?)
            }
            false => None,
        };
        let modal = match modal {
            true => {
                let ext = ModalExtents::of(info);
                let index = |n: usize| (0..n as i64).collect::<Vec<i64>>();
                let (m, p) = (&l::BAT_MODE_DIM, &l::SHAPE_POINT_DIM);
                let modes =
                    h5u::scale_coord(g, m.name, &index(ext.modes), m).ctx(out, "write bat_mode")?;
                let points = h5u::scale_coord(g, p.name, &index(ext.points), p)
                    .ctx(out, "write shape_point")?;
                Some((ext, modes, points))
            }
            false => None,
        };
        Ok(Tails {
            time: (h.n_samples, time),
            z: (h.z.len(), z),
            flight_time,
            modal,
        })
    }

    /// (size, chunk size, dimension scale) of each dim after the study's.
    fn of(&self, dims: HistoryDims) -> Vec<(usize, usize, Option<&Dataset>)> {
        let (nt, time) = (self.time.0, Some(&self.time.1));
        let m = self.modal.as_ref();
        let ext = m.map_or(
            ModalExtents {
                modes: 0,
                block: 1,
                points: 0,
            },
            |m| m.0,
        );
        match dims {
            HistoryDims::Time => vec![(nt, nt, time)],
            HistoryDims::TimeZ => vec![(nt, nt, time), (self.z.0, self.z.0, Some(&self.z.1))],
            HistoryDims::ModeTime => {
                vec![(ext.modes, ext.block, m.map(|m| &m.1)), (nt, nt, time)]
            }
            HistoryDims::ShapePoint => vec![(ext.points, ext.points, m.map(|m| &m.2))],
            HistoryDims::FlightTime => vec![(
                TRAJECTORY_SAMPLES,
                TRAJECTORY_SAMPLES,
                self.flight_time.as_ref(),
            )],
        }
    }
}
