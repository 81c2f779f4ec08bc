"""A results file checked before HDF5 reads it, and HDF5's errors named for the user.

HDF5 trusts two kinds of bytes that carry no checksum: raw data and its *global heap
collections* (the ``GCOL`` blocks that hold variable-length values: every string, and every
variable's list of dimension scales). A damaged collection can make HDF5 loop forever (an
object of length 0 never advances its parser) or copy past the collection's end (a
crash). :func:`check_structure` walks every collection in the file as HDF5 will, before
HDF5 does, and refuses the file when one would not end cleanly; everything else HDF5 reads
from a results file (superblock, object headers, B-trees, heaps of links and attributes,
chunk indices) has a checksum that HDF5 verifies itself. The Rust CLI makes the same check
(``crates/store/src/check.rs``); docs/layout.md describes it.
"""

from __future__ import annotations

import mmap
import os
import struct
from contextlib import contextmanager
from typing import Iterator

import h5py

SIGNATURE = b"\x89HDF\r\n\x1a\n"
COLLECTION = b"GCOL\x01"  # a global heap collection, version 1
COLLECTION_HEADER = 16  # signature, version, reserved, collection size (8-byte lengths)
OBJECT_HEADER = 16  # index, references, reserved, size
MIN_COLLECTION = 4096  # HDF5 never writes a smaller one


class ResultsFileError(ValueError):
    """A file that is not a complete batstudy results file: not HDF5, damaged, or another
    program's HDF5. The message names the file and what is wrong."""


def damaged(path: str, what: str) -> ResultsFileError:
    return ResultsFileError(f"{path}: not a batstudy results file: damaged: {what}")


def check_structure(path: str) -> None:
    """Raise :class:`ResultsFileError` if `path` is not HDF5, is shorter than its superblock
    says, or holds a global heap collection HDF5 could not read to its end; else return.
    Reads the file once (a memory map: a search for the collections' signature)."""
    with open(path, "rb") as fh:
        size = os.fstat(fh.fileno()).st_size
        if size < len(SIGNATURE) or fh.read(len(SIGNATURE)) != SIGNATURE:
            raise ResultsFileError(f"{path}: not a batstudy results file: not an HDF5 file "
                                   "(no HDF5 signature at its start)")  # fmt: skip
        with mmap.mmap(fh.fileno(), 0, access=mmap.ACCESS_READ) as m:
            _check_end(path, m, size)
            at = m.find(COLLECTION)
            while at >= 0:
                problem = collection_problem(m, at, size)
                if problem:
                    raise damaged(path, f"the global heap collection at byte {at} {problem}")
                at = m.find(COLLECTION, at + 1)


def _check_end(path: str, m: mmap.mmap, size: int) -> None:
    """A superblock of version 2 or 3 (what HDF5 1.10 on writes) states the file's end."""
    if size >= 48 and m[8] in (2, 3) and m[9] == 8:
        end = struct.unpack_from("<Q", m, 28)[0]
        if end > size:
            raise damaged(path, f"truncated: {size} bytes of the {end} its superblock states")


def collection_problem(m, at: int, size: int) -> str:
    """What would stop HDF5 reading the collection at `at` to its end ("" if nothing): its
    objects are parsed one after the other, each advancing by its own header and length
    (a free-space object, index 0, by its length alone), until the collection's end."""
    if at + COLLECTION_HEADER > size:
        return "is cut off by the end of the file"
    length = struct.unpack_from("<Q", m, at + 8)[0]
    if length < MIN_COLLECTION or at + length > size:
        return f"states a length of {length} bytes ({size - at} left in the file)"
    end, p = at + length, at + COLLECTION_HEADER
    while p + OBJECT_HEADER <= end:
        index, _, _, n = struct.unpack_from("<HHIQ", m, p)
        step = OBJECT_HEADER + -(-n // 8) * 8 if index else n
        if step < OBJECT_HEADER or p + step > end:
            return f"holds a broken object at byte {p} (length {n}: not within the collection)"
        p += step
    return ""


@contextmanager
def reading(path: str) -> Iterator[None]:
    """Turn what HDF5 (through h5py, h5netcdf, xarray) raises on a file it cannot read into
    a :class:`ResultsFileError` naming the file; a missing file stays FileNotFoundError."""
    try:
        yield
    except (ResultsFileError, FileNotFoundError):
        raise
    except (OSError, RuntimeError, LookupError, UnicodeError, AttributeError, TypeError) as err:
        raise damaged(path, f"HDF5 cannot read it ({type(err).__name__}: {err})") from err


def require_results(path: str, f: h5py.File) -> None:
    """Raise :class:`ResultsFileError` unless the open HDF5 file `f` is batstudy's: the root
    attribute ``layout_version`` and the points' status, ``/summary/status``."""
    if "layout_version" not in f.attrs:
        raise ResultsFileError(f"{path}: not a batstudy results file: it has no root attribute "
                               "layout_version (an HDF5 file of another program?)")  # fmt: skip
    if not isinstance(f.get("summary/status"), h5py.Dataset):
        raise ResultsFileError(f"{path}: not a batstudy results file: it has no /summary/status")
