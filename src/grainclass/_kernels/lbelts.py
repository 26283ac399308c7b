"""Belts of every length l = 3..L (Lutz et al. Sec. II.C and Def. of split type, any l).

An l-belt is a set of l faces whose dual graph is a chordless l-cycle of the dual
triangulation; for l = 3 only the non-trivial ones count (a 3-cycle that is not a face, whose
removal leaves two sides). Removing a belt leaves two discs of k and m faces, k <= m; the split
type k:l:m of a grain is that of its most balanced l-belt (largest k), 0:l:(n - l) without
one, and none (-1) for a grain of fewer than l faces. A grain's l-penalty is n times the sum
over its l-belts of k (n - l - k): for l = 4 the paper's penalty.

Each chordless cycle is grown once from its smallest vertex s, by a depth-first search of
chordless paths s, p1, p2, ... through vertices above s: the next vertex is a neighbour of the
last one that is neither in nor next to the path before it, nor next to s; a neighbour of s
closes the cycle, counted in the direction in which it comes after p1. Writes, per grain,
``out[l - 3] = (belts, split_k, penalty)``.
"""

import numpy as np

from grainclass._kernels.belts import _side_weights, side_vertices
from grainclass._kernels.bits import ONE, ZERO, bit, full, lowest, popcount
from grainclass._kernels.small import _component
from grainclass._kernels.validate import _reverse_darts, _rotation, grain_lists
from grainclass._numba import borrowed, njit, njit_leaf

MAX_BELT_LENGTH = 10


@njit(inline="always")
def _no_belts(out, n, longest):
    """``out`` (int64[longest - 2, 3]) before any belt is found: per l, no belts and no
    penalty, and the split type of a grain without an l-belt, 0:l:(n - l) by the paper's
    definition (Def. of split type), where n >= l; where n < l none (-1): 0:l:(n - l) would
    leave a disc of n - l < 0 faces, and break the definition's k <= m."""
    for r in range(longest - 2):
        out[r, 0] = 0
        out[r, 1] = 0 if n >= r + 3 else -1
        out[r, 2] = 0


@njit(inline="always")
def _record(out, n, length, k):
    """One belt of ``length`` with split type k into ``out``."""
    row = length - 3
    out[row, 0] += 1
    out[row, 1] = max(out[row, 1], k)
    out[row, 2] += n * k * (n - length - k)


@njit_leaf
def _belt_profile_small(n, adj, longest, out, cand, forb, path, cyc):
    """The belts of lengths 3..``longest`` of a triangulation on at most 64 vertices, its
    neighbourhoods as bitsets in ``adj``, into ``out`` (int64[longest - 2, 3], zeroed here).
    ``cand``, ``forb``, ``cyc`` (uint64[longest + 1]) and ``path`` (int64[longest + 1]) are
    scratch: per depth j, the choices left for p_j, the vertices next to p_1..p_{j-2}, and the
    cycle's vertices so far. A belt's sides are the components of the rest, on bitsets."""
    _no_belts(out, n, longest)
    everything = full(n)
    for s in range(n):
        above = everything & ~full(s + 1)
        near = adj[s]
        if popcount(near & above) < 2:
            continue
        cand[1] = near & above
        forb[1] = ZERO
        forb[2] = ZERO
        cyc[0] = bit(s)
        j = 1
        while j >= 1:
            if cand[j] == ZERO:
                j -= 1
                continue
            x = lowest(cand[j])
            cand[j] &= cand[j] - ONE
            path[j] = x
            cyc[j] = cyc[j - 1] | bit(x)
            if j >= 2:
                forb[j + 1] = forb[j] | adj[path[j - 1]] | bit(path[j - 1])
            # Cycles closed by a neighbour y of s after p_j: length j + 2.
            if j + 2 <= longest:
                closes = adj[x] & near & above & ~forb[j + 1] & ~cyc[j]
                closes &= ~full(path[1] + 1)  # after p1: each cycle in one direction
                if j == 1 and popcount(adj[s] & adj[x]) == 2:
                    closes = ZERO  # the two triangles on edge s-p1 are faces
                while closes:
                    y = lowest(closes)
                    closes &= closes - ONE
                    length = j + 2
                    rest = everything & ~(cyc[j] | bit(y))
                    side = popcount(_component(adj, bit(lowest(rest)), rest))
                    k = min(side, n - length - side)
                    if k > 0:  # a face (l = 3) leaves one side only
                        _record(out, n, length, k)
            if j + 3 <= longest:
                cand[j + 1] = adj[x] & above & ~near & ~forb[j + 1] & ~cyc[j]
                if cand[j + 1]:
                    j += 1


