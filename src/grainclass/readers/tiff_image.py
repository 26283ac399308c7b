"""TIFF stacks of labels (``.tif``, ``.tiff``), read with tifffile (the ``images`` extra).

What is read: the file's first image series, as tifffile groups its pages, once its axes of
length 1 are dropped: either a stack of 2D pages, one page per z slice (a multi-page TIFF, an
ImageJ hyperstack with one axis besides y and x, an OME-TIFF with one), or one page holding the
whole volume (SGI's ImageDepth, as ``tifffile.imwrite(..., volumetric=True)`` writes it). Page k
is z = k; a page's rows are y and its columns x, as the page stores them.

A slab reads only its own pages; a series tifffile can map as one contiguous block is mapped;
a volume in a single page is decoded whole the first time a slab is asked for (TIFF compresses
such a page in tiles that span z).

Refused: a 2D image (one page), an image with more axes than z, y and x (channels of a
hyperstack, RGB samples), labels stored as floats, several series of different shapes, a file
tifffile cannot read. The TIFF carries no voxel size grainclass reads: spacing is None.
"""

from __future__ import annotations

import os
import struct
from collections.abc import Iterator

import numpy as np

from grainclass.errors import InputError
from grainclass.readers.label_image import (
    LabelImage,
    check_shape,
    checked_slab,
    label_dtype,
    require,
    slabs_of,
)

_MOST_TAGS = 4096  # tifffile's bound on the tags of a page
_MAGIC = (b"II*\x00", b"MM\x00*", b"II+\x00", b"MM\x00+")  # classic TIFF and BigTIFF


def looks_like_tiff(head: bytes) -> bool:
    """True for the first bytes of a TIFF or BigTIFF file, little- or big-endian.

    >>> looks_like_tiff(b"II*\\x00\\x08\\x00\\x00\\x00"), looks_like_tiff(b"MM\\x00+")
    (True, True)
    >>> looks_like_tiff(b"II")
    False
    """
    return head[:4] in _MAGIC


def _unreadable(path: str, exc: Exception) -> InputError:
    """A failure of tifffile on a damaged file as an :class:`InputError`."""
    return InputError(path, f"not a TIFF image tifffile can read ({type(exc).__name__}: {exc})")


def open_tiff(path: str) -> LabelImage:
    """Open a TIFF stack of labels as a :class:`LabelImage` (see the module's docstring).

    Parameters
    ----------
    path : str
        The TIFF file.

    Returns
    -------
    LabelImage
        Shape ``(pages, rows, columns)``, the pages' integer type, spacing None.

    Raises
    ------
    InputError
        For what the module's docstring says is refused.
    MissingDependencyError
        Without tifffile.
    """
    tifffile = require("tifffile", "TIFF stacks")
    _check_page_chain(path)
    try:
        with tifffile.TiffFile(path) as tif:
            layout = _layout(path, tif)
    except InputError:
        raise
    except Exception as exc:  # tifffile raises many kinds on a damaged file
        raise _unreadable(path, exc) from None
    shape, dtype, _ = layout

    def slabs(depth: int) -> Iterator[np.ndarray]:
        yield from _slabs(path, shape, depth)

    return LabelImage(path, shape, dtype, None, slabs)


def _check_page_chain(path: str) -> None:
    """:class:`InputError` if the file's chain of pages (each IFD's offset to the next) comes
    back to a page it has passed: tifffile 2026.3.3 follows such a loop without end once it
    is past 100 pages."""
    with open(path, "rb") as stream:
        head = stream.read(16)
        order = {b"II": "<", b"MM": ">"}.get(head[:2])
        if order is None or len(head) < 16:
            return  # tifffile says what is wrong
        version = struct.unpack(order + "H", head[2:4])[0]
        if version == 42:
            offset, count, entry, pointer = struct.unpack(order + "I", head[4:8])[0], "H", 12, "I"
        elif version == 43:
            offset, count, entry, pointer = struct.unpack(order + "Q", head[8:16])[0], "Q", 20, "Q"
        else:
            return
        count, pointer = order + count, order + pointer
        size = os.fstat(stream.fileno()).st_size
        seen: set[int] = set()
        while 0 < offset < size:
            if offset in seen:
                raise InputError(path, f"a TIFF whose chain of pages loops back to byte {offset}")
            seen.add(offset)
            stream.seek(offset)
            data = stream.read(struct.calcsize(count))
            if len(data) < struct.calcsize(count):
                return
            tags = struct.unpack(count, data)[0]
            stream.seek(offset + len(data) + tags * entry)
            data = stream.read(struct.calcsize(pointer))
            if tags > _MOST_TAGS or len(data) < struct.calcsize(pointer):
                return
            offset = struct.unpack(pointer, data)[0]


