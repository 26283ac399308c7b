"""Points to tessellate (``grainclass voronoi --points``), from five formats.

- ``voro``: Voro++'s own input, ``id x y z`` or ``id x y z r`` per line.
- ``xyz``: (extended) XYZ, one frame: the number of points, a comment line (extended XYZ:
  ``Lattice="..."``, ``Properties=...``, ``pbc="T T T"``), then ``species x y z ...`` per point.
- ``lammps``: a LAMMPS text dump, one frame, ``ITEM: BOX BOUNDS`` with ``pp`` (periodic) or
  ``ff``/``fs``/``ss``/``fm``... (walled) per axis, or ``xy xz yz pp pp pp`` (a tilted box,
  periodic), and ``ITEM: ATOMS id ... x y z ...`` (or ``xu``/``xs`` coordinates).
- ``csv``: a header row naming ``x``, ``y``, ``z`` (and ``id``, ``r``/``radius``) columns.
- ``npy``: an (n, 3) or (n, 4) array (x, y, z, r), or a structured array with those fields.

Every point keeps where it was read (a line, or an array row) for the messages; a value that
cannot be read is an :class:`~grainclass.errors.InputError` naming its line. Points without ids
in the file are numbered 1, 2, ... in file order.
"""

from __future__ import annotations

import io
import re
from pathlib import Path

import numpy as np

from grainclass.box import Box, Points
from grainclass.errors import InputError, OptionError

POINT_FORMATS = ("voro", "xyz", "lammps", "csv", "npy")
RADIUS_NAMES = ("r", "radius")  # columns or properties read as radii unless one is named
_SUFFIXES = {
    ".npy": "npy",
    ".csv": "csv",
    ".xyz": "xyz",
    ".extxyz": "xyz",
    ".dump": "lammps",
    ".lammpstrj": "lammps",
}


def sniff_points(path: str, head: bytes) -> str:
    """The format of a points file, from its name's suffix or else its first bytes.

    Examples
    --------
    >>> sniff_points("p.txt", b"ITEM: TIMESTEP\\n0\\n")
    'lammps'
    >>> sniff_points("p.txt", b"2\\nLattice=\\"1 0 0 0 1 0 0 0 1\\"\\nH 0 0 0\\n")
    'xyz'
    >>> sniff_points("p.txt", b"id,x,y,z\\n1,0,0,0\\n")
    'csv'
    >>> sniff_points("p.txt", b"1 0.5 0.5 0.5\\n")
    'voro'
    """
    suffix = Path(path).suffix.lower()
    if suffix in _SUFFIXES:
        return _SUFFIXES[suffix]
    if head.startswith(b"\x93NUMPY"):
        return "npy"
    lines = [line.strip() for line in head.splitlines() if line.strip()]
    first = lines[0] if lines else b""
    if first.startswith(b"ITEM:"):
        return "lammps"
    if re.fullmatch(rb"\d+", first):
        return "xyz"
    if b"," in first and re.search(rb"[A-Za-z]", first):
        return "csv"
    return "voro"


def read_points(path: str, format: str | None = None, radius_column: str | None = None) -> Points:
    """The points of the file ``path`` (format sniffed unless given), with the box the file
    gives (LAMMPS dumps, extended XYZ's ``Lattice``), else ``box`` None.

    ``radius_column`` names the column (CSV, LAMMPS) or property (extended XYZ) of the radii;
    by default one named ``r`` or ``radius`` is used where there is one.
    """
    source = str(path)
    try:
        data = Path(path).read_bytes()
    except OSError as exc:
        raise InputError(source, f"cannot read the file: {exc.strerror}") from None
    format = format or sniff_points(source, data[:4096])
    if format == "npy":
        points = _read_npy(data, source, radius_column)
    else:
        text = data.decode("utf-8", "replace").replace("\r\n", "\n")
        reader = {"voro": _read_voro, "xyz": _read_xyz, "lammps": _read_lammps, "csv": _read_csv}
        points = reader[format](text.split("\n"), source, radius_column)
    if not len(points.xyz):
        raise InputError(source, "no points in the file")
    _check_ids(points)
    return points


