"""Points and the box they fill: what ``grainclass voronoi`` tessellates, as read from a
points file (:mod:`grainclass.readers.points`) or drawn at random (:mod:`grainclass.voronoi`)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

SMALLEST_SIDE, LARGEST_SIDE = 1e-30, 1e30
"""The sides a box may have: volumes are computed in a box scaled to cells of about unit volume
and scaled back, and summed; far beyond these bounds the factor or the sum leaves the range of a
float."""


@dataclass(frozen=True)
class Box:
    """A box, ``low[a] <= x[a] < high[a]``, periodic or walled per axis; with ``tilt`` (xy,
    xz, yz, as LAMMPS writes them) the triclinic box from ``low`` with edges (lx, 0, 0),
    (xy, ly, 0) and (xz, yz, lz), periodic on every side (Voro++ tessellates no other)."""

    low: tuple[float, float, float]
    high: tuple[float, float, float]
    periodic: tuple[bool, bool, bool] = (True, True, True)
    tilt: tuple[float, float, float] | None = None

    def problem(self) -> str | None:
        """What makes this no box to tessellate, in words, or None: a bound or tilt that is not
        a finite number, or a side that is not from :data:`SMALLEST_SIDE` to
        :data:`LARGEST_SIDE`."""
        if not all(np.isfinite([*self.low, *self.high, *(self.tilt or ())])):
            return "its bounds and tilts must be finite numbers"
        sides = self.lengths
        if not all(SMALLEST_SIDE <= side <= LARGEST_SIDE for side in sides):
            shown = ", ".join(f"{side:g}" for side in sides)
            return f"each side must be from {SMALLEST_SIDE:g} to {LARGEST_SIDE:g}, not {shown}"
        return None

    @property
    def matrix(self) -> np.ndarray:
        """The edges of the box as the columns of a 3 x 3 matrix."""
        lx, ly, lz = self.lengths
        xy, xz, yz = self.tilt or (0.0, 0.0, 0.0)
        return np.array([[lx, xy, xz], [0.0, ly, yz], [0.0, 0.0, lz]])

    def fractions(self, xyz: np.ndarray) -> np.ndarray:
        """Points as fractions of the box's edges from ``low`` (0 to 1 inside)."""
        if self.tilt is None:  # each axis on its own: (x - low) / length, as z_fractions has it
            return (xyz - np.asarray(self.low)) / self.lengths
        return np.linalg.solve(self.matrix, (xyz - np.asarray(self.low)).T).T

    def z_fractions(self, z: np.ndarray) -> np.ndarray:
        """Heights as fractions of the box's height, as :meth:`fractions` gives them (the third
        edge of a tilted box leans, but only it rises)."""
        return (z - self.low[2]) / self.lengths[2]

    @classmethod
    def cube(cls, side: float, periodic: tuple[bool, bool, bool] = (True, True, True)) -> Box:
        """The cube ``[0, side)^3``."""
        return cls((0.0, 0.0, 0.0), (side, side, side), periodic)

    @property
    def lengths(self) -> np.ndarray:
        return np.subtract(self.high, self.low, dtype=np.float64)

    @property
    def volume(self) -> float:
        return float(np.prod(self.lengths))

    def describe(self) -> str:
        """``[0, 1] x [0, 2] x [0, 1], periodic in x, y`` and the like."""
        sides = " x ".join(f"[{a:g}, {b:g}]" for a, b in zip(self.low, self.high, strict=True))
        axes = "".join(a for a, p in zip("xyz", self.periodic, strict=True) if p)
        tilted = (
            f" tilted by xy, xz, yz = {', '.join(f'{t:g}' for t in self.tilt)}" if self.tilt else ""
        )
        return f"{sides}{tilted}, " + (f"periodic in {', '.join(axes)}" if axes else "walled")


@dataclass
class Points:
    """Points to tessellate, as read from a file (``grainclass.readers.points``) or made here.

    ``ids`` are the points' own ids (the grains' ``grain_id``); ``locations`` where each point
    is in its input (a line number, or a record number: ``location_kind``); ``radii`` (or None)
    make the tessellation a Laguerre one.
    """

    xyz: np.ndarray  # float64[n, 3]
    ids: np.ndarray  # int64[n] or str objects
    locations: np.ndarray  # int64[n]
    source: str = "<memory>"
    location_kind: str = "record"
    radii: np.ndarray | None = None
    box: Box | None = None  # from the file, where it says

    def where(self, i: int) -> str:
        """``points.xyz:12`` (a line) or ``points.npy, record 12``: where point ``i`` is."""
        if self.location_kind == "line":
            return f"{self.source}:{self.locations[i]}"
        return f"{self.source}, record {self.locations[i]}"
