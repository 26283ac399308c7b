"""Grains from their Weinberg vectors, and the grains the paper names.

A Weinberg vector (``_kernels/weinberg.py``) is a walk on the grain's edge graph: it labels the
corners in order of first arrival and writes the label of every corner reached, turning right at
a corner reached for the first time. Read back, consecutive labels are the edges, and each first
arrival says which edge follows the one arrived by around that corner; three edges meet at a
corner, so that fixes its rotation. Only the first corner is never arrived at first: of its two
rotations, the one whose faces number E - V + 2, as a sphere's must, is the grain's. The walk is
then made again on the grain found, and it must write the vector given: anything else is no
Weinberg vector.

The grain's faces are numbered in the order in which the walk first runs along one of their
edges, each face's neighbours listed counter-clockwise seen from outside, so that the walk that
turns right (``_kernels/weinberg.py``: orientation +1) writes the vector again.
"""

from __future__ import annotations

import itertools
import re
from dataclasses import dataclass

from grainclass.errors import OptionError


@dataclass(frozen=True)
class NamedGrain:
    """A grain known by name: its Weinberg vector and what it is."""

    weinberg: str
    about: str


NAMED_GRAINS: dict[str, NamedGrain] = {
    "tetrahedron": NamedGrain(
        "(1,2,3,1,3,4,1,4,2,4,3,2,1)", "the tetrahedron, the smallest grain (4 faces)"
    ),
    "triangular-prism": NamedGrain(
        "(1,2,3,1,3,4,5,1,5,6,2,6,4,6,5,4,3,2,1)", "the triangular prism (5 faces)"
    ),
    "cube": NamedGrain(
        "(1,2,3,4,1,4,5,6,1,6,7,2,7,8,3,8,5,8,7,6,5,4,3,2,1)",
        "the cube, the smallest flag* grain (6 faces)",
    ),
    "flipped-cube": NamedGrain(
        "(1,2,3,1,3,4,5,1,5,6,7,2,7,8,4,8,6,8,7,6,5,4,3,2,1)",
        "the other grain of 6 faces, p-vector (2,2,2): the cube with an edge flipped "
        "(fig. grains_with_6_faces)",
    ),
    "smallest-sc": NamedGrain(
        "(1,2,3,4,1,4,5,6,1,6,7,2,7,8,9,10,3,10,11,12,5,12,13,8,13,14,9,14,11,14,13,12,11,10,9,"
        "8,7,6,5,4,3,2,1)",
        "the smallest severely constricted grain, p-vector (0,6,0,3) (fig. smallest_nonflag)",
    ),
    "dodecahedron": NamedGrain(
        "(1,2,3,4,5,1,5,6,7,8,1,8,9,10,2,10,11,12,3,12,13,14,4,14,15,6,15,16,17,7,17,18,9,18,"
        "19,11,19,20,13,20,16,20,19,18,17,16,15,14,13,12,11,10,9,8,7,6,5,4,3,2,1)",
        "the dodecahedron, the smallest flag* grain of split type 0:m (12 faces)",
    ),
    "A": NamedGrain(
        "(1,2,3,4,1,4,5,6,1,6,7,8,2,8,9,10,11,3,11,12,5,12,13,14,7,14,15,9,15,16,10,16,13,16,"
        "15,14,13,12,11,10,9,8,7,6,5,4,3,2,1)",
        "the paper's grain A: 10 faces, p-vector (0,4,4,2), two 3:4:3 belts, symmetry 8 "
        "(fig. three_grains)",
    ),
    "B": NamedGrain(
        "(1,2,3,4,1,4,5,6,1,6,7,8,2,8,9,10,3,10,11,12,5,12,13,14,7,14,15,9,15,16,11,16,13,16,"
        "15,14,13,12,11,10,9,8,7,6,5,4,3,2,1)",
        "the paper's grain B: 10 faces, p-vector (0,4,4,2), one 3:4:3 belt, symmetry 2 "
        "(fig. three_grains)",
    ),
    "C": NamedGrain(
        "(1,2,3,4,1,4,5,6,1,6,7,8,9,2,9,10,11,3,11,12,13,5,13,14,7,14,15,8,15,16,10,16,12,16,"
        "15,14,13,12,11,10,9,8,7,6,5,4,3,2,1)",
        "the paper's grain C: 10 faces, p-vector (0,4,4,2), no 3:4:3 belt, symmetry 2 "
        "(fig. three_grains)",
    ),
    "K": NamedGrain(
        "(1,2,3,4,1,4,5,6,7,8,1,8,9,10,11,2,11,12,13,14,3,14,15,16,5,16,17,6,17,18,19,20,7,20,"
        "9,20,19,21,22,10,22,12,22,21,23,24,13,24,15,24,23,18,23,21,19,18,17,16,15,14,13,12,"
        "11,10,9,8,7,6,5,4,3,2,1)",
        "the paper's grain K, Kelvin's cell (the truncated octahedron): 14 faces, p-vector "
        "(0,6,0,8), symmetry 48 (fig. three_grains0608)",
    ),
    "L": NamedGrain(
        "(1,2,3,4,1,4,5,6,1,6,7,8,9,2,9,10,3,10,11,12,5,12,13,14,7,14,15,16,17,8,17,18,11,18,"
        "19,20,13,20,21,22,15,22,23,16,23,24,19,24,21,24,23,22,21,20,19,18,17,16,15,14,13,12,"
        "11,10,9,8,7,6,5,4,3,2,1)",
        "one of the paper's grains L and M: 14 faces, p-vector (0,6,0,8), symmetry 8 "
        "(fig. three_grains0608)",
    ),
    "M": NamedGrain(
        "(1,2,3,4,1,4,5,6,1,6,7,8,9,2,9,10,11,12,3,12,13,14,5,14,15,16,7,16,17,8,17,18,19,10,"
        "19,20,21,22,11,22,13,22,21,23,15,23,24,18,24,20,24,23,21,20,19,18,17,16,15,14,13,12,"
        "11,10,9,8,7,6,5,4,3,2,1)",
        "the other of the paper's grains L and M: 14 faces, p-vector (0,6,0,8), symmetry 4, "
        "chiral (fig. three_grains0608)",
    ),
}
"""Grains by name: those the paper draws and defines in its text. Which of the two other
grains with p-vector (0,6,0,8) the paper calls L and which M its text does not say: L is the
more symmetric here."""


