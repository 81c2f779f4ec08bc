"""Figures of batstudy results files (matplotlib: ``pip install 'batstudy[plot]'``).

Any file, in a notebook or a script (each returns the matplotlib axes it drew on):

- :func:`exit_speed`: exit speed (or any summary variable) against impact position, one
  line per value of a dimension: ``exit_speed(path, by="swing_omega", case_label="base")``;
- :func:`sweet_spots`: the sweet spot (position and zone, or its exit speed, ...) against a
  dimension: ``sweet_spots(path, against="case", model="wave")``;
- :func:`history`: stored histories against time: ``history(path, "force", impact_z=0.6)``;
- :func:`displacement`: the bat's displacement along its length at several times;
- :func:`bat_profiles`: the profiles of the study's bats;
- :func:`compare`: the bats side by side: BBCOR along the barrel with each sweet zone, the
  lab exit speed and the vibration left in the bat against impact position;
- :func:`uncertainty`: a `sample` study's BBCOR over the sample and its sweet spot's wander;
  :func:`search`: a design search's candidates (`/optimize`).

The paper's figures: :func:`figures` draws every one the file has data for into a folder
(``FIGURES`` names them), as the command ``batstudy figures RESULTS [-o DIR]`` does.

What they are drawn from: :class:`Results`, a file as its *curves* (one exit-speed curve
along ``impact_z`` per index of every other dimension, with the parameters that describe it),
with :func:`select` and :func:`one_factor` to pick the curves that differ from a base curve
only in named parameters, and :func:`remove_rigid` / :func:`rigid_projection` for the bat's
flexible motion.
"""

try:
    import matplotlib  # noqa: F401  (only: is it there?)
except ImportError as err:  # the optional dependency: say how to get it
    raise ImportError("batstudy.plot needs matplotlib: pip install 'batstudy[plot]'") from err

from ._compare import compare
from ._curves import (
    Curve,
    Results,
    Skip,
    differing,
    excess_speed,
    one_factor,
    remove_rigid,
    rigid_projection,
    same,
    select,
)
from ._figures import ALL_FIGURES, figures, file_name, main
from ._field import tracking
from ._uncertainty import search, uncertainty
from ._paper import FIGURES, MAX_FRAMES, OTHER_FIGURES
from ._views import bat_profiles, displacement, exit_speed, history, sweet_spots

__all__ = [
    "exit_speed", "sweet_spots", "history", "displacement", "bat_profiles", "compare", "figures", "main",
    "FIGURES", "OTHER_FIGURES", "ALL_FIGURES", "MAX_FRAMES", "file_name",
    "Results", "Curve", "Skip", "select", "one_factor", "differing", "same",
    "remove_rigid", "rigid_projection", "excess_speed",
]  # fmt: skip
