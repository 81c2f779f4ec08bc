//! `/bat`: each bat variant's profile, mass, centre of mass, moments of inertia, free-free
//! modes and metrics, along the `bat` dim.

use super::shapes::{create_shapes, BatShapes};
use crate::dimscale::{self as h5u, describe, Attacher};
use crate::error::{H5Ctx, StoreError};
use crate::layout::stores_modal;
use crate::layout::{self as l, VarDef};
use crate::results::StudyInfo;
use batstudy_physics::outcome::{BatMetrics, BatProperties, RuleCheck};
use hdf5::types::VarLenUnicode;
use hdf5::Dataset;
use std::path::Path;

fn padded<T: Clone>(rows: &[Vec<T>], fill: T) -> (Vec<T>, usize) {
    let w = rows.iter().map(|r| r.len()).max().unwrap_or(0);
    let mut v = Vec::with_capacity(rows.len() * w);
    for r in rows {
        v.extend_from_slice(r);
        v.extend(std::iter::repeat_n(fill.clone(), w - r.len()));
    }
    (v, w)
}

/// `/bat` with its dims (`bat`, `mode`, `node`, `profile_point`, `bbcor_point`) and variables;
/// with the displacement's modal form also the shape points and the (empty) mode shapes
/// (`shapes`), which it returns.
pub(super) fn write_bats(
    f: &hdf5::File,
    info: &StudyInfo,
    att: &Attacher,
    out: &Path,
) -> Result<Option<BatShapes>, StoreError> {
    let g = f.create_group(l::GROUP_BAT).ctx(out, "create group bat")?;
    let labels: Vec<VarLenUnicode> = info.bats.iter().map(|b| h5u::vlstr(&b.label)).collect();
    let bat =
        h5u::scale_coord(&g, l::BAT_DIM.name, &labels, &l::BAT_DIM).ctx(out, "write bat labels")?;
    let w = BatGroup {
        g: &g,
        att,
        out,
        bat,
    };
    let p: Vec<_> = info.bats.iter().map(|b| &b.properties).collect();
    w.scalars(&p)?;
    w.modes(&p)?;
    w.profiles(&p)?;
    w.metrics(&p)?;
    w.card(&p)?;
    w.rule_checks(&p)?;
    let shapes = match info.history.as_ref().filter(|h| stores_modal(h)) {
        Some(h) => Some(create_shapes(&g, &w.bat, info, h, att, out)?),
        None => None,
    };
    let spec: Vec<VarLenUnicode> = info.bats.iter().map(|b| h5u::vlstr(&b.spec_json)).collect();
    let ds = h5u::write_1d(&g, l::BAT_SPEC.name, &spec).ctx(out, &e("spec"))?;
    describe(&ds, &l::BAT_SPEC).ctx(out, &e("spec"))?;
    att.add(&ds, &[&w.bat]);
    let shot: Vec<VarLenUnicode> = p
        .iter()
        .map(|p| h5u::vlstr(&p.metrics.bbcor_shot))
        .collect();
    let ds = h5u::write_1d(&g, l::BAT_BBCOR_SHOT.name, &shot).ctx(out, &e("bbcor_shot"))?;
    describe(&ds, &l::BAT_BBCOR_SHOT).ctx(out, &e("bbcor_shot"))?;
    att.add(&ds, &[&w.bat]);
    Ok(shapes)
}

fn e(what: &str) -> String {
    format!("write bat {what}")
}

/// The group being written, with its `bat` dimension scale.
struct BatGroup<'a> {
    g: &'a hdf5::Group,
    att: &'a Attacher,
    out: &'a Path,
    bat: Dataset,
}

