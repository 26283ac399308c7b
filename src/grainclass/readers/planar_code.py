"""Reader for plantri's planar_code: each triangulation is the dual of a grain."""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from typing import BinaryIO

import numpy as np

from grainclass.batch import GrainBatch

HEADERS = {
    b">>planar_code<<": False,
    b">>planar_code le<<": False,
    b">>planar_code be<<": True,
}
BLOCK_BYTES = 1 << 22


@dataclass(frozen=True)
class PlanarCodeRecords:
    """Complete planar_code records left as bytes, for kernels that parse them in passing.

    Record ``r`` (1-based position ``first_record + r`` in the stream) is
    ``buf[starts[r]:starts[r + 1]]``.
    """

    source: str
    first_record: int
    buf: np.ndarray
    starts: np.ndarray
    big_endian: bool

    def __len__(self) -> int:
        return len(self.starts) - 1


def _read_header(stream: BinaryIO, head: bytes) -> tuple[bool, bytes]:
    """Strip an optional header; returns (big_endian, the bytes read past it)."""
    for header, big_endian in HEADERS.items():
        if head.startswith(header):
            return big_endian, head[len(header) :]
    return False, head


def read_planar_code(
    stream: BinaryIO, source: str, chunk_size: int, raw: bool = False
) -> Iterator[GrainBatch | PlanarCodeRecords]:
    """Parse a planar_code stream into batches of at most ``chunk_size`` triangulations.

    Parameters
    ----------
    stream : binary file object
        The input, read block by block: memory stays bounded by the chunk size.
    source : str
        The input's name, used in messages.
    chunk_size : int
        Triangulations per batch.
    raw : bool
        Yield the records as :class:`PlanarCodeRecords` instead of parsing them into CSR.

    Yields
    ------
    GrainBatch or PlanarCodeRecords
        Grain ids are the 1-based positions in the stream; a record cut off by the end of the
        input becomes an unreadable grain with its own row (a GrainBatch, also when ``raw``).
    """
    from grainclass._kernels.planar_code import _fill, _scan
    from grainclass.arrow import decimal_strings

    big_endian, pending = _read_header(stream, stream.read(32))
    record = 1
    at_end = False
    while True:
        while not at_end and len(pending) < BLOCK_BYTES:
            block = stream.read(BLOCK_BYTES)
            at_end = not block
            pending += block
        buf = np.frombuffer(pending, np.uint8)
        starts = np.empty(chunk_size + 1, np.int64)
        records, vertices, entries, consumed = _scan(buf, big_endian, chunk_size, starts)
        if records == 0:
            if at_end:
                if pending:
                    yield _cut_off(source, record, len(pending))
                return
            block = stream.read(BLOCK_BYTES)  # one record longer than a block: read on
            at_end = not block
            pending += block
            continue
        if raw:
            yield PlanarCodeRecords(
                source, record, buf[:consumed], starts[: records + 1], big_endian
            )
            record += records
            pending = pending[consumed:]
            continue
        face_offsets = np.empty(records + 1, np.int64)
        nbr_offsets = np.empty(vertices + 1, np.int64)
        neighbors = np.empty(entries, np.int32)
        _fill(buf, big_endian, records, face_offsets, nbr_offsets, neighbors)
        yield GrainBatch(
            source=source,
            grain_id=decimal_strings(np.arange(record, record + records)),
            location=np.arange(record, record + records, dtype=np.int64),
            location_kind="record",
            face_offsets=face_offsets,
            nbr_offsets=nbr_offsets,
            neighbors=neighbors,
        )
        record += records
        pending = pending[consumed:]


def _cut_off(source: str, record: int, n_bytes: int) -> GrainBatch:
    return GrainBatch(
        source=source,
        grain_id=[str(record)],
        location=np.array([record]),
        location_kind="record",
        face_offsets=np.zeros(2, np.int64),
        nbr_offsets=np.zeros(1, np.int64),
        neighbors=np.zeros(0, np.int32),
        parse_errors={0: f"the input ends in the middle of this record ({n_bytes} bytes left)"},
    )
