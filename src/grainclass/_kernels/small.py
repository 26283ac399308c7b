"""The fast path: grains with at most 64 faces, each face's neighbours one uint64 bitset.

The common grain (plantri's output, a simulation's well-formed grain) is validated in O(E) and
classified without allocating: the batch kernel hands in scratch arrays reused across grains.
Anything unusual (a repeated neighbour, a face list out of cyclic order, a grain that is not ok)
makes :func:`_validate_small` say no, and the general path of ``validate.py``,
``reduce.py`` and ``belts.py`` takes over, with its exact diagnosis.
"""

import numpy as np

from grainclass._kernels.belts import belt_penalty, split_type
from grainclass._kernels.bits import ONE, ZERO, bit, full, lowest, popcount
from grainclass._numba import at, njit, njit_leaf


@njit_leaf
def _component(adj, start, allowed):
    """The vertices of ``allowed`` reachable from the bitset ``start`` within ``allowed``."""
    comp = start
    frontier = start
    while frontier:
        reached = ZERO
        while frontier:
            x = lowest(frontier)
            frontier &= frontier - ONE
            reached |= adj[x]
        frontier = reached & allowed & ~comp
        comp |= frontier
    return comp


# The corner table: uint16[ROW * ROW], the entry of face v and face x at ROW * v + x. A row is
# wide enough for a planar_code record's faces as written, 1..64, and the 0 before each list.
ROW = 128
CORNERS = ROW * ROW
STAMP_STEP = ROW  # an entry: the grain's stamp, a multiple of this, plus a face
STAMPS = (1 << 16) // STAMP_STEP - 1  # grains between clearings of the table


@njit(inline="always")
def next_stamp(following, stamp):
    """The stamp for the next grain validated with the corner table ``following`` (zeros at
    first, with ``stamp`` 0). After STAMPS grains the stamps start over and the table is
    cleared, so that no entry written for an earlier grain can match: stale corners could
    otherwise close triangles for an invalid grain."""
    stamp += STAMP_STEP
    if stamp > STAMPS * STAMP_STEP:
        for i in range(following.size):
            following[i] = 0
        stamp = STAMP_STEP
    return stamp


@njit(inline="always")
def _corner(v, x, y, stamp, following):
    """Record the corner (v, x, y) of face v: y follows x around v (``following[ROW v + x]``).

    Returns 1 if the triangle closes consistently, next_x(y) = v and next_y(v) = x, both
    written for this grain (``stamp``): that holds only at the last of the three faces to be
    listed, so each closed triangle counts once, and entries of faces not listed yet, or of
    earlier grains, never match. No branch: which corners close is data, not pattern.
    """
    following[at(ROW * v + x)] = stamp | y
    closes_x = following[at(ROW * x + y)] == np.uint16(stamp | v)
    return closes_x & (following[at(ROW * y + v)] == np.uint16(stamp | x))


@njit(inline="always")
def _reach(reached, v, row):
    """``reached`` and, if face v is in it, the faces of ``row``: in one pass over the lists,
    the faces joined to face 0 through faces listed before them (plantri's numbering: all)."""
    return reached | (row if (reached >> np.uint64(v)) & ONE else ZERO)


@njit(inline="always")
def _connected(adj, reached, n):
    """Whether all n faces are joined to face 0, given those :func:`_reach` found."""
    everything = full(n)
    return reached == everything or _component(adj, reached, everything) == everything


@njit(inline="always")
def _next_face(v, x, y, stamp, following, indices, row, closed):
    """Face y read after face x in face v's list: its index into
    ``indices``, masked (see :func:`_validate_small`), its bit into ``row``, and the corner
    (v, x, y). Returns the running (y, indices, row, closed)."""
    indices |= y
    y &= 63
    return y, indices, row | bit(y), closed + _corner(v, x, y, stamp, following)


