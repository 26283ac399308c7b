"""Neper tessellation files (``.tess``), 3D only: each polyhedron becomes a grain.

Layout (Neper's ``doc/fileformat.rst``, format 2.0 and later; Neper writes one entry a line in
``**vertex``, ``**edge`` and ``**polyhedron``, four lines a face in ``**face``)::

    ***tess
     **format
       <format>
     **general
       <dim> <type>
     **cell ... (skipped)
     **vertex
     <total_number_of_vertices>
       <ver_id> <ver_x> <ver_y> <ver_z> <ver_state>
     **edge
     <total_number_of_edges>
       <edge_id> <ver_1> <ver_2> <edge_state>
     **face
     <total_number_of_faces>
       <face_id> <number_of_vertices> <ver_1> <ver_2> ...
         <number_of_edges> <edge_1*> <edge_2*> ...
         <face_eq_d> <face_eq_a> <face_eq_b> <face_eq_c>
         <face_state> <face_point> <face_point_x> <face_point_y> <face_point_z>
     **polyhedron
     <total_number_of_polyhedra>
       <poly_id> <number_of_faces> <face_1*> <face_2*> ...
     **domain, **periodic, **scale ... (skipped)
    ***end

A face's signed id in a polyhedron is positive when the face normal (right-handed along its
vertex loop) points out of the polyhedron; the loops of a grain are its faces' vertex loops,
reversed for negative ids, so that they all turn the same way seen from outside (checked: a
wrong sign makes the grain invalid). Edge ``j`` of a face joins its vertices ``j`` and ``j + 1``,
which is checked too.

The grain id is the polyhedron id, its location the line of its entry. A grain is on the
boundary when one of its faces belongs to no other polyhedron (a domain face); in a periodic
tessellation (a ``**periodic`` section) that is unknown. Volume and area are those of the faces
fanned from their first vertex.
"""

from __future__ import annotations

import dataclasses
from collections import Counter
from collections.abc import Iterator
from typing import BinaryIO

import numpy as np

from grainclass.batch import GrainBatch, Shape
from grainclass.errors import InputError
from grainclass.geometry import loop_arrays, polytope_measures
from grainclass.readers.loops import batch_from_loops

_BOM = b"\xef\xbb\xbf"
_FACE_TAIL = 9  # the equation (4 numbers), state, point and point coordinates (3)
_READ = ("general", "vertex", "edge", "face", "polyhedron")  # other sections are skipped


def looks_like_neper(head: bytes) -> bool:
    """True when ``head`` starts, after blank lines, with ``***tess``.

    Examples
    --------
    >>> looks_like_neper(b"\\n***tess\\n **format\\n   3.4\\n")
    True
    >>> looks_like_neper(b"7 0.0351 (1,3,2)")
    False
    """
    text = head.removeprefix(_BOM).lstrip()
    return text.startswith(b"***tess") and (len(text) == 7 or text[7:8].isspace())


class _Sections:
    """The ``**`` sections of a tess file: name -> (header line, [(line number, text)])."""

    def __init__(self, stream: BinaryIO, source: str) -> None:
        self.source = source
        self.found: dict[str, tuple[int, list[tuple[int, str]]]] = {}
        current: list[tuple[int, str]] | None = None
        started = False
        for line_no, raw in enumerate(stream, 1):
            text = raw.decode("utf-8", "replace").strip()
            if line_no == 1:
                text = text.removeprefix("\ufeff")
            if not text:
                continue
            if not started:
                if text.split()[0] != "***tess":
                    raise InputError(source, "not a Neper tessellation: expected ***tess", line_no)
                started = True
                continue
            if text.startswith("***"):
                current = None
                if text.split()[0] == "***end":
                    break
                raise InputError(source, f"unexpected {text.split()[0]}", line_no)
            if text.startswith("**"):
                name = text.split()[0][2:]
                if name in self.found:
                    raise InputError(source, f"section **{name} appears twice", line_no)
                self.found[name] = (line_no, [])
                current = self.found[name][1] if name in _READ else None
            elif current is not None:
                current.append((line_no, text))
        if not started:
            raise InputError(source, "not a Neper tessellation: the input is empty")

    def entries(self, name: str) -> tuple[int, list[tuple[int, str]]]:
        """The count that opens section ``name`` and the lines after it."""
        if name not in self.found:
            raise InputError(self.source, f"no **{name} section (a 3D tessellation has one)")
        header, lines = self.found[name]
        if not lines:
            raise InputError(self.source, f"**{name}: the number of entries is missing", header)
        line_no, text = lines[0]
        try:
            (count,) = (int(t) for t in text.split())
            if count < 0:
                raise ValueError
        except ValueError:
            raise InputError(
                self.source, f"**{name}: expected the number of entries, got {text!r}", line_no
            ) from None
        return count, lines[1:]


