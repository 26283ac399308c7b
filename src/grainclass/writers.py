"""Grains written back in the formats the readers read: adjacency text and planar_code.

The lines and records are laid out by compiled kernels (``_kernels/write.py``); only the
``key=value`` fields that a batch has (volumes, areas, boundary flags, other attributes) are
formatted in Python, grain by grain, since a float is written with every digit (``repr``).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import pyarrow as pa

from grainclass.batch import GrainBatch, offsets_from_counts
from grainclass.errors import OptionError

PLANAR_CODE_HEADER = b">>planar_code<<"
_UNSAFE = str.maketrans({"\t": " ", "\n": " ", "\r": " "})


def _string_buffers(values: Sequence[str] | pa.Array | pa.ChunkedArray) -> tuple[np.ndarray, ...]:
    """UTF-8 bytes of strings and their int64 offsets, straight from an Arrow array's buffers
    where the strings are one."""
    from grainclass.arrow import strings

    if isinstance(values, pa.ChunkedArray):
        values = values.combine_chunks()
    if not isinstance(values, pa.Array):
        values = strings([str(value) for value in values])
    values = values.cast(pa.string())
    _, offsets, data = values.buffers()
    starts = np.frombuffer(offsets, np.int32, len(values) + 1, values.offset * 4)
    data = np.frombuffer(data, np.uint8) if data is not None else np.zeros(0, np.uint8)
    return starts.astype(np.int64), data


def _float_field(key: str, values: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``<TAB>key=value`` per grain, the value with every digit (``repr``), none where NaN:
    int64 offsets and ASCII bytes. The reprs come from one ``repr`` of the whole list, which
    formats them in C, not one Python call per grain."""
    prefix = f"\t{key}="
    if np.isnan(values).any():
        texts = [f"{prefix}{v!r}" if v == v else "" for v in values.tolist()]
        return _string_buffers(texts)
    reprs = repr(values.tolist())[1:-1].split(", ") if len(values) else []
    lengths = np.fromiter(map(len, reprs), np.int64, len(reprs)) + len(prefix)
    data = (prefix + prefix.join(reprs)).encode("ascii") if reprs else b""
    return offsets_from_counts(lengths), np.frombuffer(data, np.uint8)


def _fields(batch: GrainBatch) -> list[tuple[np.ndarray, np.ndarray]]:
    """Each grain's ``key=value`` fields (each after a TAB), a column per key where the batch
    has any: volume and area with every digit, boundary as 1/0, other attributes as read (TABs
    and line ends in them as blanks, which the line could not hold). Each column is int64
    offsets (one per grain and one more) into its bytes."""
    from grainclass.arrow import strings_from_codes

    columns = []
    for key, values in (("volume", batch.volume), ("area", batch.area)):
        if values is not None and not np.isnan(values).all():
            columns.append(_float_field(key, values))
    if batch.boundary is not None and (batch.boundary >= 0).any():
        flags = strings_from_codes(batch.boundary, ("\tboundary=0", "\tboundary=1"))
        columns.append(_string_buffers(flags))
    for key, values in batch.attributes.items():
        name = key.translate(_UNSAFE).replace("=", " ")
        texts = ["" if v is None else f"\t{name}={v.translate(_UNSAFE)}" for v in values]
        columns.append(_string_buffers(texts))
    return columns


def adjacency_text(batch: GrainBatch) -> bytes:
    """The batch as adjacency text, a line per grain (``id<TAB>faces[<TAB>key=value...]``),
    which :func:`grainclass.readers.adjacency.read_adjacency` reads back as it was: the same
    ids, lists, volumes, areas, boundary flags and attributes. A grain the reader could not
    parse has no faces: its line has an empty faces field, and reads as invalid again."""
    from grainclass._kernels.write import _adjacency_text

    id_offsets, id_bytes = _string_buffers(batch.grain_id)
    columns = _fields(batch)
    field_offsets = np.zeros((len(columns), len(batch) + 1), np.int64)
    at = 0
    for c, (offsets, data) in enumerate(columns):
        field_offsets[c] = offsets + at
        at += len(data)
    field_bytes = (
        np.concatenate([data for _, data in columns]) if columns else np.zeros(0, np.uint8)
    )
    return _adjacency_text(
        id_offsets,
        id_bytes,
        batch.face_offsets,
        batch.nbr_offsets,
        batch.neighbors,
        field_offsets,
        field_bytes.astype(np.uint8, copy=False),
    ).tobytes()


def planar_code(batch: GrainBatch) -> bytes:
    """The batch as planar_code records (no header: :data:`PLANAR_CODE_HEADER` goes before the
    first), each grain's lists as they are. planar_code holds nothing else: ids are positions
    in the stream. A record the reader could not parse (cut off at the end of its input) has
    no lists to write and is left out (:func:`unwritable`)."""
    from grainclass._kernels.write import _planar_code

    keep = np.ones(len(batch), np.bool_)
    keep[list(batch.parse_errors)] = False
    if keep.all():
        return _planar_code(batch.face_offsets, batch.nbr_offsets, batch.neighbors).tobytes()
    return _planar_code(*_select(batch, np.flatnonzero(keep))).tobytes()


def unwritable(batch: GrainBatch, fmt: str) -> int:
    """How many grains of the batch :func:`planar_code` leaves out (none in adjacency text)."""
    return len(batch.parse_errors) if fmt == "planar_code" else 0


def _select(batch: GrainBatch, grains: np.ndarray) -> tuple[np.ndarray, ...]:
    """The CSR arrays of the grains numbered ``grains``."""
    from grainclass.batch import run_indices

    n_faces = batch.n_faces[grains]
    faces = run_indices(batch.face_offsets[grains], n_faces)
    degrees = np.diff(batch.nbr_offsets)[faces]
    entries = run_indices(batch.nbr_offsets[faces], degrees)
    return offsets_from_counts(n_faces), offsets_from_counts(degrees), batch.neighbors[entries]


def write_batch(batch: GrainBatch, fmt: str) -> bytes:
    """The batch in ``fmt``, ``adjacency`` or ``planar_code``."""
    if fmt == "planar_code":
        return planar_code(batch)
    if fmt == "adjacency":
        return adjacency_text(batch)
    raise OptionError("format", f"grains are written as adjacency or planar_code, not {fmt!r}")
