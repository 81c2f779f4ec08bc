"""`batstudy.optimize`: a study's design search (its ``optimize`` block), as the command
``batstudy optimize`` runs it, in this process. Needs the native module."""

from __future__ import annotations

import os
import sys
import warnings
from typing import Optional, Union

from ._api import StudyLike, _command, _progress_bar, _study_source


def optimize(
    study: StudyLike,
    output: Union[str, os.PathLike, None] = None,
    *,
    jobs: Optional[int] = None,
    resume: bool = False,
    force: bool = False,
    progress: bool = True,
    quiet: bool = True,
):
    """Search the design of ``study`` (a path, YAML text or a dict with an ``optimize``
    block; relative profile paths of text and dicts are taken from the working folder) into
    the results file ``output`` (default: the study's ``output``, else
    ``results/<name>.h5``) and return the file as :func:`open_results` reads it: an
    :class:`xarray.DataTree` whose ``/optimize`` holds one row per candidate
    (``candidate × variable``, ``candidate × constraint``) and ``/optimize/best`` the best
    feasible design, its constraints' values and margins.

    The file itself holds the study run at the best design (``/summary``, ``/sweet_spot``,
    ``/bat``) beside ``/optimize``. The search runs in this process as :func:`run` does: a
    progress bar in candidates (tqdm's; a widget in Jupyter), and Ctrl-C (KeyboardInterrupt)
    stops it as the CLI's first Ctrl-C does: the candidate in flight finishes and is kept,
    then KeyboardInterrupt is raised, and ``resume=True`` continues the search (its
    candidates are replayed from ``OUT.h5.optimize``); ``force=True`` starts over. Raises
    :class:`StudyError` for a bad study or output (exit status 2) and :class:`RunError`
    when the search itself fails (3); a search that finds no feasible design, or whose
    final run has failed points, warns (exit status 1). ``quiet=False`` prints the report.
    """
    from . import _native
    from ._open import open_results

    path, text = _study_source(study)
    result, ending, message, report = _command(
        lambda bar: _native.optimize_study(
            path, text, None if output is None else os.fspath(output), jobs, resume, force, bar
        ),
        _progress_bar(progress, unit="candidates", desc="searching"),
        "batstudy.optimize(..., output={output!r}, resume=True)",
    )
    if ending == "points_failed":
        warnings.warn("\n".join(x for x in (message, report.strip()) if x), RuntimeWarning, stacklevel=2)
    elif not quiet and report:
        print(report.strip(), file=sys.stderr)
    return open_results(result)
