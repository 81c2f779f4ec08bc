#!/usr/bin/env python3
"""Compare two batstudy results files bit for bit (merged shards == single run).

Every dataset of every group (data and coordinate variables) must have the same dtype, shape
and bytes (NaN payloads included; variable-length strings compared as text), and the same
attributes except dimension-scale bookkeeping (REFERENCE_LIST / DIMENSION_LIST hold object
references). Root attributes that describe the run (created, host, threads, command_line,
study_path, shard, git_commit, git_dirty, batstudy_version) are listed when they differ but
do not fail the comparison.

Usage: compare_results.py A.h5 B.h5   (exit 0 identical, 1 different)
"""
import sys

import h5py
import numpy as np

RUN_ATTRS = {"created", "host", "threads", "command_line", "study_path", "shard",
             "git_commit", "git_dirty", "batstudy_version", "source", "history"}
SCALE_ATTRS = {"REFERENCE_LIST", "DIMENSION_LIST"}


def same_value(a, b):
    a, b = np.asarray(a), np.asarray(b)
    if a.dtype.kind == "O" or b.dtype.kind == "O":
        return a.shape == b.shape and all(
            (x.decode() if isinstance(x, bytes) else x) == (y.decode() if isinstance(y, bytes) else y)
            for x, y in zip(a.ravel(), b.ravel()))
    if a.dtype != b.dtype or a.shape != b.shape:
        return False
    # the bytes compared in place (NaN payloads included), without copying them out
    a, b = np.ascontiguousarray(a), np.ascontiguousarray(b)
    return np.array_equal(a.reshape(-1).view(np.uint8), b.reshape(-1).view(np.uint8))


# Decoded bytes compared at once (256 MiB): a larger dataset (a study's modal coordinates decode to
# gigabytes) is compared a slab at a time along its leading axes, so memory stays bounded.
SLAB_BYTES = 256 << 20


def same_data(oa, ob, prefix=()):
    rest = oa.shape[len(prefix):]
    if oa.dtype.kind == "O" or not rest or int(np.prod(rest)) * oa.dtype.itemsize <= SLAB_BYTES:
        return same_value(oa[prefix] if prefix else oa[()], ob[prefix] if prefix else ob[()])
    return all(same_data(oa, ob, prefix + (i,)) for i in range(rest[0]))


def main(pa, pb):
    bad = []
    with h5py.File(pa, "r") as fa, h5py.File(pb, "r") as fb:
        for k in sorted(set(fa.attrs) | set(fb.attrs)):
            if k not in fa.attrs or k not in fb.attrs:
                bad.append(f"root attribute {k} only in one file")
            elif not same_value(fa.attrs[k], fb.attrs[k]):
                if k in RUN_ATTRS:
                    print(f"note: root attribute {k} differs (describes the run): "
                          f"{fa.attrs[k]!r} vs {fb.attrs[k]!r}")
                else:
                    bad.append(f"root attribute {k} differs")
        names_a, names_b = [], []
        fa.visit(names_a.append)
        fb.visit(names_b.append)
        if sorted(names_a) != sorted(names_b):
            bad.append(f"different objects: {sorted(set(names_a) ^ set(names_b))}")
        n = 0
        for name in sorted(set(names_a) & set(names_b)):
            oa, ob = fa[name], fb[name]
            if isinstance(oa, h5py.Dataset) != isinstance(ob, h5py.Dataset):
                bad.append(f"{name}: group in one file, dataset in the other")
                continue
            for k in sorted((set(oa.attrs) | set(ob.attrs)) - SCALE_ATTRS):
                if k not in oa.attrs or k not in ob.attrs or not same_value(oa.attrs[k], ob.attrs[k]):
                    bad.append(f"{name}: attribute {k} differs")
            if isinstance(oa, h5py.Dataset):
                n += 1
                if oa.dtype != ob.dtype or oa.shape != ob.shape:
                    bad.append(f"{name}: dtype/shape {oa.dtype}{oa.shape} vs {ob.dtype}{ob.shape}")
                elif not same_data(oa, ob):
                    bad.append(f"{name}: data differ")
    if bad:
        for b in bad:
            print(f"DIFFERENT: {b}")
        return 1
    print(f"identical: {n} datasets of {pa} and {pb} bit for bit")
    return 0


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1], sys.argv[2]))
