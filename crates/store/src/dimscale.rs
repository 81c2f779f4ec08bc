//! HDF5 dimension scales (libhdf5_hl's H5DS API, which hdf5-metno-sys does not bind) and the
//! small attribute/dataset helpers every group uses.

use super::layout::{VarDef, DEFLATE_LEVEL};
use hdf5::types::VarLenUnicode;
use hdf5::{Dataset, Group, H5Type, Location};
use hdf5_sys::h5::herr_t;
use hdf5_sys::h5i::hid_t;
use std::ffi::{c_char, c_int, c_void, CString};
use std::str::FromStr;

extern "C" {
    fn H5DSset_scale(dsid: hid_t, dimname: *const c_char) -> herr_t;
    // the 1.8-style object reference (`H5R_OBJECT` = 0 in every version) that dimension
    // scales store; declared here so as not to depend on the -sys crate's version gates
    fn H5Rcreate(
        reference: *mut c_void,
        loc_id: hid_t,
        name: *const c_char,
        ref_type: c_int,
        space_id: hid_t,
    ) -> herr_t;
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

/// Dimension scales attached in one go. `H5DSattach_scale` rewrites a variable's
/// `DIMENSION_LIST` and its scale's whole `REFERENCE_LIST` on every call (a third of the
/// file skeleton's cost); this collects the links and writes each attribute once,
/// with the types and layout the H5DS API uses, so every reader (h5py, netCDF, xarray) sees
/// the same scales.
#[derive(Default)]
pub struct Attacher {
    links: std::cell::RefCell<Vec<(Dataset, Vec<Dataset>)>>,
}

/// One `REFERENCE_LIST` entry: H5DS's `ds_list_t` (an object reference, then the dimension).
#[repr(C)]
struct BackReference {
    dataset: u64,
    dimension: c_int,
}

/// Closes an HDF5 id when dropped.
struct Owned(hid_t, unsafe extern "C" fn(hid_t) -> herr_t);

impl Owned {
    fn new(
        id: hid_t,
        close: unsafe extern "C" fn(hid_t) -> herr_t,
        what: &str,
    ) -> hdf5::Result<Owned> {
        if id < 0 {
            return Err(fail(format!("{what} failed")));
        }
        Ok(Owned(id, close))
    }
}

impl Drop for Owned {
    fn drop(&mut self) {
        unsafe { (self.1)(self.0) };
    }
}

fn check(r: herr_t, what: &str) -> hdf5::Result<()> {
    if r < 0 {
        return Err(fail(format!("{what} failed")));
    }
    Ok(())
}

/// The object reference (`hobj_ref_t`) to `ds` that dimension-scale attributes hold.
fn object_ref(ds: &Dataset) -> hdf5::Result<u64> {
    let mut r: u64 = 0;
    let here = c".";
    check(
        unsafe { H5Rcreate((&raw mut r).cast(), ds.id(), here.as_ptr(), 0, -1) },
        "H5Rcreate",
    )?;
    Ok(r)
}

/// Create attribute `name` of type `dtype` over dataspace `space` (creation list `acpl`) on
/// `loc`, and write `buf` into it.
fn put_attr(
    loc: hid_t,
    name: &str,
    (dtype, space, acpl): (hid_t, hid_t, hid_t),
    buf: *const c_void,
) -> hdf5::Result<()> {
    use hdf5_sys::h5a::{H5Aclose, H5Acreate2, H5Awrite};
    use hdf5_sys::h5p::H5P_DEFAULT;
    let c = CString::new(name).map_err(|_| fail(format!("bad attribute name {name:?}")))?;
    let attr = Owned::new(
        unsafe { H5Acreate2(loc, c.as_ptr(), dtype, space, acpl, H5P_DEFAULT) },
        H5Aclose,
        name,
    )?;
    check(unsafe { H5Awrite(attr.0, dtype, buf) }, name)
}

/// Write attribute `name` of `len` elements of `dtype` from `buf` on `loc`.
fn write_attr(
    loc: hid_t,
    name: &str,
    dtype: hid_t,
    len: usize,
    buf: *const c_void,
) -> hdf5::Result<()> {
    use hdf5_sys::h5p::H5P_DEFAULT;
    use hdf5_sys::h5s::{H5Sclose, H5Screate_simple};
    let dims = [len as hdf5_sys::h5::hsize_t];
    let space = Owned::new(
        unsafe { H5Screate_simple(1, dims.as_ptr(), std::ptr::null()) },
        H5Sclose,
        "H5Screate_simple",
    )?;
    put_attr(loc, name, (dtype, space.0, H5P_DEFAULT), buf)
}

impl Attacher {
    /// Attach `scales[k]` to dimension k of `ds` (written by [`Self::write`]).
    pub fn add(&self, ds: &Dataset, scales: &[&Dataset]) {
        let scales = scales.iter().map(|&s| s.clone()).collect();
        self.links.borrow_mut().push((ds.clone(), scales));
    }

    /// Write every variable's `DIMENSION_LIST` and every scale's `REFERENCE_LIST` (in the
    /// order the links were added, as `H5DSattach_scale` would have appended them). Each
    /// scale must get all its links from this one attacher.
    pub fn write(self) -> hdf5::Result<()> {
        use hdf5_sys::h5t::{
            hvl_t, H5T_class_t, H5Tclose, H5Tcreate, H5Tinsert, H5Tvlen_create, H5T_NATIVE_INT,
            H5T_STD_REF_OBJ,
        };
        let links = self.links.into_inner();
        hdf5::sync::sync(|| {
            let vlen = Owned::new(
                unsafe { H5Tvlen_create(*H5T_STD_REF_OBJ) },
                H5Tclose,
                "H5Tvlen_create",
            )?;
            // scales in order of first use, each with its back references
            let mut scales: Vec<(u64, &Dataset, Vec<BackReference>)> = Vec::new();
            for (ds, dim_scales) in &links {
                let me = object_ref(ds)?;
                let mut refs = Vec::with_capacity(dim_scales.len());
                for (k, sc) in dim_scales.iter().enumerate() {
                    let r = object_ref(sc)?;
                    refs.push(r);
                    let back = BackReference {
                        dataset: me,
                        dimension: k as c_int,
                    };
                    match scales.iter_mut().find(|(s, _, _)| *s == r) {
                        Some((_, _, v)) => v.push(back),
                        None => scales.push((r, sc, vec![back])),
                    }
                }
                let lists: Vec<hvl_t> = refs
                    .iter_mut()
                    .map(|r| hvl_t {
                        len: 1,
                        p: (r as *mut u64).cast(),
                    })
                    .collect();
                write_attr(
                    ds.id(),
                    "DIMENSION_LIST",
                    vlen.0,
                    lists.len(),
                    lists.as_ptr().cast(),
                )?;
            }
            let compound = Owned::new(
                unsafe { H5Tcreate(H5T_class_t::H5T_COMPOUND, size_of::<BackReference>()) },
                H5Tclose,
                "H5Tcreate",
            )?;
            let members = [
                (
                    c"dataset",
                    std::mem::offset_of!(BackReference, dataset),
                    *H5T_STD_REF_OBJ,
                ),
                (
                    c"dimension",
                    std::mem::offset_of!(BackReference, dimension),
                    *H5T_NATIVE_INT,
                ),
            ];
            for (name, offset, member) in members {
                let r = unsafe { H5Tinsert(compound.0, name.as_ptr(), offset, member) };
                check(r, "H5Tinsert")?;
            }
            for (_, sc, backs) in &scales {
                write_attr(
                    sc.id(),
                    "REFERENCE_LIST",
                    compound.0,
                    backs.len(),
                    backs.as_ptr().cast(),
                )?;
            }
            Ok(())
        })
    }
}

pub fn vlstr(s: &str) -> VarLenUnicode {
    // Interior NULs cannot be stored in a C string: replace them.
    VarLenUnicode::from_str(&s.replace('\0', "\u{FFFD}")).expect("no NUL")
}

/// The ids every string attribute is made with: a variable-length UTF-8 string type, a
/// scalar dataspace and a creation list for UTF-8 names (what hdf5-metno's
/// `new_attr::<VarLenUnicode>()` builds for each attribute). Made once per process, never
/// closed: building them per attribute, through the wrapper's checks, would be about a third
/// of the file skeleton's instructions (the skeleton has about 140 string attributes).
struct StrAttrIds {
    string: hid_t,
    scalar: hid_t,
    acpl: hid_t,
}

fn str_attr_ids() -> hdf5::Result<&'static StrAttrIds> {
    use hdf5_sys::h5p::{H5Pcreate, H5Pset_char_encoding, H5P_CLS_ATTRIBUTE_CREATE};
    use hdf5_sys::h5s::{H5S_class_t, H5Screate};
    use hdf5_sys::h5t::{
        H5T_cset_t, H5T_str_t, H5Tcopy, H5Tset_cset, H5Tset_size, H5Tset_strpad, H5T_C_S1,
        H5T_VARIABLE,
    };
    static IDS: std::sync::OnceLock<Result<StrAttrIds, String>> = std::sync::OnceLock::new();
    let ids = IDS.get_or_init(|| {
        hdf5::sync::sync(|| unsafe {
            let string = H5Tcopy(*H5T_C_S1);
            let scalar = H5Screate(H5S_class_t::H5S_SCALAR);
            let acpl = H5Pcreate(*H5P_CLS_ATTRIBUTE_CREATE);
            let ok = string >= 0
                && scalar >= 0
                && acpl >= 0
                && H5Tset_cset(string, H5T_cset_t::H5T_CSET_UTF8) >= 0
                && H5Tset_strpad(string, H5T_str_t::H5T_STR_NULLTERM) >= 0
                && H5Tset_size(string, H5T_VARIABLE) >= 0
                && H5Pset_char_encoding(acpl, H5T_cset_t::H5T_CSET_UTF8) >= 0;
            if ok {
                Ok(StrAttrIds {
                    string,
                    scalar,
                    acpl,
                })
            } else {
                Err("making the string attribute type failed".to_string())
            }
        })
    });
    ids.as_ref().map_err(|e| fail(e.clone()))
}

