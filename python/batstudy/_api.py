"""simulate() and run(): thin wrappers over the native module."""

from __future__ import annotations

import json
import os
import pathlib
import sys
import warnings
from typing import Any, Callable, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _native

# how a native command ends beyond a plain success: one table in the library
# (`operations::KINDS`), as (name, the CLI's exit status, the exception, what it means)
ENDINGS = {name: (code, exception, meaning) for name, code, exception, meaning in _native.endings()}
# the CLI's exit statuses (README, "Exit codes"), from that table
EXIT_OK = 0
EXIT_POINTS_FAILED, EXIT_BAD_INPUT, EXIT_RUN_FAILED, EXIT_INTERRUPTED = (
    ENDINGS[n][0] for n in ("points_failed", "bad_input", "run_failed", "interrupted")
)

DEFAULT_HISTORY = {
    "fields": ["force", "compression", "ball_velocity", "displacement", "rigid_motion"],
    "interval": 1.0e-5,
    "duration": 3.0e-3,
    "z_step": 0.01,
    # arrays in memory: the displacement on its z grid (a study's default is the modal form)
    "displacement": "grid",
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
        # JSON is YAML: one flow mapping, positions stay meaningful (line 1); NumPy's
        # numbers (np.int64(-30), np.float64) as the plain numbers they are
        return json.dumps(spec, allow_nan=True, default=_plain)
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
    (``displacement`` has shape (time, z); with ``"displacement": "modal"`` in the dict,
    the modal form instead: ``modal_coordinate`` (time, mode) in m, ``bat_load`` (time) in
    N, ``static_shape`` (shape point) in m/N, docs/layout.md).

    The GIL is released while the collision runs, so threads can simulate in parallel.
    Raises :class:`StudyError` for a bad spec or a collision that fails.
    """
    text = _as_text(spec, "spec")
    hist_text = None
    if history is True:
        hist_text = json.dumps(DEFAULT_HISTORY)
    elif isinstance(history, Mapping):
        hist_text = json.dumps({**DEFAULT_HISTORY, **history}, default=_plain)
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


def _progress_bar(
    enabled: bool, unit: str = "points", desc: str = "simulating"
) -> Optional[Callable[[int, int], None]]:
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
                print(f"\r{done}/{total} {unit}", end="", file=sys.stderr, flush=True)
            return
        bar = state.get("bar")
        if bar is None:
            # what was done before this call (a resumed run's points) is where the bar
            # starts, not work done at once; the rate is the run's mean (smoothing 0), not
            # the last burst's
            bar = state["bar"] = tqdm(
                total=total, initial=done, unit=unit, desc=desc, smoothing=0
            )
        bar.update(done - bar.n)

    def close() -> None:
        bar = state.get("bar")
        if bar is not None:
            bar.close()
        elif "pct" in state:
            print(file=sys.stderr)

    update.close = close  # type: ignore[attr-defined]
    return update


StudyLike = Union[str, os.PathLike, Mapping[str, Any]]


def _study_source(study: StudyLike) -> tuple:
    """(path, text) for the native module: a path (str or os.PathLike), or YAML text (a str
    with a line break, or a dict given as JSON, which is YAML)."""
    if isinstance(study, Mapping):
        return None, json.dumps(study, allow_nan=True, default=_plain)
    if isinstance(study, os.PathLike):
        return os.fspath(study), None
    if isinstance(study, str):
        return (None, study) if ("\n" in study or "\r" in study) else (study, None)
    raise TypeError(f"study must be a path, YAML text or a dict, not {type(study).__name__}")


def _plain(value: Any) -> Any:
    """NumPy's numbers and arrays (``np.linspace(...)``, ``np.int64(-30)``) as the plain
    numbers and lists a study holds."""
    if isinstance(value, (np.generic, np.ndarray)):
        return value.tolist()
    raise TypeError(f"a study holds numbers, text, lists and mappings, not {type(value).__name__}: {value!r}")


def _shard(shard: Optional[Sequence[int]]) -> Optional[Tuple[int, int]]:
    """`(i, n)` as the native module takes it, from any pair of whole numbers (a tuple, a
    list such as a scheduler's `[task, tasks]`, NumPy integers)."""
    if shard is None:
        return None
    pair = tuple(shard) if isinstance(shard, (tuple, list, np.ndarray)) else ()
    whole = all(isinstance(x, (int, np.integer)) and not isinstance(x, bool) for x in pair)
    if len(pair) != 2 or not whole:
        raise TypeError(f"shard must be a pair of whole numbers (i, n) with 1 <= i <= n, not {shard!r}")
    return int(pair[0]), int(pair[1])


def run(
    study: StudyLike,
    output: Union[str, os.PathLike, None] = None,
    jobs: Optional[int] = None,
    resume: bool = False,
    progress: bool = True,
    force: bool = False,
    shard: Optional[Tuple[int, int]] = None,
) -> pathlib.Path:
    """Run a study as ``batstudy run`` does; returns the results file's path.

    ``study`` is a study file's path, its YAML text (a string with a line break), or a
    dict of the same content (relative profile paths of text and dicts are taken from the
    working folder). ``output`` defaults to the study's ``output`` (else
    ``results/<name>.h5``, for a shard ``results/<name>.shard-I-of-N.h5``); ``jobs`` to every
    core. ``shard=(i, n)`` runs the i-th of n disjoint blocks of the points (1 <= i <= n),
    as ``--shard i/n``: a unit of work to hand out (submitit, dask, Ray), merged afterwards
    with :func:`merge`. ``resume=True`` continues an interrupted run in the same file, and
    ``force=True`` replaces an existing one. The progress bar is tqdm's (a widget in
    Jupyter).

    Ctrl-C (KeyboardInterrupt) behaves as the CLI's first Ctrl-C: the points in flight
    finish and everything done is written; then KeyboardInterrupt is raised, and
    ``run(..., resume=True)`` finishes the study. Points that fail are recorded in the file
    (``/errors``) and reported with a warning. Raises :class:`StudyError` for a bad study or
    output (exit status 2), :class:`RunError` when the run itself fails (3).
    """
    path, text = _study_source(study)
    again = f"{path!r}" if path is not None else "<the same study>"
    result, ending, _message, report = _command(
        lambda bar: _native.run_study(
            path, text, None if output is None else os.fspath(output), jobs, resume, force, bar, _shard(shard)
        ),
        _progress_bar(progress),
        f"batstudy.run({again}, output={{output!r}}, resume=True)",
    )
    if ending == "points_failed":
        warnings.warn(report.strip(), RuntimeWarning, stacklevel=2)
    elif progress and report:
        print(report.strip(), file=sys.stderr)
    return result


def _raise_ending(ending: Optional[str], message: str) -> None:
    """Raise the exception the table of endings names for a refused or failed command."""
    if ending is None:
        return
    code, exception, _meaning = ENDINGS[ending]
    if exception == "StudyError":
        raise StudyError(message)
    if exception == "RunError":
        raise RunError(message, code)


def _command(call: Callable[[Any], tuple], bar: Any, resume_call: str) -> tuple:
    """Run a native command (`call(bar)` → its ending's name, message, output, report,
    whether it was interrupted, and its notes) with its progress bar, as the table of endings
    says: a bad study raises StudyError, a failed run RunError, an interrupted one
    KeyboardInterrupt naming `resume_call` (with ``{output!r}`` for the output); notes are
    warnings. Returns (output path, ending, message, report) of a command that finished."""
    try:
        ending, message, out, report, interrupted, notes = call(bar)
    finally:
        if bar is not None:
            bar.close()  # type: ignore[attr-defined]
    for note in notes:
        warnings.warn(note, RuntimeWarning, stacklevel=3)
    if out is None:
        _raise_ending(ending, message)
        raise RunError(message, ENDINGS["run_failed"][0])
    if interrupted:
        again = resume_call.replace("{output!r}", repr(os.fspath(out)))
        raise KeyboardInterrupt(f"{report.strip()}\n(in Python: {again})")
    return pathlib.Path(out), ending, message, report


def merge(
    output: Union[str, os.PathLike],
    shards: Sequence[Union[str, os.PathLike]],
    force: bool = False,
    jobs: Optional[int] = None,
    study: Union[str, os.PathLike, None] = None,
) -> pathlib.Path:
    """Merge shard files (from ``run(..., shard=(i, n))`` or ``batstudy run --shard``) into
    one results file, as ``batstudy merge`` does; returns its path. The data equal a
    single-process run's bit for bit. ``study`` is needed only when the study names profile
    CSV files by relative paths and its folder moved.

    Raises :class:`StudyError` (nothing written) for shards of different studies, a point
    missing or present twice (naming the shard and the call that finishes it), or an
    existing output without ``force``; :class:`RunError` when writing fails. A warning
    reports failed points (their messages are stored in the file)."""
    ending, message, _done, failed = _native.merge(
        os.fspath(output),
        [os.fspath(s) for s in shards],
        force,
        jobs,
        None if study is None else os.fspath(study),
    )
    if ending != "points_failed":
        _raise_ending(ending, message)
    if failed:
        warnings.warn(f"{output}: {failed} points failed (their messages are in /errors)", RuntimeWarning, stacklevel=2)
    return pathlib.Path(output)


def plan(study: StudyLike) -> dict:
    """What a study expands to, without running it: a dict with ``name``, ``points`` (the
    number of points), ``dims`` (``[(name, size), …]`` in row-major order), ``bats`` (the
    distinct bats' labels), ``histories`` (the number of points that record histories;
    None for studies over 20,000 points, whose points are not all checked) and ``output``
    (the study's default results file). Hand out ``run(study, shard=(i, n))`` for
    ``i in 1..n`` to scale out. Raises :class:`StudyError` for a bad study."""
    path, text = _study_source(study)
    try:
        return dict(_native.describe(path, text))
    except ValueError as e:
        raise StudyError(str(e)) from None


def validate(study: StudyLike) -> None:
    """Check a study as ``batstudy validate`` does; returns None or raises
    :class:`StudyError` naming the file, line, field, value and what is allowed."""
    plan(study)


def export_profile(
    results: Union[str, "os.PathLike[str]"],
    bat: Optional[Union[str, int]] = None,
    units: str = "m",
    path: Optional[Union[str, "os.PathLike[str]"]] = None,
) -> str:
    """A bat of a results file as a profile CSV, as ``batstudy export-profile`` writes it:
    ``z_<units>,radius_<units>`` and, for a hollow bat, ``wall_<units>`` (0 where solid),
    linear between rows; ``bat.profile.csv`` reads it back as the same bat (its comment
    lines name the material the study must set). ``bat`` is a label as
    :func:`open_results` lists them in ``/bat`` or an index (may be left out when the file
    holds one bat); ``units`` is ``"m"``, ``"mm"`` or ``"in"``. Returns the CSV text and,
    with ``path``, also writes it there (whole or not at all). Raises
    :class:`ResultsFileError` naming the file and what is allowed."""
    from ._files import ResultsFileError

    try:
        text = _native.export_profile(
            os.fspath(results), None if bat is None else str(bat), units
        )
    except ValueError as e:
        raise ResultsFileError(str(e)) from None
    if path is not None:
        target = os.fspath(path)
        tmp = f"{target}.{os.getpid()}.tmp"
        with open(tmp, "x", encoding="utf-8") as f:
            f.write(text)
        os.replace(tmp, target)
    return text
