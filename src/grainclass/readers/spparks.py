"""SPPARKS site dumps: the spins of a Potts model on a lattice, as text (``dump ID text DELTA
FILE id i1 x y z``, or the default ``id site x y z``, which SPPARKS writes as ``type``).

Layout (SPPARKS's ``dump_text.cpp``), one snapshot after another::

    ITEM: TIMESTEP
    <step> <time>
    ITEM: NUMBER OF ATOMS
    <sites>
    ITEM: BOX BOUNDS
    <xlo> <xhi>
    <ylo> <yhi>
    <zlo> <zhi>
    ITEM: ATOMS id i1 x y z
    <id> <spin> <x> <y> <z>
    ...

What is read: the last snapshot of the file, whole (sites come in any order, so the image is
made in memory: 4 bytes a site). The spin (column ``i1``, else ``type``) is the grain id; x,
y and z are lattice coordinates, which must fill a regular grid, one site per point: the
distinct values along each axis, equally spaced, give the grid's voxels, lowest first. A
simple cubic lattice does; the sites of fcc, bcc or hexagonal lattices do not, and are refused.
The labels are int32, as SPPARKS writes spins; spacing is None (lattice units only).

Refused: a snapshot cut short (fewer site lines than its ``NUMBER OF ATOMS``, or a line with
too few values; its line is named), no ``i1`` or ``type`` column, no ``x``, ``y`` or ``z``
column, a spin that is not an integer or is negative, sites that do not fill a grid (a dump of
a region, a non-cubic lattice), a 2D lattice.
"""

from __future__ import annotations

import mmap
import re
from collections.abc import Iterator

import numpy as np

from grainclass.errors import InputError
from grainclass.readers.label_image import LabelImage
from grainclass.readers.voxels import check_shape, checked_slab, slabs_of

_MARK = b"ITEM: TIMESTEP"
_NUMBER = rb"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"
_SPPARKS_STEP = re.compile(rb"\s*\d+\s+" + _NUMBER + rb"\s*")  # "<step> <time>"
_SPIN_COLUMN = re.compile(rb"^ITEM: ATOMS\b.*\s(i\d+)\b", re.MULTILINE)
_SPINS = ("i1", "type")


def looks_like_spparks(head: bytes) -> bool:
    """True for a dump that starts ``ITEM: TIMESTEP`` and is SPPARKS's: its step line holds
    the step and the time (LAMMPS writes the step alone), or its ``ITEM: ATOMS`` columns
    hold an integer site value (``i1``), which LAMMPS has not.

    >>> looks_like_spparks(b"ITEM: TIMESTEP\\n0    3.03846\\nITEM: NUMBER OF ATOMS\\n8\\n")
    True
    >>> looks_like_spparks(b"ITEM: TIMESTEP\\n100\\nITEM: NUMBER OF ATOMS\\n8\\n")
    False
    """
    lines = head.lstrip().split(b"\n", 2)
    if len(lines) < 2 or lines[0].rstrip() != _MARK:
        return False
    return bool(_SPPARKS_STEP.fullmatch(lines[1]) or _SPIN_COLUMN.search(head))


class _Lines:
    """Line numbers of byte offsets in the file, counted only when a message needs one."""

    def __init__(self, mm) -> None:
        self.mm = mm

    def of(self, offset: int) -> int:
        count, position = 1, 0
        while True:
            newline = self.mm.find(b"\n", position, offset)
            if newline < 0:
                return count
            count += 1
            position = newline + 1


def open_spparks(path: str) -> LabelImage:
    """Open the last snapshot of a SPPARKS site dump as a :class:`LabelImage` (see the
    module's docstring).

    Parameters
    ----------
    path : str
        The dump file.

    Returns
    -------
    LabelImage
        Shape ``(z, y, x)`` of the lattice, int32 spins, spacing None.

    Raises
    ------
    InputError
        For what the module's docstring says is refused.
    """
    with open(path, "rb") as stream:
        try:
            mm = mmap.mmap(stream.fileno(), 0, access=mmap.ACCESS_READ)
        except ValueError:
            raise InputError(path, "an empty file") from None
        with mm:
            labels = _last_snapshot(path, mm)
    shape = check_shape(path, labels.shape)

    def slabs(depth: int) -> Iterator[np.ndarray]:
        for z0, z1 in slabs_of(shape[0], depth):
            yield checked_slab(path, labels[z0:z1], z0)

    return LabelImage(path, shape, labels.dtype, None, slabs)


