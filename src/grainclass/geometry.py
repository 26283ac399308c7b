"""Volumes and surface areas of polytopes given as polygon loops, and the polygons' unit normals.

One layout serves every reader that has corner positions (Surface Evolver, Neper, Voronoi):

- ``positions``: float64[V, 3], the corners;
- ``corners``: int[C], rows of ``positions``, polygon after polygon;
- ``loop_offsets``: int[L + 1], polygon l is ``corners[loop_offsets[l]:loop_offsets[l + 1]]``,
  three corners or more, in order around it;
- ``polytope``: int[L], the polytope that polygon l bounds.

A polytope's loops turn the same way seen from outside (counter-clockwise for a positive
volume). Each polygon is fanned into triangles from its first corner; the area is the sum of the
triangles' areas and the volume the divergence theorem over them, both summed triangle after
triangle. The volume is taken relative to the polytope's first corner (the first of its first
polygon): the same for a closed surface, and it keeps its digits far from the origin.
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence

import numpy as np

from grainclass.batch import offsets_from_counts


def loop_arrays(loops: Sequence[Sequence[int]]) -> tuple[np.ndarray, np.ndarray]:
    """``(corners, loop_offsets)`` of polygons given as lists of corners.

    Examples
    --------
    >>> corners, offsets = loop_arrays([[0, 1, 2], [0, 2, 3, 1]])
    >>> corners.tolist(), offsets.tolist()
    ([0, 1, 2, 0, 2, 3, 1], [0, 3, 7])
    """
    loop_offsets = offsets_from_counts([len(loop) for loop in loops])
    corners = np.fromiter(itertools.chain.from_iterable(loops), np.int64, loop_offsets[-1])
    return corners, loop_offsets


def polytope_measures(
    positions: np.ndarray,
    corners: np.ndarray,
    loop_offsets: np.ndarray,
    polytope: np.ndarray,
    n_polytopes: int,
) -> tuple[np.ndarray, np.ndarray]:
    """Signed volume and surface area of each polytope (module docstring); 0 and 0 for one
    without polygons.

    Examples
    --------
    The unit cube, its faces counter-clockwise seen from outside:

    >>> cube = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float)
    >>> faces = [[0, 1, 3, 2], [4, 6, 7, 5], [0, 4, 5, 1], [2, 3, 7, 6], [0, 2, 6, 4], [1, 5, 7, 3]]
    >>> volume, area = polytope_measures(cube, *loop_arrays(faces), np.zeros(6, int), 1)
    >>> float(volume[0]), float(area[0])
    (1.0, 6.0)
    """
    loop_offsets = np.asarray(loop_offsets, np.int64)
    fans = np.diff(loop_offsets) - 2  # triangles of each polygon
    loop = np.repeat(np.arange(len(fans)), fans)  # the polygon of each triangle
    step = np.arange(len(loop)) - np.repeat(offsets_from_counts(fans)[:-1], fans)
    first = loop_offsets[loop]
    owner = np.asarray(polytope, np.int64)[loop]
    _, first_loop = np.unique(polytope, return_index=True)
    origin = np.zeros(n_polytopes, np.int64)
    origin[np.asarray(polytope)[first_loop]] = corners[loop_offsets[first_loop]]
    o = positions[origin[owner]]
    a = positions[corners[first]] - o
    b = positions[corners[first + step + 1]] - o
    c = positions[corners[first + step + 2]] - o
    cross = np.cross(b - a, c - a)
    area = 0.5 * np.bincount(owner, np.linalg.norm(cross, axis=1), minlength=n_polytopes)
    volume = np.bincount(owner, np.einsum("ij,ij->i", a, cross), minlength=n_polytopes) / 6.0
    return volume, area


def unit_normals(
    positions: np.ndarray, corners: np.ndarray, loop_offsets: np.ndarray
) -> np.ndarray:
    """Newell's normal of every polygon, of length 1 (0 for a degenerate one): float64[L, 3].

    Examples
    --------
    >>> square = np.array([[0, 0, 5], [1, 0, 5], [1, 1, 5], [0, 1, 5]], float)
    >>> unit_normals(square, *loop_arrays([[0, 1, 2, 3]])).tolist()
    [[0.0, 0.0, 1.0]]
    """
    loop_offsets = np.asarray(loop_offsets, np.int64)
    sizes = np.diff(loop_offsets)
    loop = np.repeat(np.arange(len(sizes)), sizes)  # the polygon of each corner
    following = np.arange(1, len(corners) + 1)
    following[loop_offsets[1:] - 1] = loop_offsets[:-1]  # the last corner is followed by the first
    total = np.zeros((len(sizes), 3))
    np.add.at(total, loop, np.cross(positions[corners], positions[corners[following]]))
    length = np.linalg.norm(total, axis=1, keepdims=True)
    return np.divide(total, length, out=np.zeros_like(total), where=length > 0)