def _check_ids(points: Points) -> None:
    """Two points with one id would be two grains with one grain_id: refused."""
    ids = points.ids
    order = np.argsort(ids, kind="stable")
    same = np.flatnonzero(ids[order][1:] == ids[order][:-1])
    if len(same):
        i, j = order[same[0]], order[same[0] + 1]
        raise InputError(
            points.source,
            f"point id {ids[j]} is given twice (also at {points.where(i)})",
            int(points.locations[j]) if points.location_kind == "line" else None,
        )


def _table(
    lines: list[str],
    first_line: int,
    columns: dict[str, int],
    source: str,
    what: str,
    sep: str | None = None,
    exact: bool = False,
) -> tuple[dict[str, np.ndarray], np.ndarray]:
    """Numbers separated by ``sep`` (None: by blanks): the ``columns`` (name: column index) of
    the non-blank lines of ``lines`` (the first is line ``first_line`` of the file), as
    float64, and the line number of each row. A row too short, or a value that is not a
    number, names its line. With ``exact``, every row must hold just the ``columns``."""
    import pandas as pd

    blank = [not line.strip() for line in lines]
    if any(blank):
        numbers = first_line + np.flatnonzero(~np.asarray(blank))
        rows = [lines[n - first_line] for n in numbers]
    else:
        numbers, rows = first_line + np.arange(len(lines)), lines
    width = max(columns.values()) + 1
    try:
        frame = pd.read_csv(
            io.StringIO("\n".join(rows)),
            sep=sep or r"\s+",
            header=None,
            usecols=None if exact else sorted(set(columns.values())),
            dtype=np.float64,
            engine="c",
        )
        if len(frame) != len(rows) or (exact and frame.shape[1] != width):
            raise ValueError("rows lost, or a row too long")
        out = {name: frame[column].to_numpy(np.float64) for name, column in columns.items()}
    except (ValueError, pd.errors.ParserError):
        _first_bad_row(rows, numbers, columns, width, source, what, sep, exact)
        raise InputError(source, f"cannot read the {what}s") from None
    if any(np.isnan(values).any() for values in out.values()):  # a short row pandas filled
        _first_bad_row(rows, numbers, columns, width, source, what, sep, exact)
    return out, numbers.astype(np.int64)


def _first_bad_row(
    rows: list[str],
    numbers: np.ndarray,
    columns: dict[str, int],
    width: int,
    source: str,
    what: str,
    sep: str | None,
    exact: bool = False,
) -> None:
    """Raise the InputError of the first row that is too short (or, ``exact``, too long) or
    holds a word for a number."""
    for row, number in zip(rows, numbers, strict=True):
        fields = row.split(sep)
        if len(fields) < width or (exact and len(fields) != width):
            raise InputError(
                source,
                f"cannot read this {what}: expected {width} values, found {len(fields)}",
                int(number),
            )
        for name, column in columns.items():
            try:
                value = float(fields[column])
            except ValueError:
                value = np.nan
            if np.isnan(value):
                raise InputError(
                    source,
                    f"cannot read this {what}: {name} is {fields[column]!r}, not a number",
                    int(number),
                )


def _radius_column(names: list[str], radius_column: str | None, source: str) -> str | None:
    """The column of the radii among ``names``: the one named, else ``r`` or ``radius``."""
    if radius_column is not None:
        if radius_column not in names:
            raise InputError(
                source, f"no column {radius_column!r} for the radii (columns: {' '.join(names)})"
            )
        return radius_column
    return next((name for name in names if name.lower() in RADIUS_NAMES), None)


def _ids(values: np.ndarray, source: str, numbers: np.ndarray, what: str) -> np.ndarray:
    """Ids read as numbers, as int64: each must be a whole number that an int64 holds."""
    held = np.isfinite(values) & (np.abs(values) < 2.0**63)
    ids = np.where(held, values, 0.0).astype(np.int64)
    bad = np.flatnonzero((ids != values) | ~held)
    if len(bad):
        raise InputError(
            source,
            f"cannot read this {what}: id {values[bad[0]]:g} is not a whole number from -2^63 "
            "to 2^63 - 1",
            int(numbers[bad[0]]),
        )
    return ids


