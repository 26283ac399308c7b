"""One file's entries as tables by slot (``slots.py``): what the bodies of the file need.

:func:`_file_tables` gathers a file's vertices (by *key*: a slot per vertex id, whether a line
defines it or only an edge names it), edges, facets, the *sides* of each facet (its edges in
its own order, signed, each placed in the facet's frame across the periodic box), the sides on
each edge, and the bodies, into one :class:`FileTables` that ``body.py`` reads.
"""

from typing import NamedTuple

import numpy as np

from grainclass._kernels.evolver.codes import BODY, EDGE, ENTRY_OK, FACET, VERTEX
from grainclass._kernels.evolver.slots import Defined, IdMap, _defined, _slot, _slot_at, _slots
from grainclass._numba import borrowed, njit, njit_leaf


class Edges(NamedTuple):
    """A file's edges, by slot."""

    map: IdMap
    id: np.ndarray
    """int64[ne]"""
    entry: np.ndarray
    """int64[ne]: the entry of the last readable line (-1: none)"""
    bad: np.ndarray
    """int64[ne]: the line of the last unreadable one (0: none)"""
    tail: np.ndarray
    """int64[ne]: the key of its tail vertex (-1: not defined)"""
    head: np.ndarray
    """int64[ne]: the key of its head vertex"""
    wrap: np.ndarray
    """int64[ne, 3]: its wrap marks, the lattice translation from tail to head"""
    triple: np.ndarray
    """bool[ne]: marked as a triple line"""


class EdgeUses(NamedTuple):
    """The sides on each edge, of the facets whose edges join up: edge slot ``e`` has sides
    ``side[start[e]:start[e + 1]]``."""

    count: np.ndarray
    """int64[ne]"""
    start: np.ndarray
    """int64[ne + 1]"""
    side: np.ndarray
    """int64[uses]"""


class Facets(NamedTuple):
    """A file's facets, by slot."""

    map: IdMap
    id: np.ndarray
    """int64[nf]"""
    entry: np.ndarray
    """int64[nf]: the entry of the last readable line (-1: none)"""
    bad: np.ndarray
    """int64[nf]: the line of the last unreadable one (0: none)"""
    state: np.ndarray
    """int64[nf]: 0 ok; 1 + the first side whose edge is not defined; -1 - the side whose edge
    does not start where the one before ends; -1 - sides: wrap marks that do not add up"""
    listed: np.ndarray
    """int64[nf]: how many times the bodies list it"""
    lister: np.ndarray
    """int64[nf, 3]: the first three bodies (their slots) that list it (-1: none)"""


class Sides(NamedTuple):
    """Each facet's sides, its edges in its own order: facet slot ``s`` has sides
    ``start[s]:start[s + 1]``. A side's *frame* translation is a lattice vector, the sum of
    the wrap marks along the facet's edges before it."""

    start: np.ndarray
    """int64[nf + 1]"""
    facet: np.ndarray
    """int64[n]: the facet's slot"""
    edge: np.ndarray
    """int64[n]: the edge's slot (-1: not defined)"""
    edge_id: np.ndarray
    """int64[n]: the edge's id"""
    sign: np.ndarray
    """int64[n]: 1 along the edge, -1 against it"""
    tail: np.ndarray
    """int64[n]: the key of the vertex it starts from, in the facet's direction"""
    tail_shift: np.ndarray
    """int64[n, 3]: that vertex's translation in the facet's frame"""
    edge_shift: np.ndarray
    """int64[n, 3]: the translation of the edge's own tail in the facet's frame"""


class Bodies(NamedTuple):
    """A file's bodies, by slot, in the order of their first lines."""

    last: np.ndarray
    """int64[nb]: the entry of its last line"""
    any_bad: np.ndarray
    """bool[nb]: one of its lines cannot be read"""


class FileTables(NamedTuple):
    """What the bodies of one file need."""

    vertices: Defined
    """by key: the slots of vertex ids, then keys of ids that edges name and no line defines"""
    edges: Edges
    uses: EdgeUses
    facets: Facets
    sides: Sides
    bodies: Bodies
    marked: bool
    """some edge carries the triple-line mark"""


