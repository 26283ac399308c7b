"""Readers: every input format becomes a stream of :class:`~grainclass.batch.GrainBatch` chunks.

The format is sniffed from the content: planar_code always holds 0 bytes (its terminators),
and text has none but by accident (:func:`_looks_like_planar_code` tells the two apart).
"""

from __future__ import annotations

import io
import os
import re
import stat
import sys
import warnings
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from typing import BinaryIO

from grainclass import DEFAULT_CHUNK_SIZE
from grainclass.batch import GrainBatch
from grainclass.errors import EmptyInputWarning, InputError
from grainclass.pipes import PIPE_BYTES, enlarge_pipe, reading_ahead, take_read_ahead
from grainclass.readers.adjacency import read_adjacency
from grainclass.readers.evolver import DEFAULT_TRIPLE_EDGES, read_evolver
from grainclass.readers.loops import read_loops
from grainclass.readers.neper import looks_like_neper, read_neper
from grainclass.readers.planar_code import PlanarCodeRecords, read_planar_code
from grainclass.readers.voro import looks_like_voro, read_voro
from grainclass.vocabulary import INPUT_FORMATS

_BOM = b"\xef\xbb\xbf"  # what some Windows editors put before UTF-8 text
_EVOLVER = re.compile(rb"(?im)^\s*(vertices|torus_filled|torus|periods)\s*(//.*)?$")

# Files that hold no grains a reader could take, by their first bytes (whole magic numbers: a
# grain id may start with "BZh"): named, not misread (their 0 bytes would make them planar_code).
# Compressed files, by their magic bytes: (compression, the command that decompresses to
# standard output).
_COMPRESSED = {
    re.compile(rb"\x1f\x8b\x08"): ("gzip", "zcat"),
    re.compile(rb"BZh[1-9]1AY&SY", re.DOTALL): ("bzip2", "bzcat"),
    re.compile(rb"\xfd7zXZ\x00"): ("xz", "xzcat"),
    re.compile(rb"\x28\xb5\x2f\xfd"): ("zstd", "zstdcat"),
}


def sniff(head: bytes) -> str:
    """Name the format of an input from its first bytes.

    Examples
    --------
    >>> sniff(b">>planar_code<<" + bytes([4, 2, 3, 4, 0]))
    'planar_code'
    >>> sniff(b"cube\\t1 2 3 4;0 4 5 2")
    'adjacency'
    >>> sniff(b"// a foam\\nvertices\\n1 0 0 0\\n")
    'evolver'
    >>> sniff(b"7 0.0351 (1,3,2) (1,5,4,3)\\n")
    'voro'

    Face-vertex-loop text looks like adjacency text: it is read only with ``--format loops``.
    A Parquet table or a compressed file is ``not grains``: :func:`read_dataset` says why.
    """
    if not_grains(head):
        return "not grains"
    head = head.removeprefix(_BOM)
    if _returns_alone(head):
        head = head.replace(b"\r", b"\n")
    if _looks_like_planar_code(head):
        return "planar_code"
    if _EVOLVER.search(head):
        return "evolver"
    if looks_like_voro(head):
        return "voro"
    if looks_like_neper(head):
        return "neper"
    return "adjacency"


def _returns_alone(head: bytes) -> bool:
    """Text whose lines end in a carriage return alone, as classic Mac OS saved it."""
    return b"\r" in head and b"\n" not in head


