//! The results file written around the page cache.
//!
//! A results file grows at its end (`FileSpaceStrategy::None`, `build::skeleton`), one
//! history chunk after another: 16 KB a point for a modal history study. Through the page
//! cache every byte is first copied into a page, then written back by the kernel's own
//! threads, on the cores the workers need: on the development machine about a tenth of a
//! modal history study's CPU time (its wall time fell by a tenth with the file on tmpfs).
//! The driver in `driver.c` is HDF5's default one (POSIX reads and writes through the
//! page cache), except that writes which continue one another are gathered from a block
//! boundary and each whole block goes to the disk with `O_DIRECT`, from the buffer; what
//! is left of the last block stays in the buffer. HDF5 sees the same file byte for byte
//! (tested), and a file system that refuses `O_DIRECT` is written through the page cache.
//!
//! A write with `O_DIRECT` returns when the disk has the bytes, so the whole blocks go from
//! a thread of the driver's own, one at a time, while HDF5 gathers the next ones in a
//! second buffer: the disk works while the writer thread goes on, as with the page cache.
//! A second thread makes the file durable (`fdatasync`) every 4 MiB the first writes: a
//! block written with `O_DIRECT` waits in the disk's volatile cache, and the run's final
//! fsync otherwise waited for all of them at once after the last point (50 ms of the
//! bench's 0.5 s modal history study on the development machine; 3 to 5 ms with the
//! syncs). On a thread of its own, a sync (9 to 20 ms there) does not hold up whoever waits
//! for a block to be written: the writer thread before it journals, HDF5 reading metadata.
//!
//! What is gathered, and the block on its way, are not in the OS yet: the store journals a
//! record that names bytes in the file once [`in_os`] passes them, and at each flush sends
//! everything ([`write_gathered`]) first (`store::by_reference`, `store::session`); and it
//! does so before it syncs.

use hdf5::plist::{FileAccess, FileCreate};
use hdf5_sys::h5::herr_t;
use hdf5_sys::h5i::hid_t;
use std::ffi::CString;
use std::path::Path;

extern "C" {
    fn batstudy_direct_set(fapl: hid_t) -> herr_t;
    fn batstudy_direct_flush(file: hid_t) -> herr_t;
    fn batstudy_direct_in_os(file: hid_t, end: *mut u64) -> herr_t;
}

/// Create the HDF5 file at `path` exclusively (it must not exist; no link is followed),
/// with the access and creation properties `fapl` (given this driver) and `fcpl`.
pub fn create_excl(path: &Path, fapl: &FileAccess, fcpl: &FileCreate) -> hdf5::Result<hdf5::File> {
    let name = CString::new(path.as_os_str().as_encoded_bytes())
        .map_err(|_| hdf5::Error::from("a file name with a NUL byte"))?;
    hdf5::sync::sync(|| {
        // SAFETY: property lists made by the library, and a file id it returns, owned by
        // the `File` made of it; the name is NUL-terminated and outlives the call
        unsafe {
            if batstudy_direct_set(fapl.id()) < 0 {
                return Err(hdf5::Error::from("could not set the results file's driver"));
            }
            let flags = hdf5_sys::h5f::H5F_ACC_EXCL;
            let id = hdf5_sys::h5f::H5Fcreate(name.as_ptr(), flags, fcpl.id(), fapl.id());
            if id < 0 {
                return Err(hdf5::Error::query().unwrap_or_else(|e| e));
            }
            hdf5::from_id::<hdf5::File>(id)
        }
    })
}

/// An offset of `file` (made by [`create_excl`]) below which every byte written is in the
/// OS, at once: the bytes of the block on its way to the disk, and those gathered after it,
/// are not yet.
pub fn in_os(file: &hdf5::File) -> hdf5::Result<u64> {
    let mut end = 0u64;
    // SAFETY: an open file id, and a local for the offset
    match hdf5::sync::sync(|| unsafe { batstudy_direct_in_os(file.id(), &mut end) }) >= 0 {
        true => Ok(end),
        false => Err(hdf5::Error::from("could not write the results file")),
    }
}

