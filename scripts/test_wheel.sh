#!/usr/bin/env bash
# Issue 21: the Python package as a user gets it. Builds the wheel with pip (maturin and cmake
# come from PyPI into pip's isolated build env; HDF5 is compiled from source and linked into
# the native module), installs it in a fresh venv that has never seen this repository's
# sources, and runs the API tests and the quickstart notebook against the installed package.
# The native module must need no system libhdf5 (tests/python_api checks its NEEDED entries).
# ~3 min on 2 cores the first time (HDF5's C build), under a minute after.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh >/dev/null

echo "== Building the wheel (pip wheel .)"
rm -rf target/wheels
.venv/bin/python -m pip wheel -q --no-deps -w target/wheels .
wheel=$(ls target/wheels/batstudy-*.whl)
echo "built $wheel ($(du -h "$wheel" | cut -f1))"

echo "== A fresh venv with the wheel"
rm -rf target/wheel-venv
python3 -m venv target/wheel-venv
target/wheel-venv/bin/python -m pip install -q --upgrade pip
target/wheel-venv/bin/python -m pip install -q "${wheel}[test,notebook]" \
  -c scripts/requirements.txt -c scripts/constraints-wheel.txt

echo "== Python API tests and the quickstart notebook (installed package)"
# From /: nothing of the repository is importable but what the wheel installed.
(cd / && "$OLDPWD/target/wheel-venv/bin/python" -m pytest -q -p no:cacheprovider "$OLDPWD/tests/python_api")
