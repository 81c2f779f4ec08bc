//! `/bat`: each bat variant's profile, mass, centre of mass, moments of inertia, free-free
//! modes and metrics, along the `bat` dim.

use crate::model::outcome::BatMetrics;
use crate::results::StudyInfo;
use crate::store::dimscale::{self as h5u, describe, Attacher};
use crate::store::error::{H5Ctx, StoreError};
use crate::store::layout::{self as l, VarDef};
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

/// `/bat` with its dims (`bat`, `mode`, `node`, `profile_point`, `bbcor_point`) and variables.
pub(super) fn write_bats(
    f: &hdf5::File,
    info: &StudyInfo,
    att: &Attacher,
    out: &Path,
) -> Result<(), StoreError> {
    let g = f.create_group(l::GROUP_BAT).ctx(out, "create group bat")?;
    let e = |what: &str| format!("write bat {what}");
    let labels: Vec<VarLenUnicode> = info.bats.iter().map(|b| h5u::vlstr(&b.label)).collect();
    let bat = h5u::scale_coord(&g, l::BAT_DIM.name, &labels, &l::BAT_DIM).ctx(out, &e("labels"))?;
    let p: Vec<_> = info.bats.iter().map(|b| &b.properties).collect();
    let n_modes = p.iter().map(|p| p.mode_frequency.len()).max().unwrap_or(0);
    let modes: Vec<i64> = (1..=n_modes as i64).collect();
    let mode =
        h5u::scale_coord(&g, l::MODE_DIM.name, &modes, &l::MODE_DIM).ctx(out, &e("modes"))?;
    let nodes_rows: Vec<Vec<f64>> = p
        .iter()
        .flat_map(|p| (0..n_modes).map(move |m| p.mode_nodes.get(m).cloned().unwrap_or_default()))
        .collect();
    let (nodes, n_nodes) = padded(&nodes_rows, f64::NAN);
    let node_idx: Vec<i64> = (0..n_nodes as i64).collect();
    let node =
        h5u::scale_coord(&g, l::NODE_DIM.name, &node_idx, &l::NODE_DIM).ctx(out, &e("nodes"))?;
    let (pz, n_prof) = padded(&p.iter().map(|p| p.z.clone()).collect::<Vec<_>>(), f64::NAN);
    let prof_idx: Vec<i64> = (0..n_prof as i64).collect();
    let prof = h5u::scale_coord(&g, l::PROFILE_DIM.name, &prof_idx, &l::PROFILE_DIM)
        .ctx(out, &e("profile"))?;
    let nb = info.bats.len();
    let var = |def: &VarDef,
               shape: Vec<usize>,
               data: Vec<f64>,
               sc: &[&Dataset]|
     -> Result<(), StoreError> {
        let ds = g
            .new_dataset::<f64>()
            .shape(shape.clone())
            .create(def.name)
            .ctx(out, &e(def.name))?;
        h5u::write_small(&ds, &data).ctx(out, &e(def.name))?;
        describe(&ds, def).ctx(out, &e(def.name))?;
        att.add(&ds, sc);
        Ok(())
    };
    var(
        &l::BAT_MASS,
        vec![nb],
        p.iter().map(|p| p.mass).collect(),
        &[&bat],
    )?;
    var(
        &l::BAT_Z_CM,
        vec![nb],
        p.iter().map(|p| p.z_cm).collect(),
        &[&bat],
    )?;
    var(
        &l::BAT_MOI,
        vec![nb],
        p.iter().map(|p| p.moment_of_inertia).collect(),
        &[&bat],
    )?;
    var(
        &l::BAT_MOI6,
        vec![nb],
        p.iter().map(|p| p.moment_of_inertia_knob6).collect(),
        &[&bat],
    )?;
    var(
        &l::BAT_LENGTH,
        vec![nb],
        p.iter().map(|p| p.length).collect(),
        &[&bat],
    )?;
    let (mf, _) = padded(
        &p.iter()
            .map(|p| p.mode_frequency.clone())
            .collect::<Vec<_>>(),
        f64::NAN,
    );
    let mf = if n_modes == 0 { vec![] } else { mf };
    // rows shorter than n_modes are padded by `padded` only up to the longest row: same here
    var(&l::BAT_MODE_FREQ, vec![nb, n_modes], mf, &[&bat, &mode])?;
    var(
        &l::BAT_MODE_NODES,
        vec![nb, n_modes, n_nodes],
        nodes,
        &[&bat, &mode, &node],
    )?;
    var(&l::BAT_PROFILE_Z, vec![nb, n_prof], pz, &[&bat, &prof])?;
    let (ro, _) = padded(
        &p.iter()
            .map(|p| pad_to(&p.outer_radius, n_prof))
            .collect::<Vec<_>>(),
        f64::NAN,
    );
    let (ri, _) = padded(
        &p.iter()
            .map(|p| pad_to(&p.inner_radius, n_prof))
            .collect::<Vec<_>>(),
        f64::NAN,
    );
    var(
        &l::BAT_OUTER,
        vec![nb, n_prof],
        if n_prof == 0 { vec![] } else { ro },
        &[&bat, &prof],
    )?;
    var(
        &l::BAT_INNER,
        vec![nb, n_prof],
        if n_prof == 0 { vec![] } else { ri },
        &[&bat, &prof],
    )?;
    type Getter = fn(&BatMetrics) -> f64;
    let per_bat: [(&VarDef, Getter); 7] = [
        (&l::BAT_PIVOT, |m| m.pivot),
        (&l::BAT_COP, |m| m.centre_of_percussion),
        (&l::BAT_NODE1, |m| m.node1_barrel),
        (&l::BAT_NODE2, |m| m.node2_barrel),
        (&l::BAT_BBCOR_SPEED, |m| m.bbcor_ball_speed),
        (&l::BAT_BBCOR_MAX, |m| m.bbcor_max),
        (&l::BAT_BBCOR_MAX_POS, |m| m.bbcor_max_position),
    ];
    for (def, get) in per_bat {
        var(
            def,
            vec![nb],
            p.iter().map(|p| get(&p.metrics)).collect(),
            &[&bat],
        )?;
    }
    let (bz, n_bb) = padded(
        &p.iter()
            .map(|p| p.metrics.bbcor_z.clone())
            .collect::<Vec<_>>(),
        f64::NAN,
    );
    let (bb, _) = padded(
        &p.iter()
            .map(|p| pad_to(&p.metrics.bbcor, p.metrics.bbcor_z.len()))
            .collect::<Vec<_>>(),
        f64::NAN,
    );
    let bb_idx: Vec<i64> = (0..n_bb as i64).collect();
    let bb_dim =
        h5u::scale_coord(&g, l::BBCOR_DIM.name, &bb_idx, &l::BBCOR_DIM).ctx(out, &e("bbcor"))?;
    var(&l::BAT_BBCOR_Z, vec![nb, n_bb], bz, &[&bat, &bb_dim])?;
    var(&l::BAT_BBCOR, vec![nb, n_bb], bb, &[&bat, &bb_dim])?;
    let spec: Vec<VarLenUnicode> = info.bats.iter().map(|b| h5u::vlstr(&b.spec_json)).collect();
    let ds = h5u::write_1d(&g, l::BAT_SPEC.name, &spec).ctx(out, &e("spec"))?;
    describe(&ds, &l::BAT_SPEC).ctx(out, &e("spec"))?;
    att.add(&ds, &[&bat]);
    Ok(())
}

fn pad_to(v: &[f64], n: usize) -> Vec<f64> {
    let mut v = v.to_vec();
    v.truncate(n);
    v.resize(n, f64::NAN);
    v
}
