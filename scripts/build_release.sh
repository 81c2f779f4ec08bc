#!/usr/bin/env bash
# The release binary target/release/batstudy, with HDF5 compiled in (the crate's `static`
# feature, as the Python wheel has it): a process starts in about 1 ms instead of 9 ms with
# Debian's libhdf5, which loads 38 shared libraries (docs/performance.md, "Process start,
# static HDF5 and the Python wheel"). The first
# build compiles HDF5's C sources (about 2.5 min on 2 cores) with cmake >= 3.26 from .venv
# (scripts/setup.sh installs it). Run from the repository's top directory, after setup.
set -euo pipefail
PATH="$PWD/.venv/bin:$PATH" cargo build --release --features static --quiet
