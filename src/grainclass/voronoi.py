"""Periodic Poisson-Voronoi tessellations (the paper's V data set), computed with Voro++.

Voro++ (through pyvoro2) merges vertices with an absolute tolerance suited to boxes of side about
1000; in a unit box with a quarter of a million seeds that creates false 4-valent corners and
faces seen from one side only. The seeds are therefore scaled by a power of two (exact in
floating point) to a box of side about 1000, and volumes and areas scaled back. Every cell is
then checked: three faces at each corner, and each face seen from both of its cells.

Large tessellations go slab by slab. pyvoro2 hands back every cell as Python dicts and lists
(about 8 KB a cell, and most of its time; its own checks of the input in Python take longer than
Voro++ itself), so all cells at once would not fit in 2 GB. A slab of the box is tessellated
with the seeds of a margin on either side (x and y stay periodic) by pyvoro2's Voro++ call
directly (``pyvoro2._core.compute_box_standard`` of pyvoro2 0.8.0, pinned exactly), on the
cores in parallel; only the face loops are asked for, and the corners are
computed from the seeds (``_kernels/voronoi.py``). A slab cell is the true periodic cell when
the empty sphere of each of its corners stays within the seeds present: this is checked for
every corner, and a slab that fails is done again with twice the margin. The input checks that
pyvoro2 would make (no two seeds within its safety distance) are made here, vectorized.
"""

from __future__ import annotations

import gc
import itertools
import math
from collections import Counter
from collections.abc import Iterator
from concurrent.futures import Future
from contextlib import contextmanager
from dataclasses import dataclass

import numpy as np

from grainclass import DEFAULT_CHUNK_SIZE
from grainclass.batch import GrainBatch, offsets_from_counts, run_indices
from grainclass.errors import GrainclassError
from grainclass.geometry import loop_arrays, polytope_measures

SLAB_SEEDS = 35_000  # seeds per slab at most; below two slabs' worth, one call does it all
MARGIN_SPACINGS = 3.0  # seeds around a slab, in mean seed spacings (a failed check doubles it)
SAFETY = 1e-5  # pyvoro2 refuses seeds closer than this (in the scaled box)


@dataclass
class VoronoiReport:
    """What the checks found, filled in while the cells are read."""

    cells: int = 0
    bad_corners: int = 0  # cells with a corner of more or fewer than three faces
    one_sided_faces: int = 0  # faces whose other cell does not list them back
    volume: float = 0.0
    slabs_redone: int = 0  # slab tessellations done again with a wider margin

    def problems(self, box: float) -> list[str]:
        """What the checks found wrong with a tessellation of a cube of side ``box``: empty
        when every corner has three faces, every face is seen from both sides and the cells
        fill the box (to a relative 1e-9: their volumes are summed in floating point)."""
        found = []
        if self.bad_corners:
            found.append(f"{self.bad_corners} cell(s) with a corner not of three faces")
        if self.one_sided_faces:
            found.append(f"{self.one_sided_faces} face(s) seen from one side only")
        if abs(self.volume - box**3) > 1e-9 * box**3:
            found.append(f"the cells' volume is {self.volume:.12g}, the box's {box**3:.12g}")
        return found


def poisson_voronoi(
    n_seeds: int,
    seed: int | None = None,
    box: float = 1.0,
    chunk_size: int = DEFAULT_CHUNK_SIZE,
    report: VoronoiReport | None = None,
    slab_seeds: int = SLAB_SEEDS,
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
    slab_seeds : int
        Tessellate slabs of at most about this many seeds at a time (module docstring).

    Yields
    ------
    GrainBatch
        Grain ids are the seeds' 0-based ranks by z (the uniform random seeds are numbered from
        the bottom of the box up); volumes and areas come with every grain.
    """
    report = report if report is not None else VoronoiReport()
    points = np.random.default_rng(seed).random((n_seeds, 3)) * box
    # Seeds numbered from the bottom of the box up: a slab holds consecutive ids, so grains
    # come out in id order slab after slab, written while later slabs are computed.
    points = points[np.argsort(points[:, 2], kind="stable")]
    scale = 2.0 ** round(math.log2(1000.0 / box))
    side = box * scale
    slabs = -(-n_seeds // slab_seeds)
    margin = MARGIN_SPACINGS * side / n_seeds ** (1 / 3)
    source = f"voronoi:{n_seeds}:{seed}"
    scaled = points * scale  # a power of two: exact
    if slabs < 2 or side / slabs + 2 * margin >= side:
        yield from _whole(scaled, side, scale, source, chunk_size, report)
        return
    _check_spacing(scaled, side)
    pairs = []  # (seed, neighbour) of every face, for the check that faces are mutual
    for grains in _tessellate_slabs(scaled, side, slabs, margin):
        pairs.append(grains["pairs"])
        report.slabs_redone += grains["redone"]
        yield from _slab_batches(grains, scale, source, chunk_size, report)
    owner, adjacent = np.concatenate(pairs, axis=1)
    forth, back = owner * n_seeds + adjacent, adjacent * n_seeds + owner
    if not np.array_equal(np.sort(forth), np.sort(back)):
        report.one_sided_faces += int((~np.isin(back, forth)).sum())


@contextmanager
def _gc_paused() -> Iterator[None]:
    """No cyclic garbage collection while pyvoro2 builds and we read its millions of lists and
    dicts (none of them in cycles): the collector's passes over them would take most of the
    time."""
    enabled = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if enabled:
            gc.enable()


def _cell_areas(cells: list[dict]) -> np.ndarray:
    """The surface area of each of pyvoro2's cells, from its corners and face loops."""
    vertex_offsets = offsets_from_counts([len(cell["vertices"]) for cell in cells])
    positions = np.concatenate([np.reshape(cell["vertices"], (-1, 3)) for cell in cells])
    corners, loop_offsets = loop_arrays(
        [face["vertices"] for cell in cells for face in cell["faces"]]
    )
    cell_of_loop = np.repeat(np.arange(len(cells)), [len(cell["faces"]) for cell in cells])
    corners += np.repeat(vertex_offsets[:-1][cell_of_loop], np.diff(loop_offsets))
    return polytope_measures(positions, corners, loop_offsets, cell_of_loop, len(cells))[1]


