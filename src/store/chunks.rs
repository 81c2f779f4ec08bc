//! Summary chunks compressed on every core and written whole (`H5Dwrite_chunk`): the bytes
//! HDF5's shuffle + deflate filters would store, made in parallel instead of by the library
//! one chunk at a time on the writer thread (issue 7: deflate was most of the time it took to
//! finish a run, and that time is serial). Any zlib stream is what the deflate filter reads;
//! libdeflate makes one about twice as fast as zlib.

use hdf5::Dataset;
use hdf5_sys::h5::{herr_t, hsize_t};
use hdf5_sys::h5i::hid_t;
use libdeflater::{CompressionLvl, Compressor};
use std::borrow::Cow;
use std::cell::RefCell;
use std::ffi::c_void;

extern "C" {
    // libhdf5 ≥ 1.10.2; declared here so as not to depend on the -sys crate's version gates
    fn H5Dwrite_chunk(
        dset_id: hid_t,
        dxpl_id: hid_t,
        filters: u32,
        offset: *const hsize_t,
        data_size: usize,
        buf: *const c_void,
    ) -> herr_t;
}

/// A value stored in a summary chunk: its little-endian bytes (HDF5's native types here).
pub trait ChunkValue: Copy + Send + Sync {
    const SIZE: usize;
    fn put_le(self, out: &mut Vec<u8>);
    /// The value's little-endian bytes into `out[..SIZE]`.
    fn write_le(self, out: &mut [u8]);
}

macro_rules! chunk_value {
    ($($t:ty),*) => {$(
        impl ChunkValue for $t {
            const SIZE: usize = std::mem::size_of::<$t>();
            fn put_le(self, out: &mut Vec<u8>) {
                out.extend_from_slice(&self.to_le_bytes());
            }
            fn write_le(self, out: &mut [u8]) {
                out[..Self::SIZE].copy_from_slice(&self.to_le_bytes());
            }
        }
    )*};
}
chunk_value!(f64, f32, i8, i32, u64);

/// A block's values (row-major over `count`) laid out as a whole chunk (row-major over
/// `chunk`, `count ≤ chunk`): an edge block is padded with `fill`, as HDF5 stores it.
fn padded<'a, T: Copy>(values: &'a [T], count: &[usize], chunk: &[usize], fill: T) -> Cow<'a, [T]> {
    if count == chunk {
        return Cow::Borrowed(values);
    }
    let n: usize = chunk.iter().product();
    let mut out = vec![fill; n];
    let mut idx = vec![0usize; count.len()];
    for &v in values {
        let at = idx.iter().zip(chunk).fold(0, |a, (&i, &c)| a * c + i);
        out[at] = v;
        for k in (0..idx.len()).rev() {
            idx[k] += 1;
            if idx[k] < count[k] {
                break;
            }
            idx[k] = 0;
        }
    }
    Cow::Owned(out)
}

/// HDF5's shuffle filter: byte `j` of element `i` goes to `j * n + i`.
fn shuffle(bytes: &[u8], size: usize) -> Vec<u8> {
    if size <= 1 {
        return bytes.to_vec();
    }
    let n = bytes.len() / size;
    let mut out = vec![0u8; bytes.len()];
    for (i, e) in bytes.chunks_exact(size).enumerate() {
        for (j, &b) in e.iter().enumerate() {
            out[j * n + i] = b;
        }
    }
    out
}

/// The values' little-endian bytes, one after the other.
fn le_bytes<T: ChunkValue>(values: &[T]) -> Vec<u8> {
    let mut raw = Vec::with_capacity(values.len() * T::SIZE);
    for &v in values {
        v.put_le(&mut raw);
    }
    raw
}

/// The bytes HDF5 stores for one chunk of a dataset created with shuffle then deflate(`level`).
pub fn filtered<T: ChunkValue>(
    values: &[T],
    count: &[usize],
    chunk: &[usize],
    fill: T,
    level: u8,
) -> Vec<u8> {
    let whole = padded(values, count, chunk, fill);
    let shuffled = shuffle(&le_bytes(&whole), T::SIZE);
    deflate_zlib(&shuffled, level)
}