def _table(sections: _Sections, name: str, width: int) -> dict[int, tuple[int, list[str]]]:
    """One-line entries of section ``name``: id -> (line, the ``width`` fields after the id)."""
    count, lines = sections.entries(name)
    if len(lines) != count:
        raise InputError(
            sections.source,
            f"**{name} announces {count} entries but has {len(lines)}",
            lines[0][0] if lines else sections.found[name][0],
        )
    table: dict[int, tuple[int, list[str]]] = {}
    for line_no, text in lines:
        fields = text.split()
        try:
            if len(fields) < width + 1:
                raise ValueError(f"expected an id and {width} values")
            if not fields[0].isdecimal():
                raise ValueError(f"the id {fields[0]!r} is not a whole number")
            entry_id = int(fields[0])
            if not 1 <= entry_id <= count:
                raise ValueError(f"id {entry_id} is not between 1 and {count}")
            if entry_id in table:
                raise ValueError(f"id {entry_id} appears twice")
        except ValueError as exc:
            raise InputError(sections.source, f"**{name}: {exc}", line_no) from None
        table[entry_id] = (line_no, fields[1 : width + 1])
    return table


def _vertices(sections: _Sections) -> tuple[np.ndarray, set[int]]:
    """Coordinates indexed by vertex id (NaN rows for missing ids) and the known ids."""
    table = _table(sections, "vertex", 3)
    coords = np.full((max(table, default=0) + 1, 3), np.nan)
    for vertex_id, (line_no, fields) in table.items():
        try:
            coords[vertex_id] = [float(x) for x in fields]
        except (ValueError, IndexError):
            raise InputError(
                sections.source, f"**vertex: bad vertex {vertex_id}: {' '.join(fields)}", line_no
            ) from None
    if not np.isfinite(coords[list(table)]).all():
        raise InputError(sections.source, "**vertex: coordinates must be finite numbers")
    return coords, set(table)


def _edges(sections: _Sections) -> dict[int, frozenset[int]]:
    """Edge id -> its two vertex ids."""
    edges = {}
    for edge_id, (line_no, fields) in _table(sections, "edge", 2).items():
        try:
            edges[edge_id] = frozenset(int(v) for v in fields)
        except ValueError:
            raise InputError(
                sections.source, f"**edge: bad edge {edge_id}: {' '.join(fields)}", line_no
            ) from None
    return edges


def _faces(
    sections: _Sections, vertex_ids: set[int], edges: dict[int, frozenset[int]]
) -> dict[int, tuple[int, list[int] | None, str | None]]:
    """Face id -> (line, vertex loop or None, error or None).

    A face's entry spans several lines, so the section is read as a stream of numbers; a count
    that does not fit makes the whole file unreadable. A face whose vertices or edges do not
    exist or do not match is kept with an error, which its polyhedra inherit.
    """
    count, lines = sections.entries("face")
    tokens = [(line_no, t) for line_no, text in lines for t in text.split()]
    source = sections.source
    end_line = lines[-1][0] if lines else sections.found["face"][0]
    faces: dict[int, tuple[int, list[int] | None, str | None]] = {}
    k = 0

    def take(n: int, what: str) -> list[int]:
        nonlocal k
        if k + n > len(tokens):
            raise InputError(source, f"**face: the section ends inside {what}", end_line)
        chunk = tokens[k : k + n]
        k += n
        try:
            return [int(t) for _, t in chunk]
        except ValueError:
            raise InputError(source, f"**face: expected integers in {what}", chunk[0][0]) from None

    def take_count(what: str) -> int:
        (number,) = take(1, what)
        if number < 0:
            raise InputError(source, f"**face: {what}: a count of {number}", tokens[k - 1][0])
        return number

    for _ in range(count):
        line_no = tokens[k][0] if k < len(tokens) else end_line
        (face_id,) = take(1, "a face id")
        what = f"face {face_id}"
        loop = take(take_count(what), what)
        signed_edges = take(take_count(what), what)
        tail = tokens[k : k + _FACE_TAIL]
        try:
            if len(tail) < _FACE_TAIL:
                raise ValueError
            [float(t) for _, t in tail]
        except ValueError:
            raise InputError(
                source,
                f"**face: {what}: expected the face equation, state and point (9 numbers)",
                tail[0][0] if tail else end_line,
            ) from None
        k += _FACE_TAIL
        if face_id in faces:
            raise InputError(source, f"**face: face {face_id} appears twice", line_no)
        faces[face_id] = (line_no, *_check_face(face_id, loop, signed_edges, vertex_ids, edges))
    if k != len(tokens):
        raise InputError(
            source, f"**face announces {count} faces but has more numbers", tokens[k][0]
        )
    return faces