/// Send what `file` (made by [`create_excl`]) has gathered to the OS, waiting for it: its
/// whole blocks to the disk, the rest through the page cache.
pub fn write_gathered(file: &hdf5::File) -> hdf5::Result<()> {
    // SAFETY: an open file id
    match hdf5::sync::sync(|| unsafe { batstudy_direct_flush(file.id()) }) >= 0 {
        true => Ok(()),
        false => Err(hdf5::Error::from(
            "could not write what the results file gathered",
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::chunks::write_chunk_at_end;
    use std::path::PathBuf;

    /// Datasets of chunks of 300 B to 1.5 MiB (one longer than a block, several crossing
    /// block boundaries), a dataset written in the ordinary way between them, attributes.
    const CHUNK_LENGTHS: [usize; 5] = [300, 4096, 13_001, 70_000, 1_500_000];

    fn props() -> (FileAccess, FileCreate) {
        let fapl = FileAccess::build().libver_v110().finish().unwrap();
        let fcpl = FileCreate::build()
            .file_space_strategy(hdf5::file::FileSpaceStrategy::None)
            .finish()
            .unwrap();
        (fapl, fcpl)
    }

    /// Chunk `c` of dataset `d`: bytes that differ from every other chunk's.
    fn chunk_bytes(d: usize, c: usize) -> Vec<u8> {
        (0..CHUNK_LENGTHS[d])
            .map(|i| (i * 31 + d * 7 + c * 13 + (i >> 8)) as u8)
            .collect()
    }

    /// Write the test's datasets into `f`; after each round of chunks, send what is
    /// gathered to the OS (when `gathered`) and check that the bytes each chunk's offset
    /// names are there for any reader of the file (what the journal relies on), and that
    /// HDF5 reads back what was written through the driver.
    fn write_all(f: &hdf5::File, path: &Path, gathered: bool) {
        let sets: Vec<hdf5::Dataset> = CHUNK_LENGTHS
            .iter()
            .enumerate()
            .map(|(d, &n)| {
                f.new_dataset::<u8>()
                    .chunk([1, n])
                    .shape([4, n])
                    .create(format!("d{d}").as_str())
                    .unwrap()
            })
            .collect();
        for c in 0..4 {
            let mut named = Vec::new();
            // the end of allocation carried from chunk to chunk, as a point's are written
            let mut eoa = None;
            for (d, ds) in sets.iter().enumerate() {
                let bytes = chunk_bytes(d, c);
                let at = write_chunk_at_end(ds, f.id(), &[c, 0], &bytes, &mut eoa).unwrap();
                named.extend(at.map(|at| (at, bytes)));
            }
            let plain = f
                .new_dataset_builder()
                .with_data(&[c as f64, 1.5, -2.0])
                .create(format!("plain{c}").as_str())
                .unwrap();
            plain
                .new_attr::<u32>()
                .create("round")
                .unwrap()
                .write_scalar(&(c as u32))
                .unwrap();
            assert_eq!(
                sets[0].read_2d::<u8>().unwrap().row(c).to_vec(),
                chunk_bytes(0, c)
            );
            if gathered {
                write_gathered(f).unwrap();
                let file = std::fs::read(path).unwrap();
                // (a dataset's first chunk also makes its chunk index: not placed alone)
                assert!(
                    c == 0 || named.len() >= 4,
                    "chunks written alone lie at the end"
                );
                for (at, bytes) in named {
                    assert_eq!(&file[at as usize..][..bytes.len()], &bytes[..], "round {c}");
                }
            }
        }
    }

    /// What the file holds, read back with HDF5's default driver.
    fn contents(path: &Path) -> Vec<Vec<u8>> {
        let f = hdf5::File::open(path).unwrap();
        let mut out: Vec<Vec<u8>> = (0..CHUNK_LENGTHS.len())
            .map(|d| {
                let ds = f.dataset(&format!("d{d}")).unwrap();
                ds.read_raw::<u8>().unwrap()
            })
            .collect();
        for c in 0..4 {
            let ds = f.dataset(&format!("plain{c}")).unwrap();
            let v = ds.read_raw::<f64>().unwrap();
            let round: u32 = ds.attr("round").unwrap().read_scalar().unwrap();
            out.push(v.iter().flat_map(|x| x.to_le_bytes()).collect());
            out.push(round.to_le_bytes().to_vec());
        }
        out
    }

    // The file written through this driver holds what HDF5's default driver writes, read
    // back with the default driver, on a disk (O_DIRECT) and on a file system that refuses
    // O_DIRECT (tmpfs, when there is one); and what it has gathered is, once sent, in the
    // file where the chunks' offsets say, for any reader.
    #[test]
    fn the_file_is_the_default_drivers_and_gathered_bytes_reach_the_file() {
        let disk = tempfile::tempdir().unwrap();
        let shm = Path::new("/dev/shm");
        let tmpfs = shm.is_dir().then(|| tempfile::tempdir_in(shm).unwrap());
        let mut dirs: Vec<PathBuf> = vec![disk.path().to_path_buf()];
        dirs.extend(tmpfs.as_ref().map(|d| d.path().to_path_buf()));
        let (fapl, fcpl) = props();
        for dir in dirs {
            let (a, b) = (dir.join("direct.h5"), dir.join("default.h5"));
            let f = create_excl(&a, &fapl, &fcpl).unwrap();
            write_all(&f, &a, true);
            drop(f);
            let (plain_fapl, _) = props();
            let f = hdf5::File::with_options()
                .set_access_plist(&plain_fapl)
                .unwrap()
                .set_create_plist(&fcpl)
                .unwrap()
                .create_excl(&b)
                .unwrap();
            write_all(&f, &b, false);
            drop(f);
            let want = contents(&b);
            for (d, n) in CHUNK_LENGTHS.iter().enumerate() {
                let rows: Vec<u8> = (0..4).flat_map(|c| chunk_bytes(d, c)).collect();
                assert_eq!(want[d].len(), 4 * n);
                assert_eq!(want[d], rows, "the default driver's dataset {d}");
            }
            assert_eq!(contents(&a), want, "{}", dir.display());
            assert!(
                create_excl(&a, &fapl, &fcpl).is_err(),
                "an existing file is refused"
            );
        }
    }
}
