"""Grains given by their faces' corner loops, as mesh and simulation codes (and Voro++) write them.

Text layout, one grain per line: ``id<TAB>loops[<TAB>key=value...]`` where the loops are
separated by ``;`` and each loop lists the grain's corner ids around one face, separated by
spaces. ``volume``, ``area`` and ``boundary`` are read as in the adjacency format; other keys
are not kept.

Two faces are adjacent where they share an edge (two consecutive corners); walking a face's loop
gives its neighbours in cyclic order, in the loop's sense, taken as counter-clockwise seen from
outside (what the sign of ``chirality`` is measured against). A corner on only two faces (an
edge split in two) does not start a new neighbour.
"""

from __future__ import annotations

import itertools
from collections.abc import Iterable, Iterator, Sequence

import numpy as np

from grainclass.batch import GrainBatch, offsets_from_counts, run_indices, tri_state
from grainclass.readers.adjacency import key_values, parse_face_fields
from grainclass.vocabulary import plural


def batch_from_loops(
    grains: Iterable[tuple[str, int, list[list[int]] | None, float, float, str | None]],
    source: str,
    location_kind: str = "line",
    boundary: Sequence[bool | None] | None = None,
    face_labels: Sequence[Sequence[int] | None] | None = None,
) -> GrainBatch:
    """A batch from (id, location, loops or None, volume, area, error) tuples; ``boundary``
    flags grains cut by the sample boundary (None where the input does not tell);
    ``face_labels``, the input's id of each loop of each grain, name faces in messages.

    The face adjacency is built by a compiled kernel (``_kernels/loops.py``); a grain whose
    loops do not close into a surface (an edge not on exactly two faces) becomes an invalid
    row that names the edge, and so does one whose surface is not a sphere (V - E + F != 2).

    Examples
    --------
    >>> square_pyramid = [[0, 3, 2, 1], [0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]]
    >>> batch = batch_from_loops([("p", 1, square_pyramid, 1.0, 1.0, None)], "<memory>")
    >>> batch.neighbors[: batch.nbr_offsets[1]].tolist()  # face 0's neighbours
    [4, 3, 2, 1]
    """
    rows = _Rows(source, location_kind)
    face_counts, loop_lengths, corners, labels = [], [], [], []
    for k, (grain_id, location, loops, volume, area, error) in enumerate(grains):
        rows.add(grain_id, location, volume, area, error)
        if error is None and loops is not None:
            face_counts.append(len(loops))
            loop_lengths.extend(len(loop) for loop in loops)
            corners.extend(itertools.chain.from_iterable(loops))
            if face_labels is not None:
                labels.extend(face_labels[k] or range(len(loops)))
        else:
            face_counts.append(0)
    return rows.batch(
        np.asarray(face_counts, np.int64),
        offsets_from_counts(loop_lengths),
        np.asarray(corners, np.int64),
        boundary,
        None if face_labels is None else np.asarray(labels, np.int64),
    )


class LoopText:
    """Grains whose face loops are text, ``0 3 2 1;0 1 4;...``, gathered line by line and parsed
    for a whole chunk at once by the adjacency text kernel (a loop of corner ids reads like a
    face of neighbour ids), not number by number in Python.

    ``unreadable`` is the message for loops the kernel cannot read (a character other than
    digits, blanks and ``;``, or an empty loop). Loops are read as counter-clockwise seen from
    outside (what the sign of ``chirality`` is measured against); ``clockwise`` loops, as
    Voro++ writes them, are turned round.
    """

    def __init__(self, source: str, unreadable: str, clockwise: bool = False) -> None:
        self._rows = _Rows(source, "line")
        self._texts: list[bytes] = []
        self._boundary: list[bool | None] = []
        self.unreadable = unreadable
        self.clockwise = clockwise

    def __len__(self) -> int:
        return len(self._texts)

    def add(
        self,
        grain_id: str,
        line_no: int,
        loops: bytes,
        volume: float,
        area: float,
        boundary: bool | None = None,
    ) -> None:
        self._rows.add(grain_id, line_no, volume, area, None)
        self._texts.append(loops)
        self._boundary.append(boundary)

    def add_unreadable(self, grain_id: str, line_no: int, message: str) -> None:
        self._rows.add(grain_id, line_no, np.nan, np.nan, message)
        self._texts.append(b"")
        self._boundary.append(None)

    def batch(self) -> GrainBatch:
        loop_counts, loop_lengths, corners, bad = parse_face_fields(self._texts)
        for g in np.flatnonzero(bad):
            self._rows.errors.setdefault(int(g), self.unreadable)
        told = any(flag is not None for flag in self._boundary)
        return self._rows.batch(
            loop_counts,
            offsets_from_counts(loop_lengths),
            corners.astype(np.int64),
            self._boundary if told else None,
            clockwise=self.clockwise,
        )