def _last_snapshot(path: str, mm) -> np.ndarray:
    start = mm.rfind(_MARK)
    if start < 0:
        raise InputError(path, "no ITEM: TIMESTEP: not a SPPARKS dump")
    lines = _Lines(mm)
    first = lines.of(start)
    text = mm[start:]
    rows = text.split(b"\n")
    header = [row.strip() for row in rows[:9]]

    def expect(i: int, what: str) -> bytes:
        if i >= len(header) or (not header[i] and i == len(rows) - 1):
            raise InputError(path, f"cut short: {what} expected", first + i)
        return header[i]

    if not expect(2, "ITEM: NUMBER OF ATOMS").startswith(b"ITEM: NUMBER OF ATOMS"):
        raise InputError(path, f"{header[2][:40]!r}: ITEM: NUMBER OF ATOMS expected", first + 2)
    try:
        count = int(expect(3, "the number of sites"))
    except ValueError:
        raise InputError(
            path, f"{header[3][:40]!r}: the number of sites expected", first + 3
        ) from None
    if count < 1:
        raise InputError(path, f"{count} sites", first + 3)
    if not expect(4, "ITEM: BOX BOUNDS").startswith(b"ITEM: BOX BOUNDS"):
        raise InputError(path, f"{header[4][:40]!r}: ITEM: BOX BOUNDS expected", first + 4)
    columns = expect(8, "ITEM: ATOMS").split()
    if columns[:2] != [b"ITEM:", b"ATOMS"]:
        raise InputError(path, f"{header[8][:40]!r}: ITEM: ATOMS expected", first + 8)
    names = [c.decode("ascii", "replace") for c in columns[2:]]
    spin = next((names.index(c) for c in _SPINS if c in names), None)
    if spin is None:
        raise InputError(path, f"columns {' '.join(names)}: no spin (i1 or type)", first + 8)
    missing = [axis for axis in "xyz" if axis not in names]
    if missing:
        raise InputError(path, f"columns {' '.join(names)}: no {', '.join(missing)}", first + 8)
    body = rows[9 : 9 + count]
    if len(body) < count or (len(rows) == 9 + count and body and not body[-1].strip()):
        got = len([row for row in body if row.strip()])
        raise InputError(
            path, f"cut short: {got} of the snapshot's {count} sites", first + 9 + len(body) - 1
        )
    extra = [i for i, row in enumerate(rows[9 + count :]) if row.strip()]
    if extra:
        raise InputError(
            path, "a line after the snapshot's last site", first + 9 + count + extra[0]
        )
    width = len(names)
    tokens = b" ".join(body).split()
    if len(tokens) != count * width:
        bad = next(i for i, row in enumerate(body) if len(row.split()) != width)
        raise InputError(
            path, f"{len(body[bad].split())} values, {width} columns expected", first + 9 + bad
        )
    table = np.array(tokens).reshape(count, width)
    spins = _column(path, table, spin, np.int64, first + 9, "the spin is not an integer")
    if spins.min() < np.iinfo(np.int32).min or spins.max() > np.iinfo(np.int32).max:
        raise InputError(path, "a spin past the range of SPPARKS's 32-bit integers")
    where = [
        _column(path, table, names.index(axis), np.float64, first + 9, f"{axis} is not a number")
        for axis in "xyz"
    ]
    return _grid(path, spins.astype(np.int32), where)


def _column(path: str, table, index: int, dtype, line: int, what: str) -> np.ndarray:
    try:
        values = table[:, index].astype(dtype)
    except (ValueError, OverflowError):
        for row, token in enumerate(table[:, index]):
            try:
                np.array([token]).astype(dtype)
            except (ValueError, OverflowError):
                raise InputError(path, f"{token[:40]!r}: {what}", line + row) from None
        raise
    if dtype is np.float64 and not np.isfinite(values).all():
        row = int(np.flatnonzero(~np.isfinite(values))[0])
        raise InputError(path, f"{table[row, index]!r}: {what}", line + row)
    return values


def _grid(path: str, spins: np.ndarray, coordinates: list[np.ndarray]) -> np.ndarray:
    """The spins laid on the grid their coordinates fill: labels[z, y, x]."""
    indices, sizes = [], []
    for axis, values in zip("xyz", coordinates, strict=True):
        points = np.unique(values)
        if len(points) > 1:
            steps = np.diff(points)
            if steps.max() - steps.min() > 1e-6 * steps.min():
                raise InputError(
                    path,
                    f"the sites' {axis} coordinates are not equally spaced ({len(points)} "
                    "values): not a simple cubic lattice",
                )
            index = np.rint((values - points[0]) / steps[0]).astype(np.int64)
        else:
            index = np.zeros(len(values), dtype=np.int64)
        indices.append(index)
        sizes.append(len(points))
    nx, ny, nz = sizes
    if len(spins) != nx * ny * nz:
        raise InputError(
            path,
            f"{len(spins)} sites do not fill their grid of {nx} x {ny} x {nz} points: a dump "
            "of part of the lattice, or a lattice that is not simple cubic",
        )
    flat = indices[0] + nx * (indices[1] + ny * indices[2])
    if np.bincount(flat, minlength=nx * ny * nz).max() > 1:
        raise InputError(path, "two sites at the same point")
    labels = np.empty(nx * ny * nz, dtype=np.int32)
    labels[flat] = spins
    return labels.reshape(nz, ny, nx)
