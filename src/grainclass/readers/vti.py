"""VTK XML image data (``.vti``): a grid of voxels, as DAMASK's ``GeomGrid.save`` and ParaView
write it. Read with the standard library alone.

What is read: the ``<ImageData>`` of a ``<VTKFile type="ImageData">`` with one ``<Piece>``
covering its ``WholeExtent``. The labels are a cell array (one value per voxel): the one named
``material`` (DAMASK's grain ids), else the one integer array of one component. A file without
such a cell array is read from its point arrays by the same rule, one voxel per point (ITK and
ParaView save a volume so, values on the points): an image of n points along an axis has n
voxels there. Values are stored x fastest, then y, then z, so a slab is one run of bytes.
``Spacing`` is the spacing (x, y, z); ``Origin`` and ``Direction`` are ignored (they move and
turn the grid, not which voxels touch).

Every encoding VTK writes is read a slab at a time:

- ``format="appended"`` with ``<AppendedData encoding="raw">``: the slab's bytes, at their
  offset; with ``encoding="base64"``: the characters that encode them;
- ``format="binary"`` (base64 inline): the characters that encode the slab; text broken into
  lines is read whole first (VTK writes it on one line);
- ``format="ascii"``: the numbers, parsed in order;
- compressed (``compressor="vtkZLibDataCompressor"`` or ``"vtkLZMADataCompressor"``): the
  blocks that hold the slab, decompressed one at a time.

The data's length header is ``header_type`` (``UInt32``, the default, or ``UInt64``), in
``byte_order``. Refused: another kind of VTK file (``UnstructuredGrid``, a parallel ``.pvti``),
several pieces or a piece smaller than the whole extent, no integer array to take (the arrays
are named), float labels, an array of more than one component, LZ4 compression, a length or a
block that disagrees with the extent, data cut short, a spacing that is not three positive
numbers.
"""

from __future__ import annotations

import binascii
import lzma
import mmap
import re
import zlib
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from xml.sax.saxutils import unescape

import numpy as np

from grainclass.errors import InputError
from grainclass.readers.label_image import (
    LabelImage,
    TextIntegers,
    check_shape,
    checked_slab,
    label_dtype,
    slabs_of,
    to_labels,
)

_TYPES = {"Int8": "i1", "UInt8": "u1", "Int16": "i2", "UInt16": "u2", "Int32": "i4",
          "UInt32": "u4", "Int64": "i8", "UInt64": "u8", "Float32": "f4",
          "Float64": "f8"}  # fmt: skip
_HEADER_TYPES = {"UInt32": 4, "UInt64": 8}
_ORDERS = {"LittleEndian": "<", "BigEndian": ">"}
_DECOMPRESSORS = {
    "vtkZLibDataCompressor": (zlib.decompressobj, zlib.error),
    "vtkLZMADataCompressor": (lzma.LZMADecompressor, lzma.LZMAError),
}
_VTKFILE = re.compile(rb"<VTKFile\b[^>]*>")
_IMAGE_TYPE = re.compile(rb"""\btype\s*=\s*["']ImageData["']""")
_TAG = re.compile(rb"\s*(/?)([A-Za-z_][\w.:-]*)(.*?)(/?)\s*$", re.DOTALL)
_ATTRIBUTE = re.compile(rb"""([\w.:-]+)\s*=\s*(?:"([^"]*)"|'([^']*)')""")
_BLANK = re.compile(rb"\s")
_LONGEST_TAG = 1 << 16


def looks_like_vti(head: bytes) -> bool:
    """True when the first bytes hold a ``<VTKFile type="ImageData" ...>`` tag.

    >>> looks_like_vti(b'<?xml version="1.0"?>\\n<VTKFile type="ImageData" version="1.0">')
    True
    >>> looks_like_vti(b'<VTKFile type="UnstructuredGrid">')
    False
    """
    tag = _VTKFILE.search(head)
    return tag is not None and _IMAGE_TYPE.search(tag.group()) is not None


@dataclass
class _Array:
    """A ``<DataArray>``: where its data lie (``content``: the inline text's span)."""

    kind: str  # CellData or PointData
    attributes: dict[str, str]
    content: tuple[int, int] | None = None

    @property
    def name(self) -> str:
        return self.attributes.get("Name", "")


