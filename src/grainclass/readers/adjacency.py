"""The adjacency text format: one grain per line, the project's own format.

``id<TAB>faces[<TAB>key=value...]`` where faces are separated by ``;`` and each face lists the
0-based indices of its neighbouring faces, separated by spaces, in cyclic order. Blank lines and
lines starting with ``#`` are skipped. ``volume`` and ``area`` are read as floats; other keys are
kept as string columns.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Iterable, Iterator, Sequence

import numpy as np

from grainclass.batch import GrainBatch, no_body_has, offsets_from_counts, run_indices

FLOAT_KEYS = ("volume", "area")
BOOLEANS = {"1": 1, "true": 1, "yes": 1, "0": 0, "false": 0, "no": 0}


class _Chunk:
    """Accumulates lines until a batch is full; the faces fields are parsed together at the end
    by a compiled kernel (a line it cannot read is read again here, for the message)."""

    def __init__(self, source: str) -> None:
        self.source = source
        self.grain_id: list[str] = []
        self.location: list[int] = []
        self.faces: list[bytes] = []  # each grain's faces field, b"" when unreadable
        self.parse_errors: dict[int, str] = {}
        self.floats: dict[str, list[float]] = {key: [] for key in FLOAT_KEYS}
        self.boundary: list[int] = []
        self.attributes: dict[str, list[str | None]] = {}

    def __len__(self) -> int:
        return len(self.grain_id)

    def add(self, line_no: int, line: str) -> None:
        fields = line.split("\t")
        if len(fields) == 2 and not self.attributes:  # the common line: id and faces only
            self.grain_id.append(fields[0].strip() or f"line{line_no}")
            self.location.append(line_no)
            self.faces.append(fields[1].encode())
            self.floats["volume"].append(np.nan)
            self.floats["area"].append(np.nan)
            self.boundary.append(-1)
            return
        grain_id = fields[0].strip() if len(fields) > 1 else (line.split() or [""])[0]
        if len(fields) < 2:
            self.add_unreadable(line_no, grain_id, "expected a grain id, a TAB and the faces")
            return
        floats, flag, values, error = key_values(fields[2:])
        boundary = -1 if flag is None else int(flag)
        # A field that cannot be read makes the grain unreadable; its other fields are kept.
        faces = fields[1].encode() if error is None else b""
        self._append(line_no, grain_id, faces, floats, boundary, values, error)

    def add_unreadable(self, line_no: int, grain_id: str, error: str) -> None:
        self._append(line_no, grain_id, b"", dict.fromkeys(FLOAT_KEYS, np.nan), -1, {}, error)

    def _append(
        self,
        line_no: int,
        grain_id: str,
        faces: bytes,
        floats: dict[str, float],
        boundary: int,
        values: dict[str, str],
        error: str | None,
    ) -> None:
        g = len(self.grain_id)
        self.grain_id.append(grain_id or f"line{line_no}")
        self.location.append(line_no)
        self.faces.append(faces)
        if error is not None:
            self.parse_errors[g] = error
        for key in FLOAT_KEYS:
            self.floats[key].append(floats[key])
        self.boundary.append(boundary)
        for key, value in values.items():
            self.attributes.setdefault(key, [None] * g).append(value)
        for column in self.attributes.values():
            if len(column) == g:
                column.append(None)

    def batch(self) -> GrainBatch:
        n_faces, degrees, neighbors, bad = parse_face_fields(self.faces)
        for g in np.flatnonzero(bad):
            if g not in self.parse_errors:
                self.parse_errors[int(g)] = _faces_error(self.faces[g].decode())
        return GrainBatch(
            source=self.source,
            grain_id=self.grain_id,
            location=np.asarray(self.location, np.int64),
            location_kind="line",
            face_offsets=offsets_from_counts(n_faces),
            nbr_offsets=offsets_from_counts(degrees),
            neighbors=neighbors,
            parse_errors=self.parse_errors,
            volume=np.asarray(self.floats["volume"], np.float64),
            area=np.asarray(self.floats["area"], np.float64),
            boundary=np.asarray(self.boundary, np.int8) if max(self.boundary) >= 0 else None,
            attributes=self.attributes,
        )


def _plain_batch(raw_lines: list[bytes], first_line: int, source: str) -> GrainBatch | None:
    """The batch of a run of lines that are all plain grains, ``id<TAB>faces`` in ASCII, split
    by a compiled kernel, the ids going straight into an Arrow array: no Python object per line.
    None for any other run (a comment, a blank line, a key=value field, other text), which is
    then read line by line."""
    from grainclass._kernels.text import _plain_lines
    from grainclass.arrow import string_array

    buf = np.frombuffer(b"".join(raw_lines), np.uint8)
    g = len(raw_lines)
    id_starts, id_ends, faces_starts, faces_ends = np.empty((4, g), np.int64)
    if _plain_lines(buf, id_starts, id_ends, faces_starts, faces_ends) != g:
        return None
    lengths = id_ends - id_starts
    id_offsets = offsets_from_counts(lengths)
    if id_offsets[-1] > np.iinfo(np.int32).max:  # past Arrow's string offsets: read line by line
        return None
    n_faces, degrees, neighbors, bad = parse_face_spans(buf, faces_starts, faces_ends)
    parse_errors = {
        int(i): _faces_error(buf[faces_starts[i] : faces_ends[i]].tobytes().decode())
        for i in np.flatnonzero(bad)
    }
    id_bytes = buf[run_indices(id_starts, lengths)]
    volume = np.full(g, np.nan)
    return GrainBatch(
        source=source,
        grain_id=string_array(id_offsets.astype(np.int32), id_bytes),
        location=np.arange(first_line, first_line + g, dtype=np.int64),
        location_kind="line",
        face_offsets=offsets_from_counts(n_faces),
        nbr_offsets=offsets_from_counts(degrees),
        neighbors=neighbors,
        parse_errors=parse_errors,
        volume=volume,
        area=volume.copy(),
    )


def parse_face_fields(
    fields: list[bytes],
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Faces fields (``1 2 3;0 4 5 2;...``, one per grain) parsed for a whole chunk by one
    kernel call: ``(faces per grain, entries per face, the entries, unreadable)``. An unreadable
    field (anything but digits, blanks and ``;``, or an empty face) gets no faces.
    """
    lengths = np.array([len(f) for f in fields], np.int64)
    ends = np.cumsum(lengths + 1) - 1  # fields joined by one separator byte
    starts = ends - lengths
    return parse_face_spans(np.frombuffer(b"\n".join(fields) or b"\n", np.uint8), starts, ends)