@njit
def _file_tables(entries, f0, f1):
    """The tables of the file whose entries are ``f0:f1``."""
    v_rows, e_rows, f_rows, b_rows = _rows_by_kind(entries.kind, f0, f1)
    # Vertices (room for the ids that edges name and no line defines), edges.
    vertex_map, v_slot = _slots(entries.id[v_rows], v_rows.shape[0] + 2 * e_rows.shape[0])
    n_defined = vertex_map.count[0]
    edge_map, e_slot = _slots(entries.id[e_rows], e_rows.shape[0])
    edge_lines = _defined(e_rows, e_slot, edge_map.count[0], entries)
    tail, head = _edge_ends(edge_lines.entry, entries, vertex_map)
    vertices = _vertex_keys(v_rows, v_slot, vertex_map, n_defined, entries)
    wrap, triple = _edge_marks(edge_lines.entry, entries)
    edges = Edges(
        edge_map, edge_lines.id, edge_lines.entry, edge_lines.bad, tail, head, wrap, triple
    )
    # Facets and their sides.
    facet_map, f_slot = _slots(entries.id[f_rows], f_rows.shape[0])
    facet_lines = _defined(f_rows, f_slot, facet_map.count[0], entries)
    sides, state = _sides(facet_lines.entry, entries, edges)
    uses = _edge_uses(edge_map.count[0], sides, state)
    # Bodies, and the bodies that list each facet.
    bodies = _bodies(b_rows, entries)
    listed, lister = _listers(bodies, entries, facet_map)
    facets = Facets(
        facet_map, facet_lines.id, facet_lines.entry, facet_lines.bad, state, listed, lister
    )
    marked = False
    for s in range(triple.shape[0]):
        marked |= triple[s]
    return FileTables(vertices, edges, uses, facets, sides, bodies, marked)


@njit(inline="always")
def _rows_by_kind(kind, f0, f1):
    """The entries of each kind among ``f0:f1``, in order: vertices, edges, facets, bodies."""
    counts = np.zeros(4, np.int64)
    for i in range(f0, f1):
        counts[kind[i]] += 1
    rows = (
        np.empty(counts[VERTEX], np.int64),
        np.empty(counts[EDGE], np.int64),
        np.empty(counts[FACET], np.int64),
        np.empty(counts[BODY], np.int64),
    )
    fill = np.zeros(4, np.int64)
    for i in range(f0, f1):
        k = kind[i]
        if k == VERTEX:
            rows[0][fill[0]] = i
        elif k == EDGE:
            rows[1][fill[1]] = i
        elif k == FACET:
            rows[2][fill[2]] = i
        else:
            rows[3][fill[3]] = i
        fill[k] += 1
    return rows


@njit
def _edge_ends(edge_entry, entries, vertex_map):
    """The keys of each edge's tail and head (-1: the edge is not defined). Edges may name
    vertices without a line: they get keys past the vertices' slots. (The map's arrays are
    handed on as borrowed views, as in :func:`_fill_sides`.)"""
    ne = edge_entry.shape[0]
    tail = np.full(ne, -1, np.int64)
    head = np.full(ne, -1, np.int64)
    first, last = borrowed(entries.first), borrowed(entries.last)
    keys, slots = borrowed(vertex_map.keys), borrowed(vertex_map.slots)
    count, direct = borrowed(vertex_map.count), borrowed(vertex_map.direct)
    for s in range(ne):
        i = edge_entry[s]
        if i >= 0:
            tail[s] = _slot_at(keys, slots, count, direct, first[i], True)
            head[s] = _slot_at(keys, slots, count, direct, last[i], True)
    return tail, head


@njit(inline="always")
def _vertex_keys(v_rows, v_slot, vertex_map, n_defined, entries):
    """Each vertex key's id and lines; keys from ``n_defined`` on are ids that only edges
    name."""
    vertices = _defined(v_rows, v_slot, vertex_map.count[0], entries)
    for h in range(vertex_map.keys.shape[0]):
        if vertex_map.slots[h] >= n_defined:
            vertices.id[vertex_map.slots[h]] = vertex_map.keys[h]
    for h in range(vertex_map.direct.shape[0]):
        if vertex_map.direct[h] >= n_defined:
            vertices.id[vertex_map.direct[h]] = h
    return vertices


