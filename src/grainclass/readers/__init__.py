"""Readers: every input format becomes a stream of :class:`~grainclass.batch.GrainBatch` chunks.

The format is sniffed from the content: planar_code always holds 0 bytes (its terminators)
and text never does.
"""

from __future__ import annotations

import io
import sys
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from typing import BinaryIO

from grainclass.batch import GrainBatch
from grainclass.errors import InputError
from grainclass.readers.adjacency import read_adjacency
from grainclass.readers.planar_code import read_planar_code

FORMATS = ("adjacency", "planar_code")
DEFAULT_CHUNK_SIZE = 50_000


def sniff(head: bytes) -> str:
    """Name the format of an input from its first bytes.

    Examples
    --------
    >>> sniff(b">>planar_code<<" + bytes([4, 2, 3, 4, 0]))
    'planar_code'
    >>> sniff(b"cube\\t1 2 3 4;0 4 5 2")
    'adjacency'
    """
    if head.startswith(b">>planar_code") or b"\x00" in head:
        return "planar_code"
    return "adjacency"


@contextmanager
def _open(path: str) -> Iterator[BinaryIO]:
    if path == "-":
        stream = sys.stdin.buffer
        # Sniffing needs peek(); a replaced stdin (an embedding program, a test) may lack it.
        yield stream if hasattr(stream, "peek") else io.BufferedReader(stream)
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
) -> Iterator[GrainBatch]:
    """Read grains from one or more inputs, in order, as batches.

    Parameters
    ----------
    paths : str or sequence of str
        Files to read; ``-`` is standard input.
    format : {None, "adjacency", "planar_code"}
        The input format; None sniffs it from each input's first bytes.
    chunk_size : int
        Grains per batch at most.

    Yields
    ------
    GrainBatch

    Raises
    ------
    InputError
        When an input cannot be opened or read at all.
    """
    if isinstance(paths, str):
        paths = [paths]
    if format is not None and format not in FORMATS:
        raise ValueError(f"unknown format {format!r}; expected one of {', '.join(FORMATS)}")
    for path in paths:
        with _open(path) as stream:
            fmt = format or sniff(stream.peek(4096)[:4096])
            try:
                if fmt == "planar_code":
                    yield from read_planar_code(stream, path, chunk_size)
                else:
                    yield from read_adjacency(stream, path, chunk_size)
            except OSError as exc:
                raise InputError(path, exc.strerror or str(exc)) from None
