//! The dimension scales batstudy attaches itself (`store::dimscale::Attacher`) must
//! be what HDF5's own H5DS API reads: each variable's DIMENSION_LIST and each scale's
//! REFERENCE_LIST agree. Checked with libhdf5_hl's `H5DSis_attached` (which reads both
//! lists) and `H5DSget_num_scales`, the functions h5py and netCDF use.

use batstudy::store::dimscale::{set_scale, write_1d, Attacher};
use hdf5_sys::h5::htri_t;
use hdf5_sys::h5i::hid_t;
use std::ffi::c_uint;

extern "C" {
    fn H5DSis_attached(did: hid_t, dsid: hid_t, idx: c_uint) -> htri_t;
    fn H5DSget_num_scales(did: hid_t, dim: c_uint) -> std::ffi::c_int;
    fn H5DSis_scale(did: hid_t) -> htri_t;
}

#[test]
fn attached_scales_read_back_through_h5ds() {
    let dir = tempfile::tempdir().unwrap();
    let f = hdf5::File::create(dir.path().join("scales.h5")).unwrap();
    let g = f.create_group("g").unwrap();
    let x = write_1d(&g, "x", &[0.0f64, 1.0, 2.0]).unwrap();
    let y = write_1d(&g, "y", &[10i64, 20]).unwrap();
    set_scale(&x, "x").unwrap();
    set_scale(&y, "y").unwrap();
    let a = g.new_dataset::<f64>().shape([3, 2]).create("a").unwrap();
    let b = g.new_dataset::<f64>().shape([3, 2]).create("b").unwrap();
    let c = g.new_dataset::<f64>().shape([2]).create("c").unwrap();
    let att = Attacher::default();
    att.add(&a, &[&x, &y]);
    att.add(&b, &[&x, &y]);
    att.add(&c, &[&y]);
    att.write().unwrap();

    let is = |v: &hdf5::Dataset, s: &hdf5::Dataset, k: u32| unsafe {
        H5DSis_attached(v.id(), s.id(), k)
    };
    for v in [&a, &b] {
        assert_eq!(is(v, &x, 0), 1);
        assert_eq!(is(v, &y, 1), 1);
        assert_eq!(is(v, &x, 1), 0);
        assert_eq!(is(v, &y, 0), 0);
        for k in 0..2 {
            assert_eq!(unsafe { H5DSget_num_scales(v.id(), k) }, 1);
        }
    }
    assert_eq!(is(&c, &y, 0), 1);
    assert_eq!(is(&c, &x, 0), 0);
    assert_eq!(unsafe { H5DSis_scale(x.id()) }, 1);
    assert_eq!(unsafe { H5DSis_scale(a.id()) }, 0);
    // the back references, as H5DSattach_scale would have appended them
    let refs = |s: &hdf5::Dataset| s.attr("REFERENCE_LIST").unwrap().space().unwrap().shape();
    assert_eq!(refs(&x), vec![2]);
    assert_eq!(refs(&y), vec![3]);
}

// `attr_str` builds its attributes with raw HDF5 calls (the wrapper's per-attribute type
// and property-list building would be a third of the skeleton's cost). It must store what
// hdf5-metno's `new_attr::<VarLenUnicode>()` stores — a scalar, variable-length,
// null-terminated UTF-8 string with a UTF-8 name — so that h5py, netCDF and xarray read the
// same `str`. Reference: the HDF5 attribute and datatype APIs (H5Aget_type, H5Tis_variable_str,
// H5Tget_cset, H5Tget_strpad; H5Pget_char_encoding on the attribute's creation list).
#[test]
fn string_attributes_match_the_wrappers_own() {
    use batstudy::store::dimscale::attr_str;
    use hdf5::types::VarLenUnicode;
    use hdf5_sys::h5a::{H5Aget_create_plist, H5Aget_type, H5Aopen};
    use hdf5_sys::h5p::{H5Pclose, H5Pget_char_encoding, H5P_DEFAULT};
    use hdf5_sys::h5t::{
        H5T_class_t, H5T_cset_t, H5T_str_t, H5Tclose, H5Tget_class, H5Tget_cset, H5Tget_strpad,
        H5Tis_variable_str,
    };
    use std::ffi::CString;
    use std::str::FromStr;

    let dir = tempfile::tempdir().unwrap();
    let f = hdf5::File::create(dir.path().join("attrs.h5")).unwrap();
    let value = "m/s² — ∂y/∂t";
    attr_str(&f, "ours", value).unwrap();
    f.new_attr::<VarLenUnicode>()
        .create("wrappers")
        .unwrap()
        .write_scalar(&VarLenUnicode::from_str(value).unwrap())
        .unwrap();
    // an interior NUL cannot be stored in a C string: it is replaced, not an error
    attr_str(&f, "nul", "a\0b").unwrap();

    let read = |name: &str| -> String {
        f.attr(name)
            .unwrap()
            .read_scalar::<VarLenUnicode>()
            .unwrap()
            .to_string()
    };
    assert_eq!(read("ours"), value);
    assert_eq!(read("wrappers"), value);
    assert_eq!(read("nul"), "a\u{FFFD}b");

    let describe = |name: &str| unsafe {
        let c = CString::new(name).unwrap();
        let a = H5Aopen(f.id(), c.as_ptr(), H5P_DEFAULT);
        assert!(a >= 0);
        let t = H5Aget_type(a);
        let p = H5Aget_create_plist(a);
        let mut name_cset = H5T_cset_t::H5T_CSET_ASCII;
        assert!(H5Pget_char_encoding(p, &mut name_cset) >= 0);
        let d = (
            H5Tget_class(t) == H5T_class_t::H5T_STRING,
            H5Tis_variable_str(t),
            H5Tget_cset(t) == H5T_cset_t::H5T_CSET_UTF8,
            H5Tget_strpad(t) == H5T_str_t::H5T_STR_NULLTERM,
            name_cset == H5T_cset_t::H5T_CSET_UTF8,
        );
        H5Pclose(p);
        H5Tclose(t);
        hdf5_sys::h5a::H5Aclose(a);
        d
    };
    assert_eq!(describe("ours"), describe("wrappers"));
    assert_eq!(describe("ours"), (true, 1, true, true, true));
    assert!(f.attr("ours").unwrap().is_scalar());
}
