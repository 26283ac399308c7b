"""Neper raster tessellations (``.tesr``), 3D only: a grid of voxels, each holding its cell.

Layout (Neper's ``doc/fileformat.rst``, format 2.1; 2.0, which gives the data format after
the version, is read too)::

    ***tesr
     **format
       2.1
     **general
       3
       <size_x> <size_y> <size_z>
       <voxsize_x> <voxsize_y> <voxsize_z>
      [*origin ...]
    [**cell
       <number_of_cells>
      [*id
       <cell1_id> <cell2_id> ...]
      [*seed, *ori, ... (skipped)]]
     **data
       <ascii|binary8|binary16|binary16_big|binary32|binary32_big>
    <voxel cells, x fastest, then y, then z>     or      *file <data file>
    [**oridata ..., **oridef ... (skipped)]
    ***end

What is read: each voxel's cell, 0 for a void. Where ``**cell`` has ``*id``, the cells in the
data are numbered 1 .. number_of_cells and ``*id`` gives each its identifier (as Neper reads
it): the labels are those identifiers. Binary data start after the line of their format (as
Neper writes them) and are read a slab at a time, from the ``.tesr`` or from the ``*file``
beside it; ASCII data are parsed a slab at a time. The labels' type is the stored one: uint8
(``binary8``), int16 (``binary16``, as Neper reads it), int32 (``binary32``, ASCII, and
identifiers of ``*id``). The spacing is the voxel size.

Refused: a 2D tessellation, no ``**data`` (a file of orientations only), an unknown data format,
data cut short, a cell number past ``*id``'s list, a negative cell, a voxel size that is not
three positive numbers.
"""

from __future__ import annotations

import os
import re
from collections.abc import Iterator

import numpy as np

from grainclass.errors import InputError
from grainclass.readers.label_image import (
    LabelImage,
    TextIntegers,
    check_shape,
    checked_slab,
    read_exact,
    slabs_of,
    to_labels,
)

_BINARY = {"binary8": "u1", "binary16": "<i2", "binary16_big": ">i2", "binary32": "<i4",
           "binary32_big": ">i4"}  # fmt: skip
_FORMATS = ("ascii", *_BINARY)
_DATA = b"**data"
_BLOCK = 1 << 20  # bytes of the header read at a time
_PAST_DATA = 4096  # bytes after **data that name the data format and file
_LINE_END = re.compile(rb"[ \t]*(\r\n|\n|\r)?")
_FILE = re.compile(rb"\s*\*file\s+(\S+)")
_TOKEN = re.compile(rb"\s*(\S+)")


def looks_like_tesr(head: bytes) -> bool:
    """True when ``head`` starts, after blanks, with ``***tesr``.

    >>> looks_like_tesr(b"***tesr\\n **format\\n   2.1\\n"), looks_like_tesr(b"***tess\\n")
    (True, False)
    """
    text = head.removeprefix(b"\xef\xbb\xbf").lstrip()
    return text.startswith(b"***tesr") and (len(text) == 7 or text[7:8].isspace())


def _sections(path: str, header: bytes) -> dict[str, list[bytes]]:
    """The tokens of each ``**`` section before ``**data``."""
    tokens = header.split()
    if not tokens or tokens[0] != b"***tesr":
        raise InputError(path, "no ***tesr header: not a Neper raster tessellation")
    sections: dict[str, list[bytes]] = {}
    current = None
    for token in tokens[1:]:
        if token.startswith(b"**"):
            current = token[2:].decode("latin-1")
            sections[current] = []
        elif current is None:
            raise InputError(path, f"{token[:40]!r} before the first ** section")
        else:
            sections[current].append(token)
    return sections


def _ints(path: str, tokens: list[bytes], count: int, what: str) -> list[int]:
    try:
        values = [int(t) for t in tokens[:count]]
    except ValueError:
        values = []
    if len(values) != count:
        raise InputError(path, f"**general: {what}: {count} integers expected")
    return values


def _general(path: str, tokens: list[bytes]):
    """Shape (z, y, x) and voxel size (x, y, z)."""
    (dimension,) = _ints(path, tokens, 1, "the dimension")
    if dimension != 3:
        raise InputError(path, f"a {dimension}D raster tessellation: grains need three dimensions")
    nx, ny, nz = _ints(path, tokens[1:], 3, "the size along x, y and z")
    try:
        voxel = [float(t) for t in tokens[4:7]]
    except ValueError:
        voxel = []
    if len(voxel) != 3 or not all(np.isfinite(v) and v > 0 for v in voxel):
        shown = b" ".join(tokens[4:7]).decode("latin-1")
        raise InputError(path, f"**general: voxel size {shown!r}: three positive numbers")
    return check_shape(path, (nz, ny, nx)), (voxel[0], voxel[1], voxel[2])


