"""Grains given by their faces' corner loops, as mesh and simulation codes (and Voro++) write them.

Text layout, one grain per line: ``id<TAB>loops[<TAB>key=value...]`` where the loops are
separated by ``;`` and each loop lists the grain's corner ids around one face, separated by
spaces. ``volume`` and ``area`` are read as floats, as in the adjacency format.

Two faces are adjacent where they share an edge (two consecutive corners); walking a face's loop
gives its neighbours in cyclic order. A corner on only two faces (an edge split in two) does not
start a new neighbour.
"""

from __future__ import annotations

import itertools
from collections.abc import Iterable, Iterator, Sequence

import numpy as np

from grainclass.batch import GrainBatch, offsets_from_counts, run_indices, tri_state

FLOAT_KEYS = ("volume", "area")


def batch_from_loops(
    grains: Iterable[tuple[str, int, list[list[int]] | None, float, float, str | None]],
    source: str,
    location_kind: str = "line",
    boundary: Sequence[bool | None] | None = None,
) -> GrainBatch:
    """A batch from (id, location, loops or None, volume, area, error) tuples; ``boundary``
    flags grains cut by the sample boundary (None where the input does not tell).

    The face adjacency is built by a compiled kernel (``_kernels/loops.py``); a grain whose
    loops do not close into a surface (an edge not on exactly two faces) becomes an invalid
    row that names the edge.

    Examples
    --------
    >>> square_pyramid = [[0, 3, 2, 1], [0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]]
    >>> batch = batch_from_loops([("p", 1, square_pyramid, 1.0, 1.0, None)], "<memory>")
    >>> batch.neighbors[: batch.nbr_offsets[1]].tolist()  # face 0's neighbours
    [4, 3, 2, 1]
    """
    from grainclass._kernels.loops import OPEN, _adjacency_from_loops

    ids, locations, volumes, areas, errors = [], [], [], [], {}
    face_counts, loop_lengths, corners = [], [], []
    for k, (grain_id, location, loops, volume, area, error) in enumerate(grains):
        ids.append(grain_id)
        locations.append(location)
        volumes.append(volume)
        areas.append(area)
        if error is not None:
            errors[k] = error
        if error is None and loops is not None:
            face_counts.append(len(loops))
            loop_lengths.extend(len(loop) for loop in loops)
            corners.extend(itertools.chain.from_iterable(loops))
        else:
            face_counts.append(0)
    face_offsets = offsets_from_counts(face_counts)
    loop_offsets = offsets_from_counts(loop_lengths)
    nbr_offsets = np.zeros(len(loop_lengths) + 1, np.int64)
    neighbors = np.empty(len(corners), np.int32)
    flags = np.zeros(len(ids), np.int8)
    bad = np.zeros((len(ids), 3), np.int64)
    _adjacency_from_loops(
        face_offsets,
        loop_offsets,
        np.asarray(corners, np.int64),
        nbr_offsets,
        neighbors,
        flags,
        bad,
    )
    neighbors = neighbors[: nbr_offsets[-1]]
    open_surface = (flags & OPEN) != 0
    if open_surface.any():  # such grains keep their row, without faces
        for g in np.flatnonzero(open_surface):
            u, v, count = bad[g]
            errors[int(g)] = f"not a closed surface: edge {u}-{v} lies on {count} face(s)"
        counts = np.asarray(face_counts, np.int64)
        kept_faces = np.flatnonzero(np.repeat(~open_surface, counts))
        nbr_counts = np.diff(nbr_offsets)[kept_faces]
        neighbors = neighbors[run_indices(nbr_offsets[:-1][kept_faces], nbr_counts)]
        face_offsets = offsets_from_counts(np.where(open_surface, 0, counts))
        nbr_offsets = offsets_from_counts(nbr_counts)
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