def _read_voro(lines: list[str], source: str, radius_column: str | None) -> Points:
    """Voro++'s input: ``id x y z`` or ``id x y z r`` per line, the same on every line."""
    if radius_column is not None:
        raise OptionError(
            "radius_column",
            "Voro++'s input names no columns: a radius is the fifth number of a line",
        )
    first = next((line.split() for line in lines if line.strip()), [])
    if not first:
        empty = np.empty(0, np.int64)
        return Points(np.empty((0, 3)), empty, empty, source, "line")
    with_radius = len(first) == 5
    if len(first) not in (4, 5):
        number = next(k + 1 for k, line in enumerate(lines) if line.strip())
        raise InputError(
            source,
            f"cannot read this point: expected id x y z [r], found {len(first)} values",
            number,
        )
    columns = {"id": 0, "x": 1, "y": 2, "z": 3} | ({"r": 4} if with_radius else {})
    table, numbers = _table(lines, 1, columns, source, "point", exact=True)
    return Points(
        np.column_stack([table["x"], table["y"], table["z"]]),
        _ids(table["id"], source, numbers, "point"),
        numbers,
        source,
        "line",
        table.get("r"),
    )


_KEY_VALUE = re.compile(r'(\w+)=("[^"]*"|\S+)')


def _read_xyz(lines: list[str], source: str, radius_column: str | None) -> Points:
    """(Extended) XYZ, the first frame: a count, a comment line, then one point per line."""
    try:
        count = int(lines[0].strip())
    except ValueError:
        raise InputError(source, "expected the number of points on the first line", 1) from None
    if len(lines) < count + 2 or any(not line.strip() for line in lines[2 : count + 2]):
        raise InputError(source, f"the first line says {count} points, but fewer follow", 1)
    if any(line.strip() for line in lines[count + 2 :]):
        raise InputError(source, "more than one frame: give one frame per file", count + 3)
    info = {key.lower(): value.strip('"') for key, value in _KEY_VALUE.findall(lines[1])}
    names, columns = ["species", "x", "y", "z"], {"x": 1, "y": 2, "z": 3}
    if "properties" in info:
        names = []
        fields = info["properties"].split(":")
        for name, _, width in zip(fields[::3], fields[1::3], fields[2::3], strict=False):
            names += [name] if int(width) == 1 else [f"{name}{k}" for k in range(int(width))]
        if "pos0" not in names:
            raise InputError(source, "the Properties of line 2 name no pos", 2)
        at = names.index("pos0")
        columns = {"x": at, "y": at + 1, "z": at + 2}
        if "id" in names:
            columns["id"] = names.index("id")
    radius = _radius_column(names, radius_column, source)
    if radius is not None:
        columns["r"] = names.index(radius)
    table, numbers = _table(lines[2 : count + 2], 3, columns, source, "point")
    box = None
    if "lattice" in info:
        try:
            lattice = np.array(info["lattice"].split(), np.float64).reshape(3, 3)
        except ValueError:
            raise InputError(
                source, "cannot read the Lattice of line 2: expected 9 numbers", 2
            ) from None
        if lattice[0, 1] or lattice[0, 2] or lattice[1, 2]:
            raise InputError(
                source,
                "the Lattice of line 2 is tilted otherwise than LAMMPS's boxes: expected the "
                "first edge along x and the second in the xy plane",
                2,
            )
        origin = np.zeros(3)
        if "origin" in info:
            origin = np.array(info["origin"].split(), np.float64)
        pbc = tuple(flag.upper().startswith("T") for flag in info.get("pbc", "T T T").split())
        tilt = (lattice[1, 0], lattice[2, 0], lattice[2, 1])
        if any(tilt) and not all(pbc):
            raise InputError(
                source,
                "a tilted Lattice with walls: only tilted boxes periodic on every side "
                'are tessellated (pbc="T T T")',
                2,
            )
        box = Box(
            tuple(origin),
            tuple(origin + np.diag(lattice)),
            pbc,
            tuple(float(t) for t in tilt) if any(tilt) else None,
        )
        if box.problem():
            raise InputError(source, f"the Lattice of line 2 is no box: {box.problem()}", 2)
    ids = (
        _ids(table["id"], source, numbers, "point")
        if "id" in table
        else np.arange(1, count + 1, dtype=np.int64)
    )
    xyz = np.column_stack([table["x"], table["y"], table["z"]])
    return Points(xyz, ids, numbers, source, "line", table.get("r"), box)


