//! `/errors`: the failed points, one row each along a growable dim; created empty with the
//! skeleton, grown only when points failed.

use crate::dimscale::{self as h5u, describe, Attacher};
use crate::error::{H5Ctx, StoreError};
use crate::layout::{self as l, VarDef};
use hdf5::types::VarLenUnicode;
use hdf5::Dataset;
use std::path::Path;

/// `/errors`: the failed points, one row each, along a growable dim.
pub(super) struct Errors {
    index: Dataset,
    flat_index: Dataset,
    point_id: Dataset,
    message: Dataset,
}

/// `/errors` with no rows: most runs have no failed points, and then finishing the file
/// writes nothing here.
pub(super) fn create_errors(
    f: &hdf5::File,
    att: &Attacher,
    out: &Path,
) -> Result<Errors, StoreError> {
    let g = f
        .create_group(l::GROUP_ERRORS)
        .ctx(out, "create group errors")?;
    let e = |r: hdf5::Result<Dataset>| r.ctx(out, "create the errors");
    let edef = VarDef {
        name: l::ERR_DIM,
        units: "1",
        long_name: "error",
        description: "failed point number",
    };
    let index = e(h5u::create_growable::<i64>(&g, l::ERR_DIM))?;
    h5u::set_scale(&index, l::ERR_DIM).ctx(out, "create the errors")?;
    describe(&index, &edef).ctx(out, "create the errors")?;
    let column = |def: &VarDef, ds: hdf5::Result<Dataset>| -> Result<Dataset, StoreError> {
        let ds = e(ds)?;
        describe(&ds, def).ctx(out, "create the errors")?;
        att.add(&ds, &[&index]);
        Ok(ds)
    };
    let flat_index = column(
        &l::ERR_FLAT_INDEX,
        h5u::create_growable::<u64>(&g, l::ERR_FLAT_INDEX.name),
    )?;
    let point_id = column(
        &l::ERR_POINT_ID,
        h5u::create_growable::<u64>(&g, l::ERR_POINT_ID.name),
    )?;
    let message = column(
        &l::ERR_MESSAGE,
        h5u::create_growable::<VarLenUnicode>(&g, l::ERR_MESSAGE.name),
    )?;
    Ok(Errors {
        index,
        flat_index,
        point_id,
        message,
    })
}

/// Grow `/errors` to the failed points (flat index, id, message), in flat-index order. No
/// failed points: nothing is written.
pub(super) fn write_errors(
    e: &Errors,
    mut errors: Vec<(u64, u64, String)>,
    out: &Path,
) -> Result<(), StoreError> {
    if !errors.is_empty() {
        errors.sort_by_key(|e| e.0);
        let n = errors.len();
        let grow = |ds: &Dataset| ds.resize(n).ctx(out, "write errors");
        let eidx: Vec<i64> = (0..n as i64).collect();
        let flat: Vec<u64> = errors.iter().map(|e| e.0).collect();
        let ids: Vec<u64> = errors.iter().map(|e| e.1).collect();
        let msgs: Vec<VarLenUnicode> = errors.iter().map(|e| h5u::vlstr(&e.2)).collect();
        for ds in [&e.index, &e.flat_index, &e.point_id, &e.message] {
            grow(ds)?;
        }
        let w = |r: hdf5::Result<()>| r.ctx(out, "write errors");
        w(h5u::write_small(&e.index, &eidx))?;
        w(h5u::write_small(&e.flat_index, &flat))?;
        w(h5u::write_small(&e.point_id, &ids))?;
        w(h5u::write_small(&e.message, &msgs))?;
    }
    Ok(())
}
