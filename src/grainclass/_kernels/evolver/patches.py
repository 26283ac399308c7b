"""A body's surface as patches and darts, checked to be closed and oriented.

A body's list of facets gives its *patches*, one per entry (:class:`Patches`); each patch's
sides, in the patch's direction, are its *darts* (:class:`Darts`). The darts of the body's
edges (:class:`BodyEdges`) pair off: the second dart on an edge is the first's partner, and an
edge with more darts (a cell that meets its own periodic image along it) is left to
``periodic.py``. The checks write a GRAIN_ code's params into ``params``.
"""

from typing import NamedTuple

import numpy as np

from grainclass._kernels.evolver.codes import (
    EDGE,
    FACET,
    GRAIN_FACET_OPEN,
    GRAIN_FACET_WRAPS,
    GRAIN_NOT_CLOSED,
    GRAIN_OK,
    GRAIN_ORIENTATION,
    GRAIN_TWICE,
    GRAIN_TWICE_SAME,
    GRAIN_UNDEFINED,
    USER_EDGE,
    USER_FACET,
    USER_LIST,
    VERTEX,
)
from grainclass._kernels.evolver.slots import _slot
from grainclass._numba import njit, njit_leaf


class Patches(NamedTuple):
    """A body's patches, in the order of its list of facets."""

    slot: np.ndarray
    """int64[m]: the facet's slot (-1: no facet has the id)"""
    sign: np.ndarray
    """int64[m]: 1 for the facet as defined, -1 reversed"""
    facet_id: np.ndarray
    """int64[m]: the facet's id as listed"""


class Darts(NamedTuple):
    """The sides of each patch in the patch's direction: patch ``o`` has darts
    ``start[o]:start[o + 1]``."""

    start: np.ndarray
    """int64[m + 1]"""
    patch: np.ndarray
    """int64[n]"""
    side: np.ndarray
    """int64[n]: the side it is (``tables.Sides``)"""
    edge: np.ndarray
    """int64[n]: the edge's slot"""
    direction: np.ndarray
    """int64[n]: 1 along the edge, -1 against it"""
    key: np.ndarray
    """int64[n]: the key of its tail vertex"""
    tail_shift: np.ndarray
    """int64[n, 3]: its tail's translation in its facet's frame"""
    partner: np.ndarray
    """int64[n]: the dart on the same edge that it is glued to (-1: none yet)"""


class BodyEdges(NamedTuple):
    """The body's edges, in the order it first uses them."""

    slot: np.ndarray
    """int64[k]: the edge's slot"""
    count: np.ndarray
    """int64[k]: the darts on it"""
    first: np.ndarray
    """int64[k]: the first of them"""


@njit(inline="always")
def _patches(entries, entry, facet_map, scratch, stamp):
    """The patches of the body whose line is ``entry``; notes in ``scratch`` how many times,
    and by which patches, the body lists each facet."""
    a0, m = entries.first[entry], entries.last[entry] - entries.first[entry]
    slot = np.empty(m, np.int64)
    sign = np.empty(m, np.int64)
    facet_id = np.empty(m, np.int64)
    for o in range(m):
        signed = entries.ids[a0 + o]
        s = _slot(facet_map, abs(signed), False)
        slot[o] = s
        sign[o] = -1 if signed < 0 else 1
        facet_id[o] = abs(signed)
        if s >= 0:
            if scratch.facet_stamp[s] != stamp:
                scratch.facet_stamp[s], scratch.facet_times[s] = stamp, 0
                scratch.facet_plus[s], scratch.facet_minus[s] = -1, -1
            scratch.facet_times[s] += 1
            if sign[o] > 0:
                scratch.facet_plus[s] = o
            else:
                scratch.facet_minus[s] = o
    return Patches(slot, sign, facet_id)


@njit_leaf
def _check_patches(patches, periodic, tables, scratch, params):
    """GRAIN_OK, or why the patches are not a surface: a facet listed more than once (only
    once each way, and only in a periodic file, is allowed), a facet or edge not defined, in
    the order the body names them, or a facet that is not a closed loop."""
    facets, sides, edges = tables.facets, tables.sides, tables.edges
    times, plus, minus = scratch.facet_times, scratch.facet_plus, scratch.facet_minus
    slot = patches.slot
    m = slot.shape[0]
    for o in range(m):
        s = slot[o]
        if s >= 0 and times[s] > 1:
            params[0] = facets.id[s]
            if not periodic:
                return GRAIN_TWICE
            if times[s] != 2 or plus[s] < 0 or minus[s] < 0:
                params[1], params[2] = times[s], patches.sign[o]
                return GRAIN_TWICE_SAME
    for o in range(m):
        s = slot[o]
        if s < 0 or facets.entry[s] < 0:
            params[0], params[1], params[2] = FACET, patches.facet_id[o], USER_LIST
            params[4] = facets.bad[s] if s >= 0 else 0
            return GRAIN_UNDEFINED
        if facets.state[s] > 0:
            edge = sides.edge_id[sides.start[s] + facets.state[s] - 1]
            es = _slot(edges.map, edge, False)
            params[0], params[1], params[2], params[3] = EDGE, edge, USER_FACET, facets.id[s]
            params[4] = edges.bad[es] if es >= 0 else 0
            return GRAIN_UNDEFINED
    for o in range(m):
        s = slot[o]
        if facets.state[s] < 0:
            size = sides.start[s + 1] - sides.start[s]
            params[0] = facets.id[s]
            if facets.state[s] == -1 - size:
                return GRAIN_FACET_WRAPS
            params[1] = sides.edge_id[sides.start[s] - 1 - facets.state[s]]
            return GRAIN_FACET_OPEN
    return GRAIN_OK