def _read_lammps(lines: list[str], source: str, radius_column: str | None) -> Points:
    """A LAMMPS text dump, the first frame: its box, its periodicity and its atoms."""
    items = [k for k, line in enumerate(lines) if line.startswith("ITEM:")]
    found: dict[str, int] = {}
    for k in items:
        title = lines[k][5:].strip()
        for name in ("TIMESTEP", "NUMBER OF ATOMS", "BOX BOUNDS", "ATOMS"):
            if title.startswith(name):
                if name in found:
                    raise InputError(source, "more than one frame: give one frame per file", k + 1)
                found[name] = k
                break
    for name in ("NUMBER OF ATOMS", "BOX BOUNDS", "ATOMS"):
        if name not in found:
            raise InputError(source, f"no 'ITEM: {name}' line: not a LAMMPS dump")
    at = found["NUMBER OF ATOMS"]
    try:
        count = int(lines[at + 1].strip())
    except (ValueError, IndexError):
        raise InputError(source, "expected the number of atoms", at + 2) from None
    at = found["BOX BOUNDS"]
    flags = lines[at][5:].split()[2:]
    tilted = flags[:3] == ["xy", "xz", "yz"]
    flags = flags[3:] if tilted else flags
    if len(flags) != 3:
        raise InputError(
            source, "expected BOX BOUNDS [xy xz yz] and three of pp, ff, fs, ...", at + 1
        )
    bounds = []
    for k in range(3):
        try:
            values = [float(v) for v in lines[at + 1 + k].split()[: 3 if tilted else 2]]
            if len(values) != (3 if tilted else 2):
                raise ValueError
        except (ValueError, IndexError):
            expected = "low high tilt" if tilted else "low high"
            raise InputError(
                source, f"cannot read the box: expected {expected}", at + 2 + k
            ) from None
        bounds.append(values)
    periodic = tuple(f == "pp" for f in flags)
    if tilted:
        # LAMMPS writes the bounds of the tilted box; its edges start from these lows.
        xy, xz, yz = bounds[0][2], bounds[1][2], bounds[2][2]
        x_low = bounds[0][0] - min(0.0, xy, xz, xy + xz)
        x_high = bounds[0][1] - max(0.0, xy, xz, xy + xz)
        y_low, y_high = bounds[1][0] - min(0.0, yz), bounds[1][1] - max(0.0, yz)
        if not all(periodic):
            raise InputError(
                source,
                "a tilted box with walls: only tilted boxes periodic on every side "
                "(pp pp pp) are tessellated",
                at + 1,
            )
        if not (x_high > x_low and y_high > y_low):  # NaNs too
            raise InputError(
                source, "the BOX BOUNDS are no box: a tilt larger than the box", at + 1
            )
        box = Box(
            (x_low, y_low, bounds[2][0]), (x_high, y_high, bounds[2][1]), periodic, (xy, xz, yz)
        )
    else:
        box = Box(tuple(b[0] for b in bounds), tuple(b[1] for b in bounds), periodic)
    if box.problem():
        raise InputError(source, f"the BOX BOUNDS are no box: {box.problem()}", at + 1)
    at = found["ATOMS"]
    names = lines[at][5:].split()[1:]
    columns: dict[str, int] = {}
    scaled = False
    for suffix in ("", "u", "s", "su"):
        if all(f"{axis}{suffix}" in names for axis in "xyz"):
            columns = {axis: names.index(f"{axis}{suffix}") for axis in "xyz"}
            scaled = suffix.startswith("s")
            break
    if not columns:
        raise InputError(source, "the ATOMS line names no x y z (nor xu, xs, xsu) columns", at + 1)
    if "id" in names:
        columns["id"] = names.index("id")
    radius = _radius_column(names, radius_column, source)
    if radius is not None:
        columns["r"] = names.index(radius)
    rows = lines[at + 1 : at + 1 + count]
    if len([row for row in rows if row.strip()]) != count:
        raise InputError(source, f"NUMBER OF ATOMS says {count}, but fewer atoms follow", at + 1)
    table, numbers = _table(rows, at + 2, columns, source, "atom")
    xyz = np.column_stack([table["x"], table["y"], table["z"]])
    if scaled:
        xyz = np.asarray(box.low) + xyz @ box.matrix.T
    ids = (
        _ids(table["id"], source, numbers, "atom")
        if "id" in table
        else np.arange(1, count + 1, dtype=np.int64)
    )
    return Points(xyz, ids, numbers, source, "line", table.get("r"), box)


