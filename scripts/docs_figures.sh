#!/usr/bin/env bash
# The figures shown in the docs: run the default study (studies/param_space.yaml) and the
# ball tests, draw every figure into docs/figures/ (two processes), and shrink the PNGs to
# a 256-colour palette (scripts/figures.py: batstudy.plot from python/). docs/results.md and
# README embed them; tests/python/test_docs_images.py fails when an embedded image is missing.
#   bash scripts/docs_figures.sh [BATSTUDY_BINARY]
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/release_binary.sh "${1:-}"
work=target/docs_figures
mkdir -p "$work" docs/figures
"$bin" run studies/param_space.yaml -o "$work/param_space.h5" --force --quiet
"$bin" run studies/ball_tests.yaml -o "$work/ball_tests.h5" --force --quiet
"$bin" run studies/batter.yaml -o "$work/batter.h5" --force --quiet
"$bin" run studies/undercut.yaml -o "$work/undercut.h5" --force --quiet
.venv/bin/python scripts/figures.py "$work/param_space.h5" -o docs/figures --jobs 2
.venv/bin/python scripts/figures.py "$work/ball_tests.h5" -o docs/figures --only ball_tests
.venv/bin/python scripts/figures.py "$work/batter.h5" -o docs/figures --only batter
.venv/bin/python scripts/figures.py "$work/undercut.h5" -o docs/figures --only undercut
.venv/bin/python - <<'PY'
from pathlib import Path
from PIL import Image
for p in sorted(Path("docs/figures").glob("*.png")):
    with Image.open(p) as im:
        small = im.convert("RGB").quantize(colors=256, method=Image.Quantize.MEDIANCUT)
    small.save(p, optimize=True)
    print(f"{p}: {p.stat().st_size // 1024} KiB")
PY
