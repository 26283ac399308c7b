"""Voronoi and Laguerre (power) tessellations of points in a box, computed with Voro++.

Voro++ is an installed library (Debian's ``voro++-dev``, Homebrew's or conda-forge's Voro++) that
grainclass's extension ``_voro.cpp`` is built against; without it grainclass installs without
the extension, and :func:`voro_engine` says what to install. A
:class:`grainclass._voro.Tessellation` holds the points in one Voro++ container per thread and
hands back the cells of a run of points as flat arrays (per face its number of edges, the face
across each edge and the point behind it or a wall; per cell its volume, surface area and
flags), computed on every thread without the GIL. No Python object is made per cell or face.

Cells are computed in the order of Voro++'s blocks, a chunk at a time, bottom of the box up:
neighbouring cells are computed together, and memory holds one chunk's cells at a time.

The points are scaled by a power of two (exact in floating point) to a mean cell volume of
about 1, and volumes and areas scaled back. Every tessellation is checked: each face seen from
both of its cells, the cells filling the box, and (reported) corners of three faces.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field

import numpy as np

from grainclass.batch import GrainBatch, offsets_from_counts
from grainclass.box import Box, Points
from grainclass.errors import DataError, MissingDependencyError, OptionError, TessellationError
from grainclass.options import DEFAULT_CHUNK_SIZE
from grainclass.vocabulary import plural

# Keep in step with setup.py's INSTALL_VORO.
INSTALL_VORO = (
    "apt-get install voro++-dev (Debian/Ubuntu), brew install voro++ (Homebrew) or "
    "conda install -c conda-forge voro (conda)"
)
POINTS_PER_BLOCK = 5.0  # points per Voro++ search block, as Voro++'s documentation advises
# Flags per cell from the engine (grainclass/_voro.cpp).
BAD_CORNER = 1  # a corner not on exactly three faces
OPEN = 2  # an edge not on exactly two faces
WALL = 4  # a face on a wall of the box: the cell is cut by a side that is not periodic

SAFETY = 1e-5  # points closer than this (in the scaled box) are refused: Voro++ cannot tell them
# apart reliably (its tolerance is 1e-11 on squared lengths, about 3e-6 in distance)


@dataclass
class VoronoiReport:
    """What the checks found, filled in while the cells are computed."""

    cells: int = 0
    bad_corners: int = 0  # cells with a corner of more or fewer than three faces
    one_sided_faces: int = 0  # cells listing a face that the cell behind it does not list back
    one_sided: list[str] = field(default_factory=list)  # the ids of those cells' points
    volume: float = 0.0
    boundary: int = 0  # cells with a face on a wall of the box
    no_cells: int = 0  # points without a cell (Laguerre)
    no_cell: list[str] = field(default_factory=list)  # their ids (of a part: the first few)
    unmatched_parts: list[tuple[int, int]] = field(default_factory=list)  # see voronoi_parts

    def problems(self, box_volume: float, simple: bool = True, weighted: bool = False) -> list[str]:
        """What the checks found wrong with a tessellation of a box of volume ``box_volume``:
        empty when every face is seen from both sides, the cells fill the box (to a relative
        1e-9: their volumes are summed in floating point) and, with ``simple``, every corner
        has three faces (points in general position; a lattice has corners of more). Unless
        ``weighted`` (a Laguerre tessellation, where a point may be hidden), every point must
        have a cell."""
        found = []
        if not weighted and self.no_cells:
            found.append(f"{plural(self.no_cells, 'point')} without a cell")
        if simple and self.bad_corners:
            found.append(f"{plural(self.bad_corners, 'cell')} with a corner not of three faces")
        if self.one_sided_faces:
            ids = ", ".join(self.one_sided[:10]) + (" ..." if len(self.one_sided) > 10 else "")
            found.append(
                f"{plural(self.one_sided_faces, 'cell')} with a face seen from one side only"
                + (f" (points {ids})" if ids else "")
            )
        for a, b in self.unmatched_parts:
            found.append(f"faces between parts {a} and {b} seen from one side only")
        if abs(self.volume - box_volume) > 1e-9 * box_volume:
            found.append(f"the cells' volume is {self.volume:.12g}, the box's {box_volume:.12g}")
        return found


def poisson_voronoi(
    n_seeds: int,
    seed: int | None = None,
    box: float = 1.0,
    chunk_size: int = DEFAULT_CHUNK_SIZE,
    report: VoronoiReport | None = None,
) -> Iterator[GrainBatch]:
    """Batches of the cells of a periodic Poisson-Voronoi tessellation of uniform random seeds.

    Parameters
    ----------
    n_seeds : int
        Number of seeds (and grains).
    seed : int, optional
        Seed of the random generator: the same seed gives the same tessellation.
    box : float
        Side of the periodic cube.
    chunk_size : int
        Grains per batch.
    report : VoronoiReport, optional
        Filled with the checks' counts and the total volume.

    Yields
    ------
    GrainBatch
        Grain ids are the seeds' 0-based ranks in the order the cells are computed (Voro++'s
        blocks, bottom of the box up), so grains come out in id order; volumes and areas come
        with every grain.
    """
    cube = Box.cube(box)
    xyz = np.random.default_rng(seed).random((n_seeds, 3)) * box
    xyz = xyz[block_order(xyz, cube)]
    points = Points(
        xyz, np.arange(n_seeds), np.arange(n_seeds), f"voronoi:{n_seeds}:{seed}", "record"
    )
    yield from tessellate(points, cube, chunk_size=chunk_size, report=report, ordered=True)


def cell_scale(box: Box, n: int) -> float:
    """A power of two that takes the mean cell of ``n`` points in ``box`` to a volume of about
    1. Voro++'s tolerances are absolute (1e-11 on squared lengths), made for cells of about
    that size: in much larger ones its rounding errors outgrow them, and points in degenerate
    positions (a lattice) get cells that do not fit together."""
    return 2.0 ** round(math.log2((n / box.volume) ** (1 / 3)))


def search_blocks(n: int, box: Box) -> np.ndarray:
    """Voro++'s search blocks per axis: about POINTS_PER_BLOCK points each."""
    length = (box.volume * POINTS_PER_BLOCK / n) ** (1 / 3)
    return np.maximum(1, np.round(box.lengths / length)).astype(np.int64)