def _whole(
    points: np.ndarray,
    side: float,
    scale: float,
    source: str,
    chunk_size: int,
    report: VoronoiReport,
) -> Iterator[GrainBatch]:
    """The whole periodic box in one pyvoro2 call (small tessellations); ``points`` scaled to
    a box of side ``side``, ``scale`` times the user's."""
    import pyvoro2

    from grainclass.readers.loops import batch_from_loops

    with _gc_paused():
        cells = pyvoro2.compute(
            points,
            domain=pyvoro2.OrthorhombicCell(((0.0, side),) * 3, periodic=(True, True, True)),
            output="cells",
        )
    cells.sort(key=lambda cell: cell["id"])
    seen_from = Counter(
        (cell["id"], face["adjacent_cell"]) for cell in cells for face in cell["faces"]
    )
    areas = _cell_areas(cells) / scale**2 if cells else np.empty(0)
    pending = []
    for cell, area in zip(cells, areas.tolist(), strict=True):
        loops = [face["vertices"] for face in cell["faces"]]
        report.cells += 1
        report.volume += cell["volume"] / scale**3
        if any(len(corner) != 3 for corner in cell["adjacency"]):
            report.bad_corners += 1
        report.one_sided_faces += sum(
            seen_from[(face["adjacent_cell"], cell["id"])] == 0 for face in cell["faces"]
        )
        volume = cell["volume"] / scale**3
        pending.append((str(cell["id"]), cell["id"], loops, volume, area, None))
        if len(pending) >= chunk_size:
            yield batch_from_loops(pending, source, "record", [False] * len(pending))
            pending = []
    if pending:
        yield batch_from_loops(pending, source, "record", [False] * len(pending))


def _check_spacing(points: np.ndarray, side: float) -> None:
    """Refuse seeds closer than pyvoro2's safety distance (periodic), as pyvoro2 would.

    Sorted by x, a close pair is within SAFETY in x: only such neighbours are compared.
    """
    order = np.argsort(points[:, 0], kind="stable")
    xs = points[order, 0]
    wrapped = np.concatenate([xs, xs[: np.searchsorted(xs, SAFETY, "right")] + side])
    order = np.concatenate([order, order[: len(wrapped) - len(xs)]])
    for lag in itertools.count(1):
        close = np.flatnonzero(wrapped[lag:] - wrapped[:-lag] <= SAFETY)
        if not len(close):
            return
        delta = points[order[close + lag]] - points[order[close]]
        delta -= side * np.round(delta / side)
        if (np.einsum("ij,ij->i", delta, delta) <= SAFETY**2).any():
            raise GrainclassError(
                "two seeds closer than Voro++ can separate; choose another --seed"
            )


def _tessellate_slabs(points: np.ndarray, side: float, slabs: int, margin: float) -> Iterator[dict]:
    """Every slab's grains (:func:`_slab`), bottom to top, computed on worker processes; a slab
    where a corner's empty sphere left the seeds present is done again with twice the margin."""
    from grainclass.parallel import get_jobs, worker_pool

    pool = worker_pool(min(get_jobs(), slabs))
    try:
        futures: list[Future | None] = [
            pool.submit(_slab, points, side, k, slabs, margin) for k in range(slabs)
        ]
        for k, future in enumerate(futures):
            assert future is not None
            futures[k] = None  # the result goes once its grains are out
            wider = margin
            result = future.result()
            redone = 0
            while result["redo"]:
                redone += 1
                wider *= 2
                if 2 * wider + side / slabs >= side:
                    raise GrainclassError(
                        f"slab {k} of {slabs} needs seeds from all around the box: "
                        "tessellate more seeds at a time (larger slab_seeds)"
                    )
                result = pool.submit(_slab, points, side, k, slabs, wider).result()
            yield result | {"redone": redone}
    finally:
        # A reader that stops early (a closed pipe, an error) does not wait for the other slabs.
        pool.shutdown(wait=True, cancel_futures=True)


