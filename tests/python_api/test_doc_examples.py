"""Every Python example of docs/python.md runs as written, against the files it names (made
here by running the bundled studies it names), in one namespace as a reader would type them
in order. The cluster recipes (submitit, dask-jobqueue) need a scheduler and are run by
test_scale_out.py instead; an example whose optional package is not installed is skipped by
name (pint-xarray)."""

import os
import pathlib
import re

import pytest

import batstudy

ROOT = pathlib.Path(__file__).resolve().parents[2]
DOC = ROOT / "docs" / "python.md"

# the files the examples read, and the bundled studies that write them
FILES = {
    "results/param_space.h5": "studies/param_space.yaml",
    "wall.h5": "studies/validation/wall.yaml",
    "results/undercut.h5": "studies/undercut.yaml",
    "field.h5": "studies/validation/field.yaml",
}
# what a block needs that a study does not make: a scheduler, or a package that is optional
NEEDS_A_CLUSTER = ("submitit", "dask")
OPTIONAL = {"pint_xarray": "pint-xarray"}


def blocks(text: str):
    """The ```python blocks of a Markdown text, with the line each starts on."""
    out, lines, start = [], None, 0
    for n, line in enumerate(text.splitlines(), 1):
        if line.strip() == "```python":
            lines, start = [], n + 1
        elif line.strip() == "```" and lines is not None:
            out.append((start, "\n".join(lines)))
            lines = None
        elif lines is not None:
            lines.append(line)
    return out


def test_the_doc_has_examples_and_each_is_run_or_named():
    found = blocks(DOC.read_text())
    assert len(found) >= 10, len(found)
    for start, code in found:
        named = any(n in code for n in NEEDS_A_CLUSTER) or any(m in code for m in OPTIONAL)
        assert named or "batstudy" in code or "tree" in code or "path" in code, start


@pytest.fixture(scope="module")
def workdir(tmp_path_factory):
    d = tmp_path_factory.mktemp("docs")
    (d / "data").symlink_to(ROOT / "data")
    for out, study in FILES.items():
        (d / out).parent.mkdir(parents=True, exist_ok=True)
        batstudy.run(ROOT / study, output=d / out, progress=False)
    return d


def test_every_example_runs_as_written(workdir, monkeypatch):
    import matplotlib

    matplotlib.use("Agg")
    import numpy as np

    monkeypatch.chdir(workdir)
    namespace = {"batstudy": batstudy, "np": np}
    ran, skipped = [], []
    for start, code in blocks(DOC.read_text()):
        if any(re.search(rf"\b{n}\b", code) for n in NEEDS_A_CLUSTER):
            skipped.append((start, "a cluster"))
            continue
        missing = [pkg for mod, pkg in OPTIONAL.items() if mod in code and not _importable(mod)]
        if missing:
            skipped.append((start, f"{missing[0]} not installed"))
            continue
        try:
            exec(compile(code, f"docs/python.md:{start}", "exec"), namespace)
        except Exception as e:  # the example's line and its error, for the reader
            pytest.fail(f"docs/python.md, the example at line {start}: {type(e).__name__}: {e}")
        ran.append(start)
    assert len(ran) >= 9, (ran, skipped)


def _importable(module: str) -> bool:
    try:
        __import__(module)
        return True
    except ImportError:
        return False
