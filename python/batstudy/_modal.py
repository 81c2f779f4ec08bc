"""The bat's displacement from the modal form of a results file (``history.displacement:
modal``, docs/layout.md): at the bat's shape points (its knob end, every node, its barrel end)

    y(t) = q(t)ᵀ Φ + p(t) s,

with q the history's ``modal_coordinate`` (bat_mode, time), Φ the bat's ``mode_shape``
(bat_mode, shape_point), p its ``bat_load`` (time) and s its ``static_shape`` (shape_point);
between shape points y is linear in z, as the model makes it (it interpolates between nodes
and extrapolates over the half segment at each end; the end points are on those lines). NaN
beyond the bat. A wall (no shape points) does not move: 0.
"""

from __future__ import annotations

import h5py
import numpy as np


def interpolation(zp: np.ndarray, z: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """For each of `z`: the shape point k below it, the weight a of point k + 1, and whether
    z is on the bat (between its first and last shape point)."""
    z = np.asarray(z, dtype=float)
    inside = (z >= zp[0]) & (z <= zp[-1])
    k = np.clip(np.searchsorted(zp, z, side="right") - 1, 0, len(zp) - 2)
    a = (z - zp[k]) / (zp[k + 1] - zp[k])
    return k, a, inside


class ModalReader:
    """Reads the modal form of an open results file and turns it into displacements; keeps
    each bat's shapes once read."""

    def __init__(self, f: h5py.File):
        self.f = f
        self.h = f["history"]
        self._bats: dict[int, tuple[np.ndarray, np.ndarray]] = {}

    def bat(self, b: int) -> tuple[np.ndarray, np.ndarray]:
        """Bat `b`'s shape points and mode shapes (bat_mode, its shape points)."""
        if b not in self._bats:
            g = self.f["bat"]
            zp = g["shape_z"][b]
            own = np.isfinite(zp)
            self._bats[b] = (zp[own], g["mode_shape"][b][:, own])
        return self._bats[b]

    def at_points(self, pos: tuple) -> tuple[np.ndarray, np.ndarray]:
        """The displacement of the history at grid position `pos` at its bat's shape
        points, (time, shape_point), and those points."""
        b = int(self.f["summary"]["bat_index"][pos])
        zp, phi = self.bat(b)
        p = self.h["bat_load"][pos]
        if zp.size < 2:
            return zp, np.zeros((p.size, zp.size))
        q = self.h["modal_coordinate"][pos]
        s = self.h["static_shape"][pos][: zp.size]
        used = _rows_used(q)
        return zp, q[:used].T @ phi[:used] + p[:, None] * s[None, :]

    def displacement(self, pos: tuple, z: np.ndarray) -> np.ndarray:
        """The displacement of the history at grid position `pos` at `z`, (time, z)."""
        zp, y = self.at_points(pos)
        if zp.size < 2:
            return np.zeros((y.shape[0], len(z)))
        k, a, inside = interpolation(zp, z)
        out = (1.0 - a) * y[:, k] + a * y[:, k + 1]
        out[:, ~inside] = np.nan
        return out


def _rows_used(q: np.ndarray) -> int:
    """Modes up to the last one that moves (the file's zero rows after them cost nothing)."""
    moving = np.flatnonzero(np.any(q != 0, axis=1))
    return int(moving[-1]) + 1 if moving.size else 0
