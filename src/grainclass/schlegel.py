"""The Schlegel diagram of a grain: its corners and edges drawn straight in the plane, one face
as the outer boundary and every other face a convex polygon inside it; and the grain's belts.

A grain is given by its faces' neighbour lists, each in cyclic order and all turning the same
way (counter-clockwise seen from outside, as the readers take them): the rotation lists of the
dual triangulation. The grain's corners are the dual's triangles. The dart a -> b names the
corner (a, b, c) with c the face after b around a; face a's polygon is the corners of its darts
in the order of its list, and the edge between faces a and b joins the corners of the darts
a -> b and b -> a.

The embedding is Tutte's (1963): the outer face's corners evenly on a circle, every other
corner a weighted mean of its three neighbours, found by one linear solve. The edge graph of a
simple 3-polytope is planar and 3-connected, and for such a graph any positive weights give a
drawing in which no edges cross and every inner face is a convex polygon (Tutte's proof holds
for any positive weights: Gortler, Gotsman and Thurston 2006). Equal weights crowd the corners
far from the outer face into a tiny middle; an edge d edges away from the outer face's corners
weighs :data:`DEPTH_FALLOFF` to the power -d instead, so that the inner corners pull one
another in less and the middle spreads out.

Seen from just outside the outer face, as a Schlegel diagram projects the polytope, the outer
face's corners run counter-clockwise and every other face, seen through it from inside, turns
clockwise.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from grainclass.batch import Shape
from grainclass.errors import DataError

Lists = Sequence[Sequence[int]]

DEPTH_FALLOFF = 1.5
"""How much less an edge one step further from the outer face pulls: 1 is Tutte's equal
weights; from about 2 on the outermost ring of faces thins to slivers."""


@dataclass(frozen=True)
class Diagram:
    """A grain's Schlegel diagram.

    Attributes
    ----------
    lists : tuple of tuple of int
        Each face's neighbours, in cyclic order, all turning one way.
    corners : numpy.ndarray of int64, shape (V, 3)
        The three faces at each corner, in the order of the dart that first names it.
    faces : tuple of tuple of int
        Each face's corners in the order of its neighbour list: the corner between its
        neighbours ``lists[f][i]`` and ``lists[f][i + 1]`` is ``faces[f][i]``.
    edges : numpy.ndarray of int64, shape (E, 4)
        Each edge as (corner, corner, face, face), the faces in increasing order; edges in the
        order of their first face, then of the second in its list.
    outer_face : int
        The face whose polygon bounds the drawing.
    positions : numpy.ndarray of float64, shape (V, 2)
        Each corner's place: the outer face's on the unit circle.
    """

    lists: tuple[tuple[int, ...], ...]
    corners: np.ndarray
    faces: tuple[tuple[int, ...], ...]
    edges: np.ndarray
    outer_face: int
    positions: np.ndarray

    @property
    def n_faces(self) -> int:
        return len(self.lists)

    def polygon(self, face: int) -> np.ndarray:
        """The corners of ``face`` in the plane, float64[k, 2], in the order of ``faces``."""
        return self.positions[list(self.faces[face])]

    def centre(self, face: int) -> np.ndarray:
        """The mean of a face's corners: inside it, for an inner face, which is convex."""
        return self.polygon(face).mean(axis=0)

    def edge_between(self, a: int, b: int) -> int:
        """The row of ``edges`` of the edge between faces ``a`` and ``b``.

        Raises
        ------
        KeyError
            When the two faces do not meet.
        """
        return self._edge_rows[(min(a, b), max(a, b))]

    @property
    def _edge_rows(self) -> dict[tuple[int, int], int]:
        rows = self.__dict__.get("_rows")
        if rows is None:
            rows = {(int(e[2]), int(e[3])): i for i, e in enumerate(self.edges)}
            object.__setattr__(self, "_rows", rows)
        return rows


