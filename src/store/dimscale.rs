//! HDF5 dimension scales (libhdf5_hl's H5DS API, which hdf5-metno-sys does not bind) and the
//! small attribute/dataset helpers every group uses.

use super::layout::{VarDef, DEFLATE_LEVEL};
use hdf5::types::VarLenUnicode;
use hdf5::{Dataset, Group, H5Type, Location};
use hdf5_sys::h5::herr_t;
use hdf5_sys::h5i::hid_t;
use std::ffi::{c_char, c_uint, CString};
use std::str::FromStr;

extern "C" {
    fn H5DSset_scale(dsid: hid_t, dimname: *const c_char) -> herr_t;
    fn H5DSattach_scale(did: hid_t, dsid: hid_t, idx: c_uint) -> herr_t;
}

fn fail(what: String) -> hdf5::Error {
    hdf5::Error::from(what.as_str())
}

/// Make `ds` a dimension scale named `name`.
pub fn set_scale(ds: &Dataset, name: &str) -> hdf5::Result<()> {
    let c = CString::new(name).map_err(|_| fail(format!("bad dim name {name:?}")))?;
    let r = hdf5::sync::sync(|| unsafe { H5DSset_scale(ds.id(), c.as_ptr()) });
    if r < 0 {
        return Err(fail(format!("H5DSset_scale({name}) failed")));
    }
    Ok(())
}

/// Attach `scales[k]` to dimension k of `ds`.
pub fn attach_scales(ds: &Dataset, scales: &[&Dataset]) -> hdf5::Result<()> {
    for (k, s) in scales.iter().enumerate() {
        let r = hdf5::sync::sync(|| unsafe { H5DSattach_scale(ds.id(), s.id(), k as c_uint) });
        if r < 0 {
            return Err(fail(format!("H5DSattach_scale failed on {}", ds.name())));
        }
    }
    Ok(())
}

pub fn vlstr(s: &str) -> VarLenUnicode {
    // Interior NULs cannot be stored in a C string: replace them.
    VarLenUnicode::from_str(&s.replace('\0', "\u{FFFD}")).expect("no NUL")
}

pub fn attr_str(loc: &Location, name: &str, value: &str) -> hdf5::Result<()> {
    loc.new_attr::<VarLenUnicode>()
        .create(name)?
        .write_scalar(&vlstr(value))
}

pub fn attr_num<T: H5Type>(loc: &Location, name: &str, value: T) -> hdf5::Result<()> {
    loc.new_attr::<T>().create(name)?.write_scalar(&value)
}

pub fn attr_vec<T: H5Type + Copy>(loc: &Location, name: &str, values: &[T]) -> hdf5::Result<()> {
    loc.new_attr::<T>()
        .shape(values.len())
        .create(name)?
        .write_raw(values)
}

pub fn describe(ds: &Dataset, def: &VarDef) -> hdf5::Result<()> {
    attr_str(ds, "units", def.units)?;
    attr_str(ds, "long_name", def.long_name)
}

/// Create an empty chunked + shuffled + deflated dataset (contiguous when it cannot be chunked:
/// scalars and empty arrays) with a fill value.
pub fn create_var<T: H5Type + Into<hdf5::types::OwnedDynValue>>(
    g: &Group,
    name: &str,
    shape: &[usize],
    chunk: &[usize],
    fill: T,
) -> hdf5::Result<Dataset> {
    create_var_level(g, name, shape, chunk, fill, DEFLATE_LEVEL)
}

/// `create_var` with this deflate level.
pub fn create_var_level<T: H5Type + Into<hdf5::types::OwnedDynValue>>(
    g: &Group,
    name: &str,
    shape: &[usize],
    chunk: &[usize],
    fill: T,
    level: u8,
) -> hdf5::Result<Dataset> {
    let mut b = g.new_dataset_builder().empty::<T>();
    let chunkable = !shape.is_empty() && shape.iter().all(|&n| n > 0);
    b = b.fill_value(fill);
    if chunkable {
        b = b.chunk(chunk.to_vec()).shuffle().deflate(level);
    }
    b.shape(shape.to_vec()).create(name)
}

/// A 1-D dataset with data (small coordinate/bat variables; contiguous).
pub fn write_1d<T: H5Type>(g: &Group, name: &str, data: &[T]) -> hdf5::Result<Dataset> {
    let ds = g.new_dataset::<T>().shape(data.len()).create(name)?;
    write_small(&ds, data)?;
    Ok(ds)
}

/// Write all of a small dataset. HDF5's default transfer allocates and zeroes two 1 MiB
/// conversion buffers per write when the types need converting (strings do); sizing them to
/// the data keeps a small write small.
pub fn write_small<T: H5Type>(ds: &Dataset, data: &[T]) -> hdf5::Result<()> {
    use hdf5_sys::h5d::H5Dwrite;
    use hdf5_sys::h5p::{H5Pclose, H5Pcreate, H5Pset_buffer, H5P_CLS_DATASET_XFER};
    use hdf5_sys::h5s::H5S_ALL;
    if data.is_empty() {
        return Ok(());
    }
    let mem = hdf5::Datatype::from_type::<T>()?;
    // at least one element of any type; the library needs room for one converted element
    let size = (std::mem::size_of_val(data) * 4).max(4096);
    let r = hdf5::sync::sync(|| unsafe {
        let dxpl = H5Pcreate(*H5P_CLS_DATASET_XFER);
        if dxpl < 0 {
            return -1;
        }
        let mut r = H5Pset_buffer(dxpl, size, std::ptr::null_mut(), std::ptr::null_mut());
        if r >= 0 {
            r = H5Dwrite(
                ds.id(),
                mem.id(),
                H5S_ALL,
                H5S_ALL,
                dxpl,
                data.as_ptr().cast(),
            );
        }
        H5Pclose(dxpl);
        r
    });
    if r < 0 {
        return Err(fail(format!("H5Dwrite failed on {}", ds.name())));
    }
    Ok(())
}

/// An empty 1-D dataset that can grow (chunked; rows are added by resizing it).
pub fn create_growable<T: H5Type>(g: &Group, name: &str) -> hdf5::Result<Dataset> {
    g.new_dataset::<T>().shape(0..).chunk(1024).create(name)
}

/// Create a dimension-scale coordinate variable of numbers or labels.
pub fn scale_coord<T: H5Type>(
    g: &Group,
    name: &str,
    data: &[T],
    def: &VarDef,
) -> hdf5::Result<Dataset> {
    let ds = write_1d(g, name, data)?;
    set_scale(&ds, name)?;
    describe(&ds, def)?;
    Ok(ds)
}

/// Selection of a block: start/count per dim.
pub fn block(start: &[usize], count: &[usize]) -> hdf5::Hyperslab {
    use hdf5::SliceOrIndex;
    start
        .iter()
        .zip(count)
        .map(|(&s, &c)| SliceOrIndex::SliceCount {
            start: s,
            step: 1,
            count: c,
            block: 1,
        })
        .collect::<Vec<_>>()
        .into()
}