def _check_face(
    face_id: int,
    loop: list[int],
    signed_edges: list[int],
    vertex_ids: set[int],
    edges: dict[int, frozenset[int]],
) -> tuple[list[int] | None, str | None]:
    if len(loop) < 3:
        return None, f"face {face_id} has {len(loop)} vertices"
    missing = [v for v in loop if v not in vertex_ids]
    if missing:
        return None, f"face {face_id}: vertex {missing[0]} does not exist"
    if len(set(loop)) != len(loop):
        return None, f"face {face_id} repeats a vertex"
    if len(signed_edges) != len(loop):
        return None, f"face {face_id} has {len(loop)} vertices but {len(signed_edges)} edges"
    # A face's edges go round it as its vertices do, but Neper may start them at another
    # vertex: each side of the loop needs one edge of the list, wherever it is.
    sides = [(loop[j], loop[(j + 1) % len(loop)]) for j in range(len(loop))]
    unmatched = {frozenset(side) for side in sides}
    stray = None
    for signed in signed_edges:
        if abs(signed) not in edges:
            return None, f"face {face_id}: edge {abs(signed)} does not exist"
        ends = edges[abs(signed)]
        if ends in unmatched:
            unmatched.discard(ends)
        elif stray is None:
            stray = abs(signed)
    if stray is not None:
        a, b = next(side for side in sides if frozenset(side) in unmatched)
        return None, f"face {face_id}: edge {stray} does not join vertices {a} and {b}"
    return loop, None


def _measures(
    coords: np.ndarray, grain_loops: list[list[list[int]] | None]
) -> tuple[np.ndarray, np.ndarray]:
    """Volume and area of each grain whose loops are given (NaN otherwise), all at once
    (:func:`grainclass.geometry.polytope_measures`)."""
    loops = [loop for grain in grain_loops if grain for loop in grain]
    grain = [k for k, grain in enumerate(grain_loops) if grain for _ in grain]
    volume, area = polytope_measures(
        coords, *loop_arrays(loops), np.asarray(grain, np.int64), len(grain_loops)
    )
    known = np.asarray([bool(loops) for loops in grain_loops], np.bool_)
    return np.where(known, np.abs(volume), np.nan), np.where(known, area, np.nan)