class _Rows:
    """What a batch of loop grains holds besides the loops: ids, where they are, volumes,
    areas and the errors of rows that could not be read."""

    def __init__(self, source: str, location_kind: str) -> None:
        self.source, self.location_kind = source, location_kind
        self.ids: list[str] = []
        self.locations: list[int] = []
        self.volumes: list[float] = []
        self.areas: list[float] = []
        self.errors: dict[int, str] = {}

    def add(self, grain_id: str, location: int, volume: float, area: float, error: str | None):
        if error is not None:
            self.errors[len(self.ids)] = error
        self.ids.append(grain_id)
        self.locations.append(location)
        self.volumes.append(volume)
        self.areas.append(area)

    def batch(
        self,
        face_counts: np.ndarray,
        loop_offsets: np.ndarray,
        corners: np.ndarray,
        boundary: Sequence[bool | None] | None,
        face_labels: np.ndarray | None = None,
        clockwise: bool = False,
    ) -> GrainBatch:
        """The batch, with each grain's ``face_counts[g]`` loops, loop k being
        ``corners[loop_offsets[k]:loop_offsets[k + 1]]`` (0 loops for a row with an error),
        and loop k's id in the input ``face_labels[k]``, if given; loops that turn
        ``clockwise`` seen from outside give their neighbours the other way round."""
        from grainclass._kernels.loops import OPEN, PINCHED, _adjacency_from_loops

        face_offsets = offsets_from_counts(face_counts)
        n_loops = len(loop_offsets) - 1
        nbr_offsets = np.zeros(n_loops + 1, np.int64)
        neighbors = np.empty(len(corners), np.int32)
        flags = np.zeros(len(self.ids), np.int8)
        bad = np.zeros((len(self.ids), 3), np.int64)
        _adjacency_from_loops(
            face_offsets, loop_offsets, corners, nbr_offsets, neighbors, flags, bad, clockwise
        )
        neighbors = neighbors[: nbr_offsets[-1]]
        not_sphere = (flags & (OPEN | PINCHED)) != 0
        if not_sphere.any():  # such grains keep their row, without faces
            for g in np.flatnonzero(not_sphere):
                u, v, count = bad[g]
                self.errors[int(g)] = (
                    f"not a closed surface: edge {u}-{v} lies on {plural(count, 'face')}"
                    if flags[g] & OPEN
                    else f"not a sphere: corners - edges + faces = {count}, not 2 (two corners "
                    "with one id, where the surface touches itself, or a handle)"
                )
            kept_faces = np.flatnonzero(np.repeat(~not_sphere, face_counts))
            if face_labels is not None:
                face_labels = face_labels[kept_faces]
            nbr_counts = np.diff(nbr_offsets)[kept_faces]
            neighbors = neighbors[run_indices(nbr_offsets[:-1][kept_faces], nbr_counts)]
            face_offsets = offsets_from_counts(np.where(not_sphere, 0, face_counts))
            nbr_offsets = offsets_from_counts(nbr_counts)
        return GrainBatch(
            source=self.source,
            grain_id=self.ids,
            location=np.asarray(self.locations, np.int64),
            location_kind=self.location_kind,
            face_offsets=face_offsets,
            nbr_offsets=nbr_offsets,
            neighbors=neighbors,
            parse_errors=self.errors,
            volume=np.asarray(self.volumes, np.float64),
            area=np.asarray(self.areas, np.float64),
            boundary=None if boundary is None else tri_state(boundary),
            face_labels=face_labels,
        )


def read_loops(lines: Iterable[bytes], source: str, chunk_size: int) -> Iterator[GrainBatch]:
    """Parse face-loop text (module docstring) into batches of at most ``chunk_size`` grains."""
    rows = LoopText(source, "cannot read the loops: expected corner numbers, loops split by ';'")
    for line_no, raw in enumerate(lines, 1):
        line = raw.decode("utf-8", "replace").strip()
        if not line or line.startswith("#"):
            continue
        fields = line.split("\t")
        grain_id = fields[0].strip() or f"line{line_no}"
        floats, boundary, _, error = key_values(fields[2:])
        if len(fields) < 2:
            rows.add_unreadable(grain_id, line_no, "expected a grain id, a TAB and the face loops")
        elif error is not None:
            rows.add_unreadable(grain_id, line_no, error)
        else:
            loops = fields[1].strip(" ;").encode()
            rows.add(grain_id, line_no, loops, floats["volume"], floats["area"], boundary)
        if len(rows) >= chunk_size:
            yield rows.batch()
            rows = LoopText(source, rows.unreadable)
    if len(rows):
        yield rows.batch()