/// A scalar variable-length UTF-8 string attribute (interior NULs replaced, as [`vlstr`]).
pub fn attr_str(loc: &Location, name: &str, value: &str) -> hdf5::Result<()> {
    let ids = str_attr_ids()?;
    let c_value = CString::new(value.replace('\0', "\u{FFFD}")).expect("no NUL left");
    let ptr: *const c_char = c_value.as_ptr();
    let types = (ids.string, ids.scalar, ids.acpl);
    hdf5::sync::sync(|| put_attr(loc.id(), name, types, (&raw const ptr).cast()))
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

/// `units` (none on text: CF has no unit for it), `long_name` (short, for plot labels) and
/// `description` (the full sentence).
pub fn describe(ds: &Dataset, def: &VarDef) -> hdf5::Result<()> {
    describe_parts(ds, def.units, def.long_name, def.description)
}

pub fn describe_parts(
    ds: &Dataset,
    units: &str,
    long_name: &str,
    description: &str,
) -> hdf5::Result<()> {
    if !units.is_empty() {
        attr_str(ds, "units", units)?;
    }
    attr_str(ds, "long_name", long_name)?;
    if !description.is_empty() && description != long_name {
        attr_str(ds, "description", description)?;
    }
    let name = ds.name();
    let short = name.rsplit('/').next().unwrap_or(&name);
    if let Some((_, axis, standard)) = crate::layout::CF_NAMES.iter().find(|c| c.0 == short) {
        if !axis.is_empty() {
            attr_str(ds, "axis", axis)?;
        }
        attr_str(ds, "standard_name", standard)?;
    }
    Ok(())
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

/// `create_var` with this deflate level (0: chunked, no filters).
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
        b = b.chunk(chunk.to_vec());
        // level 0: stored as it is (no filter), see `layout::history_deflate_level`
        if level > 0 {
            b = b.shuffle().deflate(level);
        }
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
    hdf5::sync::sync(|| {
        let dxpl = Owned::new(
            unsafe { H5Pcreate(*H5P_CLS_DATASET_XFER) },
            H5Pclose,
            "H5Pcreate",
        )?;
        let none = std::ptr::null_mut();
        check(
            unsafe { H5Pset_buffer(dxpl.0, size, none, none) },
            "H5Pset_buffer",
        )?;
        let (all, buf) = (H5S_ALL, data.as_ptr().cast());
        let r = unsafe { H5Dwrite(ds.id(), mem.id(), all, all, dxpl.0, buf) };
        check(r, &format!("H5Dwrite on {}", ds.name()))
    })
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

/// The coordinate of a dim without values of its own: its index 0..`len`, as a dimension
/// scale named `name`.
pub fn index_coord(g: &Group, name: &str, len: usize) -> hdf5::Result<Dataset> {
    let idx: Vec<i64> = (0..len as i64).collect();
    let (long_name, description) = (format!("{name} index"), format!("index along {name}"));
    let def = VarDef {
        name: "",
        units: "1",
        long_name: &long_name,
        description: &description,
    };
    scale_coord(g, name, &idx, &def)
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