def _slab(points: np.ndarray, side: float, k: int, slabs: int, margin: float) -> dict:
    """The grains of the seeds with z in slab k of ``slabs``, from a Voro++ call on those seeds
    and the seeds within ``margin`` of the slab (periodic in z too), walls above and below."""
    from pyvoro2 import _core

    from grainclass._kernels.loops import BAD_CORNER
    from grainclass._kernels.voronoi import OUTSIDE, WALL, _voronoi_grains

    z0, z1 = side * k / slabs, side * (k + 1) / slabs
    low, high = z0 - margin, z1 + margin
    lift = (points[:, 2] - low) % side
    band = np.flatnonzero(lift < high - low)
    band_points = points[band].copy()
    band_points[:, 2] = low + lift[band]
    first, last = np.searchsorted(points[:, 2], [z0, z1])  # seeds are in z order
    inside = (band >= first) & (band < last)
    per_block = 5.0  # seeds per Voro++ block, as pyvoro2 chooses them
    length = (side * side * (high - low) * per_block / len(band)) ** (1 / 3)
    blocks = tuple(max(1, round(extent / length)) for extent in (side, side, high - low))
    with _gc_paused():
        cells = _core.compute_box_standard(
            band_points,
            np.arange(len(band), dtype=np.int32),
            ((0.0, side), (0.0, side), (low, high)),
            blocks,
            (True, True, False),
            8,
            (False, False, True),  # faces only: no corner positions, no corner adjacency
        )
        cells = [cell for cell in cells if inside[cell["id"]]]
        faces = [face for cell in cells for face in cell["faces"]]
        loops = [face["vertices"] for face in faces]
        cell_seed = np.array([cell["id"] for cell in cells], np.int64)
        face_offsets = offsets_from_counts([len(cell["faces"]) for cell in cells])
        adjacent = np.array([face["adjacent_cell"] for face in faces], np.int64)
        loop_offsets = offsets_from_counts([len(loop) for loop in loops])
        loop_corners = np.fromiter(itertools.chain.from_iterable(loops), np.int32, loop_offsets[-1])
        volume = np.array([cell["volume"] for cell in cells])
        del cells, faces, loops
    nbr_offsets = np.zeros(len(adjacent) + 1, np.int64)
    neighbors = np.empty(len(loop_corners), np.int32)
    area = np.empty(len(cell_seed))
    flags = np.zeros(len(cell_seed), np.int8)
    _voronoi_grains(
        cell_seed,
        face_offsets,
        adjacent,
        loop_offsets,
        loop_corners,
        band_points,
        side,
        low,
        high,
        volume,
        nbr_offsets,
        neighbors,
        area,
        flags,
    )
    seeds = band[cell_seed]
    return {
        "redo": bool((flags & (WALL | OUTSIDE)).any()),
        "seed": seeds,
        "face_offsets": face_offsets,
        "pairs": np.stack([np.repeat(seeds, np.diff(face_offsets)), band[adjacent]]),
        "nbr_offsets": nbr_offsets,
        "neighbors": neighbors[: nbr_offsets[-1]],
        "volume": volume,
        "area": area,
        "bad_corner": (flags & BAD_CORNER) != 0,
        "flags": flags,
    }


def _slab_batches(
    grains: dict, scale: float, source: str, chunk_size: int, report: VoronoiReport
) -> Iterator[GrainBatch]:
    """One slab's grains in id order, as batches; its corner counts and volume go to the
    report."""
    from grainclass._kernels.loops import OPEN
    from grainclass._kernels.voronoi import GEOMETRY
    from grainclass.arrow import decimal_strings

    if (grains["flags"] & (GEOMETRY | OPEN)).any():
        raise GrainclassError("Voro++ returned cells whose faces do not close up; report this")
    seeds = grains["seed"]
    face_counts = np.diff(grains["face_offsets"])
    nbr_counts = np.diff(grains["nbr_offsets"])
    volume = grains["volume"] / scale**3
    area = grains["area"] / scale**2
    report.cells += len(seeds)
    report.bad_corners += int(grains["bad_corner"].sum())
    report.volume += float(volume.sum())
    order = np.argsort(seeds, kind="stable")
    face_starts = grains["face_offsets"][:-1]
    nbr_starts = grains["nbr_offsets"][:-1]
    for a in range(0, len(seeds), chunk_size):
        cells = order[a : a + chunk_size]
        faces = run_indices(face_starts[cells], face_counts[cells])
        yield GrainBatch(
            source=source,
            grain_id=decimal_strings(seeds[cells]),
            location=seeds[cells],
            location_kind="record",
            face_offsets=offsets_from_counts(face_counts[cells]),
            nbr_offsets=offsets_from_counts(nbr_counts[faces]),
            neighbors=grains["neighbors"][run_indices(nbr_starts[faces], nbr_counts[faces])],
            volume=volume[cells],
            area=area[cells],
            boundary=np.zeros(len(cells), np.int8),  # periodic: no grain is cut
        )