@njit(inline="always")
def _edge_marks(edge_entry, entries):
    """Each edge's wrap marks and triple-line mark (none for an edge without a line)."""
    ne = edge_entry.shape[0]
    wrap = np.zeros((ne, 3), np.int64)
    triple = np.zeros(ne, np.bool_)
    for s in range(ne):
        i = edge_entry[s]
        if i < 0:
            continue
        for k in range(3):
            wrap[s, k] = entries.wraps[i, k]
        triple[s] = entries.flag[i] != 0
    return wrap, triple


@njit(inline="always")
def _sides(facet_entry, entries, edges):
    """The sides of each facet that has a line, and each facet's state (see
    :class:`Facets`)."""
    nf = facet_entry.shape[0]
    start = np.zeros(nf + 1, np.int64)
    for s in range(nf):
        i = facet_entry[s]
        start[s + 1] = start[s] + (entries.last[i] - entries.first[i] if i >= 0 else 0)
    n = start[nf]
    sides = Sides(
        start,
        np.empty(n, np.int64),
        np.full(n, -1, np.int64),
        np.empty(n, np.int64),
        np.empty(n, np.int64),
        np.empty(n, np.int64),
        np.zeros((n, 3), np.int64),
        np.zeros((n, 3), np.int64),
    )
    state = np.zeros(nf, np.int64)
    _fill_sides(facet_entry, entries, edges, sides, state)
    return sides, state


@njit
def _fill_sides(facet_entry, entries, edges, sides, state):
    """The sides and state of each facet that has a line.

    The loop hands the arrays to :func:`_facet_sides` as borrowed views made here (see
    :func:`~grainclass._numba.borrowed`): named tuples handed on would have each of their
    arrays counted up and down for every facet."""
    ids, first = borrowed(entries.ids), borrowed(entries.first)
    keys, slots = borrowed(edges.map.keys), borrowed(edges.map.slots)
    count, direct = borrowed(edges.map.count), borrowed(edges.map.direct)
    defined, ends = borrowed(edges.entry), (borrowed(edges.tail), borrowed(edges.head))
    wrap = borrowed(edges.wrap)
    start, facet, edge = borrowed(sides.start), borrowed(sides.facet), borrowed(sides.edge)
    edge_id, sign, tail = borrowed(sides.edge_id), borrowed(sides.sign), borrowed(sides.tail)
    tail_shift, edge_shift = borrowed(sides.tail_shift), borrowed(sides.edge_shift)
    for s in range(facet_entry.shape[0]):
        i = facet_entry[s]
        if i >= 0:
            state[s] = _facet_sides(
                s, ids, first[i], keys, slots, count, direct, defined, ends[0], ends[1], wrap,
                start, facet, edge, edge_id, sign, tail, tail_shift, edge_shift,
            )  # fmt: skip


@njit_leaf
def _facet_sides(
    s, ids, first, keys, slots, count, direct, defined, edge_tail, edge_head, wrap, start,
    facet, edge, edge_id, sign, tail, tail_shift, edge_shift,
):  # fmt: skip
    """The sides of facet slot ``s``, whose line lists ``ids[first:]``: returns its state.
    Handed the arrays of the edges' :class:`~.slots.IdMap`, of :class:`Edges` (``defined``:
    its ``entry``) and of :class:`Sides`."""
    a = start[s]
    size = start[s + 1] - a
    for k in range(size):
        signed = ids[first + k]
        facet[a + k] = s
        edge_id[a + k] = abs(signed)
        sign[a + k] = -1 if signed < 0 else 1
        es = _slot_at(keys, slots, count, direct, abs(signed), False)
        if es >= 0 and defined[es] >= 0:
            edge[a + k] = es
    for k in range(size):
        if edge[a + k] < 0:
            return 1 + k
    # Walk around the facet, adding up the wrap marks: each side's place in the facet's frame.
    cx, cy, cz = 0, 0, 0
    for k in range(size):
        es = edge[a + k]
        forward = sign[a + k] > 0
        tail[a + k] = edge_tail[es] if forward else edge_head[es]
        tail_shift[a + k, 0], tail_shift[a + k, 1], tail_shift[a + k, 2] = cx, cy, cz
        wx, wy, wz = wrap[es, 0], wrap[es, 1], wrap[es, 2]
        if forward:
            edge_shift[a + k, 0], edge_shift[a + k, 1], edge_shift[a + k, 2] = cx, cy, cz
            cx, cy, cz = cx + wx, cy + wy, cz + wz
        else:
            cx, cy, cz = cx - wx, cy - wy, cz - wz
            edge_shift[a + k, 0], edge_shift[a + k, 1], edge_shift[a + k, 2] = cx, cy, cz
    for k in range(size):
        es = edge[a + k]
        head = edge_head[es] if sign[a + k] > 0 else edge_tail[es]
        if head != tail[a + (k + 1) % size]:
            return -1 - ((k + 1) % size)
    if cx != 0 or cy != 0 or cz != 0:
        return -1 - size
    return 0


