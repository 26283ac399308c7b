"""Voronoi and Laguerre tessellations in parts, on Dask: the box cut into slabs along z, each
slab's cells computed by one task into one part of a data set (:mod:`grainclass.parts`).

**Slabs.** The slabs follow Voro++'s search blocks of the whole tessellation
(:func:`grainclass.voronoi.block_order`): slab k owns the points of z-blocks ``cuts[k]`` to
``cuts[k + 1] - 1``. Its points, taken in that order, are the whole tessellation's in its order,
so grain ids and rows come out as one process gives them, whatever the number of parts.

**Margins.** A task holds its own points and, beyond each side of its slab, a margin of its
neighbours' points (their periodic images across a periodic side), and computes the cells of
its own. Voro++ gives each cell's reach along z: how far above and below its point another
point could still cut it (``grainclass/_voro.cpp``). A cell that reaches past the margin may
miss a neighbour; the task then stops, and the part is computed again with a margin wide enough
for the cells that reached past, never written truncated. A margin that would cover the whole
box holds every point: the part is then computed in the whole (periodic) box.

**Random seeds** are drawn in every task from the seed alone, in the order one process draws
them (chunk by chunk from the same generator, which gives the same numbers): the same ``--seed``
gives the same points, and so the same cells, for any number of parts. Each task keeps the
points of its slab and margin, and counts the others by z-block to number its own.

**Checks across parts.** Within a part, faces are seen from both sides as in one process.
A face between two parts is seen once from each: each task sums a hash of the pair of points
(their rank among all points) over its faces towards each other part, with their count, and the
two sums of each pair of parts must agree. Corners of three faces and the volumes, summed over
the parts, are checked as one process checks them.
"""

from __future__ import annotations

import dataclasses
import math
import os
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from grainclass.box import Box, Points
from grainclass.errors import DataError, OptionError
from grainclass.options import DEFAULT_CHUNK_SIZE
from grainclass.parts import PART_METADATA, DatasetFolder, PartsProgress
from grainclass.voronoi import (
    VoronoiReport,
    cell_scale,
    check_points,
    close_pair,
)
from grainclass.voronoi_slabs import Container, PartPoints, Slabs, seed_points, split_points

if TYPE_CHECKING:
    from distributed import Client

MARGIN = 3.5
"""The first margin of a slab, in mean spacings of the points ((volume / n)^(1/3)): the reach
of a million Poisson-Voronoi cells is at most 3.3 of them."""
CELLS_PER_PART = 1_000_000  # the default number of parts gives each about as many
IDS_KEPT = 10  # ids of points a part's record keeps of each problem it found


@dataclass(frozen=True)
class PartJob:
    """One task: part ``index`` of ``slabs`` with ``margin`` into ``path``; random seeds (``seed``)
    or points sent with it; ``identity`` goes into the part file's metadata."""

    index: int
    slabs: Slabs
    margin: float
    path: str
    identity: dict
    scale: float
    reach_radius: float = 0.0
    seed: int | None = None  # random seeds: drawn from this
    source: str = ""
    chunk_size: int = DEFAULT_CHUNK_SIZE


@dataclass
class PartRecord:
    """What a part's task found: its checks' counts, the hashes of its faces towards each other
    part (``cross``: part -> [faces, sum of hashes mod 2^64]), the margin it took."""

    index: int
    report: VoronoiReport
    cross: dict[int, list[int]] = field(default_factory=dict)
    margin: float = 0.0
    whole_box: bool = False
    seconds: float = 0.0

    def to_json(self) -> dict:
        report = dataclasses.asdict(self.report)
        report["one_sided"] = report["one_sided"][:IDS_KEPT]
        report["no_cell"] = report["no_cell"][:IDS_KEPT]
        return {
            "report": report,
            "cross": {str(k): v for k, v in sorted(self.cross.items())},
            "margin": self.margin,
            "whole_box": self.whole_box,
            "seconds": round(self.seconds, 3),
        }

    @classmethod
    def from_json(cls, index: int, record: dict) -> PartRecord:
        report = VoronoiReport(**record["report"])
        report.unmatched_parts = [tuple(pair) for pair in report.unmatched_parts]
        cross = {int(k): list(v) for k, v in record["cross"].items()}
        return cls(index, report, cross, record["margin"], record["whole_box"], record["seconds"])


@dataclass(frozen=True)
class Wider:
    """A part whose cells reached past its margin: to be computed again with ``margin``."""

    index: int
    margin: float


