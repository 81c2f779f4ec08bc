#!/usr/bin/env bash
# The Python package as a user gets it. Builds the wheel with pip (maturin and cmake
# come from PyPI into pip's isolated build env; HDF5 is compiled from source and linked into
# the native module), installs it in a fresh venv that has never seen this repository's
# sources, and runs the API tests and the quickstart notebook against the installed package.
# They run where the system's libhdf5 is hidden (bubblewrap), as on a machine without
# libhdf5-dev; tests/python_api also checks the module's NEEDED entries and what it maps.
# ~3 min on 2 cores the first time (HDF5's C build), under a minute after.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/stage.sh
bash scripts/setup.sh >/dev/null

# The fresh venv and the wheel's dependencies (pyproject.toml's, with the test and notebook
# extras) are installed while the wheel builds: pip waits on files, the build on the cores.
rm -rf target/wheel-venv target/wheel-deps.log
python3 -m venv target/wheel-venv
wheel_deps() {
  target/wheel-venv/bin/python -m pip install -q --upgrade pip &&
    target/wheel-venv/bin/python -m pip install -q \
      $(.venv/bin/python - <<'PY'
import tomllib
p = tomllib.load(open("pyproject.toml", "rb"))["project"]
extras = p["optional-dependencies"]
deps = p["dependencies"] + [d for e in ("test", "notebook", "plot") for d in extras[e]]
print(" ".join(d for d in deps if not d.startswith("batstudy")))
PY
      ) -c scripts/requirements.txt -c scripts/constraints-wheel.txt
}
wheel_deps > target/wheel-deps.log 2>&1 &
deps_pid=$!

stage "Building the wheel (pip wheel .), the venv's dependencies alongside"
rm -rf target/wheels
.venv/bin/python -m pip wheel -q --no-deps -w target/wheels .
wheel=$(ls target/wheels/batstudy-*.whl)
echo "built $wheel ($(du -h "$wheel" | cut -f1))"

stage "A fresh venv with the wheel"
if ! wait "$deps_pid"; then
  cat target/wheel-deps.log >&2
  echo "test_wheel: installing the wheel's dependencies failed" >&2
  exit 1
fi
target/wheel-venv/bin/python -m pip install -q "${wheel}[test,notebook]" \
  -c scripts/requirements.txt -c scripts/constraints-wheel.txt

# A machine without the system's HDF5: bubblewrap runs the tests in a view of this machine in
# which every libhdf5 file of Debian's packages is an empty file and its directories are empty.
# The control: the CLI built against the system HDF5 must then fail to start.
if ! command -v bwrap >/dev/null 2>&1; then
  as_root() { if [ "$(id -u)" = 0 ]; then "$@"; else sudo "$@"; fi; }
  stage "Installing Debian's bubblewrap (to hide the system HDF5 from the wheel's tests)"
  as_root apt-get update -qq
  DEBIAN_FRONTEND=noninteractive as_root apt-get install -y -qq bubblewrap >/dev/null
fi
hide=(--dev-bind / /)
for f in /usr/lib/*-linux-gnu/*hdf5* /usr/lib/*-linux-gnu/hdf5; do
  [ -e "$f" ] || continue
  if [ -d "$f" ]; then hide+=(--tmpfs "$f"); else hide+=(--ro-bind /dev/null "$f"); fi
done
without_hdf5() { bwrap "${hide[@]}" "$@"; }
if [ -x target/debug/batstudy ] && without_hdf5 target/debug/batstudy --version >/dev/null 2>&1; then
  echo "test_wheel: the system HDF5 is still visible in the sandbox (target/debug/batstudy starts)" >&2
  exit 1
fi

stage "Python API tests and the quickstart notebook (installed package, no system HDF5)"
# From /: nothing of the repository is importable but what the wheel installed.
repo=$PWD
without_hdf5 bash -c "cd / && '$repo/target/wheel-venv/bin/python' -m pytest -q --durations=8 -p no:cacheprovider '$repo/tests/python_api'"