def block_order(xyz: np.ndarray, box: Box, blocks: np.ndarray | None = None) -> np.ndarray:
    """The order in which the cells of points ``xyz`` are computed: by Voro++'s blocks (those
    of ``len(xyz)`` points unless ``blocks`` is given), x fastest, then y, then z (stable:
    points of one block in their given order)."""
    blocks = search_blocks(len(xyz), box) if blocks is None else blocks
    cell = block_cells(xyz, box, blocks)
    key = (cell[:, 2] * blocks[1] + cell[:, 1]) * blocks[0] + cell[:, 0]
    return np.argsort(key, kind="stable")


def block_cells(xyz: np.ndarray, box: Box, blocks: np.ndarray) -> np.ndarray:
    """The block of each point, per axis (int64[n, 3]): periodic axes wrapped, walled ones
    clipped."""
    cell = np.floor(box.fractions(xyz) * blocks).astype(np.int64)
    return np.where(box.periodic, cell % blocks, np.clip(cell, 0, blocks - 1))


def check_points(points: Points, box: Box) -> None:
    """Refuse what Voro++ cannot tessellate, naming the points and where they are: a point
    outside a walled side of the box, a negative radius, and two points at one place or
    closer than Voro++ can separate."""
    xyz = points.xyz
    if not len(xyz):
        raise DataError(f"{points.source}: no points in the box")
    if not np.isfinite(xyz).all():
        i = int(np.flatnonzero(~np.isfinite(xyz).all(axis=1))[0])
        raise DataError(f"{points.where(i)}: point {points.ids[i]} is not a finite point")
    walled = ~np.asarray(box.periodic)
    outside = ((xyz < box.low) | (xyz > box.high)) & walled
    if outside.any():
        i = int(np.flatnonzero(outside.any(axis=1))[0])
        raise DataError(
            f"{points.where(i)}: point {points.ids[i]} at ({', '.join(f'{v:g}' for v in xyz[i])})"
            f" lies outside the box {box.describe()}"
        )
    if points.radii is not None and (points.radii < 0).any():
        i = int(np.flatnonzero(points.radii < 0)[0])
        raise DataError(
            f"{points.where(i)}: point {points.ids[i]} has a negative radius ({points.radii[i]:g})"
        )
    if box.tilt is not None and not all(box.periodic):
        raise DataError(f"a tilted box must be periodic on every side: {box.describe()}")
    close = close_pair(box.fractions(xyz), box.matrix * cell_scale(box, len(xyz)), box.periodic)
    if close is not None:
        i, j = sorted(close)
        same = np.array_equal(xyz[i], xyz[j])
        raise DataError(
            f"{points.where(j)}: point {points.ids[j]} "
            + ("is at the same place as" if same else "is closer than Voro++ can separate to")
            + f" point {points.ids[i]} ({points.where(i)})"
        )