@dataclass
class VoronoiPartsResult:
    """What :func:`tessellate_in_parts` did: the checks over all parts (``report``), the parts
    computed now and those kept from an earlier run, the parts computed again with a wider
    margin (part -> margins taken), and the parts that failed."""

    report: VoronoiReport
    box: Box
    parts: int
    computed: int = 0
    skipped: int = 0
    widened: dict[int, list[float]] = field(default_factory=dict)
    failures: list[str] = field(default_factory=list)
    seconds: float = 0.0

    @property
    def ok(self) -> bool:
        return not self.failures


def default_parts(n: int, workers: int) -> int:
    """Parts of about :data:`CELLS_PER_PART` cells, at least one per worker."""
    return max(math.ceil(n / CELLS_PER_PART), workers, 1)


def tessellate_in_parts(
    directory: str,
    client: Client,
    parts: int,
    n_seeds: int | None = None,
    seed: int | None = None,
    side: float = 1.0,
    points: Points | None = None,
    box: Box | None = None,
    checked: bool = False,
    chunk_size: int = DEFAULT_CHUNK_SIZE,
    margin: float = MARGIN,
    report: Callable[[PartsProgress], None] | None = None,
) -> VoronoiPartsResult:
    """The cells of ``n_seeds`` random seeds in the periodic cube of side ``side`` (or of
    ``points`` in ``box``), classified, as a data set of ``parts`` parts in ``directory``,
    each part a task on ``client``. Parts an earlier run of the same tessellation finished are
    kept.

    Parameters
    ----------
    directory : str
        The data set's folder (:mod:`grainclass.parts`).
    client : distributed.Client
        Where the tasks run. The workers must see ``directory`` at that path.
    parts : int
        Slabs along z, at most one per layer of Voro++'s blocks.
    n_seeds, seed, side : int, int, float
        Random seeds: how many, the generator's seed (None: drawn now, and recorded; an
        unfinished data set of the same seeds in ``directory`` is resumed with its own), the
        cube's side.
    points, box : Points, Box
        Points instead, in their box (checked here, :func:`grainclass.voronoi.check_points`,
        unless ``checked``: the caller did it).
    margin : float
        The first margin, in mean spacings of the points.
    report : callable, optional
        Called with a :class:`~grainclass.parts.PartsProgress` as parts finish.

    Raises
    ------
    OptionError
        For more parts than layers of blocks, or a tilted box in more than one part.
    DataError, OutputError
    """
    from grainclass.cluster import Tasks, task_failure
    from grainclass.parts import read_dataset_file

    start = time.perf_counter()
    if points is None:
        if n_seeds is None:
            raise OptionError("n_seeds", "give a number of seeds or points")
        box = Box.cube(side)
        n = n_seeds
        identity = {"command": "voronoi", "seeds": n, "side": side, "parts": parts}
        if seed is None:  # a run of the same seeds stopped before its end is resumed
            held = read_dataset_file(directory) or {}
            previous = dict(held.get("identity") or {})
            drawn = previous.pop("seed", None)
            seed = drawn if previous == identity and not held.get("complete") else None
        if seed is None:  # 64 bits, which --seed takes back
            seed = int(np.random.SeedSequence().generate_state(1, np.uint64)[0])
        identity["seed"] = seed
        source = f"voronoi:{n}:{seed}"
    else:
        if box is None:
            raise OptionError("box", "points are tessellated in a box: give it")
        if not checked:
            check_points(points, box)
        n = len(points.xyz)
        identity = {
            "command": "voronoi",
            "points": _fingerprint(points.source),
            "box": [list(box.low), list(box.high)],
            "periodic": list(box.periodic),
            "tilt": None if box.tilt is None else list(box.tilt),
            "radii": points.radii is not None,
            "parts": parts,
        }
        source = points.source
    slabs = Slabs(box, n, parts)
    folder = DatasetFolder(directory, identity, parts)
    spacing = slabs.spacing
    job = PartJob(
        index=0,
        slabs=slabs,
        margin=margin * spacing,
        path="",
        identity={},
        scale=cell_scale(box, n),
        reach_radius=0.0 if points is None or points.radii is None else float(points.radii.max()),
        seed=seed if points is None else None,
        source=source,
        chunk_size=chunk_size,
    )
    by_part = split_points(points, slabs) if points is not None else None
    weighted = points is not None and points.radii is not None
    result = VoronoiPartsResult(VoronoiReport(), box, parts)
    records: dict[int, PartRecord] = {}
    tasks = Tasks(client, "voronoi")
    cells_now = 0

    def submit(index: int, wider: float) -> None:
        part = dataclasses.replace(
            job,
            index=index,
            margin=wider,
            path=folder.path(index),
            identity={**identity, "part": index},
        )
        data = None if by_part is None else tasks.scatter(by_part(index, wider))
        # Thicker slabs first (more layers of blocks: more cells), so that the last to finish
        # are short; among equals, lower parts first.
        layers = int(slabs.cuts[index + 1] - slabs.cuts[index])
        priority = layers * (parts + 1) + parts - index
        tasks.submit(f"part-{index:05d}", tessellation_part, part, data, priority=priority)

    for index in range(parts):
        found = folder.done(index, {**identity, "part": index})
        if found is not None:
            records[index] = PartRecord.from_json(index, found)
            result.skipped += 1
        else:
            submit(index, job.margin)

    def progress() -> None:
        if report is None:
            return
        rate = cells_now / max(time.perf_counter() - start, 1e-9)
        cells = sum(r.report.cells for r in records.values())
        left = (n - cells) / rate if rate > 0 else None
        report(PartsProgress(len(records), parts, cells, rate, left))

    for name, outcome in tasks.finished(progress):
        if isinstance(outcome, Wider):
            result.widened.setdefault(outcome.index, []).append(outcome.margin / spacing)
            submit(outcome.index, outcome.margin)
        elif isinstance(outcome, PartRecord):
            records[outcome.index] = outcome
            part_identity = {**identity, "part": outcome.index}
            folder.add(outcome.index, {"identity": part_identity, **outcome.to_json()})
            cells_now += outcome.report.cells
            result.computed += 1
        else:
            result.failures.append(task_failure(name, outcome))
    progress()
    folder.remove_temporaries()
    result.report = _merged([records[i] for i in sorted(records)])
    result.seconds = time.perf_counter() - start
    problems = result.report.problems(box.volume, simple=points is None, weighted=weighted)
    folder.finish(
        {
            "cells": result.report.cells,
            "volume": result.report.volume,
            "checks_passed": not problems and not result.failures,
            "problems": problems,
            "failures": result.failures,
        }
    )
    return result


