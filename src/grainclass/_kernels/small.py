"""The fast path: grains with at most 64 faces, each face's neighbours one uint64 bitset.

The common grain (plantri's output, a simulation's well-formed grain) is validated in O(E) and
classified without allocating: the batch kernel hands in scratch arrays reused across grains.
Anything unusual (a repeated neighbour, a face list out of cyclic order, a grain that is not ok)
makes :func:`_validate_small` return False, and the general path of ``validate.py``,
``reduce.py`` and ``belts.py`` takes over, with its exact diagnosis.
"""

from grainclass._kernels.bits import ONE, ZERO, bit, full, lowest, popcount
from grainclass._numba import njit


@njit
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


@njit
def _validate_small(n, nbr_offsets, neighbors, f0, adj, following):
    """True if grain (faces from ``f0``) is certainly a simple grain with consistent cyclic lists.

    Fills ``adj`` (uint64[>=n]) and ``following`` (uint8[64 * 64]: the neighbour after x around
    v at ``64 v + x``). One pass over the darts checks 6n - 12 of them, indices in range, no
    repeats, and counts the corners (v, x, y = next_v(x)) whose triangle closes consistently,
    next_x(y) = v and next_y(v) = x, each triangle once, at its largest vertex (the other two
    lists are complete by then). A dart determines its triangle, so 2n - 4 closed triangles use
    every dart: every dual face is a triangle, each face is in the list of each of its
    neighbours, F = 2n - 4 and, with connectivity, the Euler characteristic is 2: a sphere.
    Branch-free inside a list (indices masked to 0..63 so that bad input cannot index outside
    the tables; it is rejected at the end).
    """
    if nbr_offsets[f0 + n] - nbr_offsets[f0] != 6 * n - 12:
        return False
    bad = False
    closed = 0
    for v in range(n):
        s, e = nbr_offsets[f0 + v], nbr_offsets[f0 + v + 1]
        if e - s < 3:
            return False
        row = ZERO
        x = neighbors[e - 1] & 63
        for i in range(s, e):
            y = neighbors[i]
            bad |= (y < 0) | (y >= n)
            y &= 63
            b = bit(y)
            bad |= (row & b) != ZERO
            row |= b
            following[64 * v + x] = y
            closes = (x < v) & (y < v) & ((adj[x] & b) != ZERO) & ((adj[y] & bit(v)) != ZERO)
            closes &= (following[64 * x + y] == v) & (following[64 * y + v] == x)
            closed += closes
            x = y
        bad |= (row & bit(v)) != ZERO
        adj[v] = row
    if bad or closed != 2 * n - 4:
        return False
    return _component(adj, ONE, full(n)) == full(n)


@njit
def _reduce_small(n, adj, removed_round, link):
    """Remove degree-3 vertices round by round (see ``reduce.py``); returns the alive bitset.

    ``link[v]`` is the bitset of v's three neighbours when it went, ``removed_round[v]`` its
    round (0 if it stayed).
    """
    alive = full(n)
    n_alive = n
    for v in range(n):
        removed_round[v] = 0
    rnd = 0
    while n_alive > 4:
        cubic = ZERO
        m = alive
        while m:
            v = lowest(m)
            m &= m - ONE
            if popcount(adj[v] & alive) == 3:
                cubic |= bit(v)
        if cubic == ZERO:
            break
        rnd += 1
        while cubic and n_alive > 4:  # the bipyramid has two: keep the tetrahedron
            v = lowest(cubic)
            cubic &= cubic - ONE
            link[v] = adj[v] & alive
            removed_round[v] = rnd
            alive &= ~bit(v)
            n_alive -= 1
    return alive


@njit
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


@njit
def _parents_small(n, alive, removed_round, link, parent):
    """Parent in the truncation forest: the linked removed vertex that went first (``trees.py``)."""
    removed = full(n) & ~alive
    for v in range(n):
        parent[v] = -1
        if alive & bit(v):
            continue
        m = link[v] & removed
        while m:
            x = lowest(m)
            m &= m - ONE
            if parent[v] < 0 or removed_round[x] < removed_round[parent[v]]:
                parent[v] = x


@njit
def _four_belts_small(n, adj, out):
    """As ``belts._four_belts``: chordless 4-cycles a-b-c-d, each found once from its smallest
    vertex a; writes ``out = (split_k, belts, sum of k * (n - k - 4))``.
    """
    everything = full(n)
    split_k, belts, weight = 0, 0, 0
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
                    k = min(side, n - 4 - side)
                    belts += 1
                    weight += k * (n - 4 - k)
                    split_k = max(split_k, k)
    out[0], out[1], out[2] = split_k, belts, weight
