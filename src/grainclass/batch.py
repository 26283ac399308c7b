"""`GrainBatch`: a chunk of grains as flat arrays, the unit that flows from readers to kernels."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from grainclass.errors import OptionError

if TYPE_CHECKING:
    import pyarrow as pa


def isoperimetric_quotient(volume, area):
    """Q = 36 pi V^2 / S^3 (1 for a ball, less for any other body), for floats or arrays:
    computed as 36 pi (V / S)^2 / S, since V^2 and S^3 overflow from V = 1e154 and S = 1e103
    on, where the quotient of a body does not. NaN where V or S is, or both are 0."""
    if isinstance(volume, float) and isinstance(area, float):  # one grain, read from text:
        # plain floats, where numpy's errstate and divide cost twice the rest of the line
        if area == 0:
            return math.inf if volume > 0 else math.nan
        ratio = volume / area
        return 36 * math.pi * ratio * ratio / area
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        ratio = np.divide(volume, area)
        return 36 * np.pi * ratio * ratio / area


def no_body_has(volume: float, area: float) -> bool:
    """True for a volume and a surface area that no body has together: 36 pi V^2 > S^3, past
    rounding (Q > 1 + 1e-6). False where either is NaN. The readers refuse such a pair."""
    return bool(isoperimetric_quotient(volume, area) > 1 + 1e-6)


@dataclass(frozen=True)
class Shape:
    """A grain in space, as an input with corner positions gives it.

    Attributes
    ----------
    positions : numpy.ndarray of float64, shape (V, 3)
        Its corners (a grain across a periodic box unwrapped, in one piece).
    polygons : tuple of numpy.ndarray of int64
        Its surface: polygons of rows of ``positions``, turning as the input gives them
        (counter-clockwise seen from outside, for a body listed as the formats say); a whole
        face each, or a patch of one (Surface Evolver's facets).
    face : numpy.ndarray of int64, shape (P,), optional
        The face each polygon is (0-based, in the grain's face order); None where the input
        does not say which face a patch belongs to.
    """

    positions: np.ndarray
    polygons: tuple[np.ndarray, ...]
    face: np.ndarray | None = None


@dataclass(frozen=True)
class GrainBatch:
    """Grains from one input, as CSR arrays of face adjacencies.

    Attributes
    ----------
    source : str or list of str
        Name of the input (a path, or ``-`` for standard input), or one name per grain.
    grain_id : list of str or pyarrow.StringArray
        One id per grain.
    location : numpy.ndarray of int64, shape (G,)
        Where each grain starts in the input: a line number (text) or record number (binary),
        or a label image's label.
    location_kind : str
        ``"line"``, ``"record"`` or ``"label"``.
    face_offsets : numpy.ndarray of int64, shape (G + 1,)
        Grain ``g`` has faces ``face_offsets[g]:face_offsets[g + 1]``.
    nbr_offsets : numpy.ndarray of int64, shape (F + 1,)
        Face ``f`` has the neighbours ``neighbors[nbr_offsets[f]:nbr_offsets[f + 1]]``.
    neighbors : numpy.ndarray of int32, shape (M,)
        0-based indices of neighbouring faces, local to the grain, in cyclic order where known.
    parse_errors : dict of int to str
        Why a grain could not be read (it then has no faces), by position in the batch.
    volume, area : numpy.ndarray of float64, shape (G,), optional
        Grain volume and surface area where the input gives them (NaN where it does not).
    boundary : numpy.ndarray of int8, shape (G,), optional
        1 for grains cut by a non-periodic sample boundary, 0 for grains that are not, -1 where
        the input does not tell.
    attributes : dict of str to list of (str or None)
        Further ``key=value`` fields of the input, kept as string columns.
    face_labels : numpy.ndarray of int64, shape (F,), optional
        The input's own id of each face (Neper's face ids), by which messages name faces;
        without them a face is named by its 0-based position in its grain.
    voxels : numpy.ndarray of int64, shape (G,), optional
        Voxels of each grain, for grains read from a label image.
    shortest_triple_line : numpy.ndarray of int64, shape (G,), optional
        The length of a grain's shortest triple line in voxels, as a label image shows it
        (the lattice edges around which its three grains alone meet); -1 where not known.
    shapes : list of (Shape or None), optional
        Each grain in space, read only when asked for (``ReadOptions.geometry``) and only
        where the input has corner positions (Surface Evolver, Neper); None for a grain that
        could not be read.
    """

    source: str | list[str]
    grain_id: Sequence[str] | pa.Array
    location: np.ndarray
    location_kind: str
    face_offsets: np.ndarray
    nbr_offsets: np.ndarray
    neighbors: np.ndarray
    volume: np.ndarray | None = None
    area: np.ndarray | None = None
    boundary: np.ndarray | None = None
    parse_errors: dict[int, str] = field(default_factory=dict)
    attributes: dict[str, list[str | None]] = field(default_factory=dict)
    face_labels: np.ndarray | None = None
    shapes: list[Shape | None] | None = None
    voxels: np.ndarray | None = None
    shortest_triple_line: np.ndarray | None = None

    def __post_init__(self) -> None:
        # Coerce once at the boundary so that the kernels see one layout only.
        for name, dtype in (
            ("location", np.int64),
            ("face_offsets", np.int64),
            ("nbr_offsets", np.int64),
            ("neighbors", np.int32),
        ):
            object.__setattr__(self, name, np.ascontiguousarray(getattr(self, name), dtype=dtype))
        g = len(self.grain_id)
        if self.face_offsets.shape != (g + 1,) or self.face_offsets[0] != 0:
            raise OptionError(
                "face_offsets", "face_offsets must have one entry per grain plus a leading 0"
            )
        if self.nbr_offsets.shape != (self.face_offsets[-1] + 1,) or self.nbr_offsets[0] != 0:
            raise OptionError(
                "nbr_offsets", "nbr_offsets must have one entry per face plus a leading 0"
            )
        if self.neighbors.shape != (self.nbr_offsets[-1],):
            raise OptionError("neighbors", "neighbors must end where nbr_offsets says")
        if len(self.location) != g:
            raise OptionError("location", "location needs one entry per grain")
        if not isinstance(self.source, str) and len(self.source) != g:
            raise OptionError("source", "source needs one entry per grain, or one for all")
        if self.face_labels is not None:
            labels = np.ascontiguousarray(self.face_labels, dtype=np.int64)
            object.__setattr__(self, "face_labels", labels)
            if labels.shape != (self.face_offsets[-1],):
                raise OptionError("face_labels", "face_labels needs one entry per face")
        if self.shapes is not None and len(self.shapes) != g:
            raise OptionError("shapes", "shapes needs one entry per grain")

    def __len__(self) -> int:
        return len(self.grain_id)

    @property
    def n_faces(self) -> np.ndarray:
        """Number of faces of each grain (int64, shape (G,))."""
        return np.diff(self.face_offsets)

    @property
    def isoperimetric(self) -> np.ndarray | None:
        """Isoperimetric quotient Q = 36 pi V^2 / S^3 of each grain (NaN where its volume or
        area is missing), or None when the input gives no volumes or no areas."""
        if self.volume is None or self.area is None:
            return None
        return isoperimetric_quotient(self.volume, self.area)

    @classmethod
    def from_lists(
        cls,
        grains: list[list[list[int]]],
        *,
        grain_id: list[str] | None = None,
        source: str = "<memory>",
    ) -> GrainBatch:
        """Build a batch from Python lists: ``grains[g][f]`` lists the neighbours of face ``f``.

        Examples
        --------
        >>> cube = [[1, 2, 3, 4], [0, 4, 5, 2], [0, 1, 5, 3],
        ...         [0, 2, 5, 4], [0, 3, 5, 1], [1, 4, 3, 2]]
        >>> GrainBatch.from_lists([cube]).n_faces.tolist()
        [6]
        """
        face_offsets, nbr_offsets, neighbors = csr_from_lists(grains)
        return cls(
            source=source,
            grain_id=grain_id if grain_id is not None else [str(i + 1) for i in range(len(grains))],
            location=np.arange(1, len(grains) + 1),
            location_kind="record",
            face_offsets=face_offsets,
            nbr_offsets=nbr_offsets,
            neighbors=neighbors,
        )


def csr_from_lists(
    grains: Sequence[Sequence[Sequence[int]]],
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(face_offsets, nbr_offsets, neighbors)`` of :class:`GrainBatch` from nested lists:
    ``grains[g][f]`` lists the neighbours of face ``f`` of grain ``g``."""
    n_faces = [len(faces) for faces in grains]
    degrees = [len(nbrs) for faces in grains for nbrs in faces]
    return (
        offsets_from_counts(n_faces),
        offsets_from_counts(degrees),
        np.asarray([x for faces in grains for nbrs in faces for x in nbrs], np.int32),
    )


def offsets_from_counts(counts: Sequence[int] | np.ndarray) -> np.ndarray:
    """CSR offsets (int64, a leading 0 and the running totals) from per-item counts."""
    offsets = np.zeros(len(counts) + 1, np.int64)
    np.cumsum(counts, out=offsets[1:])
    return offsets


def run_indices(starts: np.ndarray, counts: np.ndarray) -> np.ndarray:
    """The indices ``starts[i] .. starts[i] + counts[i] - 1``, one run after another: picks
    grains' faces, or faces' neighbours, out of CSR arrays."""
    run_starts = offsets_from_counts(counts)[:-1]
    return np.repeat(starts - run_starts, counts) + np.arange(int(np.sum(counts)))


def tri_state(flags: Sequence[bool | None]) -> np.ndarray:
    """True/False/None as the int8 1/0/-1 of :attr:`GrainBatch.boundary`."""
    return np.array([-1 if flag is None else int(flag) for flag in flags], np.int8)