def not_grains(head: bytes, file_only: bool = False) -> str | None:
    """What an input that holds no grains is, from its first bytes; None for anything else.
    ``file_only``: the input must be a file (Surface Evolver), so a compressed one is to be
    decompressed into another file, not into a pipe."""
    if head[:2] in (b"\xff\xfe", b"\xfe\xff"):  # a byte order mark, as Windows writes UTF-16
        try:
            head[: len(head) // 2 * 2].decode("utf-16")
        except UnicodeDecodeError:
            return None
        return "UTF-16 text: save it as UTF-8 (iconv -f UTF-16 -t UTF-8 FILE)"
    encoding = _utf16_without_mark(head)
    if encoding:
        return (
            f"{encoding} text without a byte order mark: save it as UTF-8 "
            f"(iconv -f {encoding} -t UTF-8 FILE)"
        )
    if head.startswith(b"PAR1"):
        return "a Parquet table, not grains: summarize and types read it, classify reads grains"
    for magic, (compression, cat) in _COMPRESSED.items():
        if magic.match(head):
            how = f"{cat} FILE > NEW.fe" if file_only else f"{cat} FILE | grainclass ... -"
            return f"{compression}-compressed: decompress it first ({how})"
    return None


_TEXT = frozenset(b"\t\n\r" + bytes(range(32, 127)))


def _utf16_without_mark(head: bytes) -> str | None:
    """``UTF-16LE`` or ``UTF-16BE`` for ASCII text so encoded without a byte order mark (every
    other byte 0, the others printable), else None. planar_code has no such rhythm: a 0 ends a
    list of three neighbours or more, and 2-byte entries are used for numbers past 255."""
    sample = head[:256]
    if len(sample) < 16:
        return None
    sample = sample[: len(sample) // 2 * 2]
    for encoding, zeros, text in (
        ("UTF-16LE", sample[1::2], sample[0::2]),
        ("UTF-16BE", sample[0::2], sample[1::2]),
    ):
        if not any(zeros) and set(text) <= _TEXT:
            return encoding
    return None


def _looks_like_planar_code(head: bytes) -> bool:
    """planar_code: a header, or a first record that holds together: n, then n lists ended by
    0 bytes, every entry at most n, the first list without a repeat (or n in 2-byte entries,
    after a 0). Text, repeating its blanks and digits, would have to start with a control
    character: a stray 0 byte in text does not make it planar_code."""
    if head.startswith(b">>planar_code"):
        return True
    if b"\x00" not in head:
        return False
    n = head[0]
    if n == 0:
        return True
    first_list = head[1:].split(b"\x00", 1)[0]
    if len(set(first_list)) != len(first_list):
        return False
    zeros = 0
    for byte in head[1:]:
        if byte > n:
            return False
        zeros += byte == 0
        if zeros == n:
            return True
    return True  # a record longer than the head: nothing against it


def _sniff_path(path: str, format: str | None) -> str:
    if format is not None:
        return format
    if path != "-" and path.lower().endswith(".fe"):
        return "evolver"
    if path == "-" or _is_stream(path):
        return ""  # sniffed from the stream itself, once it is opened in its turn
    try:
        with open(path, "rb") as handle:
            return sniff(handle.read(4096))
    except OSError as exc:
        raise InputError(path, exc.strerror or str(exc)) from None


def _expand(paths: Sequence[str]) -> list[str]:
    """A folder stands for its ``*.fe`` files, in name order (one grain-growth dump)."""
    expanded = []
    for path in paths:
        if path != "-" and os.path.isdir(path):
            files = sorted(f for f in os.listdir(path) if f.lower().endswith(".fe"))
            if not files:
                raise InputError(path, "a folder given as input must hold *.fe files")
            expanded += [os.path.join(path, f) for f in files]
        else:
            expanded.append(path)
    return expanded


_read_once: dict[str, BinaryIO] = {}
# sys.stdin.buffer as last seen, and the stream read_once("-") gives for it.
_stdin: tuple[BinaryIO, BinaryIO] | None = None
SNIFF_BYTES = 4096


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


def read_dataset(
    paths: Sequence[str] | str,
    format: str | None = None,
    chunk_size: int = DEFAULT_CHUNK_SIZE,
    triple_edges: tuple[str, str] = DEFAULT_TRIPLE_EDGES,
    raw_planar_code: bool = False,
) -> Iterator[GrainBatch | PlanarCodeRecords]:
    """Read grains from one or more inputs, in order, as batches.

    Parameters
    ----------
    paths : str or sequence of str
        Files to read; ``-`` is standard input; a folder stands for its ``*.fe`` files.
    format : {None, "adjacency", "planar_code", "evolver", "voro", "neper", "loops"}
        The input format; None sniffs it from each input (``.fe`` files are Surface Evolver;
        face-vertex-loop text must be named, it looks like adjacency text).
    chunk_size : int
        Grains per batch at most.
    triple_edges : (str, str)
        Surface Evolver only: the edge attribute and value marking triple lines.
    raw_planar_code : bool
        Leave planar_code records as bytes (:class:`PlanarCodeRecords`), for the census path.

    Yields
    ------
    GrainBatch or PlanarCodeRecords

    Raises
    ------
    InputError
        When an input cannot be opened or read at all.
    """
    if isinstance(paths, str):
        paths = [paths]
    if format is not None and format not in INPUT_FORMATS:
        raise ValueError(f"unknown format {format!r}; expected one of {', '.join(INPUT_FORMATS)}")
    paths = _expand(paths)
    formats = [_sniff_path(path, format) for path in paths]
    # Consecutive .fe files are read as one dataset (standard input cannot be one of them).
    evolver_files = [
        fmt == "evolver" and path != "-" for path, fmt in zip(paths, formats, strict=True)
    ]
    k = 0
    while k < len(paths):
        if evolver_files[k]:
            end = k
            while end < len(paths) and evolver_files[end]:
                end += 1
            yield from read_evolver(paths[k:end], chunk_size, triple_edges)
            k = end
            continue
        path = paths[k]
        k += 1
        with _open(path) as stream:
            head = stream.peek(SNIFF_BYTES)[:SNIFF_BYTES]
            fmt = formats[k - 1] or sniff(head)
            # Named as a text format or not, UTF-16, a compressed file or a Parquet table is
            # refused for what it is (planar_code is bytes: its records may start like them).
            why = None if fmt == "planar_code" else not_grains(head)
            if why:
                raise InputError(path, why)
            if fmt != "planar_code" and head.startswith(_BOM):
                stream.read(len(_BOM))
            if fmt != "planar_code" and _returns_alone(head):
                stream = io.BufferedReader(_ReturnsAsNewlines(stream), 1 << 16)
            if fmt == "evolver":
                raise InputError(path, "Surface Evolver input must be a file or a folder")
            if fmt == "planar_code":
                batches = read_planar_code(stream, path, chunk_size, raw_planar_code)
            elif fmt == "voro":
                batches = read_voro(stream, path, chunk_size)
            elif fmt == "neper":
                batches = read_neper(stream, path, chunk_size)
            elif fmt == "loops":
                batches = read_loops(stream, path, chunk_size)
            else:
                batches = read_adjacency(stream, path, chunk_size)
            grains = 0
            try:
                for batch in batches:
                    grains += len(batch)
                    yield batch
            except OSError as exc:
                raise InputError(path, exc.strerror or str(exc)) from None
            if not grains:
                warnings.warn(f"{path}: no grains", EmptyInputWarning, stacklevel=2)
