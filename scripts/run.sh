#!/usr/bin/env bash
# The main job: set up (idempotent), build, run a study (default: the bundled
# studies/param_space.yaml) and draw its figures. Extra arguments go to `batstudy run`.
#   bash scripts/run.sh                       # default study -> results/param_space.h5
#   bash scripts/run.sh studies/hoop.yaml -j 8
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build_release.sh
study=studies/param_space.yaml
if [ $# -gt 0 ] && [ "${1#-}" = "$1" ]; then study=$1; shift; fi
# --force: rerunning the main job recomputes it (use --resume to finish an interrupted run).
./target/release/batstudy run "$study" --force "$@"
# The figures of the default study: scripts/figures.py runs batstudy.plot from python/ with
# .venv (the figures read only the HDF5 file and need no native module, so no wheel).
if [ "$study" = studies/param_space.yaml ] && [ $# -eq 0 ]; then
  .venv/bin/python scripts/figures.py results/param_space.h5 -o figures/param_space --jobs 2
fi