@njit(inline="always")
def _darts(patches, sides, scratch, stamp):
    """The darts of the patches, the body's edges and whether one has more than two darts:
    ``(darts, edges, ambiguous)``. The second dart on an edge is the first's partner."""
    m = patches.slot.shape[0]
    start = np.empty(m + 1, np.int64)
    n = 0
    for o in range(m):
        start[o] = n
        n += sides.start[patches.slot[o] + 1] - sides.start[patches.slot[o]]
    start[m] = n
    darts = Darts(
        start,
        np.empty(n, np.int64),
        np.empty(n, np.int64),
        np.empty(n, np.int64),
        np.empty(n, np.int64),
        np.empty(n, np.int64),
        np.empty((n, 3), np.int64),
        np.full(n, -1, np.int64),
    )
    edge_slot = np.empty(n, np.int64)
    edge_count = np.zeros(n, np.int64)
    edge_first = np.empty(n, np.int64)
    n_local = 0
    ambiguous = False
    for o in range(m):
        a = sides.start[patches.slot[o]]
        size = sides.start[patches.slot[o] + 1] - a
        forward = patches.sign[o] > 0
        for i in range(size):
            d = start[o] + i
            k = i if forward else size - 1 - i
            t = k if forward else (k + 1) % size
            es = sides.edge[a + k]
            darts.patch[d], darts.side[d], darts.edge[d] = o, a + k, es
            darts.direction[d] = patches.sign[o] * sides.sign[a + k]
            darts.key[d] = sides.tail[a + t]
            for x in range(3):
                darts.tail_shift[d, x] = sides.tail_shift[a + t, x]
            if scratch.edge_stamp[es] != stamp:
                scratch.edge_stamp[es], scratch.edge_local[es] = stamp, n_local
                edge_slot[n_local], edge_first[n_local] = es, d
                n_local += 1
            local = scratch.edge_local[es]
            edge_count[local] += 1
            if edge_count[local] == 2:
                darts.partner[d], darts.partner[edge_first[local]] = edge_first[local], d
            elif edge_count[local] == 3:
                ambiguous = True
    edges = BodyEdges(edge_slot[:n_local], edge_count[:n_local], edge_first[:n_local])
    return darts, edges, ambiguous


@njit_leaf
def _check_closed(patches, darts, body_edges, periodic, tables, params):
    """GRAIN_OK, or why the darts do not close up: an edge with other than two darts (an even
    number, in a periodic file), or two on an edge that run along it the same way."""
    n_local = body_edges.slot.shape[0]
    for local in range(n_local):
        c = body_edges.count[local]
        if c != 2 and (not periodic or c % 2 == 1):
            params[0], params[1] = tables.edges.id[body_edges.slot[local]], c
            return GRAIN_NOT_CLOSED
    for local in range(n_local):
        d1 = body_edges.first[local]
        d2 = darts.partner[d1]
        if body_edges.count[local] == 2 and darts.direction[d1] == darts.direction[d2]:
            params[0] = tables.facets.id[patches.slot[darts.patch[d1]]]
            params[1] = tables.facets.id[patches.slot[darts.patch[d2]]]
            params[2] = tables.edges.id[body_edges.slot[local]]
            return GRAIN_ORIENTATION
    return GRAIN_OK


@njit_leaf
def _undefined_vertex(key, tables, dart_edge, params):
    """GRAIN_UNDEFINED for a vertex without coordinates, named with the first edge the body
    uses that ends at it."""
    edges = tables.edges
    user = 0
    for d in range(dart_edge.shape[0]):
        es = dart_edge[d]
        if edges.tail[es] == key or edges.head[es] == key:
            user = edges.id[es]
            break
    params[0], params[1], params[2], params[3] = VERTEX, tables.vertices.id[key], USER_EDGE, user
    params[4] = tables.vertices.bad[key]
    return GRAIN_UNDEFINED
