"""batstudy: baseball bat–ball collisions (Brody's rigid model and the wave model).

- :func:`simulate` runs one collision and returns every summary value (and, on request,
  the time histories as NumPy arrays).
- :func:`run` runs a whole study (a file, YAML text or a dict) into one HDF5 results file,
  on all cores, or one shard of it (``shard=(i, n)``); :func:`merge` joins the shards;
  :func:`plan` and :func:`validate` check a study without running it.
- :func:`open_results` (also ``batstudy.open``) opens a results file as an
  :class:`xarray.DataTree`, with the grid as named dimensions, resolved parameter values
  and case labels as coordinates, and the stored histories only (see :func:`histories`);
  a file that is not a complete batstudy results file (damaged, or another program's HDF5)
  raises :class:`ResultsFileError`.
- :func:`bat_card` says what each bat of a results file is, as the trade states it (weight
  and drop, balance point, swing weights, BBCOR, sweet zone, frequencies, each rule's
  margin).
- :func:`ball_rig` gives what a ball certification reports (COR, peak force, contact time,
  dynamic stiffness) from a study of balls fired at ``bat.preset: wall``.
- :func:`longest_carry` says where a study's ball flies farthest: the impact position and,
  over a swept ``impact.offset``, the offset (a study with a ``flight``).
- :func:`report` writes a results file's explorer, one HTML file.
- :func:`fly` flies one batted ball on its own (exit speed, launch angle, spin, the air) and
  returns its trajectory as a Dataset; :mod:`batstudy.units` converts mph, ft, rpm and
  degrees to SI.
- :func:`optimize` searches a study's design (its ``optimize`` block) within its rules;
  :func:`sobol_indices` gives the global sensitivity of a ``sample`` study's answers.
- :mod:`batstudy.plot` draws the paper's figures, or any figure of a results file
  (matplotlib: ``pip install 'batstudy[plot]'``).

The command line is installed as ``batstudy`` (``batstudy --help``).

``simulate``, ``run`` and their exceptions are the native module's (the Rust library); they
are imported on first use, so that the analysis (``open_results``, ``histories``,
``report``, ``batstudy.plot``) works from a source tree without it (docs/architecture.md).
"""

from importlib import import_module as _import_module
from importlib.util import find_spec as _find_spec

from ._ball_rig import ball_rig
from ._card import bat_card
from ._carry import longest_carry
from ._files import ResultsFileError
from ._open import histories, open, open_results  # noqa: F401  (open: batstudy.open, not in __all__)
from ._report import report
from ._sensitivity import sobol_indices

__all__ = [
    "simulate",
    "run",
    "merge",
    "plan",
    "validate",
    "open_results",
    "histories",
    "ball_rig",
    "bat_card",
    "longest_carry",
    "report",
    "sobol_indices",
    "optimize",
    "export_profile",
    "fly",
    "ShardTask",
    "StudyError",
    "RunError",
    "ResultsFileError",
    "__version__",
]

# name -> the module that defines it, imported when the name is first used
_ON_FIRST_USE = {
    "simulate": "._api",
    "run": "._api",
    "merge": "._api",
    "plan": "._api",
    "validate": "._api",
    "optimize": "._optimize",
    "export_profile": "._api",
    "fly": "._fly",
    "units": ".units",
    "tracking": ".tracking",
    "ShardTask": "._scale_out",
    "StudyError": "._api",
    "RunError": "._api",
    "__version__": "._native",
    "plot": ".plot",
}


def __getattr__(name: str):
    module = _ON_FIRST_USE.get(name)
    if module is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    if module not in (".plot", ".units", ".tracking") and _find_spec("._native", __name__) is None:
        raise ImportError(
            f"batstudy.{name} needs the native module batstudy._native, which this copy of batstudy "
            "does not have (a source tree: build and install the wheel with `pip install .`); "
            "open_results, histories, report and batstudy.plot work without it"
        )
    imported = _import_module(module, __name__)
    value = imported if module in (".plot", ".units", ".tracking") else getattr(imported, name)
    globals()[name] = value
    return value


def __dir__():  # what completion offers: the names imported on first use too
    return sorted(set(globals()) | set(_ON_FIRST_USE))