def structure(lists: Lists) -> tuple[np.ndarray, tuple[tuple[int, ...], ...], np.ndarray]:
    """The corners, face polygons and edges of a grain (see :class:`Diagram`), from its
    neighbour lists, which must be those of an ok grain, turning one way.

    Examples
    --------
    >>> tetrahedron = [[1, 2, 3], [0, 3, 2], [0, 1, 3], [0, 2, 1]]
    >>> corners, faces, edges = structure(tetrahedron)
    >>> len(corners), faces[0], edges[:2].tolist()
    (4, (0, 1, 2), [[0, 2, 0, 1], [1, 0, 0, 2]])
    """
    position = [{b: i for i, b in enumerate(nbrs)} for nbrs in lists]
    corner_of: dict[frozenset[int], int] = {}
    corners: list[tuple[int, int, int]] = []
    faces = []
    for a, nbrs in enumerate(lists):
        polygon = []
        for i, b in enumerate(nbrs):
            c = nbrs[(i + 1) % len(nbrs)]
            key = frozenset((a, b, c))
            if key not in corner_of:
                corner_of[key] = len(corners)
                corners.append((a, b, c))
            polygon.append(corner_of[key])
        faces.append(tuple(polygon))
    edges = []
    for a, nbrs in enumerate(lists):
        for i, b in enumerate(nbrs):
            if a < b:
                # The corner of dart a -> b is polygon i of a; that of b -> a polygon j of b.
                j = position[b][a]
                edges.append((faces[a][i], faces[b][j], a, b))
    return np.array(corners, np.int64), tuple(faces), np.array(edges, np.int64).reshape(-1, 4)


def largest_face(lists: Lists) -> int:
    """The default outer face: one with the most sides, and of those the one whose farthest
    face is fewest steps away in the dual graph (the first such): the diagram nests as many
    rings of faces inside the outer face as that distance, and the fewer, the less crowded
    its middle.

    >>> cube_truncated = [[1, 2, 3], [0, 3, 4, 5, 2], [0, 1, 5, 6, 3], [0, 2, 6, 4, 1],
    ...                   [1, 3, 6, 5], [1, 4, 6, 2], [2, 5, 4, 3]]
    >>> largest_face(cube_truncated)
    1
    """
    sizes = [len(nbrs) for nbrs in lists]
    most = max(sizes)
    candidates = [f for f, size in enumerate(sizes) if size == most]
    return min(candidates, key=lambda f: (_eccentricity(lists, f), f))


def _eccentricity(lists: Lists, face: int) -> int:
    """Steps from ``face`` to the farthest face in the dual graph."""
    distance = {face: 0}
    frontier = [face]
    while frontier:
        following = []
        for f in frontier:
            for g in lists[f]:
                if g not in distance:
                    distance[g] = distance[f] + 1
                    following.append(g)
        frontier = following
    return max(distance.values())


def diagram(lists: Lists, outer_face: int | None = None) -> Diagram:
    """The Schlegel diagram of an ok grain with ``outer_face`` (default:
    :func:`largest_face`) as the outer boundary.

    Raises
    ------
    DataError
        For an outer face that is not one of the grain's.

    Examples
    --------
    >>> cube = [[1, 2, 3, 4], [0, 4, 5, 2], [0, 1, 5, 3], [0, 2, 5, 4], [0, 3, 5, 1], [1, 4, 3, 2]]
    >>> d = diagram(cube, outer_face=5)
    >>> np.round(np.hypot(*d.polygon(5).T), 6).tolist()  # the outer face on the unit circle
    [1.0, 1.0, 1.0, 1.0]
    >>> bool(np.abs(d.polygon(0)).max() < 1)
    True
    """
    lists = tuple(tuple(int(x) for x in nbrs) for nbrs in lists)
    n = len(lists)
    if outer_face is None:
        outer_face = largest_face(lists)
    if not 0 <= outer_face < n:
        raise DataError(f"the grain has {n} faces, 0 to {n - 1}: there is no face {outer_face}")
    corners, faces, edges = structure(lists)
    positions = _tutte(len(corners), edges[:, :2], faces[outer_face])
    return Diagram(lists, corners, faces, edges, outer_face, positions)


def _tutte(n_corners: int, links: np.ndarray, boundary: Sequence[int]) -> np.ndarray:
    """Corner positions: ``boundary`` counter-clockwise on the unit circle, starting at the
    top, every other corner the weighted mean of its neighbours (see the module's text)."""
    positions = np.zeros((n_corners, 2))
    k = len(boundary)
    angles = np.pi / 2 + 2 * np.pi * np.arange(k) / k
    positions[list(boundary)] = np.column_stack([np.cos(angles), np.sin(angles)])
    depth = _depths(n_corners, links, boundary)
    inner = depth > 0
    if inner.any():
        weights = DEPTH_FALLOFF ** -np.minimum(depth[links[:, 0]], depth[links[:, 1]])
        index = np.cumsum(inner) - 1
        _solve(positions, links, weights.astype(float), inner, index)
    return positions


