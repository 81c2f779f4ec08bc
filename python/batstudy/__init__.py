"""batstudy: baseball bat–ball collisions (Brody's rigid model and the wave model).

- :func:`simulate` runs one collision and returns every summary value (and, on request,
  the time histories as NumPy arrays).
- :func:`run` runs a whole study file into one HDF5 results file, on all cores.
- :func:`open` opens a results file as an :class:`xarray.DataTree`, lazily, with the
  grid as named dimensions, resolved parameter values and case labels as coordinates, and
  the stored histories only (see :func:`histories`).

The command line is installed as ``batstudy`` (``batstudy --help``).
"""

from ._api import StudyError, RunError, simulate, run
from ._open import open, histories

__all__ = ["simulate", "run", "open", "histories", "StudyError", "RunError", "__version__"]

from ._native import __version__
