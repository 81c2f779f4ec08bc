"""pyproject.toml's `requires-python` tells the truth: pip's resolver finds binary wheels of
every dependency for the lowest Python it names, and none for the Python before it (xarray
>= 2024.10, the first with DataTree, needs 3.10). Asks the package index (PyPI) about the
dependencies only, downloading nothing; skipped when the index cannot be reached."""
import re
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def project() -> dict:
    return tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]


def resolve(python_version: str, tmp_path) -> subprocess.CompletedProcess:
    """pip's resolver for the package's dependencies on `python_version` (wheels only, as a
    machine of that Python would install them); nothing is installed."""
    return subprocess.run(
        [sys.executable, "-m", "pip", "install", "--dry-run", "--quiet", "--no-cache-dir",
         "--ignore-installed", "--only-binary=:all:", "--python-version", python_version,
         "--target", str(tmp_path / python_version), *project()["dependencies"]],
        capture_output=True, text=True, timeout=600)  # fmt: skip


def test_the_lowest_python_named_is_the_lowest_the_dependencies_support(tmp_path):
    m = re.fullmatch(r">=\s*3\.(\d+)", project()["requires-python"])
    assert m, f"requires-python {project()['requires-python']!r} is not of the form >=3.N"
    lowest, before = f"3.{m.group(1)}", f"3.{int(m.group(1)) - 1}"
    ok = resolve(lowest, tmp_path)
    if ok.returncode != 0 and "(from versions: none)" in ok.stderr:
        pytest.skip(f"the package index cannot be reached:\n{ok.stderr[-500:]}")
    assert ok.returncode == 0, f"the dependencies do not resolve on Python {lowest}:\n{ok.stderr}"
    too_old = resolve(before, tmp_path)
    assert too_old.returncode != 0, f"the dependencies resolve on Python {before}: requires-python could be lower"
    assert "Requires-Python" in too_old.stderr, too_old.stderr