impl BatGroup<'_> {
    /// A float variable of this shape along these dimension scales.
    fn var(
        &self,
        def: &VarDef,
        shape: Vec<usize>,
        data: Vec<f64>,
        sc: &[&Dataset],
    ) -> Result<(), StoreError> {
        let ds = self
            .g
            .new_dataset::<f64>()
            .shape(shape)
            .create(def.name)
            .ctx(self.out, &e(def.name))?;
        h5u::write_small(&ds, &data).ctx(self.out, &e(def.name))?;
        describe(&ds, def).ctx(self.out, &e(def.name))?;
        self.att.add(&ds, sc);
        Ok(())
    }

    /// A dimension scale 0, 1, …, n−1.
    fn index_scale(&self, def: &VarDef, n: usize, first: i64) -> Result<Dataset, StoreError> {
        let idx: Vec<i64> = (first..first + n as i64).collect();
        h5u::scale_coord(self.g, def.name, &idx, def).ctx(self.out, &e(def.name))
    }

    /// One value per bat: mass, CM, moments of inertia, length.
    fn scalars(&self, p: &[&BatProperties]) -> Result<(), StoreError> {
        type Getter = fn(&BatProperties) -> f64;
        let per_bat: [(&VarDef, Getter); 6] = [
            (&l::BAT_MASS, |p| p.mass),
            (&l::BAT_Z_CM, |p| p.z_cm),
            (&l::BAT_MOI, |p| p.moment_of_inertia),
            (&l::BAT_MOI6, |p| p.moment_of_inertia_knob6),
            (&l::BAT_MOI_KNOB, |p| p.moment_of_inertia_knob()),
            (&l::BAT_LENGTH, |p| p.length),
        ];
        for (def, get) in per_bat {
            self.var(
                def,
                vec![p.len()],
                p.iter().map(|p| get(p)).collect(),
                &[&self.bat],
            )?;
        }
        Ok(())
    }

    /// The free-free modes' frequencies and nodes.
    fn modes(&self, p: &[&BatProperties]) -> Result<(), StoreError> {
        let nb = p.len();
        let n_modes = p.iter().map(|p| p.mode_frequency.len()).max().unwrap_or(0);
        let mode = self.index_scale(&l::MODE_DIM, n_modes, 1)?;
        let nodes_rows: Vec<Vec<f64>> = p
            .iter()
            .flat_map(|p| {
                (0..n_modes).map(move |m| p.mode_nodes.get(m).cloned().unwrap_or_default())
            })
            .collect();
        let (nodes, n_nodes) = padded(&nodes_rows, f64::NAN);
        let node = self.index_scale(&l::NODE_DIM, n_nodes, 0)?;
        let rows: Vec<_> = p.iter().map(|p| p.mode_frequency.clone()).collect();
        let (mf, _) = padded(&rows, f64::NAN);
        let mf = if n_modes == 0 { vec![] } else { mf };
        // rows shorter than n_modes are padded by `padded` only up to the longest row: same here
        self.var(
            &l::BAT_MODE_FREQ,
            vec![nb, n_modes],
            mf,
            &[&self.bat, &mode],
        )?;
        let shape = vec![nb, n_modes, n_nodes];
        self.var(&l::BAT_MODE_NODES, shape, nodes, &[&self.bat, &mode, &node])
    }

    /// The profiles: z, outer and inner radius along `profile_point`.
    fn profiles(&self, p: &[&BatProperties]) -> Result<(), StoreError> {
        let nb = p.len();
        let (pz, n_prof) = padded(&p.iter().map(|p| p.z.clone()).collect::<Vec<_>>(), f64::NAN);
        let prof = self.index_scale(&l::PROFILE_DIM, n_prof, 0)?;
        self.var(&l::BAT_PROFILE_Z, vec![nb, n_prof], pz, &[&self.bat, &prof])?;
        for (def, radius) in [
            (
                &l::BAT_OUTER,
                p.iter()
                    .map(|p| pad_to(&p.outer_radius, n_prof))
                    .collect::<Vec<_>>(),
            ),
            (
                &l::BAT_INNER,
                p.iter()
                    .map(|p| pad_to(&p.inner_radius, n_prof))
                    .collect::<Vec<_>>(),
            ),
        ] {
            let (r, _) = padded(&radius, f64::NAN);
            let r = if n_prof == 0 { vec![] } else { r };
            self.var(def, vec![nb, n_prof], r, &[&self.bat, &prof])?;
        }
        Ok(())
    }

    /// The metrics: pivot, centre of percussion, nodes, BBCOR and its scan.
    fn metrics(&self, p: &[&BatProperties]) -> Result<(), StoreError> {
        let nb = p.len();
        type Getter = fn(&BatMetrics) -> f64;
        let per_bat: [(&VarDef, Getter); 9] = [
            (&l::BAT_PIVOT, |m| m.pivot),
            (&l::BAT_COP, |m| m.centre_of_percussion),
            (&l::BAT_NODE1, |m| m.node1_barrel),
            (&l::BAT_NODE2, |m| m.node2_barrel),
            (&l::BAT_BBCOR_SPEED, |m| m.bbcor_ball_speed),
            (&l::BAT_BBCOR_MAX, |m| m.bbcor_max),
            (&l::BAT_BBCOR_MAX_POS, |m| m.bbcor_max_position),
            (&l::BAT_BEST_Q, |m| m.best_q),
            (&l::BAT_BEST_Q_POS, |m| m.best_q_position),
        ];
        for (def, get) in per_bat {
            self.var(
                def,
                vec![nb],
                p.iter().map(|p| get(&p.metrics)).collect(),
                &[&self.bat],
            )?;
        }
        let rows: Vec<_> = p.iter().map(|p| p.metrics.bbcor_z.clone()).collect();
        let (bz, n_bb) = padded(&rows, f64::NAN);
        let rows: Vec<_> = p
            .iter()
            .map(|p| pad_to(&p.metrics.bbcor, p.metrics.bbcor_z.len()))
            .collect();
        let (bb, _) = padded(&rows, f64::NAN);
        let bb_dim = self.index_scale(&l::BBCOR_DIM, n_bb, 0)?;
        self.var(&l::BAT_BBCOR_Z, vec![nb, n_bb], bz, &[&self.bat, &bb_dim])?;
        self.var(&l::BAT_BBCOR, vec![nb, n_bb], bb, &[&self.bat, &bb_dim])
    }
}