def read_neper(
    stream: BinaryIO, source: str, chunk_size: int, geometry: bool = False
) -> Iterator[GrainBatch]:
    """Parse a 3D Neper ``.tess`` file (module docstring) into batches of at most
    ``chunk_size`` grains, one a polyhedron, in file order; with ``geometry``, each grain's
    shape too (its faces' polygons, in its face order).

    Raises
    ------
    InputError
        When the file is not a 3D tessellation or its vertex, edge, face or polyhedron section
        cannot be read (a bad polyhedron entry is an invalid grain instead).
    """
    sections = _Sections(stream, source)
    if "general" in sections.found:
        header, lines = sections.found["general"]
        dim = lines[0][1].split()[0] if lines else ""
        if dim != "3":
            raise InputError(
                source, f"only 3D tessellations are read (dimension {dim or '?'})", header
            )
    coords, vertex_ids = _vertices(sections)
    faces = _faces(sections, vertex_ids, _edges(sections))

    count, lines = sections.entries("polyhedron")
    if len(lines) != count:
        raise InputError(
            source,
            f"**polyhedron announces {count} polyhedra but has {len(lines)} entries",
            lines[0][0] if lines else sections.found["polyhedron"][0],
        )
    face_uses: Counter[int] = Counter()
    entries = []  # (grain id, line, signed face ids or None, error or None)
    seen: set[str] = set()
    for line_no, text in lines:
        grain_id = text.split()[0]
        signed, reason = _polyhedron_entry(text.split())
        if signed is not None:
            face_uses.update({abs(f) for f in signed})
        if reason is None and grain_id in seen:
            reason = f"polyhedron {grain_id} appears twice"
        seen.add(grain_id)
        error = None if reason is None else f"bad polyhedron entry: {reason}"
        entries.append((grain_id, line_no, signed if error is None else None, error))

    periodic = "periodic" in sections.found
    rows, grain_loops, boundary = [], [], []
    for grain_id, line_no, signed, error in entries:
        loops = None
        if signed is not None:
            loops, error = _polyhedron_loops(signed, faces)
            if error is not None:
                error = f"polyhedron {grain_id}: {error}"
        rows.append((grain_id, line_no, error))
        grain_loops.append(loops)
        if periodic or loops is None:  # periodic: box faces are not cuts; no loops: no faces
            boundary.append(None)
        else:
            boundary.append(any(face_uses[abs(f)] == 1 for f in signed))
    volume, area = _measures(coords, grain_loops)

    chunk_size = max(chunk_size, 1)
    for start in range(0, len(rows), chunk_size):
        stop = min(start + chunk_size, len(rows))
        batch = batch_from_loops(
            [
                (grain_id, line_no, grain_loops[k], volume[k], area[k], error)
                for k, (grain_id, line_no, error) in enumerate(rows[start:stop], start)
            ],
            source,
            boundary=boundary[start:stop],
            face_labels=[
                None if entry[2] is None else [abs(f) for f in entry[2]]
                for entry in entries[start:stop]
            ],
        )
        if geometry:
            shapes = [_shape(coords, grain_loops[k]) for k in range(start, stop)]
            batch = dataclasses.replace(batch, shapes=shapes)
        yield batch


def _shape(coords: np.ndarray, loops: list[list[int]] | None) -> Shape | None:
    """A grain's faces in space, each its own polygon, in the grain's face order."""
    if loops is None:
        return None
    used = sorted({v for loop in loops for v in loop})
    row = {v: i for i, v in enumerate(used)}
    polygons = tuple(np.array([row[v] for v in loop], np.int64) for loop in loops)
    return Shape(coords[used], polygons, np.arange(len(loops), dtype=np.int64))


def _polyhedron_entry(fields: list[str]) -> tuple[list[int] | None, str | None]:
    """The signed face ids of a polyhedron entry (None if not integers), and what is wrong."""
    try:
        numbers = [int(t) for t in fields]
    except ValueError:
        return None, "expected integers: polyhedron id, number of faces, signed face ids"
    if len(numbers) < 2:
        return None, "the number of faces is missing"
    signed = numbers[2:]
    if numbers[1] != len(signed):
        return signed, f"announces {numbers[1]} faces but lists {len(signed)}"
    return signed, None


def _polyhedron_loops(
    signed: list[int], faces: dict[int, tuple[int, list[int] | None, str | None]]
) -> tuple[list[list[int]] | None, str | None]:
    """The outward vertex loops of a polyhedron's faces, or an error."""
    if len(signed) < 4:
        return None, f"{len(signed)} faces (a polyhedron has at least 4)"
    if len({abs(f) for f in signed}) != len(signed):
        return None, "a face is listed twice"
    loops = []
    for f in signed:
        if f == 0 or abs(f) not in faces:
            return None, f"face {abs(f)} does not exist"
        face_line, loop, face_error = faces[abs(f)]
        if loop is None:
            return None, f"{face_error} (line {face_line})"
        loops.append(loop if f > 0 else loop[::-1])
    # Outward loops run along each edge once each way: a face turned the other way (a wrong
    # sign) runs along an edge the same way as its neighbour, and would make the volume wrong.
    along: dict[tuple[int, int], int] = {}
    for f, loop in zip(signed, loops, strict=True):
        for j in range(len(loop)):
            edge = (loop[j], loop[(j + 1) % len(loop)])
            if edge in along:
                return None, (
                    f"faces {along[edge]} and {abs(f)} both run from vertex {edge[0]} to "
                    f"{edge[1]}: the sign of one of them is wrong"
                )
            along[edge] = abs(f)
    return loops, None
