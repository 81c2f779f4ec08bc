"""simulate() and run(): thin wrappers over the native module."""

from __future__ import annotations

import json
import os
import pathlib
import sys
import warnings
from typing import Any, Callable, Mapping, Optional, Union

import numpy as np

from . import _native

# exit codes of `batstudy run` (README, "Exit codes")
EXIT_OK, EXIT_POINTS_FAILED, EXIT_BAD_INPUT, EXIT_RUN_FAILED, EXIT_INTERRUPTED = 0, 1, 2, 3, 130

DEFAULT_HISTORY = {
    "fields": ["force", "compression", "ball_velocity", "displacement", "rigid_motion"],
    "interval": 1.0e-5,
    "duration": 3.0e-3,
    "z_step": 0.01,
}


class StudyError(ValueError):
    """A bad study or spec (the CLI's exit status 2). The message names the file (``spec``
    for a spec given as text or dict), line, field, value and what is allowed."""


class RunError(RuntimeError):
    """The run itself failed (the CLI's exit status 3), e.g. the output could not be written."""

    def __init__(self, message: str, code: int):
        super().__init__(message)
        self.code = code


def _as_text(spec: Union[str, Mapping[str, Any]], what: str) -> str:
    if isinstance(spec, str):
        return spec
    if isinstance(spec, Mapping):
        # JSON is YAML: one flow mapping, positions stay meaningful (line 1)
        return json.dumps(spec, allow_nan=True)
    raise TypeError(f"{what} must be a dict or YAML text, not {type(spec).__name__}")


def simulate(
    spec: Union[str, Mapping[str, Any]],
    history: Union[bool, Mapping[str, Any], None] = False,
) -> dict:
    """Simulate one collision.

    ``spec`` is what a study's ``base`` block holds (``docs/study-files.md``), as a dict or
    YAML text, e.g. ``{"bat": {"preset": "aluminum"}, "ball": {"speed": 40},
    "impact": {"z": 0.7}}``. Every unset field takes its default.

    Returns a dict of every summary variable of the results file's ``/summary`` by its
    name (SI units: ``exit_speed`` in m/s, ``contact_time`` in s, …), plus ``point_id`` and
    ``bat`` (the prepared bat's mass, centre of mass, moment of inertia, length and mode
    frequencies). With ``history=True`` (or a dict like a study's ``history`` block, e.g.
    ``{"fields": ["force"], "interval": 1e-6, "duration": 2e-3}``) the dict also holds
    ``history``: ``time`` (s), ``z`` (m) and each recorded variable as a NumPy array
    (``displacement`` has shape (time, z)).

    The GIL is released while the collision runs, so threads can simulate in parallel.
    Raises :class:`StudyError` for a bad spec or a collision that fails.
    """
    text = _as_text(spec, "spec")
    hist_text = None
    if history is True:
        hist_text = json.dumps(DEFAULT_HISTORY)
    elif isinstance(history, Mapping):
        hist_text = json.dumps({**DEFAULT_HISTORY, **history})
    elif history not in (False, None):
        raise TypeError("history must be True, False, None or a dict")
    try:
        summary, hist = _native.simulate(text, hist_text)
    except ValueError as e:
        raise StudyError(str(e)) from None
    summary["recontact"] = bool(summary["recontact"])
    if hist is not None:
        summary["history"] = {
            name: np.frombuffer(raw, dtype="<f8").reshape(shape) for name, (raw, shape) in hist.items()
        }
    return summary


def _progress_bar(enabled: bool) -> Optional[Callable[[int, int], None]]:
    if not enabled:
        return None
    try:
        from tqdm.auto import tqdm
    except ImportError:  # a plain line on stderr instead
        tqdm = None
    state: dict = {}

    def update(done: int, total: int) -> None:
        if total == 0:
            return
        if tqdm is None:
            pct = 100 * done // total
            if state.get("pct") != pct:
                state["pct"] = pct
                print(f"\r{done}/{total} points", end="", file=sys.stderr, flush=True)
            return
        bar = state.get("bar")
        if bar is None:
            bar = state["bar"] = tqdm(total=total, unit="points", desc="simulating")
        bar.update(done - bar.n)

    def close() -> None:
        bar = state.get("bar")
        if bar is not None:
            bar.close()
        elif "pct" in state:
            print(file=sys.stderr)

    update.close = close  # type: ignore[attr-defined]
    return update


def run(
    study: Union[str, os.PathLike],
    output: Union[str, os.PathLike, None] = None,
    jobs: Optional[int] = None,
    resume: bool = False,
    progress: bool = True,
    force: bool = False,
) -> pathlib.Path:
    """Run a study file as ``batstudy run`` does; returns the results file's path.

    ``output`` defaults to the study's ``output`` (else ``results/<name>.h5``); ``jobs`` to
    every core. ``resume=True`` continues an interrupted run in the same file, and
    ``force=True`` replaces an existing one. The progress bar is tqdm's (a widget in
    Jupyter).

    Ctrl-C (KeyboardInterrupt) behaves as the CLI's first Ctrl-C: the points in flight
    finish and everything done is written; then KeyboardInterrupt is raised, and
    ``run(..., resume=True)`` finishes the study. Points that fail are recorded in the file
    (``/errors``) and reported with a warning. Raises :class:`StudyError` for a bad study or
    output (exit status 2), :class:`RunError` when the run itself fails (3).
    """
    bar = _progress_bar(progress)
    try:
        code, message, out, report, interrupted = _native.run_study(
            os.fspath(study),
            None if output is None else os.fspath(output),
            jobs,
            resume,
            force,
            bar,
        )
    finally:
        if bar is not None:
            bar.close()  # type: ignore[attr-defined]
    if code == EXIT_BAD_INPUT:
        raise StudyError(message)
    if out is None:
        raise RunError(message, code)
    path = pathlib.Path(out)
    if interrupted:
        raise KeyboardInterrupt(
            f"{report.strip()}\n(in Python: batstudy.run({os.fspath(study)!r}, "
            f"output={os.fspath(path)!r}, resume=True))"
        )
    if code == EXIT_POINTS_FAILED:
        warnings.warn(report.strip(), RuntimeWarning, stacklevel=2)
    elif progress and report:
        print(report.strip(), file=sys.stderr)
    return path