@njit(inline="always")
def _close_list(
    v, x, first, row, count, stamp, following, adj, closed, bad, triangular, listed, reached
):
    """The end of face v's list of ``count`` faces, ``row`` their bitset: its last corner
    (v, x, first), its checks (a repeat, fewer than three faces, v itself), and v's bits.
    Returns the running (closed, bad, triangular, listed, reached)."""
    closed += _corner(v, x, first, stamp, following)
    bad |= (popcount(row) != count) | (count < 3) | ((row >> np.uint64(v)) & ONE != ZERO)
    triangular |= bit(v) if count == 3 else ZERO
    adj[at(v)] = row
    return closed, bad, triangular, listed | row, _reach(reached, v, row)


@njit(inline="always")
def _verdict(n, adj, indices, bad, listed, closed, reached, triangular):
    """``(ok, triangular)`` once every list is read (see :func:`_validate_small`)."""
    if indices < 0 or indices > 63 or bad or listed & ~full(n) or closed != 2 * n - 4:
        return False, ZERO
    return _connected(adj, reached, n), triangular


@njit_leaf
def _validate_small(n, nbr_offsets, neighbors, f0, adj, following, stamp):
    """``(ok, triangular)``: ok if grain (faces from ``f0``) is certainly a simple grain with
    consistent cyclic lists, and then the bitset of its triangular faces (its dual's degree-3
    vertices, where reduction starts: known here from the lists' lengths).

    Fills ``adj`` (uint64[>=n]) and the corner table ``following`` (see :func:`next_stamp`).
    One pass over the 6n - 12 darts, O(n): indices in range, no repeats, and the count of
    corners whose triangle closes (:func:`_corner`). A dart determines its triangle, so
    2n - 4 closed triangles use every dart: every dual face is a triangle, each face is in the
    list of each of its neighbours, F = 2n - 4 and, with connectivity, the Euler characteristic
    is 2: a sphere. Indices are masked to 0..63 so that bad input cannot index outside the
    tables, and rejected at the end: the checks accumulate in integers tested once
    (:func:`_verdict`), not in a branch per dart, which a predictor would miss (an index out of
    range shows in the OR of all indices or in the union of the lists, a repeat in a list's
    bitset holding fewer faces than the list has entries). The corner that closes a list,
    (v, last, first), is recorded after the others.
    """
    if nbr_offsets[at(f0 + n)] - nbr_offsets[at(f0)] != 6 * n - 12:
        return False, ZERO
    indices = 0  # the OR of every index: negative, or 64 or more, once one is outside 0..63
    listed = ZERO  # every face in a list: none at n or beyond
    bad = False  # a list with a repeat, with fewer than three faces, or with its own face
    closed = 0
    reached = ONE
    triangular = ZERO
    i = nbr_offsets[at(f0)]
    for v in range(n):
        end = nbr_offsets[at(f0 + v + 1)]
        count = end - i
        if count < 3:
            return False, ZERO
        first = int(neighbors[at(i)])
        indices |= first
        first &= 63
        x = first
        row = bit(x)
        i += 1
        while i < end:
            x, indices, row, closed = _next_face(
                v, x, int(neighbors[at(i)]), stamp, following, indices, row, closed
            )
            i += 1
        closed, bad, triangular, listed, reached = _close_list(
            v, x, first, row, count, stamp, following, adj, closed, bad, triangular, listed, reached
        )
    return _verdict(n, adj, indices, bad, listed, closed, reached, triangular)