def _fingerprint(path: str) -> dict:
    """A points file as a part's identity knows it: its path, size and time of change."""
    try:
        info = os.stat(path)
        return {"path": os.path.realpath(path), "bytes": info.st_size, "mtime_ns": info.st_mtime_ns}
    except OSError:
        return {"path": path}


class _ReachedPast(Exception):
    """A cell reached past the margin (raised inside the part's writer, which then removes its
    temporary file)."""

    def __init__(self, margin: float) -> None:
        super().__init__(margin)
        self.margin = margin


def tessellation_part(job: PartJob, data: PartPoints | None) -> PartRecord | Wider:
    """Compute, classify and write the cells of one part (runs on a Dask worker): its record,
    or :class:`Wider` if a cell reached past the margin."""
    from grainclass.parallel import set_jobs

    set_jobs(1)  # parallel over parts: one thread per task
    start = time.perf_counter()
    container = job.slabs.container(job.index, job.margin)
    if data is None:
        data = seed_points(job.slabs, job.index, job.seed, job.source, container)
    try:
        record = _write_part(job, data, container)
    except _ReachedPast as wider:
        return Wider(job.index, wider.margin)
    record.seconds = time.perf_counter() - start
    return record


def _write_part(job: PartJob, data: PartPoints, container: Container) -> PartRecord:
    import json

    from grainclass.classification import classify
    from grainclass.parquet import GrainTableWriter
    from grainclass.voronoi import cells_batch, computed_cells, make_engine

    own = data.own
    n_own = len(own.xyz)
    points = Points(
        np.concatenate([own.xyz, data.margin_xyz]),
        own.ids,
        own.locations,
        own.source,
        own.location_kind,
        None if own.radii is None else np.concatenate([own.radii, data.margin_radii]),
    )
    if job.seed is not None:
        _refuse_close_seeds(points, job)
    record = PartRecord(job.index, VoronoiReport(), margin=job.margin, whole_box=container.whole)
    metadata = {PART_METADATA: json.dumps(job.identity)}
    with GrainTableWriter(job.path, metadata) as writer:
        if n_own == 0:
            return record
        engine, scale = make_engine(points, container.box, job.scale, n_own, job.reach_radius)
        for cells, raw in computed_cells(engine, np.arange(n_own), job.chunk_size):
            _check_reach(job, container, points.xyz[cells, 2], raw, scale)
            _cross_faces(record.cross, data, cells, raw, n_own)
            batch = cells_batch(own, cells, raw, scale, record.report)
            if len(batch):
                writer.write(classify(batch))
        one_sided = engine.one_sided()
        record.report.one_sided_faces += len(one_sided)
        record.report.one_sided.extend(str(i) for i in own.ids[one_sided[:IDS_KEPT]])
    return record


