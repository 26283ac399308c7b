"""Readers: every input format becomes a stream of :class:`~grainclass.batch.GrainBatch` chunks.

:func:`read_dataset` opens each input (``streams.py``), names its format unless it is given
(``sniffing.py``) and hands it to that format's reader (:data:`STREAM_READERS`); Surface Evolver
datafiles are read by file, consecutive ones as one dataset (``evolver.py``), and so are label
images (``images.py``: each opened into a ``LabelImage``, its grains found by ``voxels.py``).
"""

from __future__ import annotations

import io
import warnings
from collections.abc import Callable, Iterator, Sequence
from typing import Any

from grainclass.batch import GrainBatch
from grainclass.errors import EmptyInputWarning, InputError
from grainclass.options import ReadOptions
from grainclass.readers.adjacency import read_adjacency
from grainclass.readers.evolver import read_evolver
from grainclass.readers.images import IMAGE_OPENERS, sniff_image
from grainclass.readers.loops import read_loops
from grainclass.readers.neper import read_neper
from grainclass.readers.planar_code import PlanarCodeRecords, read_planar_code
from grainclass.readers.sniffing import _BOM, SNIFF_BYTES, _returns_alone, not_grains, sniff
from grainclass.readers.streams import (
    _is_stream,
    _open,
    _ReturnsAsNewlines,
    done_reading,
    expand_paths,
    read_once,
)
from grainclass.readers.voro import read_voro

__all__ = [
    "SNIFF_BYTES",
    "STREAM_READERS",
    "done_reading",
    "expand_paths",
    "not_grains",
    "read_dataset",
    "read_once",
    "sniff",
]

# The reader of each format read from a stream: (stream, source, chunk_size) -> batches
# (planar_code's also takes ``raw``, Neper's ``geometry``). Surface Evolver, read by file, is
# not among them.
STREAM_READERS: dict[str, Callable[..., Iterator[GrainBatch | PlanarCodeRecords]]] = {
    "adjacency": read_adjacency,
    "planar_code": read_planar_code,
    "voro": read_voro,
    "neper": read_neper,
    "loops": read_loops,
}


def _sniff_path(path: str, format: str | None) -> str:
    if format is not None:
        return format
    if path != "-" and path.lower().endswith(".fe"):
        return "evolver"
    if path == "-" or _is_stream(path):
        return ""  # sniffed from the stream itself, once it is opened in its turn
    try:
        with open(path, "rb") as handle:
            head = handle.read(SNIFF_BYTES)
            return sniff_image(path, head) or sniff(head)
    except OSError as exc:
        raise InputError(path, exc.strerror or str(exc)) from None


def _read_image(path: str, format: str, options: ReadOptions) -> Iterator[GrainBatch]:
    from grainclass.voxels import read_image

    if path == "-" or _is_stream(path):
        raise InputError(path, "a label image is read from a file, not from a pipe")
    grains = 0
    for batch in read_image(IMAGE_OPENERS[format](path), options):
        grains += len(batch)
        yield batch
    if not grains:
        warnings.warn(f"{path}: no grains", EmptyInputWarning, stacklevel=3)


def read_dataset(
    paths: Sequence[str] | str,
    options: ReadOptions | None = None,
    raw_planar_code: bool = False,
    **settings: Any,
) -> Iterator[GrainBatch | PlanarCodeRecords]:
    """Read grains from one or more inputs, in order, as batches.

    Parameters
    ----------
    paths : str or sequence of str
        Files to read; ``-`` is standard input; a folder stands for its ``*.fe`` files.
    options : ReadOptions, optional
        How to read them: ``input_format`` (None sniffs each input: ``.fe`` files are Surface
        Evolver; face-vertex-loop text must be named, it looks like adjacency text),
        ``chunk_size`` (grains per batch at most), ``triple_edges`` (Surface Evolver: the edge
        attribute and value marking triple lines).
    raw_planar_code : bool
        Leave planar_code records as bytes (:class:`PlanarCodeRecords`), for the census path.
    **settings
        Fields of :class:`~grainclass.options.ReadOptions` in place of those of ``options``.

    Yields
    ------
    GrainBatch or PlanarCodeRecords

    Raises
    ------
    InputError
        When an input cannot be opened or read at all.
    OptionError
        For a setting that is not a reading option, or a value it cannot take.
    """
    options = ReadOptions.of(options, **settings)
    if isinstance(paths, str):
        paths = [paths]
    format, chunk_size = options.input_format, options.chunk_size
    triple_edges = options.triple_edges
    paths = expand_paths(paths)
    formats = [_sniff_path(path, format) for path in paths]
    # Consecutive .fe files are read as one dataset (standard input cannot be one of them).
    evolver_files = [
        fmt == "evolver" and path != "-" for path, fmt in zip(paths, formats, strict=True)
    ]
    k = 0
    while k < len(paths):
        if formats[k] in IMAGE_OPENERS:
            yield from _read_image(paths[k], formats[k], options)
            k += 1
            continue
        if evolver_files[k]:
            end = k
            while end < len(paths) and evolver_files[end]:
                end += 1
            yield from read_evolver(paths[k:end], chunk_size, triple_edges, options.geometry)
            k = end
            continue
        path = paths[k]
        k += 1
        with _open(path) as stream:
            head = stream.peek(SNIFF_BYTES)[:SNIFF_BYTES]
            image = sniff_image(path, head)
            if image and (path == "-" or _is_stream(path)):
                raise InputError(path, "a label image: images are read from files, not a pipe")
            if image:  # a file named as another format: sniffed, it would have been read
                raise InputError(path, f"a label image ({image}), not {formats[k - 1]} input")
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
            extra: dict[str, bool] = {}
            if fmt == "planar_code":
                extra["raw"] = raw_planar_code
            elif fmt == "neper":
                extra["geometry"] = options.geometry
            batches = STREAM_READERS[fmt](stream, path, chunk_size, **extra)
            grains = 0
            try:
                for batch in batches:
                    grains += len(batch)
                    yield batch
            except OSError as exc:
                raise InputError(path, exc.strerror or str(exc)) from None
            if not grains:
                warnings.warn(f"{path}: no grains", EmptyInputWarning, stacklevel=2)