def _depths(n_corners: int, links: np.ndarray, boundary: Sequence[int]) -> np.ndarray:
    """Each corner's distance, in edges, from the nearest corner of ``boundary``."""
    neighbours: list[list[int]] = [[] for _ in range(n_corners)]
    for u, v in links.tolist():
        neighbours[u].append(v)
        neighbours[v].append(u)
    depth = np.full(n_corners, -1, np.int64)
    frontier = list(boundary)
    depth[frontier] = 0
    while frontier:
        following = []
        for u in frontier:
            for v in neighbours[u]:
                if depth[v] < 0:
                    depth[v] = depth[u] + 1
                    following.append(v)
        frontier = following
    return depth


def _solve(
    positions: np.ndarray,
    links: np.ndarray,
    weights: np.ndarray,
    inner: np.ndarray,
    index: np.ndarray,
) -> None:
    """Place every inner corner at the weighted mean of its neighbours, the others fixed."""
    m = int(inner.sum())
    matrix = np.zeros((m, m))
    rhs = np.zeros((m, 2))
    for (u, v), w in zip(links.tolist(), weights.tolist(), strict=True):
        for a, b in ((u, v), (v, u)):
            if not inner[a]:
                continue
            i = index[a]
            matrix[i, i] += w
            if inner[b]:
                matrix[i, index[b]] -= w
            else:
                rhs[i] += w * positions[b]
    positions[inner] = np.linalg.solve(matrix, rhs)


@dataclass(frozen=True)
class Belt:
    """An l-belt: ``faces`` in cyclic order, from the smallest, towards the smaller of its two
    neighbours in the belt; ``sides`` the numbers of faces of the two discs its removal
    leaves, the smaller first (its split type is sides[0]:l:sides[1])."""

    faces: tuple[int, ...]
    sides: tuple[int, int]


def belts(lists: Lists, length: int) -> list[Belt]:
    """Every ``length``-belt of an ok grain (for length 3 the non-trivial ones, whose three
    faces share no corner), in the order of their faces.

    A belt is a chordless cycle of the dual graph; each is grown once, from its smallest face
    s, as a path s, p1, p2, ... through faces above s, each next to the last and to none before
    it (s only where it closes the cycle), kept in the direction in which p1 is the smaller end.

    Examples
    --------
    >>> cube = [[1, 2, 3, 4], [0, 4, 5, 2], [0, 1, 5, 3], [0, 2, 5, 4], [0, 3, 5, 1], [1, 4, 3, 2]]
    >>> [(b.faces, b.sides) for b in belts(cube, 4)]
    [((0, 1, 5, 3), (1, 1)), ((0, 2, 5, 4), (1, 1)), ((1, 2, 3, 4), (1, 1))]
    >>> belts(cube, 3)
    []
    """
    neighbours = [frozenset(nbrs) for nbrs in lists]
    found: list[Belt] = []

    def grow(path: list[int]) -> None:
        s, last = path[0], path[-1]
        if len(path) == length:
            if s in neighbours[last] and path[1] < last:
                sides = _sides(neighbours, path)
                if sides is not None:
                    found.append(Belt(tuple(path), sides))
            return
        closing = len(path) == length - 1
        for x in sorted(neighbours[last]):
            if x <= s or x in path:
                continue
            if any(x in neighbours[p] for p in path[1:-1]):
                continue
            if (s in neighbours[x]) != closing and len(path) > 1:
                continue  # a chord to s, or a path that cannot close
            grow([*path, x])

    for s in range(len(lists)):
        grow([s])
    return sorted(found, key=lambda belt: belt.faces)


def _sides(neighbours: list[frozenset[int]], belt: list[int]) -> tuple[int, int] | None:
    """The sizes of the two discs the removal of ``belt`` leaves, the smaller first; None for
    a belt that leaves one (three faces around a corner)."""
    n = len(neighbours)
    seen = [False] * n
    for face in belt:
        seen[face] = True
    sizes = []
    for start in range(n):
        if seen[start]:
            continue
        seen[start] = True
        stack, size = [start], 0
        while stack:
            face = stack.pop()
            size += 1
            for x in neighbours[face]:
                if not seen[x]:
                    seen[x] = True
                    stack.append(x)
        sizes.append(size)
    if len(sizes) != 2:
        return None
    return min(sizes), max(sizes)


@dataclass(frozen=True)
class Truncations:
    """A grain's reverse truncations (Lutz et al. Sec. II.B): each face's ``depth`` in its
    truncation tree (1 for a root, 0 for a face of the fundamental polytope) and its
    ``parent`` there (-1 for a root or a fundamental face), and the forest as the ``trees``
    column writes it (None for a stacked grain, whose column is null)."""

    depth: tuple[int, ...]
    parent: tuple[int, ...]
    forest: str | None