@dataclass
class _Layout:
    """What the header says: the file's attributes, the grid and the arrays."""

    file: dict[str, str]
    image: dict[str, str]
    pieces: list[dict[str, str]]
    arrays: list[_Array]
    appended: tuple[str, int] | None = None  # encoding, first byte after the "_"


def _tags(path: str, mm, limit: int) -> Iterator[tuple[bool, str, dict[str, str], bool, int, int]]:
    """``(closing, name, attributes, self_closing, start, end)`` of each tag before ``limit``.
    Inline data holds no ``<``, so it is skipped over."""
    position = 0
    while True:
        start = mm.find(b"<", position, limit)
        if start < 0:
            return
        if mm[start : start + 4] == b"<!--":
            end = mm.find(b"-->", start, limit)
            if end < 0:
                raise InputError(path, f"a comment at byte {start} that does not end")
            position = end + 3
            continue
        end = mm.find(b">", start, min(limit, start + _LONGEST_TAG))
        if end < 0:
            raise InputError(path, f"a tag at byte {start} that does not end")
        position = end + 1
        if mm[start + 1 : start + 2] in (b"?", b"!"):
            continue
        tag = _TAG.match(mm[start + 1 : end])
        if tag is None:
            raise InputError(path, f"a tag at byte {start} that cannot be read")
        attributes = {
            key.decode("latin-1"): unescape((double or single).decode("latin-1"))
            for key, double, single in _ATTRIBUTE.findall(tag.group(3))
        }
        yield (
            bool(tag.group(1)),
            tag.group(2).decode("latin-1"),
            attributes,
            bool(tag.group(4)),
            start,
            end + 1,
        )


def _layout(path: str, mm) -> _Layout:
    limit = mm.find(b"<AppendedData")
    limit = len(mm) if limit < 0 else limit
    layout = _Layout({}, {}, [], [])
    kind = None
    inline: _Array | None = None
    for closing, name, attributes, self_closing, start, end in _tags(path, mm, limit):
        if inline is not None:
            if not (closing and name == "DataArray"):
                raise InputError(path, f"a <{name}> tag inside the data of {inline.name!r}")
            inline.content = (inline.content[0], start)
            inline = None
        elif closing:
            if name in ("CellData", "PointData"):
                kind = None
        elif name == "VTKFile":
            layout.file = attributes
        elif name == "ImageData":
            layout.image = attributes
        elif name == "Piece":
            layout.pieces.append(attributes)
        elif name in ("CellData", "PointData") and not self_closing:
            kind = name
        elif name == "DataArray" and kind is not None:
            layout.arrays.append(_Array(kind, attributes))
            if not self_closing and attributes.get("format") != "appended":
                inline = layout.arrays[-1]
                inline.content = (end, end)
    if inline is not None:
        raise InputError(path, f"cut short: the data of {inline.name!r} do not end")
    if limit < len(mm):
        tag = next(_tags_from(path, mm, limit), None)
        if tag is not None:
            attributes, end = tag
            underscore = re.compile(rb"\s*_").match(mm, end)
            if underscore is None:
                raise InputError(path, "<AppendedData> without the '_' that starts its data")
            layout.appended = (attributes.get("encoding", ""), underscore.end())
    return layout


def _tags_from(path: str, mm, start: int) -> Iterator[tuple[dict[str, str], int]]:
    """The attributes and end of the ``<AppendedData>`` tag at ``start``."""
    for _, _, attributes, _, _, end in _tags(path, mm[start : start + _LONGEST_TAG], _LONGEST_TAG):
        yield attributes, start + end
        return


def _numbers(path: str, text: str | None, count: int, what: str, kind=float) -> list | None:
    if text is None:
        return None
    try:
        values = [kind(v) for v in text.split()]
    except ValueError:
        values = []
    if len(values) != count:
        raise InputError(path, f"{what}={text!r}: expected {count} numbers")
    return values


