"""A closed body's faces and their neighbours in cyclic order.

A grain's faces are its patches joined across the edges that are not triple lines: what lies
across two patches (:class:`Across`: the other bodies that list their facets, the sample's
boundary, the outward normal there) must agree for them to join. Each face's boundary is then
walked from a corner (:func:`_walk_faces`), and every run of darts along one neighbouring face
is one neighbour.
"""

import math
from typing import NamedTuple

import numpy as np

from grainclass._kernels.evolver.codes import GRAIN_NO_TRIPLE, GRAIN_NOT_DISC, GRAIN_OK
from grainclass._kernels.evolver.periodic import _dot3
from grainclass._numba import njit, njit_leaf


class Across(NamedTuple):
    """What lies across each patch of a body."""

    bodies: np.ndarray
    """int64[m, 3]: how many other bodies list its facet (the body's own image counts), then
    the first two of them (the body itself for a facet it lists twice; -1: none)"""
    outside: np.ndarray
    """bool[m]: no other body lists its facet (the sample's boundary)"""
    normal: np.ndarray
    """float64[m, 3]: its unit normal, where the file marks no triple lines (else zero)"""


class Boundaries(NamedTuple):
    """The darts on each face's boundary, and how many triple lines meet at each corner."""

    start: np.ndarray
    """int64[faces + 1]: face ``f`` has darts ``dart[start[f]:start[f + 1]]``"""
    dart: np.ndarray
    degree: np.ndarray
    """int64[corners]"""


@njit(inline="always")
def _across(patches, j, facets, scratch):
    """The bodies across each patch of body ``j`` and whether it is on the sample's boundary
    (the first two fields of :class:`Across`)."""
    m = patches.slot.shape[0]
    bodies = np.full((m, 3), -1, np.int64)
    outside = np.zeros(m, np.bool_)
    for o in range(m):
        s = patches.slot[o]
        others = facets.listed[s] - scratch.facet_times[s]
        x = 1
        for r in range(min(facets.listed[s], 3)):
            if facets.lister[s, r] != j and x < 3:
                bodies[o, x] = facets.lister[s, r]
                x += 1
        if scratch.facet_times[s] == 2:
            others += 1
            bodies[o, 2] = bodies[o, 1]
            bodies[o, 1] = j
        bodies[o, 0] = others
        outside[o] = others == 0
    return bodies, outside


@njit(inline="always")
def _normals(darts, corners, position, marked):
    """Each patch's unit normal from its corners' positions (zero where ``marked``: the triple
    lines are given, and the normals are not needed)."""
    m = darts.start.shape[0] - 1
    normal = np.zeros((m, 3))
    if marked:
        return normal
    for o in range(m):
        for d in range(darts.start[o], darts.start[o + 1]):
            pa, pb = position[corners.tail[d]], position[corners.head[d]]
            normal[o, 0] += pa[1] * pb[2] - pa[2] * pb[1]
            normal[o, 1] += pa[2] * pb[0] - pa[0] * pb[2]
            normal[o, 2] += pa[0] * pb[1] - pa[1] * pb[0]
        length = math.sqrt(_dot3(normal[o], normal[o]))
        for x in range(3):
            normal[o, x] = normal[o, x] / length if length > 0 else 0.0
    return normal


@njit_leaf
def _root(parent, k):
    while parent[k] != k:
        parent[k] = parent[parent[k]]
        k = parent[k]
    return k


@njit(inline="always")
def _join_faces(darts, across, tables):
    """The face of each patch: patches joined across edges that are not triple lines (not
    marked, on at most two facets of the file), where the same bodies lie across both and, on
    the sample's boundary of a file without marks, the two are flat. Returns ``(face,
    faces)``."""
    m = darts.start.shape[0] - 1
    bodies = across.bodies
    parent = np.empty(m, np.int64)
    for o in range(m):
        parent[o] = o
    for d in range(darts.patch.shape[0]):
        p = darts.partner[d]
        if p < d:
            continue
        o, o2 = darts.patch[d], darts.patch[p]
        es = darts.edge[d]
        if tables.edges.triple[es] or tables.uses.count[es] > 2:
            continue
        if bodies[o, 0] != bodies[o2, 0] or bodies[o, 1] != bodies[o2, 1]:
            continue
        if bodies[o, 2] != bodies[o2, 2]:
            continue
        if (
            not tables.marked
            and across.outside[o]
            and _dot3(across.normal[o], across.normal[o2]) < 1 - 1e-9
        ):
            continue
        ra, rb = _root(parent, o), _root(parent, o2)
        parent[ra] = rb
    face = np.full(m, -1, np.int64)
    face_of_root = np.full(m, -1, np.int64)
    n_faces = 0
    for o in range(m):
        r = _root(parent, o)
        if face_of_root[r] < 0:
            face_of_root[r] = n_faces
            n_faces += 1
        face[o] = face_of_root[r]
    return face, n_faces