def parse_weinberg(text: str) -> tuple[int, ...]:
    """A Weinberg vector written as grainclass and VoroTop write it, ``(1,2,3,1,...)``, or with
    spaces or commas between its numbers and without the parentheses.

    Raises
    ------
    OptionError
        For anything but positive integers.

    Examples
    --------
    >>> parse_weinberg("(1,2,3,1,3,4,1,4,2,4,3,2,1)")[:4]
    (1, 2, 3, 1)
    """
    body = text.strip().removeprefix("(").removesuffix(")")
    fields = [field for field in re.split(r"[\s,]+", body) if field]
    if not fields or not all(field.isdigit() for field in fields):
        shown = text if len(text) <= 40 else text[:37] + "..."
        raise OptionError("weinberg", f"{shown!r}: a Weinberg vector is (1,2,3,...)")
    return tuple(int(field) for field in fields)


def grain_from_weinberg(code: tuple[int, ...] | str) -> list[list[int]]:
    """The grain whose right-turning Weinberg walk from its first corner writes ``code``: each
    face's neighbours, counter-clockwise seen from outside (see the module's text).

    Raises
    ------
    OptionError
        For a vector that no grain's walk writes.

    Examples
    --------
    >>> grain_from_weinberg("(1,2,3,1,3,4,1,4,2,4,3,2,1)")
    [[3, 1, 2], [3, 2, 0], [3, 0, 1], [2, 1, 0]]
    """
    if isinstance(code, str):
        code = parse_weinberg(code)
    succeeding, first_neighbours = _rotations(code)
    a, b, c = first_neighbours
    for first in ({a: b, b: c, c: a}, {a: c, c: b, b: a}):
        rotation = {**succeeding, 1: first}
        faces = _faces(rotation, code)
        n_corners = len(rotation)
        if len(faces) == n_corners // 2 + 2 and _walk(rotation, code[1]) == code:
            return _neighbour_lists(faces)
    raise _not_a_walk(code)


