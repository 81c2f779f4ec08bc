//! The dimension scales batstudy attaches itself (`store::dimscale::Attacher`, issue 7) must
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
