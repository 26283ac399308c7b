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
from grainclass.readers.label_image import LabelImage, check_shape, checked_slab, slabs_of

_MARK = b"ITEM: TIMESTEP"
_NUMBER = rb"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"
_SPPARKS_STEP = re.compile(rb"\s*\d+\s+" + _NUMBER + rb"\s*")  # "<step> <time>"
_SPIN_COLUMN = re.compile(rb"^ITEM: ATOMS\b.*\s(i\d+)\b", re.MULTILINE)
_SPINS = ("i1", "type")
_BLOCK = 1 << 23  # bytes of site lines parsed at a time
_LONGEST_VALUE = 32  # characters of the longest number a dump holds ("%g" of a double: 13)


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
    first = _Lines(mm).of(start)
    header, data = _header(path, mm, start, first)
    count, names = _counts(path, header, first)
    spin = next((names.index(c) for c in _SPINS if c in names), None)
    if spin is None:
        raise InputError(path, f"columns {' '.join(names)}: no spin (i1 or type)", first + 8)
    missing = [axis for axis in "xyz" if axis not in names]
    if missing:
        raise InputError(path, f"columns {' '.join(names)}: no {', '.join(missing)}", first + 8)
    room = (len(mm) - data + 1) // (2 * len(names))  # a value and a blank at least
    if count > room:
        raise InputError(
            path,
            f"cut short: {count} sites, and the rest of the file holds at most {room} lines of "
            f"{len(names)} values",
            first + 3,
        )
    wanted = [spin, *(names.index(axis) for axis in "xyz")]
    spins = np.empty(count, dtype=np.int64)
    where = np.empty((3, count), dtype=np.float64)
    done = 0
    for rows in _blocks(path, mm, data, count, first + 9):
        table = _table(path, rows, len(names), first + 9 + done)
        line = first + 9 + done
        spins[done : done + len(rows)] = _column(path, table, spin, np.int64, line, "spin")
        for axis, index in enumerate(wanted[1:]):
            values = _column(path, table, index, np.float64, line, "xyz"[axis])
            where[axis, done : done + len(rows)] = values
        done += len(rows)
    if spins.min() < np.iinfo(np.int32).min or spins.max() > np.iinfo(np.int32).max:
        raise InputError(path, "a spin past the range of SPPARKS's 32-bit integers")
    return _grid(path, spins.astype(np.int32), list(where))


def _header(path: str, mm, start: int, first: int) -> tuple[list[bytes], int]:
    """The snapshot's 9 header lines, stripped, and where its sites start."""
    header, position = [], start
    for i in range(9):
        end = mm.find(b"\n", position)
        if end < 0:
            if position >= len(mm) or i < 8:
                raise InputError(path, "cut short in the snapshot's header", first + i)
            end = len(mm)
        header.append(mm[position:end].strip())
        position = end + 1
    return header, position


def _counts(path: str, header: list[bytes], first: int) -> tuple[int, list[str]]:
    """The number of sites and the names of the columns, from the header."""
    for i, item in ((2, b"ITEM: NUMBER OF ATOMS"), (4, b"ITEM: BOX BOUNDS"), (8, b"ITEM: ATOMS")):
        if not header[i].startswith(item):
            shown = header[i][:40].decode("latin-1")
            raise InputError(path, f"{shown!r}: {item.decode()} expected", first + i)
    try:
        count = int(header[3])
    except ValueError:
        shown = header[3][:40].decode("latin-1")
        raise InputError(path, f"{shown!r}: the number of sites expected", first + 3) from None
    if count < 1:
        raise InputError(path, f"{count} sites", first + 3)
    return count, [c.decode("ascii", "replace") for c in header[8].split()[2:]]


def _blocks(path: str, mm, position: int, count: int, line: int) -> Iterator[list[bytes]]:
    """The snapshot's site lines, a block of whole lines at a time; :class:`InputError` if
    there are fewer than ``count`` (the file cut short) or lines after them."""
    done = 0
    while done < count:
        end = mm.find(b"\n", min(position + _BLOCK, len(mm)))
        end = len(mm) if end < 0 else end
        rows = mm[position:end].split(b"\n") if position < end else []
        if end == len(mm) and rows and not rows[-1].strip():
            rows.pop()  # the file's last line end
        rows = rows[: count - done]
        if end >= len(mm) and done + len(rows) < count:
            raise InputError(
                path,
                f"cut short: {done + len(rows)} of the snapshot's {count} sites",
                line + done + len(rows) - 1,
            )
        yield rows
        done += len(rows)
        position = end + 1 if done < count else position + len(b"\n".join(rows)) + 1
    rest = mm[position : position + _BLOCK] if position < len(mm) else b""
    if rest.strip():
        extra = len(rest[: len(rest) - len(rest.lstrip())].split(b"\n")) - 1
        raise InputError(path, "a line after the snapshot's last site", line + count + extra)


def _table(path: str, rows: list[bytes], width: int, line: int) -> np.ndarray:
    """The values of ``rows`` as a (rows, width) array of bytes."""
    tokens = b" ".join(rows).split()
    bad = None
    if len(tokens) != len(rows) * width:
        bad = next(i for i, row in enumerate(rows) if len(row.split()) != width)
        found = len(rows[bad].split())
        raise InputError(path, f"{found} values, {width} columns expected", line + bad)
    if tokens and max(map(len, tokens)) > _LONGEST_VALUE:  # too wide an array; no number is
        bad = next(i for i, row in enumerate(rows) if max(map(len, row.split())) > _LONGEST_VALUE)
        raise InputError(path, f"a value of more than {_LONGEST_VALUE} characters", line + bad)
    return np.array(tokens).reshape(len(rows), width)


def _column(path: str, table, index: int, dtype, line: int, name: str) -> np.ndarray:
    """Column ``index`` of ``table`` (its first row on ``line``) as ``dtype``."""
    what = f"the {name} is not an integer" if dtype is np.int64 else f"{name} is not a number"
    try:
        values = table[:, index].astype(dtype)
    except (ValueError, OverflowError):
        for row, token in enumerate(table[:, index]):
            try:
                np.array([token]).astype(dtype)
            except (ValueError, OverflowError):
                shown = token[:40].decode("latin-1")
                raise InputError(path, f"{shown!r}: {what}", line + row) from None
        raise InputError(path, what, line) from None
    if dtype is np.float64 and not np.isfinite(values).all():
        row = int(np.flatnonzero(~np.isfinite(values))[0])
        shown = table[row, index][:40].decode("latin-1")
        raise InputError(path, f"{shown!r}: {what}", line + row)
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