@njit(inline="always")
def _block(off, rot, v, blocked, step):
    """v and its neighbours in or out of the blocked vertices."""
    blocked[v] += step
    for i in range(off[v], off[v + 1]):
        blocked[rot[i]] += step


@njit
def _belt_profile(n, off, rot, longest, out):
    """:func:`_belt_profile_small` for a triangulation of any size, with counter-clockwise
    rotation lists ``rot``: the path's neighbours are counted in an array, and a belt's sides
    come from the weights of its darts (``belts._side_weights``) without a search. O(n + E)
    memory; time as the number of chordless paths of fewer than ``longest`` vertices."""
    _no_belts(out, n, longest)
    rev = _reverse_darts(n, off, rot)
    w = _side_weights(n, off, rot, rev)
    blocked = np.zeros(n, np.int64)  # times a vertex is in or next to p_1..p_{j-2}
    on_path = np.zeros(n, np.bool_)
    near = np.full(n, -1, np.int64)  # s, for the neighbours of s
    dart_from_s = np.empty(n, np.int64)
    path = np.empty(longest + 1, np.int64)
    next_dart = np.empty(longest + 1, np.int64)  # the next to try out of p_{j-1}
    weight = np.zeros(longest + 1, np.int64)  # of the darts s -> p1 -> ... -> p_j
    for s in range(n):
        for i in range(off[s], off[s + 1]):
            near[rot[i]] = s
            dart_from_s[rot[i]] = i
        path[0] = s
        j = 1
        next_dart[1] = off[s]
        while j >= 1:
            u = path[j - 1]
            if next_dart[j] == off[u + 1]:  # no choices left at depth j: back to depth j - 1
                j -= 1
                if j >= 1:
                    on_path[path[j]] = False
                    if j >= 2:  # p_{j-1} stops blocking at depth j + 1
                        _block(off, rot, path[j - 1], blocked, -1)
                continue
            i = next_dart[j]
            next_dart[j] += 1
            x = rot[i]
            if x <= s or on_path[x] or blocked[x] > 0:
                continue
            if j >= 2 and near[x] == s:
                continue  # a chord to s, unless it closes the cycle (below)
            path[j] = x
            on_path[x] = True
            weight[j] = weight[j - 1] + w[i]
            if j >= 2:
                _block(off, rot, path[j - 1], blocked, 1)
            if j + 2 <= longest:
                for c in range(off[x], off[x + 1]):
                    y = rot[c]
                    if y <= path[1] or near[y] != s or on_path[y] or blocked[y] > 0:
                        continue
                    length = j + 2
                    total = weight[j] + w[c] - w[dart_from_s[y]]
                    side = side_vertices(n, total, length)
                    k = min(side, n - length - side)
                    if k > 0:  # a face (l = 3) leaves one side only
                        _record(out, n, length, k)
            if j + 3 <= longest:
                j += 1
                next_dart[j] = off[x]
            else:
                on_path[x] = False
                if j >= 2:
                    _block(off, rot, path[j - 1], blocked, -1)


@njit
def _belts_batch(first, last, grains, face_offsets, nbr_offsets, neighbors, longest, out):
    """The belts of lengths 3..``longest`` of the ok grains ``grains[first:last]`` of a CSR
    batch into ``out`` (int64[G, longest - 2, 3]: per l, the number of l-belts, the split type
    k of the most balanced and the l-penalty); rows of other grains are left alone. Grains of
    at most 64 faces on bitsets, larger ones on their rotation lists."""
    adj = np.empty(64, np.uint64)
    cand = np.empty(longest + 1, np.uint64)
    forb = np.zeros(longest + 2, np.uint64)
    cyc = np.empty(longest + 1, np.uint64)
    path = np.empty(longest + 1, np.int64)
    for i in range(first, last):
        g = grains[i]
        n, off, nb = grain_lists(g, face_offsets, nbr_offsets, neighbors)
        if n <= 64:
            for v in range(n):
                row = ZERO
                for k in range(off[v], off[v + 1]):
                    row |= bit(nb[k])
                adj[v] = row
            _belt_profile_small(
                n, borrowed(adj), longest, borrowed(out[g]), borrowed(cand), borrowed(forb),
                borrowed(path), borrowed(cyc),
            )  # fmt: skip
        else:
            rot = np.empty(off[n], np.int64)
            _rotation(n, off, nb, rot)
            _belt_profile(n, off, rot, longest, out[g])