def _refuse_close_seeds(points: Points, job: PartJob) -> None:
    """Refuse random seeds closer than Voro++ can separate, as one process does: any such pair
    with a point of this part is among its points and margin."""
    box = job.slabs.box
    close = close_pair(box.fractions(points.xyz), box.matrix * job.scale, box.periodic)
    if close is not None:
        raise DataError(
            f"{job.source}: two random seeds are closer than Voro++ can separate: draw others "
            "(another seed)"
        )


def _check_reach(
    job: PartJob, container: Container, z: np.ndarray, raw: dict, scale: float
) -> None:
    """Raise :class:`_ReachedPast` with a wider margin if a cell reaches past the container's
    sides that are not the box's own walls."""
    if container.whole:
        return
    low, high = job.slabs.bounds(job.index)
    top = z + raw["reach_up"] / scale
    bottom = z - raw["reach_down"] / scale
    needed = 0.0
    if not container.wall_above and top.max(initial=-np.inf) > container.box.high[2]:
        needed = max(needed, float(top.max()) - high)
    if not container.wall_below and bottom.min(initial=np.inf) < container.box.low[2]:
        needed = max(needed, low - float(bottom.min()))
    if needed > 0:
        # The cells that reached past may have been cut short by the wall: their reach says
        # how far at least, and the margin grows by half as much again to spare another round.
        raise _ReachedPast(1.5 * max(needed, job.margin))


def _cross_faces(
    cross: dict[int, list[int]], data: PartPoints, cells: np.ndarray, raw: dict, n_own: int
) -> None:
    """Add the faces of these cells towards other parts' points to ``cross``: per part, their
    number and the sum of a hash of each face's pair of points (which the other part sums the
    same)."""
    behind = raw["neighbors"]
    counts = raw["face_counts"].astype(np.int64)
    owner = np.repeat(cells, counts)
    across = behind >= n_own
    if not across.any():
        return
    margin = behind[across] - n_own
    a = data.own_keys[owner[across]].astype(np.uint64)
    b = data.margin_keys[margin].astype(np.uint64)
    hashes = _mix(_mix(np.minimum(a, b)) ^ np.maximum(a, b))
    parts = data.margin_parts[margin]
    for part in np.unique(parts):
        chosen = hashes[parts == part]
        faces, total = cross.get(int(part), [0, 0])
        cross[int(part)] = [faces + len(chosen), (total + int(chosen.sum())) % 2**64]


def _mix(x: np.ndarray) -> np.ndarray:
    """splitmix64's finalizer on uint64 arrays (wrapping)."""
    x = x + np.uint64(0x9E3779B97F4A7C15)
    x = (x ^ (x >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)
    x = (x ^ (x >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)
    return x ^ (x >> np.uint64(31))


def _merged(records: list[PartRecord]) -> VoronoiReport:
    """The checks of the parts together: counts and volumes summed, faces across parts paired."""
    merged = VoronoiReport()
    for record in records:
        part = record.report
        merged.cells += part.cells
        merged.bad_corners += part.bad_corners
        merged.one_sided_faces += part.one_sided_faces
        merged.one_sided.extend(part.one_sided)
        merged.volume += part.volume
        merged.boundary += part.boundary
        merged.no_cells += part.no_cells
        merged.no_cell.extend(part.no_cell)
    by_index = {r.index: r for r in records}
    pairs = {tuple(sorted((r.index, other))) for r in records for other in r.cross}
    for low, high in sorted(pairs):
        if low not in by_index or high not in by_index:
            continue  # a part failed, and the run with it
        if by_index[low].cross.get(high) != by_index[high].cross.get(low):
            merged.unmatched_parts.append((low, high))
    return merged
