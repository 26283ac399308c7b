"""`LabelImage`: a 3D image whose voxels hold grain ids, as every image reader opens it.

Every image format (NumPy, TIFF stacks, DREAM.3D, VTK image data, SPPARKS dumps, Neper
raster tessellations) is opened into one of these; the topology pass reads it slab by slab
along z, so that an image larger than memory never has to be held whole.

Axes are named as the formats store voxels: x varies fastest, z slowest. A slab is a C-ordered
array indexed ``[z, y, x]``; for a NumPy array that is its own indexing (its last axis is x).

Every reader opens its file in two steps: the opener reads the header and checks what can be
checked without the voxels (the shape, the label type, where the voxels lie in the file); the
``slabs(depth)`` of the :class:`LabelImage` it returns opens the file anew each time it is
called and reads one slab at a time, checking each as it goes (a negative label, data cut
short), so a bad voxel is found when its slab is read. What the readers share for this (the
optional libraries they need, the checks of a label type, a shape and a slab, integers read as
text a block at a time) is here too.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from types import ModuleType
from typing import BinaryIO

import numpy as np

from grainclass.errors import InputError, MissingDependencyError, OptionError


@dataclass(frozen=True)
class LabelImage:
    """A 3D label image, opened but not read.

    Attributes
    ----------
    source : str
        The path it was opened from, by which messages name it.
    shape : (int, int, int)
        Voxels along z, y and x.
    dtype : numpy.dtype
        The integer type its labels are stored as.
    spacing : (float, float, float) or None
        The size of a voxel along x, y and z where the file carries it, else None.
    slabs : callable
        ``slabs(depth)`` yields consecutive integer arrays of shape ``(k, ny, nx)`` with
        ``1 <= k <= depth``, together covering z = 0 .. nz - 1 in order, each read from the file
        only when asked for.
    periodic : (bool, bool, bool) or None
        Axes x, y, z that wrap where the file says so (DAMASK's grids do not say; none does
        yet), else None: the user's ``--periodic`` decides.
    """

    source: str
    shape: tuple[int, int, int]
    dtype: np.dtype
    spacing: tuple[float, float, float] | None
    slabs: Callable[[int], Iterator[np.ndarray]]
    periodic: tuple[bool, bool, bool] | None = None

    @property
    def voxels(self) -> int:
        nz, ny, nx = self.shape
        return nz * ny * nx


def in_memory(source: str, labels: np.ndarray, spacing=None, periodic=None) -> LabelImage:
    """A `LabelImage` over an array already in memory (indexed ``[z, y, x]``)."""

    def slabs(depth: int) -> Iterator[np.ndarray]:
        for z in range(0, labels.shape[0], depth):
            yield labels[z : z + depth]

    shape = (int(labels.shape[0]), int(labels.shape[1]), int(labels.shape[2]))
    return LabelImage(source, shape, labels.dtype, spacing, slabs, periodic)


IMAGES_EXTRA = "pip install 'grainclass[images]'"
_TOKEN_BLOCK = 1 << 20  # bytes of text read at a time for integers written as text
_LONGEST_INTEGER = 24  # characters of the longest int64 written with a sign and zeros


def require(module: str, what: str) -> ModuleType:
    """``module`` imported, or :class:`MissingDependencyError` naming the ``images`` extra.

    ``what`` names the format that needs it (``"TIFF stacks"``).
    """
    try:
        return importlib.import_module(module)
    except ImportError:
        raise MissingDependencyError(
            f"reading {what} needs {module}, which is not installed: {IMAGES_EXTRA}"
        ) from None


def label_dtype(source: str, dtype: np.dtype, what: str = "labels") -> np.dtype:
    """``dtype`` if it is an integer type, else :class:`InputError` (float labels, booleans)."""
    dtype = np.dtype(dtype)
    if dtype.kind not in "iu":
        raise InputError(
            source, f"{what} stored as {dtype.name}: a label image holds integer grain ids"
        )
    return dtype


def check_shape(source: str, shape: tuple[int, int, int]) -> tuple[int, int, int]:
    """``shape`` (voxels along z, y, x) of an image with at least 2 voxels along each axis:
    a grain's faces need three dimensions."""
    nz, ny, nx = (int(n) for n in shape)
    if min(nz, ny, nx) < 1:
        raise InputError(source, f"an empty image ({nx} x {ny} x {nz} voxels along x, y, z)")
    flat = [axis for axis, n in zip("xyz", (nx, ny, nz), strict=True) if n == 1]
    if flat:
        raise InputError(
            source,
            f"a 2D image ({nx} x {ny} x {nz} voxels along x, y, z; one voxel along "
            f"{' and '.join(flat)}): grains need three dimensions",
        )
    return nz, ny, nx


