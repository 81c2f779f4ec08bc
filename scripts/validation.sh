#!/usr/bin/env bash
# The validation table: run the six studies of studies/validation/ and write
# docs/validation.md with scripts/validation.py (about 10 s once built; it reads the files with
# batstudy.open_results from python/).
#   bash scripts/validation.sh [BATSTUDY_BINARY]
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/release_binary.sh "${1:-}"
out=target/validation
mkdir -p "$out"
for s in certification wall game low_speed oblique field; do
  "$bin" run "studies/validation/$s.yaml" -o "$out/$s.h5" --force --quiet
done
.venv/bin/python scripts/validation.py "$out"/certification.h5 "$out"/wall.h5 "$out"/game.h5 "$out"/low_speed.h5 \
  "$out"/oblique.h5 "$out"/field.h5 --check
# the figure of "Against the field" (batstudy.plot.tracking)
PYTHONPATH=python .venv/bin/python - "$out"/field.h5 <<'PY'
import sys
from pathlib import Path
import matplotlib
matplotlib.use("Agg")
from PIL import Image
from batstudy import plot
ax = plot.tracking(sys.argv[1], "data/bat_tracking_2025.csv")
p = Path("docs/figures/field.png")
ax[0].figure.savefig(p, dpi=90)
with Image.open(p) as im:
    small = im.convert("RGB").quantize(colors=256, method=Image.Quantize.MEDIANCUT)
small.save(p, optimize=True)
PY