def _ids(path: str, tokens: list[bytes]) -> np.ndarray | None:
    """``*id`` of ``**cell``: the identifier of cell k at k - 1."""
    if b"*id" not in tokens:
        return None
    try:
        count = int(tokens[0])
    except (ValueError, IndexError):
        raise InputError(path, "**cell: the number of cells expected first") from None
    start = tokens.index(b"*id") + 1
    listed = tokens[start : start + count]
    try:
        ids = np.array([int(t) for t in listed], dtype=np.int64)
    except (ValueError, OverflowError):
        ids = np.zeros(0, dtype=np.int64)
    if len(ids) != count or count < 0:
        raise InputError(path, f"**cell *id: {count} cell identifiers expected")
    return to_labels(path, ids, np.dtype(np.int32), "**cell *id")


def _header(path: str) -> tuple[bytes, int]:
    """The file up to a little past ``**data`` (its data are read by the slabs), and where
    ``**data`` is (-1: nowhere)."""
    text = b""
    with open(path, "rb") as stream:
        while True:
            block = stream.read(_BLOCK)
            text += block
            at = text.find(_DATA, max(0, len(text) - len(block) - len(_DATA)))
            if at >= 0:
                return text + stream.read(_PAST_DATA), at
            if not block:
                return text, -1


def open_tesr(path: str) -> LabelImage:
    """Open a Neper raster tessellation as a :class:`LabelImage` (see the module's docstring).

    Parameters
    ----------
    path : str
        The ``.tesr`` file.

    Returns
    -------
    LabelImage
        Shape ``(size_z, size_y, size_x)``, the stored integer type (int32 through ``*id``),
        the voxel size as spacing.

    Raises
    ------
    InputError
        For what the module's docstring says is refused.
    """
    text, at = _header(path)
    if at < 0:
        if not looks_like_tesr(text[:4096]):
            raise InputError(path, "no ***tesr header: not a Neper raster tessellation")
        raise InputError(path, "no **data section: no cells to read")
    sections = _sections(path, text[:at])
    version = sections.get("format", [])
    if "general" not in sections:
        raise InputError(path, "no **general section")
    shape, spacing = _general(path, sections["general"])
    ids = _ids(path, sections.get("cell", []))
    position = at + len(_DATA)
    token = _TOKEN.match(text, position)
    data_format = token.group(1).decode("latin-1") if token else ""
    if data_format in _FORMATS:
        position = token.end()
    elif len(version) > 1:  # format 2.0: "**format 2.0 <data format>"
        data_format = version[1].decode("latin-1")
    if data_format not in _FORMATS:
        raise InputError(path, f"**data: format {data_format[:40]!r}: one of {', '.join(_FORMATS)}")
    named = _FILE.match(text, position)
    if named:
        data_path = os.path.join(os.path.dirname(path), os.fsdecode(named.group(1)))
        offset = 0
    else:
        data_path = path
        offset = position if data_format == "ascii" else _LINE_END.match(text, position).end()
    stored = np.dtype(_BINARY.get(data_format, "<i4"))
    size = shape[0] * shape[1] * shape[2]
    if data_format != "ascii":
        try:
            available = os.path.getsize(data_path) - offset
        except OSError as exc:
            raise InputError(path, f"*file {data_path}: {exc.strerror}") from None
        if available < size * stored.itemsize:
            raise InputError(
                path,
                f"cut short: {size} voxels of {data_format} need {size * stored.itemsize} "
                f"bytes, {max(available, 0)} are there",
            )
    dtype = np.dtype(np.int32) if ids is not None else stored.newbyteorder("=")
    del text

    def slabs(depth: int) -> Iterator[np.ndarray]:
        nz, ny, nx = shape
        layer = ny * nx
        with open(data_path, "rb") as stream:
            numbers = TextIntegers(path, stream, offset, None, "**data")
            for z0, z1 in slabs_of(nz, depth):
                if data_format == "ascii":
                    values = to_labels(path, numbers.take((z1 - z0) * layer), np.int32, "**data")
                else:
                    at = offset + z0 * layer * stored.itemsize
                    data = read_exact(path, stream, at, (z1 - z0) * layer * stored.itemsize,
                                      f"slices z = {z0} to {z1 - 1}")  # fmt: skip
                    values = np.frombuffer(data, dtype=stored).astype(stored.newbyteorder("="))
                slab = checked_slab(path, values.reshape(z1 - z0, ny, nx), z0)
                yield slab if ids is None else _identified(path, slab, ids, z0)

    return LabelImage(path, shape, dtype, spacing, slabs)


def _identified(path: str, slab: np.ndarray, ids: np.ndarray, z0: int) -> np.ndarray:
    """Cells 1 .. n by their ``*id`` identifiers; 0 (void) stays 0."""
    if slab.size and slab.max() > len(ids):
        z, y, x = (int(i) for i in np.argwhere(slab > len(ids))[0])
        raise InputError(
            path,
            f"voxel x={x}, y={y}, z={z0 + z} holds cell {slab[z, y, x]}, past the "
            f"{len(ids)} of **cell *id",
        )
    lookup = np.concatenate([np.zeros(1, dtype=np.int32), ids])
    return lookup[slab]
