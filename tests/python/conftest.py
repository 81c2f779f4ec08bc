"""Shared by the Python tests: the package's analysis from the source tree, and the project's
own results-layout checker, scripts/check_layout.py.

The tests import `batstudy` from python/ (its analysis needs no native module: the wheel's
own tests are tests/python_api). The checker is part of the repository; a missing checker is
a failure, never a skip."""
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "python"))
CHECK_LAYOUT = ROOT / "scripts" / "check_layout.py"


def run_check_layout(path, *args):
    """Run scripts/check_layout.py on `path`; returns the CompletedProcess (text output)."""
    if not CHECK_LAYOUT.is_file():
        pytest.fail(f"{CHECK_LAYOUT} is missing: the layout checker is part of the repository")
    return subprocess.run([sys.executable, str(CHECK_LAYOUT), str(path), *args],
                          capture_output=True, text=True)


@pytest.fixture
def check_layout():
    """`check_layout(path, *args)` runs scripts/check_layout.py and returns its result."""
    return run_check_layout


def assert_layout_ok(path):
    r = run_check_layout(path)
    assert r.returncode == 0 and "layout ok" in r.stdout, \
        f"scripts/check_layout.py {path}:\n{r.stdout}{r.stderr}"