def close_pair(
    fractions: np.ndarray, matrix: np.ndarray, periodic: tuple[bool, bool, bool]
) -> tuple[int, int] | None:
    """Two points within SAFETY of each other (through the periodic sides), or None; points as
    fractions of the box's edges, the columns of ``matrix`` (scaled as Voro++ gets them).

    Sorted by their first fraction, a close pair is within SAFETY times the norm of the first
    row of the inverse matrix in it: only such neighbours are compared.
    """
    wrap = np.asarray(periodic)
    u = np.where(wrap, fractions % 1.0, fractions)
    window = SAFETY * np.linalg.norm(np.linalg.inv(matrix)[0])
    order = np.argsort(u[:, 0], kind="stable")
    us = u[order, 0]
    if wrap[0]:  # the points near the first side again, past the opposite one
        extra = np.searchsorted(us, window, "right")
        us = np.concatenate([us, us[:extra] + 1.0])
        order = np.concatenate([order, order[:extra]])
    lag = 1
    while lag < len(us):
        close = np.flatnonzero(us[lag:] - us[:-lag] <= window)
        if not len(close):
            return None
        a, b = order[close], order[close + lag]
        delta = u[b] - u[a]
        delta -= np.where(wrap, np.round(delta), 0.0)
        delta = delta @ matrix.T
        hit = np.flatnonzero((np.einsum("ij,ij->i", delta, delta) <= SAFETY**2) & (a != b))
        if len(hit):
            return int(a[hit[0]]), int(b[hit[0]])
        lag += 1
    return None


def voro_engine():
    """The compiled extension ``grainclass._voro``, which is built only where the Voro++ library
    is installed when grainclass is; :class:`MissingDependencyError` where it cannot be loaded."""
    try:
        from grainclass import _voro
    except ImportError:
        raise MissingDependencyError(
            "Voronoi tessellations need the Voro++ library, and grainclass was installed "
            f"without it: {INSTALL_VORO}, then install grainclass again"
        ) from None
    return _voro


def tessellate(
    points: Points,
    box: Box,
    chunk_size: int = DEFAULT_CHUNK_SIZE,
    report: VoronoiReport | None = None,
    ordered: bool = False,
    checked: bool = False,
) -> Iterator[GrainBatch]:
    """Batches of the Voronoi cells of ``points`` in ``box`` (Laguerre cells where the points
    have radii), one grain per point with a cell, its ``grain_id`` the point's id.

    Cells with a face on a wall (a side that is not periodic) are ``boundary``. The points are
    checked first (:func:`check_points`: a :class:`GrainclassError` names the point; unless
    ``checked``, where the caller did it); grains
    come in the order of Voro++'s blocks (``ordered``: the points are in that order already).
    A point whose Laguerre cell is empty (hidden by its neighbours' radii) has no grain; its id
    goes to ``report.no_cell``.
    """
    report = report if report is not None else VoronoiReport()
    if not checked:
        check_points(points, box)
    engine, scale = make_engine(points, box)
    order = np.arange(len(points.xyz)) if ordered else block_order(points.xyz, box)
    for cells, raw in computed_cells(engine, order, chunk_size):
        batch = cells_batch(points, cells, raw, scale, report)
        if len(batch):
            yield batch
    one_sided = engine.one_sided()
    report.one_sided_faces += len(one_sided)
    report.one_sided.extend(str(i) for i in points.ids[one_sided])


