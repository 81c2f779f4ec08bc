#!/usr/bin/env bash
# Every test: set up (idempotent), Rust tests, the study files against the committed
# JSON schema, the smoke study on 2 threads, and the Python tests that open its output.
# Exits non-zero if any of them fails.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/stage.sh
stage "Set-up"
bash scripts/setup.sh

stage "Rust tests: build"
cargo test --all-targets -p batstudy -p batstudy-physics -p batstudy-store --no-run
stage "Rust tests: run"
cargo test --all-targets -p batstudy -p batstudy-physics -p batstudy-store

stage "Study files against schemas/study.schema.json"
.venv/bin/check-jsonschema --schemafile schemas/study.schema.json studies/*.yaml examples/*.yaml

stage "Smoke study (--jobs 2)"
mkdir -p target/smoke
./target/debug/batstudy run studies/smoke.yaml -o target/smoke/smoke.h5 --jobs 2 --force --quiet

# A real one-node Slurm on 127.0.0.1 runs a 4-shard array and the merge job; the
# merged file must equal a single-process run bit for bit (~20-25 s, ~8 s of it installing the
# Debian packages slurmctld, slurmd, munge; needs root). Runs when BATSTUDY_SLURM_TEST=1
# or CI=true; BATSTUDY_SLURM_TEST=0 skips it.
if [ "${BATSTUDY_SLURM_TEST:-}" = 1 ] || { [ "${CI:-}" = true ] && [ "${BATSTUDY_SLURM_TEST:-}" != 0 ]; }; then
  stage "Slurm array + merge on a local one-node cluster"
  BATSTUDY_BIN="$PWD/target/debug/batstudy" bash scripts/slurm-local-test.sh
else
  stage "Slurm test skipped (BATSTUDY_SLURM_TEST=1 runs scripts/slurm-local-test.sh)"
fi

# The explorer's browser test drives Debian's chromium (a browser is not part of the set-up
# of the main job, only of the tests).
if ! command -v chromium >/dev/null 2>&1; then
  stage "Installing Debian's chromium for the browser test"
  as_root() { if [ "$(id -u)" = 0 ]; then "$@"; else sudo "$@"; fi; }
  as_root apt-get update -qq
  DEBIAN_FRONTEND=noninteractive as_root apt-get install -y -qq chromium >/dev/null
fi

stage "Python tests"
BATSTUDY_BIN="$PWD/target/debug/batstudy" SMOKE_H5="$PWD/target/smoke/smoke.h5" \
  .venv/bin/python -m pytest -q -n auto --durations=12 tests/python

# The wheel, built and installed in a fresh venv, and the API tests + notebook
# against it (BATSTUDY_WHEEL_TEST=0 skips it: ~3 min the first time, for the HDF5 build).
if [ "${BATSTUDY_WHEEL_TEST:-1}" != 0 ]; then
  stage_end
  bash scripts/test_wheel.sh
else
  stage "Wheel test skipped (BATSTUDY_WHEEL_TEST=0)"
fi
