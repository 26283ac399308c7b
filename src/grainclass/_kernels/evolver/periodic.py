"""Unwrapping a body across the periodic box: darts paired by the geometry around an edge,
each patch's lattice translation, and the cell's corners as (vertex, translation) pairs.

In a periodic file every patch sits at a translation of its facet's own frame; the patches'
common edges (the darts' partners) give the translations (:func:`_translations`), and the
translations give the corners (:class:`Corners`) and their positions. Where a cell meets its
own image along an edge, it has more than two darts on the edge, and :func:`_pair_ambiguous`
pairs them by turning about the edge (:func:`_pair_around`). A file that is not periodic has
no wrap marks: every translation is zero and every corner a vertex.
"""

import math
from typing import NamedTuple

import numpy as np

from grainclass._kernels.evolver.codes import GRAIN_OK, GRAIN_POINT_EDGE, GRAIN_UNPAIRED
from grainclass._kernels.evolver.patches import _undefined_vertex
from grainclass._numba import njit, njit_leaf

NO_LENGTH = -2  # what _pair_around gives for an edge of no length, beside a vertex key or -1


class Geometry(NamedTuple):
    """Where a file's vertices are."""

    xyz: np.ndarray
    """float64[n, 3]: the entries' coordinates (``Entries.xyz``)"""
    periods: np.ndarray
    """float64[3, 3]: the file's periods, one per row"""
    periodic: bool


class EdgeDarts(NamedTuple):
    """The body's edges (``patches.BodyEdges``) and the darts on each: edge ``k`` has darts
    ``dart[start[k]:start[k + 1]]``."""

    slot: np.ndarray
    count: np.ndarray
    start: np.ndarray
    dart: np.ndarray


class Corners(NamedTuple):
    """A body's corners, (vertex, translation) pairs, and the corners each dart joins."""

    key: np.ndarray
    """int64[c]: the vertex's key"""
    shift: np.ndarray
    """int64[c, 3]: the translation"""
    tail: np.ndarray
    """int64[n]: each dart's tail corner"""
    head: np.ndarray
    """int64[n]: its head corner"""