def _read_csv(lines: list[str], source: str, radius_column: str | None) -> Points:
    """CSV with a header row naming x, y, z (and id, r or radius) columns."""
    header = next((k for k, line in enumerate(lines) if line.strip()), None)
    if header is None:
        raise InputError(source, "no header row")
    names = [name.strip().strip('"') for name in lines[header].split(",")]
    lower = [name.lower() for name in names]
    missing = [axis for axis in "xyz" if axis not in lower]
    if missing:
        raise InputError(
            source,
            f"the header names no {', '.join(missing)} column (it has: {lines[header]})",
            header + 1,
        )
    columns = {axis: lower.index(axis) for axis in "xyz"}
    if "id" in lower:
        columns["id"] = lower.index("id")
    radius = _radius_column(names, radius_column, source)
    if radius is not None:
        columns["r"] = names.index(radius)
    table, numbers = _table(lines[header + 1 :], header + 2, columns, source, "row", ",")
    ids = (
        _ids(table["id"], source, numbers, "row")
        if "id" in table
        else np.arange(1, len(numbers) + 1, dtype=np.int64)
    )
    xyz = np.column_stack([table["x"], table["y"], table["z"]])
    return Points(xyz, ids, numbers, source, "line", table.get("r"))


def _read_npy(data: bytes, source: str, radius_column: str | None) -> Points:
    """An (n, 3) or (n, 4) array (x, y, z, r), or a structured array with x, y, z fields
    (and id, r or radius); rows are records 0, 1, ..."""
    try:
        array = np.load(io.BytesIO(data), allow_pickle=False)
    except ValueError as exc:
        raise InputError(source, f"cannot read the array: {exc}") from None
    records = np.arange(len(array), dtype=np.int64)
    ids = np.arange(1, len(array) + 1, dtype=np.int64)
    radii = None
    if array.dtype.names:
        names = list(array.dtype.names)
        missing = [axis for axis in "xyz" if axis not in names]
        if missing:
            raise InputError(source, f"the array has no field {', '.join(missing)}")
        xyz = np.column_stack([array[axis] for axis in "xyz"]).astype(np.float64)
        radius = _radius_column(names, radius_column, source)
        if radius is not None:
            radii = array[radius].astype(np.float64)
        if "id" in names:
            ids = np.asarray(array["id"]).astype(np.int64)
    elif array.ndim == 2 and array.shape[1] in (3, 4) and array.dtype.kind in "fiu":
        xyz = array[:, :3].astype(np.float64)
        if array.shape[1] == 4:
            radii = array[:, 3].astype(np.float64)
    else:
        raise InputError(
            source,
            f"expected an array of shape (n, 3) or (n, 4), not {array.shape} of {array.dtype}",
        )
    bad = np.flatnonzero(~np.isfinite(xyz).all(axis=1))
    if len(bad):
        raise InputError(source, f"record {bad[0]}: a coordinate is not a finite number")
    return Points(xyz, ids, records, source, "record", radii)
