//! A results file's structure checked before HDF5 reads it (docs/layout.md, "A damaged
//! file"): the same check as the Python package's `batstudy._files`.
//!
//! HDF5 verifies a checksum on everything it reads of a results file (superblock, object
//! headers, B-trees, the heaps of links and attributes, chunk indices) except raw data and
//! the *global heap collections* (`GCOL`), which hold every variable-length value: strings,
//! and each variable's list of dimension scales. In a damaged collection an object of length
//! 0 makes HDF5's parser loop forever, and one longer than its collection makes it copy past
//! the collection's end (a crash). So every collection in the file is walked here as HDF5
//! walks it, and a file in which one would not end cleanly is refused.

use super::error::StoreError;
use std::fs::File;
use std::io::Read;
use std::os::unix::fs::FileExt;
use std::path::Path;

const SIGNATURE: &[u8] = b"\x89HDF\r\n\x1a\n";
/// A global heap collection, version 1.
const COLLECTION: &[u8] = b"GCOL\x01";
/// Signature, version, reserved, the collection's length (8-byte lengths).
const COLLECTION_HEADER: u64 = 16;
/// Index, references, reserved, length.
const OBJECT_HEADER: u64 = 16;
/// HDF5 never writes a smaller collection.
const MIN_COLLECTION: u64 = 4096;
/// The file is searched in blocks of this many bytes.
const BLOCK: usize = 4 << 20;

/// "not a batstudy results file: damaged: `what`".
pub fn damaged(path: &Path, what: String) -> StoreError {
    StoreError::BadFile {
        path: path.to_path_buf(),
        what: format!("damaged: {what}"),
    }
}

/// Refuse anything but a regular file before it is opened: opening a pipe waits for a
/// writer that may never come, and a device (`/dev/zero`) has no end to read to.
pub fn regular_file(path: &Path) -> Result<(), StoreError> {
    match is_regular(path, "open the results file")? {
        true => Ok(()),
        false => Err(StoreError::BadFile {
            path: path.to_path_buf(),
            what: NOT_REGULAR.into(),
        }),
    }
}

/// What a reader says of a path that is not a regular file.
pub(crate) const NOT_REGULAR: &str = "not a regular file (a folder, a device or a pipe)";

/// Whether `path` is a regular file, asked without opening it (`opening`: what the error
/// of a missing path says was being done).
pub(crate) fn is_regular(path: &Path, opening: &str) -> Result<bool, StoreError> {
    std::fs::metadata(path)
        .map(|m| m.is_file())
        .map_err(|e| StoreError::io(path, opening, e))
}

/// Refuse `path` if it is not HDF5, is shorter than its superblock says, or holds a global
/// heap collection HDF5 could not read to its end. Reads the file once.
pub fn check_structure(path: &Path) -> Result<(), StoreError> {
    regular_file(path)?;
    let mut f = File::open(path).map_err(|e| StoreError::io(path, "open the results file", e))?;
    let size = f
        .metadata()
        .map_err(|e| StoreError::io(path, "read the results file", e))?
        .len();
    let mut head = [0u8; 48];
    let n = read_up_to(&mut f, &mut head).map_err(|e| StoreError::io(path, "read it", e))?;
    if n < SIGNATURE.len() || &head[..SIGNATURE.len()] != SIGNATURE {
        return Err(StoreError::BadFile {
            path: path.to_path_buf(),
            what: "not an HDF5 file (no HDF5 signature at its start)".into(),
        });
    }
    check_end(path, &head[..n], size)?;
    for at in collections(&f, path)? {
        if let Some(problem) = collection_problem(&f, at, size) {
            return Err(damaged(
                path,
                format!("the global heap collection at byte {at} {problem}"),
            ));
        }
    }
    Ok(())
}

fn read_up_to(f: &mut File, buf: &mut [u8]) -> std::io::Result<usize> {
    let mut n = 0;
    while n < buf.len() {
        match f.read(&mut buf[n..])? {
            0 => break,
            k => n += k,
        }
    }
    Ok(n)
}

/// A superblock of version 2 or 3 (what HDF5 1.10 on writes) states the file's end.
fn check_end(path: &Path, head: &[u8], size: u64) -> Result<(), StoreError> {
    if head.len() == 48 && matches!(head[8], 2 | 3) && head[9] == 8 {
        let end = u64::from_le_bytes(head[28..36].try_into().expect("8 bytes"));
        if end > size {
            return Err(damaged(
                path,
                format!("truncated: {size} bytes of the {end} its superblock states"),
            ));
        }
    }
    Ok(())
}

/// Where the file holds a collection's signature, in order.
fn collections(f: &File, path: &Path) -> Result<Vec<u64>, StoreError> {
    let finder = memchr::memmem::Finder::new(COLLECTION);
    let keep = COLLECTION.len() - 1; // a signature may straddle two blocks
    let mut buf = vec![0u8; BLOCK + keep];
    let (mut found, mut filled, mut base) = (Vec::new(), 0usize, 0u64);
    loop {
        let n = f
            .read_at(&mut buf[filled..], base + filled as u64)
            .map_err(|e| StoreError::io(path, "read it", e))?;
        let len = filled + n;
        found.extend(finder.find_iter(&buf[..len]).map(|i| base + i as u64));
        if n == 0 {
            return Ok(found);
        }
        // the last `keep` bytes start the next block (none of them begins a whole signature)
        let tail = len.saturating_sub(keep);
        buf.copy_within(tail..len, 0);
        (filled, base) = (len - tail, base + tail as u64);
    }
}

/// What would stop HDF5 reading the collection at `at` to its end (None if nothing): its
/// objects are parsed one after the other, each advancing by its header and its length
/// rounded up to 8 (a free-space object, index 0, by its length alone).
fn collection_problem(f: &File, at: u64, size: u64) -> Option<String> {
    let length = match read_u64(f, at + 8) {
        Some(l) if l >= MIN_COLLECTION && at.checked_add(l).is_some_and(|e| e <= size) => l,
        Some(l) => return Some(format!("states a length of {l} bytes ({} left)", size - at)),
        None => return Some("is cut off by the end of the file".into()),
    };
    let (end, mut p) = (at + length, at + COLLECTION_HEADER);
    while p + OBJECT_HEADER <= end {
        let mut h = [0u8; 16];
        if f.read_exact_at(&mut h, p).is_err() {
            return Some(format!("cannot be read at byte {p}"));
        }
        let index = u16::from_le_bytes([h[0], h[1]]);
        let n = u64::from_le_bytes(h[8..16].try_into().expect("8 bytes"));
        let step = if index == 0 {
            Some(n)
        } else {
            n.checked_add(7)
                .and_then(|m| (m / 8 * 8).checked_add(OBJECT_HEADER))
        };
        match step {
            Some(s) if s >= OBJECT_HEADER && s <= end - p => p += s,
            _ => {
                return Some(format!(
                    "holds a broken object at byte {p} (length {n}: not within the collection)"
                ))
            }
        }
    }
    None
}

fn read_u64(f: &File, at: u64) -> Option<u64> {
    let mut b = [0u8; 8];
    f.read_exact_at(&mut b, at).ok()?;
    Some(u64::from_le_bytes(b))
}