def parse_face_spans(
    buf: np.ndarray, starts: np.ndarray, ends: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """:func:`parse_face_fields` for the fields ``buf[starts[g]:ends[g]]`` of one buffer."""
    from grainclass._kernels.text import _parse_faces

    n_faces = np.zeros(len(starts), np.int64)
    degrees = np.empty(len(buf) + 1, np.int64)
    neighbors = np.empty(len(buf) + 1, np.int32)
    faces, entries, bad = _parse_faces(buf, starts, ends, n_faces, degrees, neighbors)
    return n_faces, degrees[:faces], neighbors[:entries], bad


def key_values(
    fields: Sequence[str],
) -> tuple[dict[str, float], bool | None, dict[str, str], str | None]:
    """The ``key=value`` fields of a grain's line (adjacency text, face loops): ``volume`` and
    ``area`` as floats (NaN when absent), the ``boundary`` flag (None when absent), the other
    keys' values as strings, and what is wrong with the first field that cannot be read (None
    if none): a bad field is left out, and the others are kept. Empty fields (a TAB at the end
    of the line) are none."""
    errors: list[str] = []
    values: dict[str, str] = {}
    for text in fields:
        if not text.strip():
            continue
        key, sep, value = text.partition("=")
        if not sep or not key.strip():
            errors.append(f"field {text!r} is not key=value")
            continue
        values[key.strip()] = value.strip()
    floats = {}
    for key in FLOAT_KEYS:
        number = values.pop(key, None)
        floats[key] = np.nan
        try:
            value = np.nan if number is None else float(number)
        except ValueError:
            errors.append(f"{key}={number!r} is not a number")
            continue
        if number is not None and not (math.isfinite(value) and value >= 0):
            errors.append(f"{key}={number!r}: expected a finite number, 0 or more")
            continue
        floats[key] = value
    volume, area = floats["volume"], floats["area"]
    if no_body_has(volume, area):
        errors.append(f"volume={volume:g} and area={area:g} cannot both be right (36 pi V^2 > S^3)")
        floats["volume"] = floats["area"] = np.nan
    flag = values.pop("boundary", None)
    if flag is not None and flag.lower() not in BOOLEANS:
        errors.append(f"boundary={flag!r}: expected 1/0, true/false or yes/no")
        flag = None
    boundary = None if flag is None else bool(BOOLEANS[flag.lower()])
    return floats, boundary, values, errors[0] if errors else None


def _faces_error(text: str) -> str:
    """What is wrong with a faces field the kernel could not read."""
    from grainclass._kernels.text import LARGEST

    for f, face in enumerate(text.strip().rstrip(";").split(";")):
        tokens = face.split()
        if not tokens:
            return f"face {f} lists no neighbours"
        for token in tokens:
            if not (token.isascii() and token.isdigit()):  # int() takes "²" or "٣" too
                return f"face {f}: {token!r} is not a face index"
            if int(token) > LARGEST:
                return f"face {f}: {token} is too large for a face index"
    return "unreadable faces"


def read_adjacency(lines: Iterable[bytes], source: str, chunk_size: int) -> Iterator[GrainBatch]:
    """Parse adjacency text into batches of at most ``chunk_size`` grains.

    Parameters
    ----------
    lines : iterable of bytes
        The input's lines (a binary file object will do).
    source : str
        The input's name, used in messages.
    chunk_size : int
        Grains per batch.

    Yields
    ------
    GrainBatch
        Every non-comment line becomes one grain, readable or not.
    """
    chunk = _Chunk(source)
    stream = iter(lines)
    first_line = 1
    while raw_lines := list(itertools.islice(stream, chunk_size)):
        plain = _plain_batch(raw_lines, first_line, source)
        if plain is not None:
            if len(chunk):
                yield chunk.batch()
                chunk = _Chunk(source)
            yield plain
        else:
            for line_no, raw in enumerate(raw_lines, first_line):
                if not raw.strip() or raw.lstrip().startswith(b"#"):
                    continue  # a comment need not be UTF-8
                try:
                    line = raw.decode("utf-8").rstrip("\r\n")
                except UnicodeDecodeError as exc:
                    grain_id = raw.split(b"\t", 1)[0].decode("utf-8", "replace").strip()
                    chunk.add_unreadable(line_no, grain_id, f"not UTF-8 text ({exc.reason})")
                else:
                    chunk.add(line_no, line)
                if len(chunk) >= chunk_size:
                    yield chunk.batch()
                    chunk = _Chunk(source)
        first_line += len(raw_lines)
    if len(chunk):
        yield chunk.batch()
