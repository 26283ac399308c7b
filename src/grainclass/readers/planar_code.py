"""Reader for plantri's planar_code: each triangulation is the dual of a grain."""

from __future__ import annotations

import sys
from collections.abc import Iterator
from dataclasses import dataclass
from typing import BinaryIO

import numpy as np

from grainclass.batch import GrainBatch
from grainclass.pipes import gathers_reads, let_gather

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

    def as_csr(self, records: np.ndarray) -> GrainBatch:
        """The records numbered ``records`` parsed into a CSR batch (for the general path),
        each keeping its position in the stream as its id and location."""
        import dataclasses
        import io

        from grainclass.arrow import decimal_strings

        header = b">>planar_code be<<" if self.big_endian else b">>planar_code<<"
        data = b"".join(self.buf[self.starts[r] : self.starts[r + 1]].tobytes() for r in records)
        batch = next(iter(read_planar_code(io.BytesIO(header + data), self.source, len(records))))
        position = self.first_record + np.asarray(records, np.int64)
        return dataclasses.replace(batch, grain_id=decimal_strings(position), location=position)


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
    from grainclass._kernels.planar_code import _fill, _scan, header_length
    from grainclass.arrow import decimal_strings

    big_endian = False
    gather = gathers_reads(stream)
    buffers = _BufferPool()
    buffer = np.zeros(0, np.uint8)  # bytes not yet parsed: buffer[pos:]
    at_end, pos = False, 0
    last_chunk = BLOCK_BYTES  # bytes the last batch took
    record = 1
    while True:
        # Read on when the rest may not hold a batch: with small batches, the bytes copied to
        # the new buffer stay small too.
        if not at_end and len(buffer) - pos < min(last_chunk, BLOCK_BYTES):
            buffer, at_end = buffers.refill(stream, buffer[pos:], gather)
            pos = 0
        buf = buffer[pos:]
        buf.flags.writeable = False  # the batches share it; one numba signature for all callers
        starts = np.empty(chunk_size + 1, np.int64)
        records, vertices, entries, consumed = _scan(buf, big_endian, chunk_size, starts)
        if records == 0 and (header := header_length(buf, 0)):  # this stream's or the next's
            big_endian = HEADERS[buf[:header].tobytes()]
            pos += header
            continue
        if records == 0:
            if at_end:
                if len(buf):
                    yield _cut_off(source, record, len(buf))
                return
            buffer, at_end = buffers.refill(stream, buf, gather)  # a record longer than a block
            pos = 0
            continue
        if raw:
            yield PlanarCodeRecords(
                source, record, buf[:consumed], starts[: records + 1], big_endian
            )
        else:
            face_offsets = np.empty(records + 1, np.int64)
            nbr_offsets = np.empty(vertices + 1, np.int64)
            neighbors = np.empty(entries + 1, np.int32)
            _fill(buf, big_endian, records, starts, face_offsets, nbr_offsets, neighbors)
            yield GrainBatch(
                source=source,
                grain_id=decimal_strings(np.arange(record, record + records)),
                location=np.arange(record, record + records, dtype=np.int64),
                location_kind="record",
                face_offsets=face_offsets,
                nbr_offsets=nbr_offsets,
                neighbors=neighbors[:entries],
            )
        record += records
        pos += consumed
        last_chunk = consumed


class _BufferPool:
    """Buffers for a stream's bytes, each filled once and then only read: the batches yielded
    are views into it. A buffer is reused once no view refers to it any more, because a fresh
    4 MB buffer costs a thousand page faults, more than the copy into it."""

    SPARE = 8

    def __init__(self) -> None:
        self._owners: list[np.ndarray] = []

    def _take(self, size: int) -> np.ndarray:
        for i in range(len(self._owners)):
            # Referenced only by the list and by getrefcount's argument: no batch holds a view.
            if len(self._owners[i]) >= size and sys.getrefcount(self._owners[i]) == 2:
                return self._owners[i]
        owner = np.empty(size, np.uint8)
        if len(self._owners) < self.SPARE:
            self._owners.append(owner)
        return owner

    def refill(self, stream: BinaryIO, rest: np.ndarray, gather: bool) -> tuple[np.ndarray, bool]:
        """``rest`` followed by up to BLOCK_BYTES more of the stream, and whether it has ended.

        With ``gather`` (a large pipe), a read that finds it nearly empty is followed by a short
        wait, so that the next read takes what the writer wrote meanwhile in one piece (see
        :mod:`grainclass.pipes`).
        """
        owner = self._take(len(rest) + BLOCK_BYTES)
        owner[: len(rest)] = rest
        filled = len(rest)
        end = len(rest) + BLOCK_BYTES
        with memoryview(owner) as view:
            while filled < end:
                got = stream.readinto1(view[filled:end])  # one system call at most
                if not got:
                    break
                filled += got
                if gather:
                    let_gather(got)
        return owner[:filled], filled < end


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
