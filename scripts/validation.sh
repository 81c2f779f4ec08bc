#!/usr/bin/env bash
# The validation table: run the three studies of studies/validation/ and write
# docs/validation.md with scripts/validation.py (about 10 s once built).
#   bash scripts/validation.sh [BATSTUDY_BINARY]
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-}
if [ -z "$bin" ]; then
  bash scripts/setup.sh >/dev/null
  cargo build --release --quiet
  bin=target/release/batstudy
fi
out=target/validation
mkdir -p "$out"
for s in certification wall game; do
  "$bin" run "studies/validation/$s.yaml" -o "$out/$s.h5" --force --quiet
done
.venv/bin/python scripts/validation.py "$out"/certification.h5 "$out"/wall.h5 "$out"/game.h5 --check
