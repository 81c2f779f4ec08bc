"""`batstudy.optimize`: a study's design search (its ``optimize`` block), the command
``batstudy optimize`` from Python (issue 36). Needs the native module."""

from __future__ import annotations

import os
import pathlib
import subprocess
import sys
import tempfile
from typing import Any, Mapping, Optional, Union


def optimize(
    study: Union[str, os.PathLike, Mapping[str, Any]],
    output: Union[str, os.PathLike],
    *,
    jobs: Optional[int] = None,
    resume: bool = False,
    force: bool = False,
    quiet: bool = True,
):
    """Search the design of ``study`` (a path, YAML text or a dict with an ``optimize``
    block) into the results file ``output`` and return the results file's ``/optimize`` group as an :class:`xarray.Dataset`
    (one row per candidate; the best feasible design and its margins in ``.attrs``).

    The file itself holds the study run at the best design (``/summary``, ``/sweet_spot``,
    ``/bat``) beside ``/optimize``. ``resume=True`` continues a search that was stopped
    (its candidates are replayed from ``OUT.h5.optimize``); ``force=True`` starts over.
    The search runs in a process of its own (``python -m batstudy optimize``), so Ctrl-C
    stops it as it stops the command (:class:`KeyboardInterrupt` here; resume with
    ``resume=True``). Raises :class:`RuntimeError` with the command's message when it does
    not finish (bad input: exit status 2)."""
    import xarray as xr

    with tempfile.TemporaryDirectory() as tmp:
        path = _study_path(study, pathlib.Path(tmp))
        argv = [sys.executable, "-m", "batstudy", "optimize", str(path), "-o", os.fspath(output)]
        if jobs is not None:
            argv += ["-j", str(int(jobs))]
        argv += ["--resume"] * bool(resume) + ["--force"] * bool(force) + ["--quiet"] * bool(quiet)
        # a process of its own: Ctrl-C stops its search (the candidate in flight finishes and
        # is kept), and this interpreter's own handling of Ctrl-C is left alone
        r = subprocess.run(argv, stderr=subprocess.PIPE, text=True)
    if r.stderr and not quiet:
        print(r.stderr, end="", file=sys.stderr)
    if r.returncode == 130:
        raise KeyboardInterrupt("the search was interrupted: resume=True continues it")
    if r.returncode not in (0, 1):
        raise RuntimeError(f"batstudy optimize exited with status {r.returncode}:\n{r.stderr}")
    with xr.open_dataset(output, engine="h5netcdf", group="optimize") as ds:
        return ds.load()


def _study_path(study, tmp: pathlib.Path) -> pathlib.Path:
    """A study file for the command: the path itself, or text / a dict written to ``tmp``."""
    if isinstance(study, Mapping):
        import json

        text = json.dumps(study)  # JSON is YAML
    elif isinstance(study, (str, os.PathLike)) and pathlib.Path(study).is_file():
        return pathlib.Path(study)
    else:
        text = str(study)
    p = tmp / "study.yaml"
    p.write_text(text)
    return p