@njit(inline="always")
def _boundaries(darts, corners, face, n_faces):
    """The darts between two faces, by face, and the corners' numbers of triple lines:
    ``(boundaries, triple line segments)``."""
    degree = np.zeros(corners.key.shape[0], np.int64)
    start = np.zeros(n_faces + 1, np.int64)
    separating = 0
    for d in range(darts.patch.shape[0]):
        p = darts.partner[d]
        if face[darts.patch[d]] != face[darts.patch[p]]:
            start[face[darts.patch[d]] + 1] += 1
            if d < p:
                separating += 1
                degree[corners.tail[d]] += 1
                degree[corners.head[d]] += 1
    for f in range(n_faces):
        start[f + 1] += start[f]
    dart = np.empty(start[n_faces], np.int64)
    fill = start[:-1].copy()
    for d in range(darts.patch.shape[0]):
        f = face[darts.patch[d]]
        if f != face[darts.patch[darts.partner[d]]]:
            dart[fill[f]] = d
            fill[f] += 1
    return Boundaries(start, dart, degree), separating


@njit(inline="always")
def _walk_faces(darts, corners, face, n_faces, out):
    """Walk each face's boundary from a corner: its neighbours in cyclic order, into
    ``out.nbr_counts`` and ``out.neighbours``. Returns ``(GRAIN_ code, neighbours)``."""
    boundaries, separating = _boundaries(darts, corners, face, n_faces)
    if separating == 0:
        return GRAIN_NO_TRIPLE, 0
    n_darts = darts.patch.shape[0]
    n_corners = corners.key.shape[0]
    leaving = np.full(n_corners, -1, np.int64)
    leaving_face = np.full(n_corners, -1, np.int64)
    next_leaving = np.empty(n_darts, np.int64)
    used = np.zeros(n_darts, np.bool_)
    loop = np.empty(n_darts, np.int64)
    degree, neighbours = boundaries.degree, out.neighbours
    n_nbrs = 0
    for f in range(n_faces):
        b0, b1 = boundaries.start[f], boundaries.start[f + 1]
        for w in range(b1 - 1, b0 - 1, -1):
            d = boundaries.dart[w]
            v = corners.tail[d]
            if leaving_face[v] != f:
                leaving_face[v], leaving[v] = f, -1
            next_leaving[d] = leaving[v]
            leaving[v] = d
        first = boundaries.dart[b0]
        for w in range(b0, b1):
            if degree[corners.tail[boundaries.dart[w]]] >= 3:
                first = boundaries.dart[w]
                break
        length = 0
        d = first
        while not used[d]:
            used[d] = True
            loop[length] = d
            length += 1
            v = corners.head[d]
            nd = leaving[v] if leaving_face[v] == f else -1
            while nd >= 0 and used[nd]:
                nd = next_leaving[nd]
            if nd < 0:
                break
            d = nd
        if length != b1 - b0:
            out.params[0] = f
            return GRAIN_NOT_DISC, n_nbrs
        first_nbr = n_nbrs
        for i in range(length):
            d = loop[i]
            g = face[darts.patch[darts.partner[d]]]
            if i == 0 or degree[corners.tail[d]] >= 3 or g != neighbours[n_nbrs - 1]:
                neighbours[n_nbrs] = g
                n_nbrs += 1
        if (
            n_nbrs - first_nbr > 1
            and neighbours[first_nbr] == neighbours[n_nbrs - 1]
            and degree[corners.tail[loop[0]]] < 3
        ):
            n_nbrs -= 1  # the walk started inside a triple line: its two ends are one
        out.nbr_counts[f] = n_nbrs - first_nbr
    return GRAIN_OK, n_nbrs