def _not_a_walk(code: tuple[int, ...] | str) -> OptionError:
    if not isinstance(code, str):
        code = "(" + ",".join(map(str, code)) + ")"
    shown = code if len(code) <= 40 else code[:37] + "..."
    return OptionError("weinberg", f"{shown}: no grain's Weinberg walk writes this")


def _rotations(
    code: tuple[int, ...],
) -> tuple[dict[int, dict[int, int]], list[int]]:
    """Each corner's rotation but the first's (for each of its neighbours, the one after it in
    the walk's turning direction), and the first corner's neighbours. Checks what a walk on a
    grain's edge graph writes: labels in order of first arrival, every edge run along once
    each way, three edges at every corner."""
    n_corners = max(code)
    n_edges = 3 * n_corners // 2
    if code[0] != 1 or n_corners < 4 or n_corners % 2 or len(code) != 2 * n_edges + 1:
        raise _not_a_walk(code)
    darts = list(itertools.pairwise(code))
    unique = set(darts)
    if len(unique) != len(darts) or any(u == v or (v, u) not in unique for u, v in darts):
        raise _not_a_walk(code)
    neighbours: dict[int, list[int]] = {v: [] for v in range(1, n_corners + 1)}
    for u, v in darts:
        neighbours[u].append(v)
    if any(len(around) != 3 for around in neighbours.values()):
        raise _not_a_walk(code)
    rotation: dict[int, dict[int, int]] = {}
    newest = 1
    for i in range(1, len(code) - 1):
        v = code[i]
        if v > newest + 1:
            raise _not_a_walk(code)  # labels come in order of first arrival
        if v == newest + 1:
            newest = v
            u, w = code[i - 1], code[i + 1]
            (x,) = set(neighbours[v]) - {u, w}
            rotation[v] = {u: w, w: x, x: u}
    return rotation, neighbours[1]


def _faces(
    rotation: dict[int, dict[int, int]], code: tuple[int, ...]
) -> list[list[tuple[int, int]]]:
    """The faces of a rotation system, each as its darts u -> v counter-clockwise around it
    seen from outside (after u -> v comes v -> the corner before u around v), in the order of
    the walk's first dart along each."""
    preceding = {v: {w: u for u, w in after.items()} for v, after in rotation.items()}
    face_of: dict[tuple[int, int], int] = {}
    faces: list[list[tuple[int, int]]] = []
    for dart in itertools.pairwise(code):
        if dart in face_of:
            continue
        face: list[tuple[int, int]] = []
        u, v = dart
        while (u, v) not in face_of:
            face_of[(u, v)] = len(faces)
            face.append((u, v))
            u, v = v, preceding[v][u]
        faces.append(face)
    return faces


def _neighbour_lists(faces: list[list[tuple[int, int]]]) -> list[list[int]]:
    """Each face's neighbours in the order of its darts: across dart u -> v, the face of v -> u."""
    face_of = {dart: f for f, face in enumerate(faces) for dart in face}
    return [[face_of[(v, u)] for u, v in face] for face in faces]


def _walk(rotation: dict[int, dict[int, int]], second: int) -> tuple[int, ...]:
    """The labels the right-turning walk writes that leaves corner 1 towards ``second``."""
    label = {1: 1, second: 2}
    used = {(1, second)}
    written = [1, 2]
    previous, current = 1, second
    arrived_new = True
    for _ in range(3 * len(rotation) - 1):
        after = rotation[current]
        if arrived_new:
            going = after[previous]
        elif (current, previous) not in used:
            going = previous
        else:
            going = after[previous]
            if (current, going) in used:
                going = after[going]
        if (current, going) in used:
            break
        used.add((current, going))
        previous, current = current, going
        arrived_new = current not in label
        if arrived_new:
            label[current] = len(label) + 1
        written.append(label[current])
    return tuple(written)