@njit(inline="always")
def _edge_uses(ne, sides, state):
    """The sides on each edge, of the facets whose state is 0."""
    count = np.zeros(ne, np.int64)
    nf = state.shape[0]
    for s in range(nf):
        if state[s] == 0:
            for q in range(sides.start[s], sides.start[s + 1]):
                count[sides.edge[q]] += 1
    start = np.zeros(ne + 1, np.int64)
    for e in range(ne):
        start[e + 1] = start[e] + count[e]
    side = np.empty(start[ne], np.int64)
    fill = start[:-1].copy()
    for s in range(nf):
        if state[s] == 0:
            for q in range(sides.start[s], sides.start[s + 1]):
                e = sides.edge[q]
                side[fill[e]] = q
                fill[e] += 1
    return EdgeUses(count, start, side)


@njit(inline="always")
def _bodies(b_rows, entries):
    """The bodies, in the order of their first line: each one's last line, and whether any of
    its lines cannot be read."""
    body_map, b_slot = _slots(entries.id[b_rows], b_rows.shape[0])
    nb = body_map.count[0]
    last = np.empty(nb, np.int64)
    any_bad = np.zeros(nb, np.bool_)
    for j in range(b_rows.shape[0]):
        s = b_slot[j]
        last[s] = b_rows[j]
        if entries.status[b_rows[j]] != ENTRY_OK:
            any_bad[s] = True
    return Bodies(last, any_bad)


@njit(inline="always")
def _listers(bodies, entries, facet_map):
    """The bodies that list each facet: how many times in all, and the first three."""
    nf = facet_map.count[0]
    listed = np.zeros(nf, np.int64)
    lister = np.full((nf, 3), -1, np.int64)
    for j in range(bodies.last.shape[0]):
        if bodies.any_bad[j]:
            continue
        i = bodies.last[j]
        for q in range(entries.first[i], entries.last[i]):
            s = _slot(facet_map, abs(entries.ids[q]), False)
            if s >= 0:
                if listed[s] < 3:
                    lister[s, listed[s]] = j
                listed[s] += 1
    return listed, lister


class Scratch(NamedTuple):
    """Per file, what a body notes by facet slot, edge slot and vertex key while it is built;
    a row stamped by another body (another stamp) counts as empty."""

    facet_stamp: np.ndarray
    facet_times: np.ndarray
    """how many times the body lists the facet"""
    facet_plus: np.ndarray
    """the patch that lists it as defined (-1: none)"""
    facet_minus: np.ndarray
    """the patch that lists it reversed (-1: none)"""
    edge_stamp: np.ndarray
    edge_local: np.ndarray
    """the edge's place among the body's edges"""
    key_stamp: np.ndarray
    key_first: np.ndarray
    """the last corner made of the vertex (-1: none)"""


@njit(inline="always")
def _new_scratch(tables):
    nf = tables.facets.id.shape[0]
    ne = tables.edges.id.shape[0]
    nk = tables.vertices.id.shape[0]
    return Scratch(
        np.zeros(nf, np.int64),
        np.zeros(nf, np.int64),
        np.zeros(nf, np.int64),
        np.zeros(nf, np.int64),
        np.zeros(ne, np.int64),
        np.zeros(ne, np.int64),
        np.zeros(nk, np.int64),
        np.zeros(nk, np.int64),
    )
