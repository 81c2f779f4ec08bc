//! Creating the file's variables: the coordinates and dimension scales of the study's dims
//! in a group, and empty, chunked, described variables attached to them.

use crate::dimscale::{self as h5u, attr_str, describe, describe_parts, Attacher};
use crate::error::{H5Ctx, StoreError};
use crate::layout::{self as l, VarDef};
use crate::results::{CoordValues, Dim};
use hdf5::types::VarLenUnicode;
use hdf5::{Dataset, Group};
use std::path::Path;

/// Coordinate variables of the study dims in one group; returns the scales (one per dim) and
/// the names of auxiliary coordinates (for the `coordinates` attribute).
pub(super) fn study_dims(
    g: &Group,
    dims: &[Dim],
    att: &Attacher,
    path: &Path,
) -> Result<(Vec<Dataset>, Vec<String>), StoreError> {
    let mut scales = Vec::new();
    let mut aux = Vec::new();
    for d in dims {
        let own = d.coords.iter().find(|c| c.name == d.name);
        let scale = match own {
            Some(c) => {
                let ds = coord_values(g, &d.name, &c.values, path)?;
                h5u::set_scale(&ds, &d.name).ctx(path, "make a dimension scale")?;
                describe_parts(&ds, &c.units, &c.long_name, &c.description)
                    .ctx(path, "describe a coordinate")?;
                attr_str(&ds, "parameter_path", &c.path).ctx(path, "describe a coordinate")?;
                ds
            }
            None => h5u::index_coord(g, &d.name, d.size).ctx(path, "write an index coordinate")?,
        };
        for c in d.coords.iter().filter(|c| c.name != d.name) {
            let ds = coord_values(g, &c.name, &c.values, path)?;
            describe_parts(&ds, &c.units, &c.long_name, &c.description)
                .ctx(path, "describe a coordinate")?;
            if !c.path.is_empty() {
                attr_str(&ds, "parameter_path", &c.path).ctx(path, "describe a coordinate")?;
            }
            att.add(&ds, &[&scale]);
            aux.push(c.name.clone());
        }
        scales.push(scale);
    }
    Ok((scales, aux))
}

fn coord_values(
    g: &Group,
    name: &str,
    v: &CoordValues,
    path: &Path,
) -> Result<Dataset, StoreError> {
    match v {
        CoordValues::Numbers(x) => h5u::write_1d(g, name, x),
        CoordValues::Labels(s) => {
            let s: Vec<VarLenUnicode> = s.iter().map(|s| h5u::vlstr(s)).collect();
            h5u::write_1d(g, name, &s)
        }
    }
    .ctx(path, &format!("write coordinate {name}"))
}

pub(super) fn new_var<T: hdf5::H5Type + Into<hdf5::types::OwnedDynValue>>(
    g: &Group,
    def: &VarDef,
    shape_chunk: (&[usize], &[usize]),
    fill: T,
    links: (&[&Dataset], &[String], &Attacher),
    path: &Path,
) -> Result<Dataset, StoreError> {
    new_var_level(g, def, shape_chunk, fill, links, l::DEFLATE_LEVEL, path)
}

pub(super) fn new_var_level<T: hdf5::H5Type + Into<hdf5::types::OwnedDynValue>>(
    g: &Group,
    def: &VarDef,
    (shape, chunk): (&[usize], &[usize]),
    fill: T,
    (scales, aux, att): (&[&Dataset], &[String], &Attacher),
    level: u8,
    path: &Path,
) -> Result<Dataset, StoreError> {
    let what = format!("create variable {}/{}", g.name(), def.name);
    let ds = h5u::create_var_level(g, def.name, shape, chunk, fill, level).ctx(path, &what)?;
    describe(&ds, def).ctx(path, &what)?;
    if !aux.is_empty() {
        attr_str(&ds, "coordinates", &aux.join(" ")).ctx(path, &what)?;
    }
    att.add(&ds, scales);
    Ok(ds)
}
