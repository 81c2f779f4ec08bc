"""The explorer of a results file, one HTML file: `batstudy.report` (python/batstudy/_report.py)
from this repository's sources, for .venv (no wheel needed: the explorer needs no native module).

    .venv/bin/python scripts/report.py RESULTS.h5 [-o report.html]

The installed wheel has the same as `batstudy report RESULTS.h5 [-o FILE]`.
"""
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "python"))
from batstudy._report import main  # noqa: E402

if __name__ == "__main__":
    sys.exit(main(prog="scripts/report.py"))