@njit_leaf
def _validate_record(buf, p, end, n, adj, following, stamp):
    """:func:`_validate_small` reading a planar_code record of 1-byte entries in place: the
    lists of faces 1..n, each ended by a 0, in ``buf[p:end]``, which holds 6n - 12 faces and n
    zeros, the last byte one of them (the caller checks). Returns ``(ok, triangular)`` and
    fills ``adj`` and ``following`` as that does.

    One pass over the bytes, without a branch: a loop per list would be mispredicted at each
    list's end (see docs/performance.md). Each byte b ends the corner (v, prev, b) of face v,
    or at a 0 the list's last corner (v, prev, first); the bytes keep their 1-based faces, so
    that a list's first corner, (v, 0, b), is written in column 0, of no face, and never
    closes. v's bitset is stored at every byte, whole at its 0. The checks
    of whole lists (repeats, v in its own list, degree 3) are made on the bitsets once every
    list is read, the faces' range by the largest byte, in a loop of its own that LLVM
    vectorizes.
    """
    closed = 0
    v = 1
    prev = 0
    first = 0
    row = ZERO
    for i in range(p, end):
        b = int(buf[at(i)])
        last = b == 0
        first = b if prev == 0 else first
        y = (first if last else b) & (ROW - 1)  # masked: bad input stays inside the table
        closed += _corner(v, prev, y, stamp, following)
        adj[at(v - 1)] = row
        row = ZERO if last else row | bit((b - 1) & 63)
        v += last
        prev = b & (ROW - 1)
    largest = 0
    for i in range(p, end):
        largest = max(largest, int(buf[at(i)]))
    if n < 4 or largest > n or closed != 2 * n - 4:
        return False, ZERO
    darts = 0
    loops = ZERO
    triangular = ZERO
    for v in range(n):
        degree = popcount(adj[v])
        darts += degree
        loops |= adj[v] & bit(v)
        triangular |= bit(v) if degree == 3 else ZERO
    everything = full(n)
    if darts != 6 * n - 12 or loops or _component(adj, ONE, everything) != everything:
        return False, ZERO
    return True, triangular


@njit_leaf
def _reduce_small(n, adj, cubic, removed_round, link):
    """Remove degree-3 vertices round by round (see ``reduce.py``), starting from those of the
    bitset ``cubic``; returns the alive bitset.

    ``link[v]`` is the bitset of v's three neighbours when it went, ``removed_round[v]`` its
    round (0 if it stayed). Only the neighbours of the vertices a round removes can be of
    degree 3 in the next, so only they are looked at again, not every vertex left.
    """
    alive = full(n)
    n_alive = n
    for v in range(n):
        removed_round[v] = 0
    rnd = 0
    while cubic and n_alive > 4:
        rnd += 1
        touched = ZERO
        while cubic and n_alive > 4:  # the bipyramid has two: keep the tetrahedron
            v = lowest(cubic)
            cubic &= cubic - ONE
            link[v] = adj[v] & alive
            touched |= link[v]
            removed_round[v] = rnd
            alive &= ~bit(v)
            n_alive -= 1
        m = touched & alive
        while m:
            u = lowest(m)
            m &= m - ONE
            if popcount(adj[u] & alive) == 3:
                cubic |= bit(u)
    return alive


@njit_leaf
def _has_empty_triangle_small(adj, alive):
    """True if an edge of the fundamental triangulation has a third common neighbour (sc)."""
    m = alive
    while m:
        u = lowest(m)
        m &= m - ONE
        higher = adj[u] & m
        while higher:
            v = lowest(higher)
            higher &= higher - ONE
            if popcount(adj[u] & adj[v] & alive) > 2:
                return True
    return False


@njit_leaf
def _four_belts_small(n, adj, out):
    """As ``belts._four_belts``: chordless 4-cycles a-b-c-d, each found once from its smallest
    vertex a; writes ``out = (split_k, belts, penalty)``.
    """
    everything = full(n)
    split_k, belts, penalty = 0, 0, 0
    for a in range(n):
        above_a = everything & ~full(a + 1)
        for c in range(a + 1, n):
            if adj[a] & bit(c):
                continue
            bs = adj[a] & adj[c] & above_a
            while bs:
                b = lowest(bs)
                bs &= bs - ONE
                ds = bs & ~adj[b]
                while ds:
                    d = lowest(ds)
                    ds &= ds - ONE
                    belt = bit(a) | bit(b) | bit(c) | bit(d)
                    rest = everything & ~belt
                    side = popcount(_component(adj, bit(lowest(rest)), rest))
                    k = split_type(n, side)
                    belts += 1
                    penalty += belt_penalty(n, k)
                    split_k = max(split_k, k)
    out[0], out[1], out[2] = split_k, belts, penalty