@dataclass(frozen=True)
class GrainDrawing:
    """One grain as ``grainclass draw`` draws it: its diagram and what is drawn on it.

    ``title`` and ``caption`` head its panels; ``face_ids`` name its faces (the input's face
    ids where it has them, else their 0-based positions); ``labels`` says which of the two
    (or nothing) each face shows (:data:`grainclass.vocabulary.FACE_LABELS`). ``flips`` gives
    each edge of ``diagram.edges`` what its flip gives
    (:data:`grainclass.vocabulary.FLIP_RESULTS`), ``belts`` the belts drawn, one panel each,
    ``belt_numbers`` their numbers among the grain's ``belt_count`` belts of ``belt_length``
    faces, from 1; ``truncations`` the faces reverse truncations remove; ``shape`` the grain
    in space. ``fields`` is what the drawing's data says of the grain besides (source,
    Weinberg vector, p-vector, class, split type, count, ...).
    """

    grain_id: str
    title: str
    caption: str
    diagram: Diagram
    face_ids: tuple[str, ...]
    labels: str = "sides"
    dual: bool = False
    flips: tuple[str, ...] | None = None
    belt_length: int | None = None
    belts: tuple[Belt, ...] = ()
    belt_numbers: tuple[int, ...] = ()
    belt_count: int = 0
    truncations: Truncations | None = None
    shape: Shape | None = None
    fields: dict = field(default_factory=dict)

    def label(self, face: int) -> str:
        """What face ``face`` is labelled with."""
        if self.labels == "sides":
            return str(len(self.diagram.lists[face]))
        if self.labels == "ids":
            return self.face_ids[face]
        return ""


def drawing_data(drawings: Sequence[GrainDrawing]) -> dict:
    """What is drawn, as plain data for JSON: per grain its id, its corners' places
    (``vertices``), each face's corners in the input's face order, the outer face, each face's
    label and label place, its edges (with what their flips give, where drawn), its belts
    (where drawn) and its truncations (where drawn), and the ``fields`` of
    :class:`GrainDrawing`."""
    grains = []
    for drawing in drawings:
        d = drawing.diagram
        entry: dict = {"grain_id": drawing.grain_id, **drawing.fields}
        entry["vertices"] = [[round(x, 6), round(y, 6)] for x, y in d.positions.tolist()]
        entry["faces"] = [list(face) for face in d.faces]
        entry["outer_face"] = d.outer_face
        entry["face_ids"] = list(drawing.face_ids)
        entry["labels"] = [drawing.label(f) for f in range(d.n_faces)]
        entry["label_places"] = [
            [round(float(x), 6) for x in label_place(d, f)] for f in range(d.n_faces)
        ]
        edges = []
        for i, (a, b, f, g) in enumerate(d.edges.tolist()):
            edge: dict = {"corners": [a, b], "faces": [f, g]}
            if drawing.flips is not None:
                edge["flip"] = drawing.flips[i]
            edges.append(edge)
        entry["edges"] = edges
        if drawing.belt_length is not None:
            entry["belt_length"] = drawing.belt_length
            entry["belts"] = [list(belt.faces) for belt in drawing.belts]
            entry["belt_sides"] = [list(belt.sides) for belt in drawing.belts]
            entry["belt_numbers"] = list(drawing.belt_numbers)
            entry["belt_count"] = drawing.belt_count
        if drawing.truncations is not None:
            entry["truncation_depth"] = list(drawing.truncations.depth)
            entry["truncation_parent"] = list(drawing.truncations.parent)
            entry["trees"] = drawing.truncations.forest
        if drawing.shape is not None:
            shape = drawing.shape
            entry["shape"] = {
                "positions": shape.positions.tolist(),
                "polygons": [polygon.tolist() for polygon in shape.polygons],
                "polygon_faces": None if shape.face is None else shape.face.tolist(),
            }
        grains.append(entry)
    return {"grains": grains}


OUTER_LABEL_ANGLE = -np.pi / 4
"""Where the outer face's label stands: outside the drawing, to the lower right."""


def label_place(d: Diagram, face: int) -> np.ndarray:
    """Where ``face``'s label (and its dual vertex) is drawn: its centre, or for the outer
    face a point just outside the unit circle."""
    if face == d.outer_face:
        return 1.18 * np.array([np.cos(OUTER_LABEL_ANGLE), np.sin(OUTER_LABEL_ANGLE)])
    return d.centre(face)
