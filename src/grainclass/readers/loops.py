"""Grains given by their faces' corner loops, as mesh and simulation codes (and Voro++) write them.

Text layout, one grain per line: ``id<TAB>loops[<TAB>key=value...]`` where the loops are
separated by ``;`` and each loop lists the grain's corner ids around one face, separated by
spaces. ``volume`` and ``area`` are read as floats, as in the adjacency format.

Two faces are adjacent where they share an edge (two consecutive corners); walking a face's loop
gives its neighbours in cyclic order. A corner on only two faces (an edge split in two) does not
start a new neighbour.
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Iterable, Iterator, Sequence

import numpy as np

from grainclass.batch import GrainBatch, csr_from_lists, tri_state

FLOAT_KEYS = ("volume", "area")


class LoopError(ValueError):
    """Loops that do not close into a surface: the grain becomes an invalid row."""


def adjacency_from_loops(loops: Sequence[Sequence[int]]) -> list[list[int]]:
    """Face adjacency lists, in cyclic order, from the corner loops of a grain's faces.

    Raises
    ------
    LoopError
        When an edge does not lie on exactly two faces (an open or pinched surface).

    Examples
    --------
    >>> square_pyramid = [[0, 3, 2, 1], [0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]]
    >>> adjacency_from_loops(square_pyramid)[0]
    [4, 3, 2, 1]
    """
    on_edge: dict[tuple[int, int], list[int]] = defaultdict(list)
    faces_at: dict[int, set[int]] = defaultdict(set)
    for f, loop in enumerate(loops):
        for u, v in zip(loop, [*loop[1:], loop[0]], strict=True):
            on_edge[(min(u, v), max(u, v))].append(f)
            faces_at[u].add(f)
    lists = []
    for f, loop in enumerate(loops):
        neighbours: list[int] = []
        corners: list[int] = []
        for u, v in zip(loop, [*loop[1:], loop[0]], strict=True):
            faces = on_edge[(min(u, v), max(u, v))]
            if len(faces) != 2 or faces[0] == faces[1]:
                raise LoopError(f"not a closed surface: edge {u}-{v} lies on {len(faces)} face(s)")
            neighbours.append(faces[1] if faces[0] == f else faces[0])
            corners.append(u)
        lists.append(_merge_runs(neighbours, corners, faces_at))
    return lists


def _merge_runs(neighbours: list[int], corners: list[int], faces_at) -> list[int]:
    """Join consecutive edges to the same face across corners that only those two faces share."""
    keep = [
        i
        for i in range(len(neighbours))
        if neighbours[i] != neighbours[i - 1] or len(faces_at[corners[i]]) > 2
    ]
    return [neighbours[i] for i in keep] if keep else neighbours[:1]


def batch_from_loops(
    grains: Iterable[tuple[str, int, list[list[int]] | None, float, float, str | None]],
    source: str,
    location_kind: str = "line",
    boundary: Sequence[bool | None] | None = None,
) -> GrainBatch:
    """A batch from (id, location, loops or None, volume, area, error) tuples; ``boundary``
    flags grains cut by the sample boundary (None where the input does not tell)."""
    ids, locations, lists, volumes, areas, errors = [], [], [], [], [], {}
    for k, (grain_id, location, loops, volume, area, error) in enumerate(grains):
        ids.append(grain_id)
        locations.append(location)
        volumes.append(volume)
        areas.append(area)
        faces: list[list[int]] = []
        if error is None and loops is not None:
            try:
                faces = adjacency_from_loops(loops)
            except LoopError as exc:
                error = str(exc)
        if error is not None:
            errors[k] = error
            faces = []
        lists.append(faces)
    face_offsets, nbr_offsets, neighbors = csr_from_lists(lists)
    return GrainBatch(
        source=source,
        grain_id=ids,
        location=np.asarray(locations, np.int64),
        location_kind=location_kind,
        face_offsets=face_offsets,
        nbr_offsets=nbr_offsets,
        neighbors=neighbors,
        parse_errors=errors,
        volume=np.asarray(volumes, np.float64),
        area=np.asarray(areas, np.float64),
        boundary=None if boundary is None else tri_state(boundary),
    )


def read_loops(lines: Iterable[bytes], source: str, chunk_size: int) -> Iterator[GrainBatch]:
    """Parse face-loop text (module docstring) into batches of at most ``chunk_size`` grains."""
    pending = []
    for line_no, raw in enumerate(lines, 1):
        line = raw.decode("utf-8", "replace").strip()
        if not line or line.startswith("#"):
            continue
        fields = line.split("\t")
        grain_id = fields[0].strip()
        try:
            if len(fields) < 2:
                raise ValueError("expected a grain id, a TAB and the face loops")
            loops = [[int(t) for t in loop.split()] for loop in fields[1].strip(" ;").split(";")]
            values = dict(f.partition("=")[::2] for f in fields[2:])
            volume, area = (float(values.get(key, "nan")) for key in FLOAT_KEYS)
            pending.append((grain_id, line_no, loops, volume, area, None))
        except ValueError as exc:
            message = str(exc) if "expected" in str(exc) else f"cannot read the loops ({exc})"
            pending.append((grain_id or f"line{line_no}", line_no, None, np.nan, np.nan, message))
        if len(pending) >= chunk_size:
            yield batch_from_loops(pending, source)
            pending = []
    if pending:
        yield batch_from_loops(pending, source)