@njit_leaf
def _dot3(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


@njit_leaf
def _shifted(geometry, entry, off, out):
    """The position of vertex ``entry`` translated by ``off`` (whole periods) into ``out``."""
    xyz, periods = geometry.xyz, geometry.periods
    for k in range(3):
        out[k] = (
            xyz[entry, k] + off[0] * periods[0, k] + off[1] * periods[1, k] + off[2] * periods[2, k]
        )


@njit(inline="always")
def _pair_ambiguous(patches, darts, body_edges, tables, scratch, stamp, geometry, params):
    """GRAIN_OK with the darts of edges that have more than two paired off by the geometry,
    taking the body's list of facets as outward, then as inward; or why they do not pair."""
    n_local = body_edges.slot.shape[0]
    start = np.zeros(n_local + 1, np.int64)
    for local in range(n_local):
        start[local + 1] = start[local] + body_edges.count[local]
    on_edge = np.empty(darts.patch.shape[0], np.int64)
    fill = start[:-1].copy()
    for d in range(darts.patch.shape[0]):
        local = scratch.edge_local[darts.edge[d]]
        on_edge[fill[local]] = d
        fill[local] += 1
    edge_darts = EdgeDarts(body_edges.slot, body_edges.count, start, on_edge)
    ok, failed, key = False, -1, -1
    for attempt in range(2):  # outward lists, then inward ones
        if attempt == 0 or key == -1:
            rule = 1 - 2 * attempt
            ok, failed, key = _pair_around(
                rule, stamp, patches, darts, edge_darts, tables, scratch, geometry
            )
        if ok:
            break
    if ok:
        return GRAIN_OK
    if key >= 0:
        return _undefined_vertex(key, tables, darts.edge, params)
    params[0], params[1] = tables.edges.id[body_edges.slot[failed]], body_edges.count[failed]
    return GRAIN_POINT_EDGE if key == NO_LENGTH else GRAIN_UNPAIRED


@njit
def _pair_around(rule, stamp, patches, darts, edge_darts, tables, scratch, geometry):
    """Pair off the darts of edges that a body uses more than twice (it meets its own image
    along them), by the geometry around each edge: from a patch, turning about the edge into
    the cell (away from the patch's outward side when ``rule`` is 1, towards it when -1: a
    body that lists its facets inwards), the first facet met is the patch's partner, a patch
    of the same body that runs along the edge the other way.

    Returns ``(ok, local edge that failed, vertex key without coordinates, or NO_LENGTH for an
    edge of no length, or -1)``."""
    vk_entry = tables.vertices.entry
    edges, uses, sides = tables.edges, tables.uses, tables.sides
    point = np.empty(3)
    tail = np.empty(3)
    along = np.empty(3)
    centre = np.empty(3)
    nowhere = np.zeros(3, np.int64)
    for local in range(edge_darts.slot.shape[0]):
        if edge_darts.count[local] <= 2:
            continue
        es = edge_darts.slot[local]
        u0, u1 = uses.start[es], uses.start[es + 1]
        k = u1 - u0
        if vk_entry[edges.tail[es]] < 0:
            return False, local, edges.tail[es]
        if vk_entry[edges.head[es]] < 0:
            return False, local, edges.head[es]
        _shifted(geometry, vk_entry[edges.tail[es]], nowhere, tail)
        _shifted(geometry, vk_entry[edges.head[es]], edges.wrap[es], along)
        for x in range(3):
            along[x] -= tail[x]
        along2 = _dot3(along, along)
        if along2 == 0.0:  # no direction to turn about
            return False, local, NO_LENGTH
        # The direction from the edge into each facet that uses it (its centre, in its frame).
        into = np.empty((k, 3))
        for c in range(k):
            q = uses.side[u0 + c]
            g = sides.facet[q]
            a, b = sides.start[g], sides.start[g + 1]
            centre[0] = centre[1] = centre[2] = 0.0
            for r in range(a, b):
                if vk_entry[sides.tail[r]] < 0:
                    return False, local, sides.tail[r]
                _shifted(geometry, vk_entry[sides.tail[r]], sides.tail_shift[r], point)
                for x in range(3):
                    centre[x] += point[x] / (b - a)
            _shifted(geometry, vk_entry[edges.tail[es]], sides.edge_shift[q], point)
            for x in range(3):
                centre[x] -= point[x]
            height = _dot3(centre, along) / along2
            for x in range(3):
                into[c, x] = centre[x] - height * along[x]
        for w in range(edge_darts.start[local], edge_darts.start[local + 1]):
            d = edge_darts.dart[w]
            mine = -1
            for c in range(k):
                if uses.side[u0 + c] == darts.side[d]:
                    mine = c
            best, best_angle = -1, 0.0
            for c in range(k):
                if c == mine:
                    continue
                u, v = into[mine], into[c]
                turn = darts.direction[d] * (
                    (u[1] * v[2] - u[2] * v[1]) * along[0]
                    + (u[2] * v[0] - u[0] * v[2]) * along[1]
                    + (u[0] * v[1] - u[1] * v[0]) * along[2]
                )
                angle = math.atan2(turn / math.sqrt(along2), _dot3(u, v))
                if angle <= 0.0:
                    angle += 2 * math.pi
                if best < 0 or (angle > best_angle if rule > 0 else angle < best_angle):
                    best, best_angle = c, angle
            if best < 0:
                return False, local, -1
            q = uses.side[u0 + best]
            g = sides.facet[q]
            sign = -darts.direction[d] * sides.sign[q]
            if scratch.facet_stamp[g] != stamp:
                return False, local, -1
            o = scratch.facet_plus[g] if sign > 0 else scratch.facet_minus[g]
            if o < 0:
                return False, local, -1
            size = sides.start[g + 1] - sides.start[g]
            offset = q - sides.start[g]
            darts.partner[d] = darts.start[o] + (
                offset if patches.sign[o] > 0 else size - 1 - offset
            )
        for w in range(edge_darts.start[local], edge_darts.start[local + 1]):
            d = edge_darts.dart[w]
            if darts.partner[darts.partner[d]] != d:
                return False, local, -1
    return True, -1, -1


@njit(inline="always")
def _translations(darts, edge_shift):
    """Each patch's translation, across the edges it shares with its partners: ``(shift,
    pieces, a dart where two ways around disagree or -1)``; the patches of each connected
    piece are placed from its first."""
    m = darts.start.shape[0] - 1
    shift = np.zeros((m, 3), np.int64)
    piece = np.full(m, -1, np.int64)
    queue = np.empty(m, np.int64)
    pieces = 0
    for first in range(m):
        if piece[first] >= 0:
            continue
        piece[first] = pieces
        queue[0] = first
        head, tail = 0, 1
        while head < tail:
            o = queue[head]
            head += 1
            for d in range(darts.start[o], darts.start[o + 1]):
                p = darts.partner[d]
                o2 = darts.patch[p]
                qa, qb = darts.side[d], darts.side[p]
                same = True
                for k in range(3):
                    want = shift[o, k] + edge_shift[qa, k] - edge_shift[qb, k]
                    if piece[o2] < 0:
                        shift[o2, k] = want
                    elif shift[o2, k] != want:
                        same = False
                if piece[o2] < 0:
                    piece[o2] = pieces
                    queue[tail] = o2
                    tail += 1
                elif not same:
                    return shift, pieces, d
        pieces += 1
    return shift, pieces, -1


@njit(inline="always")
def _corners(darts, shift, scratch, stamp, tail):
    """The corners of the patches placed by ``shift``, each dart's tail corner written into
    ``tail``."""
    n_darts = darts.patch.shape[0]
    n = 0
    key = np.empty(n_darts, np.int64)
    offset = np.empty((n_darts, 3), np.int64)
    next_of_key = np.empty(n_darts, np.int64)
    off = np.empty(3, np.int64)
    for d in range(n_darts):
        o, k0 = darts.patch[d], darts.key[d]
        for x in range(3):
            off[x] = shift[o, x] + darts.tail_shift[d, x]
        if scratch.key_stamp[k0] != stamp:
            scratch.key_stamp[k0], scratch.key_first[k0] = stamp, -1
        v = scratch.key_first[k0]
        while v >= 0 and not (
            offset[v, 0] == off[0] and offset[v, 1] == off[1] and offset[v, 2] == off[2]
        ):
            v = next_of_key[v]
        if v < 0:
            v = n
            key[v] = k0
            offset[v, 0], offset[v, 1], offset[v, 2] = off[0], off[1], off[2]
            next_of_key[v] = scratch.key_first[k0]
            scratch.key_first[k0] = v
            n += 1
        tail[d] = v
    head = np.empty(n_darts, np.int64)
    for o in range(darts.start.shape[0] - 1):
        end = darts.start[o + 1]
        for d in range(darts.start[o], end):
            head[d] = tail[d + 1 if d + 1 < end else darts.start[o]]
    return Corners(key[:n], offset[:n], tail, head)


@njit(inline="always")
def _place_corners(corners, vertices, geometry, position):
    """Each corner's position into ``position``; returns -1, or the key of a vertex that has
    no coordinates."""
    for v in range(corners.key.shape[0]):
        key = corners.key[v]
        if vertices.entry[key] < 0:
            return key
        _shifted(geometry, vertices.entry[key], corners.shift[v], position[v])
    return -1