def _choose(path: str, arrays: list[_Array]) -> _Array:
    """The array of labels: ``material``, else the one integer array of one component."""
    for kind in ("CellData", "PointData"):
        group = [a for a in arrays if a.kind == kind]
        for array in group:
            if array.name == "material":
                return array
        integers = [
            a for a in group
            if _TYPES.get(a.attributes.get("type", ""), "f")[0] in "iu"
            and a.attributes.get("NumberOfComponents", "1") == "1"
        ]  # fmt: skip
        if len(integers) == 1:
            return integers[0]
        if len(integers) > 1:
            names = ", ".join(repr(a.name) for a in integers)
            raise InputError(
                path,
                f"{len(integers)} integer {kind} arrays ({names}) and none named 'material': "
                "which holds the grain ids is not known",
            )
    if not arrays:
        raise InputError(path, "no cell or point data arrays: no labels")
    names = ", ".join(f"{a.name!r} ({a.attributes.get('type', '?')})" for a in arrays)
    raise InputError(path, f"no integer array of one component to take as labels: {names}")


def _shape(path: str, layout: _Layout, kind: str) -> tuple[int, int, int]:
    whole = _numbers(path, layout.image.get("WholeExtent"), 6, "WholeExtent", int)
    if whole is None:
        raise InputError(path, "<ImageData> without a WholeExtent")
    if len(layout.pieces) != 1:
        raise InputError(path, f"{len(layout.pieces)} pieces: one piece is read")
    piece = _numbers(path, layout.pieces[0].get("Extent"), 6, "Extent", int)
    if piece is not None and piece != whole:
        raise InputError(path, f"a piece of extent {piece} in a whole extent of {whole}")
    extra = 1 if kind == "PointData" else 0
    counts = [whole[2 * i + 1] - whole[2 * i] + extra for i in range(3)]
    return check_shape(path, (counts[2], counts[1], counts[0]))


def open_vti(path: str) -> LabelImage:
    """Open a VTK image data file's labels as a :class:`LabelImage` (see the module's
    docstring).

    Parameters
    ----------
    path : str
        The ``.vti`` file.

    Returns
    -------
    LabelImage
        Shape ``(z, y, x)`` of the cells (or points), the array's integer type, ``Spacing``.

    Raises
    ------
    InputError
        For what the module's docstring says is refused.
    """
    with _mapped(path) as mm:
        layout = _layout(path, mm)
        if layout.file.get("type") != "ImageData" or not layout.image:
            raise InputError(path, 'not a VTK ImageData file (no <VTKFile type="ImageData">)')
        array = _choose(path, layout.arrays)
        shape = _shape(path, layout, array.kind)
        where = f"array {array.name!r}"
        type_name = array.attributes.get("type", "")
        if type_name not in _TYPES:
            raise InputError(path, f"{where} of type {type_name!r}, which VTK does not name")
        components = array.attributes.get("NumberOfComponents", "1")
        if components != "1":
            raise InputError(
                path, f"{where} has {components} components per voxel: labels have one"
            )
        dtype = label_dtype(path, np.dtype(_TYPES[type_name]), where)
        spacing = _numbers(path, layout.image.get("Spacing"), 3, "Spacing")
        if spacing is not None and not all(np.isfinite(s) and s > 0 for s in spacing):
            raise InputError(path, f"Spacing={spacing}: three positive numbers")
        read = _reader(path, layout, array, dtype, shape)  # checks what the header can
        del read

    def slabs(depth: int) -> Iterator[np.ndarray]:
        nz, ny, nx = shape
        starts = list(slabs_of(nz, depth))
        with _mapped(path) as mm:
            read = _reader(path, _layout(path, mm), array, dtype, shape, mm)
            for z0, z1 in starts:
                yield checked_slab(path, read(z0, z1).reshape(z1 - z0, ny, nx), z0)

    return LabelImage(path, shape, dtype, None if spacing is None else tuple(spacing), slabs)


class _mapped:
    """The file memory-mapped (an empty one refused)."""

    def __init__(self, path: str) -> None:
        self.path = path

    def __enter__(self):
        self.stream = open(self.path, "rb")  # closed in __exit__
        try:
            self.map = mmap.mmap(self.stream.fileno(), 0, access=mmap.ACCESS_READ)
        except ValueError:
            self.stream.close()
            raise InputError(self.path, "an empty file") from None
        return self.map

    def __exit__(self, *exc) -> None:
        self.map.close()
        self.stream.close()


