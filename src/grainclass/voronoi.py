"""Periodic Poisson-Voronoi tessellations (the paper's V data set), computed with Voro++.

Voro++ (through pyvoro2) merges vertices with an absolute tolerance suited to boxes of side about
1000; in a unit box with a quarter of a million seeds that creates false 4-valent corners and
faces seen from one side only. The seeds are therefore scaled by a power of two (exact in
floating point) to a box of side about 1000, and volumes and areas scaled back. Every cell is
then checked: three faces at each corner, and each face seen from both of its cells.
"""

from __future__ import annotations

import itertools
import math
from collections import Counter
from collections.abc import Iterator
from dataclasses import dataclass

import numpy as np

from grainclass.batch import GrainBatch
from grainclass.readers.loops import batch_from_loops


@dataclass
class VoronoiReport:
    """What the checks found, filled in while the cells are read."""

    cells: int = 0
    bad_corners: int = 0  # cells with a corner of more or fewer than three faces
    one_sided_faces: int = 0  # faces whose other cell does not list them back
    volume: float = 0.0


def _polygon_areas(vertices: np.ndarray, loops: list[list[int]]) -> float:
    """Total area of planar polygons (fanned from their first corner)."""
    fans = np.array([(p[0], b, c) for p in loops for b, c in itertools.pairwise(p[1:])])
    a, b, c = vertices[fans[:, 0]], vertices[fans[:, 1]], vertices[fans[:, 2]]
    return 0.5 * float(np.linalg.norm(np.cross(b - a, c - a), axis=1).sum())


def poisson_voronoi(
    n_seeds: int,
    seed: int | None = None,
    box: float = 1.0,
    chunk_size: int = 50_000,
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
        Grain ids are the seeds' 0-based positions; volumes and areas come with every grain.
    """
    import pyvoro2

    report = report if report is not None else VoronoiReport()
    points = np.random.default_rng(seed).random((n_seeds, 3)) * box
    scale = 2.0 ** round(math.log2(1000.0 / box))
    side = box * scale
    cells = pyvoro2.compute(
        points * scale,
        domain=pyvoro2.OrthorhombicCell(((0.0, side),) * 3, periodic=(True, True, True)),
        output="cells",
    )
    cells.sort(key=lambda cell: cell["id"])
    seen_from = Counter(
        (cell["id"], face["adjacent_cell"]) for cell in cells for face in cell["faces"]
    )
    pending = []
    for cell in cells:
        loops = [face["vertices"] for face in cell["faces"]]
        vertices = np.asarray(cell["vertices"])
        report.cells += 1
        report.volume += cell["volume"] / scale**3
        if any(len(corner) != 3 for corner in cell["adjacency"]):
            report.bad_corners += 1
        report.one_sided_faces += sum(
            seen_from[(face["adjacent_cell"], cell["id"])] == 0 for face in cell["faces"]
        )
        area = _polygon_areas(vertices, loops) / scale**2
        pending.append((str(cell["id"]), cell["id"], loops, cell["volume"] / scale**3, area, None))
        if len(pending) >= chunk_size:
            yield _batch(pending, n_seeds, seed)
            pending = []
    if pending:
        yield _batch(pending, n_seeds, seed)


def _batch(pending: list, n_seeds: int, seed: int | None) -> GrainBatch:
    # Periodic: no grain is cut by a sample boundary.
    return batch_from_loops(pending, f"voronoi:{n_seeds}:{seed}", "record", [False] * len(pending))