/// [`filtered`] for values that fill their chunk (a history: one chunk per point); level 0:
/// the raw values of a dataset without filters. Shuffled
/// straight from the values: the same bytes with one copy less. Runs on the workers
/// (`store::encode`, issue 22).
pub fn filtered_whole<T: ChunkValue>(values: &[T], level: u8) -> Vec<u8> {
    let n = values.len();
    if level == 0 {
        return le_bytes(values); // no filters: the values as they are
    }
    let mut shuffled = vec![0u8; n * T::SIZE];
    let mut e = [0u8; 16];
    for (i, &v) in values.iter().enumerate() {
        v.write_le(&mut e);
        for (j, &b) in e[..T::SIZE].iter().enumerate() {
            shuffled[j * n + i] = b;
        }
    }
    deflate_zlib(&shuffled, level)
}

thread_local! {
    /// One compressor per thread and level: libdeflate's state is a few hundred KiB, too
    /// much to allocate (and fault in) for every chunk.
    static COMPRESSOR: RefCell<Option<(u8, Compressor)>> = const { RefCell::new(None) };
}

/// `bytes` as a zlib stream (what HDF5's deflate filter stores), by libdeflate: whole
/// buffers only, about twice as fast as zlib at the same level for the same size (issue 7:
/// deflate was most of finishing a small study's file).
fn deflate_zlib(bytes: &[u8], level: u8) -> Vec<u8> {
    COMPRESSOR.with(|c| {
        let mut c = c.borrow_mut();
        if c.as_ref().is_none_or(|(l, _)| *l != level) {
            let lvl = CompressionLvl::new(level.into()).unwrap_or_default();
            *c = Some((level, Compressor::new(lvl)));
        }
        let (_, comp) = c.as_mut().expect("set above");
        let mut out = vec![0u8; comp.zlib_compress_bound(bytes.len())];
        let n = comp
            .zlib_compress(bytes, &mut out)
            .expect("the output buffer is the compressor's own bound");
        out.truncate(n);
        out
    })
}

/// Write a chunk's filtered bytes at its (chunk-aligned) start.
pub fn write_chunk(ds: &Dataset, start: &[usize], bytes: &[u8]) -> hdf5::Result<()> {
    let offset: Vec<hsize_t> = start.iter().map(|&s| s as hsize_t).collect();
    let r = hdf5::sync::sync(|| unsafe {
        H5Dwrite_chunk(
            ds.id(),
            hdf5_sys::h5p::H5P_DEFAULT,
            0,
            offset.as_ptr(),
            bytes.len(),
            bytes.as_ptr().cast(),
        )
    });
    if r < 0 {
        return Err(hdf5::Error::from(
            format!("H5Dwrite_chunk failed on {}", ds.name()).as_str(),
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    // HDF5's shuffle transposes bytes (H5Zshuffle.c): for two 2-byte elements AB CD the
    // stored bytes are A C B D.
    #[test]
    fn shuffle_transposes_bytes() {
        assert_eq!(shuffle(&[1, 2, 3, 4], 2), vec![1, 3, 2, 4]);
        assert_eq!(shuffle(&[1, 2, 3], 1), vec![1, 2, 3]);
    }

    // The workers' history chunks are the bytes the finish made before issue 22.
    #[test]
    fn whole_chunks_are_filtered_as_before() {
        let v: Vec<f32> = (0..1000).map(|i| (i as f32 * 0.37).sin()).collect();
        assert_eq!(
            filtered_whole(&v, 1),
            filtered(&v, &[1000], &[1000], f32::NAN, 1)
        );
        let w: Vec<f64> = (0..999).map(|i| (i as f64).sqrt()).collect();
        assert_eq!(
            filtered_whole(&w, 1),
            filtered(&w, &[1, 999], &[1, 999], f64::NAN, 1)
        );
    }

    // An edge block keeps its values at their places in the whole chunk; the rest is fill.
    #[test]
    fn edge_block_is_padded_in_place() {
        let v = padded(&[1, 2, 3, 4], &[2, 2], &[3, 3], 0);
        assert_eq!(&*v, &[1, 2, 0, 3, 4, 0, 0, 0, 0]);
    }
}