def _reader(
    path: str, layout: _Layout, array: _Array, dtype: np.dtype, shape, mm=None
) -> Callable[[int, int], np.ndarray]:
    """``read(z0, z1)``: the labels of slices z0 .. z1 - 1, flat. Without ``mm`` (at open),
    only the header is checked and a reader that reads nothing is returned."""
    nz, ny, nx = shape
    layer = ny * nx
    where = f"array {array.name!r}"
    encoding = array.attributes.get("format", "")
    if encoding == "ascii":
        if array.content is None:
            raise InputError(path, f"{where}: ascii data without text")
        if mm is None:
            return _nothing
        numbers = TextIntegers(path, mm, *array.content, where)

        def read_text(z0: int, z1: int) -> np.ndarray:
            values = to_labels(path, numbers.take((z1 - z0) * layer), dtype, where)
            if z1 == nz and not numbers.rest_is_blank():
                raise InputError(path, f"{where}: more values than the {nz * layer} voxels")
            return values

        return read_text
    order = layout.file.get("byte_order", "LittleEndian")
    if order not in _ORDERS:
        raise InputError(path, f"byte_order={order!r}: LittleEndian or BigEndian")
    header_type = layout.file.get("header_type", "UInt32")
    if header_type not in _HEADER_TYPES:
        raise InputError(path, f"header_type={header_type!r}: UInt32 or UInt64")
    compressor = layout.file.get("compressor")
    if compressor is not None and compressor not in _DECOMPRESSORS:
        raise InputError(path, f"compressor={compressor!r}: zlib and LZMA are read")
    stored = dtype.newbyteorder(_ORDERS[order])
    if mm is None:
        return _nothing
    stream = _stream(path, layout, array, mm, where)
    blocks = _Blocks(path, stream, _HEADER_TYPES[header_type], _ORDERS[order], compressor, where)
    blocks.expect(nz * layer * dtype.itemsize)

    def read_binary(z0: int, z1: int) -> np.ndarray:
        size = layer * dtype.itemsize
        data = blocks.get(z0 * size, z1 * size)
        return np.frombuffer(data, dtype=stored).astype(dtype)

    return read_binary


def _nothing(z0: int, z1: int) -> np.ndarray:
    raise AssertionError("a reader made without the file")


def _stream(path: str, layout: _Layout, array: _Array, mm, where: str):
    """The array's bytes: ``get(a, b)`` of its stream (length header included)."""
    encoding = array.attributes.get("format", "")
    if encoding == "binary":
        if array.content is None:
            raise InputError(path, f"{where}: binary data without text")
        start, end = array.content
        while start < end and mm[start : start + 1].isspace():
            start += 1
        while end > start and mm[end - 1 : end].isspace():
            end -= 1
        if _BLANK.search(mm, start, end):  # lines: read whole, blanks dropped
            text = _BLANK.sub(b"", mm[start:end])
            return _Base64(path, lambda a, b: text[a:b], where)
        return _Base64(path, _span(mm, start, end), where)
    if encoding != "appended":
        raise InputError(path, f"{where}: format={encoding!r}: ascii, binary or appended")
    if layout.appended is None:
        raise InputError(path, f"{where}: appended data without <AppendedData>")
    kind, first = layout.appended
    try:
        offset = int(array.attributes.get("offset", ""))
    except ValueError:
        raise InputError(path, f"{where}: appended without an offset") from None
    if offset < 0:
        raise InputError(path, f"{where}: offset {offset}")
    end = mm.rfind(b"</AppendedData>")
    end = len(mm) if end < first else end
    if kind == "raw":
        return _Raw(path, _span(mm, first + offset, end), where)
    if kind == "base64":
        return _Base64(path, _span(mm, first + offset, end), where)
    raise InputError(path, f"<AppendedData encoding={kind!r}>: raw or base64")


def _span(mm, start: int, end: int) -> Callable[[int, int], bytes]:
    return lambda a, b: mm[start + a : min(end, start + b)]


class _Raw:
    """Bytes of the file, from where the array starts."""

    def __init__(self, path: str, chars: Callable[[int, int], bytes], where: str) -> None:
        self.path, self.chars, self.where = path, chars, where

    def get(self, a: int, b: int) -> bytes:
        data = self.chars(a, b)
        if len(data) != b - a:
            raise InputError(self.path, f"cut short: {self.where} needs bytes {a} to {b - 1}")
        return data

    def after(self, count: int) -> _Raw:
        return _Raw(self.path, lambda a, b: self.chars(a + count, b + count), self.where)