def make_engine(
    points: Points,
    box: Box,
    scale: float | None = None,
    owned: int | None = None,
    reach_radius: float = 0.0,
):
    """The Voro++ engine (``grainclass._voro.Tessellation``) of ``points`` in ``box``, scaled by
    ``scale`` (default: :func:`cell_scale` of the box and the points), and the scale. Points from
    ``owned`` on are a margin of other parts' points (``grainclass.voronoi_parts``), whose radii
    reach at most ``reach_radius`` (of the box's units)."""
    from grainclass.parallel import get_jobs

    _voro = voro_engine()
    n = len(points.xyz)
    scale = cell_scale(box, n) if scale is None else scale
    low, high = tuple(v * scale for v in box.low), tuple(v * scale for v in box.high)
    xyz, tilt = points.xyz * scale, None
    # Voro++ places a point at low <= x < high; a point on the upper wall (a LAMMPS box shrunk
    # to its atoms has some) is kept by standing that wall 1e-12 of the side further out.
    high = tuple(
        h if periodic else h + 1e-12 * (h - lo)
        for lo, h, periodic in zip(low, high, box.periodic, strict=True)
    )
    if box.tilt is not None:  # Voro++'s tilted boxes start at 0
        xyz, tilt = (points.xyz - np.asarray(box.low)) * scale, tuple(t * scale for t in box.tilt)
        low, high = (0.0, 0.0, 0.0), tuple(box.lengths * scale)
    engine = _voro.Tessellation(
        xyz,
        None if points.radii is None else points.radii * scale,
        (low[0], high[0], low[1], high[1], low[2], high[2]),
        box.periodic,
        tuple(int(b) for b in search_blocks(n, box)),
        min(get_jobs(), max(1, n // 1000)),
        tilt,
        owned,
        reach_radius * scale,
    )
    return engine, scale


def computed_cells(engine, order: np.ndarray, chunk_size: int) -> Iterator[tuple[np.ndarray, dict]]:
    """The cells of the points ``order`` (indices), ``chunk_size`` at a time: each chunk's
    indices and the engine's arrays for them."""
    chunks = [order[a : a + chunk_size] for a in range(0, len(order), chunk_size)]
    if not chunks:
        return
    # The next chunk's cells are computed (without the GIL) while this chunk's grains are
    # classified and written: one engine call at a time, one chunk ahead.
    with ThreadPoolExecutor(1, thread_name_prefix="grainclass-voro") as ahead:
        pending = ahead.submit(engine.cells, chunks[0])
        for k, cells in enumerate(chunks):
            raw = pending.result()
            if k + 1 < len(chunks):
                pending = ahead.submit(engine.cells, chunks[k + 1])
            yield cells, raw


def cells_batch(
    points: Points, cells: np.ndarray, raw: dict, scale: float, report: VoronoiReport
) -> GrainBatch:
    """The grains of the points ``cells`` (indices into ``points``), from the engine's arrays
    ``raw`` for them."""
    from grainclass.arrow import decimal_strings

    face_counts = raw["face_counts"].astype(np.int64)
    has_cell = face_counts > 0
    if not has_cell.all():
        report.no_cells += int((~has_cell).sum())
        report.no_cell.extend(str(points.ids[i]) for i in cells[~has_cell])
        cells, face_counts = cells[has_cell], face_counts[has_cell]
    flags = raw["flags"][has_cell]
    if (flags & OPEN).any():
        raise TessellationError("Voro++ returned cells whose faces do not close up; report this")
    volume = raw["volume"][has_cell] / scale**3
    boundary = (flags & WALL) != 0
    report.cells += len(cells)
    report.bad_corners += int(((flags & BAD_CORNER) != 0).sum())
    report.boundary += int(boundary.sum())
    report.volume += float(volume.sum())
    ids = points.ids[cells]
    integers = ids.dtype.kind in "iu" and (ids >= 0).all()
    return GrainBatch(
        source=points.source,
        grain_id=decimal_strings(ids) if integers else [str(i) for i in ids],
        location=points.locations[cells],
        location_kind=points.location_kind,
        face_offsets=offsets_from_counts(face_counts),
        nbr_offsets=offsets_from_counts(raw["loop_lengths"]),
        neighbors=raw["adjacent"],
        volume=volume,
        area=raw["area"][has_cell] / scale**2,
        boundary=boundary.astype(np.int8),
    )


def random_seeds_box(box: Box | None, periodic: tuple[bool, bool, bool] | None) -> Box:
    """The box of random seeds: the periodic cube ``box`` (default: the unit cube).

    Raises
    ------
    OptionError
        For a box that is not a cube from the origin, or one that is not periodic.
    """
    if periodic is not None and not all(periodic):
        raise OptionError("periodic", "random seeds fill a periodic box")
    if box is None:
        return Box.cube(1.0)
    if set(box.low) != {0.0} or len(set(box.high)) != 1 or box.tilt is not None:
        raise OptionError("box", "random seeds fill a cube from the origin: give its side")
    return Box.cube(box.high[0])


def points_box(points: Points, box: Box | None, periodic: tuple[bool, bool, bool] | None) -> Box:
    """The box of a tessellation of ``points``: ``box`` if given, else the one their file
    gives (LAMMPS, extended XYZ), else the unit cube; periodic on the axes of ``periodic`` if
    given, else as the file says, else on every axis."""
    if box is None:
        box = points.box if points.box is not None else Box.cube(1.0)
    if periodic is None:
        periodic = points.box.periodic if points.box is not None else (True, True, True)
    return Box(box.low, box.high, tuple(periodic), box.tilt)


def write_cells(batches: Iterator[GrainBatch], output: str) -> None:
    """The cells to ``output``, whole or not at all: classified into a per-grain Parquet table
    (``*.parquet``), else as adjacency text with ``volume=`` and ``area=`` per grain."""
    from grainclass.atomic import atomic_output
    from grainclass.writers import adjacency_text

    if output.lower().endswith(".parquet"):
        from grainclass.classification import classify
        from grainclass.parquet import GrainTableWriter

        with GrainTableWriter(output) as writer:
            for batch in batches:
                writer.write(classify(batch))
        return
    with atomic_output(output) as sink:
        for batch in batches:
            view = memoryview(adjacency_text(batch))
            while view:
                view = view[sink.write(view) :]
