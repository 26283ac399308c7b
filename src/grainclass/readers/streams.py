"""Opening inputs: files, and inputs that can be read only once (standard input, a FIFO, a
process substitution), whose first bytes are peeked at to sniff their format and then given
back to their reader.
"""

from __future__ import annotations

import io
import os
import stat
import sys
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from typing import BinaryIO

from grainclass.errors import InputError
from grainclass.pipes import (
    CLOSED_STANDARD_STREAMS,
    PIPE_BYTES,
    enlarge_pipe,
    reading_ahead,
    take_read_ahead,
)
from grainclass.readers.sniffing import SNIFF_BYTES


def expand_paths(paths: Sequence[str]) -> list[str]:
    """A folder stands for its per-grain Parquet files (a data set written in parts, which must
    be whole: :func:`grainclass.parts.require_complete`) or else its ``*.fe`` files (one
    grain-growth dump), in name order."""
    from grainclass.parts import require_complete

    expanded = []
    for path in paths:
        if path != "-" and os.path.isdir(path):
            require_complete(path)
            names = sorted(os.listdir(path))
            files = [f for f in names if f.lower().endswith(".parquet")]
            files = files or [f for f in names if f.lower().endswith(".fe")]
            if not files:
                raise InputError(path, "a folder given as input must hold *.parquet or *.fe files")
            expanded += [os.path.join(path, f) for f in files]
        else:
            expanded.append(path)
    return expanded


_read_once: dict[str, BinaryIO] = {}
# sys.stdin.buffer as last seen, and the stream read_once("-") gives for it.
_stdin: tuple[BinaryIO, BinaryIO] | None = None


def _is_stream(path: str) -> bool:
    """Whether ``path`` names something other than a file or a folder (a FIFO, a device)."""
    try:
        mode = os.stat(path).st_mode
    except (OSError, ValueError):
        return False
    return not (stat.S_ISREG(mode) or stat.S_ISDIR(mode))


def read_once(path: str) -> BinaryIO | None:
    """The stream of an input that can be read only once: standard input (``-``), a FIFO, a
    process substitution (``<(plantri 10)``), a device. It is opened once, and sniffing peeks
    into it: opened again, it would have lost what was read, or, a FIFO, wait for a writer
    that is gone. Its first SNIFF_BYTES can be peeked at (:func:`_with_head`). None for a
    file (or a path that is not there: its reader says so)."""
    global _stdin
    if path == "-":
        if "stdin" in CLOSED_STANDARD_STREAMS:
            raise InputError(path, "standard input is closed")
        # A replaced stdin (a test, an embedding program) is another stream: it is held here,
        # not known by its id, so that no new one can pass for it. One without peek() is
        # wrapped once, so that every reader sees the bytes another one peeked at; a pipe that
        # the command line reads ahead is taken from its read-ahead (grainclass.pipes), any
        # other gets a larger buffer (:func:`enlarge_pipe`).
        source = sys.stdin.buffer
        if _stdin is None or _stdin[0] is not source:
            ahead = reading_ahead(source)
            if ahead is not None:
                peekable = io.BufferedReader(ahead, PIPE_BYTES)
            else:
                enlarge_pipe(source)
                peekable = source if hasattr(source, "peek") else io.BufferedReader(source)
            _stdin = (source, _with_head(peekable, path))
        return _stdin[1]
    if path not in _read_once:
        if not _is_stream(path):
            return None
        ahead = take_read_ahead(path)  # the command line's first input, if a FIFO
        if ahead is not None:
            stream: BinaryIO = io.BufferedReader(ahead, PIPE_BYTES)
        else:
            try:
                stream = open(path, "rb")  # noqa: SIM115 (closed by _open, once read)
            except OSError as exc:
                raise InputError(path, exc.strerror or str(exc)) from None
            enlarge_pipe(stream)
        _read_once[path] = _with_head(stream, path)
    return _read_once[path]


def done_reading(path: str) -> None:
    """Close the :func:`read_once` stream of ``path`` once it is read (standard input stays)."""
    stream = _read_once.pop(path, None)
    if stream is not None:
        stream.close()


class _Replayed(io.RawIOBase):
    """``head``, then the rest of ``stream``: bytes read to sniff, given back."""

    def __init__(self, head: bytes, stream: BinaryIO, ended: bool, owned: bool) -> None:
        super().__init__()
        self._head = memoryview(head)
        self._stream = stream
        self._ended = ended  # read to its end: a terminal would wait for a second Ctrl-D
        self._owned = owned  # closed with this one (a FIFO opened here; not standard input)

    def close(self) -> None:
        if not self.closed and self._owned:
            self._stream.close()
        super().close()

    def readable(self) -> bool:
        return True

    def fileno(self) -> int:
        return self._stream.fileno()  # for is_pipe(): the pipe is the stream's

    def readinto(self, buffer) -> int:  # type: ignore[override]
        if self._head:
            n = min(len(buffer), len(self._head))
            buffer[:n] = self._head[:n]
            self._head = self._head[n:]
            return n
        return 0 if self._ended else self._stream.readinto1(buffer)


def _with_head(stream: BinaryIO, path: str) -> BinaryIO:
    """``stream``, or one that gives the same bytes, whose peek() shows its first SNIFF_BYTES
    (fewer at its end), to sniff. A peek takes what one read gives: from a writer that has
    written only a few bytes yet (a header cut across two writes, over a network), too few to
    tell the format. Then the head is read until there is enough, and given back in front of
    the rest."""
    try:
        head = stream.peek(SNIFF_BYTES)[:SNIFF_BYTES]
        if len(head) >= SNIFF_BYTES or not head:
            return stream
        read = bytearray()
        ended = False
        while len(read) < SNIFF_BYTES and not ended:
            more = stream.read1(SNIFF_BYTES - len(read))
            read += more
            ended = not more
    except OSError as exc:
        raise InputError(path, exc.strerror or str(exc)) from None
    replayed = _Replayed(bytes(read), stream, ended, owned=path != "-")
    return io.BufferedReader(replayed, 1 << 16)


class _ReturnsAsNewlines(io.RawIOBase):
    """``stream`` with every carriage return read as a newline: text saved with CR alone
    ending its lines (classic Mac OS) would otherwise be one long line."""

    def __init__(self, stream: BinaryIO) -> None:
        super().__init__()
        self._stream = stream

    def readable(self) -> bool:
        return True

    def readinto(self, buffer) -> int:  # type: ignore[override]
        data = self._stream.read1(len(buffer)).replace(b"\r", b"\n")
        buffer[: len(data)] = data
        return len(data)


@contextmanager
def _open(path: str) -> Iterator[BinaryIO]:
    once = read_once(path)
    if once is not None:
        try:
            yield once
        finally:
            done_reading(path)
        return
    try:
        stream = open(path, "rb")  # noqa: SIM115 (closed below, after the generator is done)
    except OSError as exc:
        raise InputError(path, exc.strerror or str(exc)) from None
    with stream:
        yield stream