impl BatGroup<'_> {
    /// The bat card's derived quantities: drop, barrel diameter, sweet zone, hoop mode,
    /// barrel compression.
    fn card(&self, p: &[&BatProperties]) -> Result<(), StoreError> {
        type Getter = fn(&BatProperties) -> f64;
        let per_bat: [(&VarDef, Getter); 9] = [
            (&l::BAT_DROP, |p| p.drop()),
            (&l::BAT_BARREL_DIAMETER, |p| p.barrel_diameter()),
            (&l::BAT_SWEET_ZONE_START, |p| p.metrics.sweet_zone_start),
            (&l::BAT_SWEET_ZONE_END, |p| p.metrics.sweet_zone_end),
            (&l::BAT_SWEET_ZONE_LENGTH, |p| {
                p.metrics.sweet_zone_end - p.metrics.sweet_zone_start
            }),
            (&l::BAT_HOOP_MODE_FREQ, |p| p.metrics.hoop_mode_frequency),
            (&l::BAT_BARREL_COMPRESSION, |p| p.metrics.barrel_compression),
            (&l::BAT_WALL_STRESS_RATIO, |p| p.metrics.wall_stress_ratio),
            (&l::BAT_WALL_STRESS_POS, |p| {
                p.metrics.wall_stress_ratio_position
            }),
        ];
        for (def, get) in per_bat {
            let values = p.iter().map(|p| get(p)).collect();
            self.var(def, vec![p.len()], values, &[&self.bat])?;
        }
        Ok(())
    }

    /// Each bat against each rule book's limits (the same limits for every bat, in order).
    fn rule_checks(&self, p: &[&BatProperties]) -> Result<(), StoreError> {
        // a wall has none: the labels are those of the bats
        let first = p
            .iter()
            .map(|p| &p.rule_checks[..])
            .max_by_key(|c| c.len())
            .unwrap_or(&[]);
        let labels: Vec<VarLenUnicode> = first.iter().map(|c| h5u::vlstr(&c.label)).collect();
        let rule = h5u::scale_coord(self.g, l::RULE_CHECK_DIM.name, &labels, &l::RULE_CHECK_DIM)
            .ctx(self.out, &e("rule_check"))?;
        let units: Vec<VarLenUnicode> = first.iter().map(|c| h5u::vlstr(&c.units)).collect();
        let ds = h5u::write_1d(self.g, l::BAT_RULE_UNITS.name, &units)
            .ctx(self.out, &e("rule_units"))?;
        describe(&ds, &l::BAT_RULE_UNITS).ctx(self.out, &e("rule_units"))?;
        self.att.add(&ds, &[&rule]);
        let n = first.len();
        let column = |get: fn(&RuleCheck) -> f64| -> Vec<f64> {
            p.iter()
                .flat_map(|p| (0..n).map(move |k| p.rule_checks.get(k).map_or(f64::NAN, get)))
                .collect()
        };
        let shape = vec![p.len(), n];
        type Getter = fn(&RuleCheck) -> f64;
        let getters: [(&VarDef, Getter); 2] = [
            (&l::BAT_RULE_VALUE, |c| c.value),
            (&l::BAT_RULE_MARGIN, |c| c.margin),
        ];
        for (def, get) in getters {
            self.var(def, shape.clone(), column(get), &[&self.bat, &rule])?;
            // each limit in its own units: one `units` attribute cannot say them
            let ds = self.g.dataset(def.name).ctx(self.out, &e(def.name))?;
            h5u::attr_str(&ds, "units_from", l::BAT_RULE_UNITS.name).ctx(self.out, &e(def.name))?;
        }
        Ok(())
    }
}

fn pad_to(v: &[f64], n: usize) -> Vec<f64> {
    let mut v = v.to_vec();
    v.truncate(n);
    v.resize(n, f64::NAN);
    v
}