def _layout(path: str, tif) -> tuple[tuple[int, int, int], np.dtype, str]:
    """Shape (z, y, x), label type and how slabs are read: ``"pages"`` (one page a slice),
    ``"memmap"`` (one contiguous block) or ``"whole"`` (one page holds the volume)."""
    series = tif.series
    if not series:
        raise InputError(path, "a TIFF file without images")
    if len(series) > 1 and len({s.shape for s in series}) > 1:
        shapes = ", ".join("x".join(map(str, s.shape)) for s in series[:4])
        raise InputError(
            path, f"{len(series)} images of different shapes ({shapes}): one stack is read"
        )
    first = series[0]
    dtype = label_dtype(path, first.dtype, "pixels")
    kept = [(axis, n) for axis, n in zip(first.axes, first.shape, strict=True) if n != 1]
    if len(kept) < 3:
        shape = "x".join(str(n) for _, n in kept) or "1"
        raise InputError(path, f"a 2D image ({shape} pixels): grains need three dimensions")
    if len(kept) > 3 or "S" in "".join(axis for axis, _ in kept):
        axes = "".join(axis for axis, _ in kept)
        sizes = "x".join(str(n) for _, n in kept)
        raise InputError(
            path,
            f"an image with axes {axes} ({sizes}): a label image has z, y and x only "
            "(no channels or samples)",
        )
    shape = check_shape(path, tuple(n for _, n in kept))
    pages = first.pages
    if len(pages) == shape[0] and all(p is not None and p.shape == shape[1:] for p in pages):
        return shape, dtype, "pages"
    if first.dataoffset is not None:
        return shape, dtype, "memmap"
    return shape, dtype, "whole"


def _slabs(path: str, shape: tuple[int, int, int], depth: int) -> Iterator[np.ndarray]:
    tifffile = require("tifffile", "TIFF stacks")
    nz, ny, nx = shape
    starts = list(slabs_of(nz, depth))
    with open(path, "rb") as stream:
        try:
            tif = tifffile.TiffFile(stream)
        except Exception as exc:  # tifffile raises many kinds on a damaged file
            raise _unreadable(path, exc) from None
        with tif:
            try:
                got, dtype, how = _layout(path, tif)
            except InputError:
                raise
            except Exception as exc:  # tifffile raises many kinds on a damaged file
                raise _unreadable(path, exc) from None
            if got != shape:
                raise InputError(path, "the file changed since it was opened")
            series = tif.series[0]
            volume = None
            for z0, z1 in starts:
                try:
                    if how == "pages":
                        slab = np.stack([series.pages[z].asarray() for z in range(z0, z1)])
                    else:
                        if volume is None:
                            volume = _volume(path, tif, series, shape, how)
                        slab = np.array(volume[z0:z1])
                except Exception as exc:  # tifffile raises many kinds on a damaged file
                    raise _unreadable(path, exc) from None
                if slab.size != (z1 - z0) * ny * nx:
                    raise InputError(
                        path,
                        f"{_pages(z0, z1)} hold {slab.size} pixels, "
                        f"{(z1 - z0) * ny * nx} expected ({ny} x {nx} a page)",
                    )
                yield checked_slab(path, slab.reshape(z1 - z0, ny, nx).astype(dtype), z0)


def _volume(path: str, tif, series, shape: tuple[int, int, int], how: str) -> np.ndarray:
    """The whole stack: mapped from the file where it is one uncompressed block (an ImageJ
    hyperstack past 4 GB lists one page only), else decoded (a volume in one page)."""
    if how == "memmap":
        dtype = np.dtype(series.dtype).newbyteorder(tif.byteorder)
        size = int(np.prod(shape)) * dtype.itemsize
        if series.dataoffset + size > tif.filehandle.size:
            raise InputError(
                path,
                f"cut short: the stack needs {size} bytes at byte "
                f"{series.dataoffset}, past the end of the file",
            )
        return np.memmap(path, dtype=dtype, mode="r", offset=series.dataoffset, shape=shape)
    return series.asarray().reshape(shape)


def _pages(z0: int, z1: int) -> str:
    """Pages z0 .. z1 - 1 in words."""
    return f"page {z0}" if z1 == z0 + 1 else f"pages {z0} to {z1 - 1}"
