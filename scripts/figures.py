"""The figures of a results file: `batstudy.plot` (python/batstudy/plot/) from this
repository's sources, for .venv (no wheel needed: the figures need no native module).

    .venv/bin/python scripts/figures.py RESULTS.h5 [-o OUTDIR] [--only fig6,fig14,...] [--jobs N] [--format svg]

Writes one file per figure, named after the paper's figures (batstudy.plot.FIGURES), plus
``anim_displacement.gif``, ``bat_profiles.png`` and ``sweet_spot_definitions.png``; a figure
whose data the file does not hold is skipped with a one-line message. Exit status: 0 if
every figure was written or skipped, 1 if one failed. The installed wheel has the same as
`batstudy figures RESULTS.h5 [-o DIR]`.
"""
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "python"))
from batstudy.plot import main  # noqa: E402

if __name__ == "__main__":
    sys.exit(main(prog="scripts/figures.py"))