def slab_starts(nz: int, depth: int) -> range:
    """The first z of each slab of at most ``depth`` slices."""
    if isinstance(depth, bool) or not isinstance(depth, (int, np.integer)) or depth < 1:
        raise OptionError("depth", f"slabs of {depth!r} slices: a depth is an integer, 1 or more")
    return range(0, nz, int(depth))


def checked_slab(source: str, slab: np.ndarray, z0: int) -> np.ndarray:
    """``slab`` (z from ``z0``) if no label is negative, else :class:`InputError` naming the
    first negative voxel."""
    if slab.dtype.kind == "i" and slab.size and slab.min() < 0:
        z, y, x = (int(i) for i in np.argwhere(slab < 0)[0])
        raise InputError(
            source,
            f"negative label {slab[z, y, x]} at voxel x={x}, y={y}, z={z0 + z}: "
            "grain ids are 0 or more",
        )
    return slab


def read_exact(source: str, stream: BinaryIO, offset: int, size: int, what: str) -> bytes:
    """``size`` bytes at ``offset``, or :class:`InputError`: the file is cut short."""
    stream.seek(offset)
    data = stream.read(size)
    if len(data) != size:
        raise InputError(
            source,
            f"cut short: {what} needs {size} bytes at byte {offset}, the file has {len(data)}",
        )
    return data


def to_labels(source: str, values: np.ndarray, dtype: np.dtype, where: str) -> np.ndarray:
    """Integers read as int64 cast to ``dtype``, or :class:`InputError` for one that it cannot
    hold (a negative one in an unsigned type included)."""
    dtype = np.dtype(dtype)
    info = np.iinfo(dtype)
    if values.size and (values.min() < info.min or values.max() > info.max):
        bad = values[(values < info.min) | (values > info.max)][0]
        raise InputError(source, f"{where}: value {bad} does not fit the type {dtype.name}")
    return values.astype(dtype, copy=False)


class TextIntegers:
    """Integers written as text, separated by blanks, read a block at a time from ``offset``
    of ``stream`` up to ``end`` (None: the end of the file), so that a slab of voxels is parsed
    without the rest of the file. ``what`` names them in messages."""

    def __init__(
        self, source: str, stream: BinaryIO, offset: int, end: int | None, what: str
    ) -> None:
        self.source = source
        self.stream = stream
        self.position = offset  # the next byte of the file not yet read
        self.end = end
        self.what = what
        self.pending: list[bytes] = []
        self.tail = b""  # a token that a block cut in two
        self.read = 0  # integers taken so far

    def _fill(self) -> bool:
        """More tokens into ``pending``; False at the end of the text."""
        size = _TOKEN_BLOCK if self.end is None else min(_TOKEN_BLOCK, self.end - self.position)
        if size <= 0:
            block = b""
        else:
            self.stream.seek(self.position)
            block = self.stream.read(size)
            self.position += len(block)
        if not block:
            if self.tail:
                self.pending.append(self.tail)
                self.tail = b""
                return True
            return False
        text = self.tail + block
        tokens = text.split()
        if not text[-1:].isspace() and tokens:
            self.tail = tokens.pop()
        else:
            self.tail = b""
        self.pending.extend(tokens)
        return True

    def take(self, count: int) -> np.ndarray:
        """The next ``count`` integers as int64, or :class:`InputError`: fewer than that
        (the data cut short) or a token that is not an integer."""
        while len(self.pending) < count:
            if not self._fill():
                raise InputError(
                    self.source,
                    f"cut short: {self.what} ends after {self.read + len(self.pending)} "
                    f"values, {self.read + count} needed at least",
                )
        tokens, self.pending = self.pending[:count], self.pending[count:]
        try:
            if tokens and max(map(len, tokens)) > _LONGEST_INTEGER:
                raise ValueError  # named below; an array of such tokens would be too wide
            values = np.array(tokens, dtype=bytes).astype(np.int64)
        except (ValueError, OverflowError):
            for i, token in enumerate(tokens):
                try:
                    if len(token) > _LONGEST_INTEGER:
                        raise ValueError
                    np.int64(int(token))
                except (ValueError, OverflowError):
                    shown = token[:40].decode("ascii", "replace")
                    raise InputError(
                        self.source,
                        f"{self.what}: value {self.read + i + 1} is {shown!r}, not an integer "
                        "label",
                    ) from None
            raise InputError(self.source, f"{self.what}: values that are not integers") from None
        self.read += count
        return values

    def rest_is_blank(self) -> bool:
        """True when no integer is left (extra values make the count wrong)."""
        while not self.pending:
            if not self._fill():
                return True
        return False


def slabs_of(nz: int, depth: int) -> Iterator[tuple[int, int]]:
    """``(z0, z1)`` of each slab of at most ``depth`` slices."""
    for z0 in slab_starts(nz, depth):
        yield z0, min(nz, z0 + depth)