class _Base64(_Raw):
    """Bytes encoded in base64 characters, decoded a few at a time: byte k is in the 4
    characters from 4 * (k // 3)."""

    def __init__(self, path: str, chars, where: str, shift: int = 0) -> None:
        super().__init__(path, chars, where)
        self.shift = shift

    def get(self, a: int, b: int) -> bytes:
        p0, p1 = a + self.shift, b + self.shift
        c0, c1 = p0 // 3 * 4, -(-p1 // 3) * 4
        text = self.chars(c0, c1)
        if len(text) != c1 - c0:
            raise InputError(self.path, f"cut short: {self.where} needs bytes {a} to {b - 1}")
        try:
            data = binascii.a2b_base64(text, strict_mode=True)
        except binascii.Error as exc:
            raise InputError(self.path, f"{self.where}: not base64 ({exc})") from None
        data = data[p0 - p0 // 3 * 3 :][: b - a]
        if len(data) != b - a:
            raise InputError(self.path, f"{self.where}: base64 padding inside the data")
        return data

    def after(self, count: int) -> _Base64:
        """The stream after a header of ``count`` bytes: encoded apart from it (as VTK
        encodes a header, padded) or with it."""
        chars = -(-count // 3) * 4
        if count % 3 and self.chars(chars - 1, chars) == b"=":
            return _Base64(self.path, lambda a, b: self.chars(a + chars, b + chars), self.where)
        return _Base64(self.path, self.chars, self.where, self.shift + count)


class _Blocks:
    """The array's data after its length header: uncompressed, or in compressed blocks
    (header: number of blocks, block size, size of the last block, each block's compressed
    size), decompressed one block at a time."""

    def __init__(self, path: str, stream: _Raw, width: int, order: str, compressor, where: str):
        self.path, self.stream, self.width, self.where = path, stream, width, where
        self.word = np.dtype(f"{order}u{width}")
        self.compressor = compressor
        self.cached: tuple[int, bytes] | None = None

    def _words(self, count: int) -> np.ndarray:
        return np.frombuffer(self.stream.get(0, count * self.width), dtype=self.word)

    def expect(self, size: int) -> None:
        """Read the header; :class:`InputError` unless it holds ``size`` bytes."""
        self.size = size
        if self.compressor is None:
            declared = int(self._words(1)[0])
            if declared != size:
                raise InputError(
                    self.path, f"{self.where} holds {declared} bytes, the extent needs {size}"
                )
            self.data = self.stream.after(self.width)
            return
        blocks = int(self._words(1)[0])
        if blocks < 1 or blocks > size:
            raise InputError(self.path, f"{self.where}: {blocks} compressed blocks")
        header = self._words(3 + blocks).astype(np.int64)
        self.block, last = int(header[1]), int(header[2])
        total = (blocks - 1) * self.block + (last or self.block)
        if self.block < 1 or total != size or last > self.block:
            raise InputError(
                self.path,
                f"{self.where}: {blocks} blocks of {self.block} bytes (the last {last}) do "
                f"not hold the {size} bytes the extent needs",
            )
        self.last = last or self.block
        self.offsets = np.concatenate([[0], np.cumsum(header[3:])])
        self.data = self.stream.after((3 + blocks) * self.width)

    def get(self, a: int, b: int) -> bytes:
        if self.compressor is None:
            return self.data.get(a, b)
        first, last = a // self.block, (b - 1) // self.block
        data = b"".join(self._block(i) for i in range(first, last + 1))
        return data[a - first * self.block :][: b - a]

    def _block(self, i: int) -> bytes:
        if self.cached is not None and self.cached[0] == i:
            return self.cached[1]
        expected = self.last if i == len(self.offsets) - 2 else self.block
        packed = self.data.get(int(self.offsets[i]), int(self.offsets[i + 1]))
        make, failure = _DECOMPRESSORS[self.compressor]
        try:
            data = make().decompress(packed, expected + 1)
        except failure as exc:
            raise InputError(
                self.path, f"{self.where}: block {i} cannot be decompressed ({exc})"
            ) from None
        if len(data) != expected:
            raise InputError(
                self.path,
                f"{self.where}: block {i} holds {len(data)} bytes, {expected} expected",
            )
        self.cached = (i, data)
        return data
