"""4-belts and split types of flag grains (Lutz et al. Sec. III.D, Def. of split type and penalty).

A 4-belt is a chordless 4-cycle a-b-c-d of the dual triangulation. Rather than the paper's scan of
all 4-subsets, cycles are built from pairs of non-adjacent vertices (a, c) and pairs of their
common neighbours (b, d) that are non-adjacent too.

The general path measures a cycle's sides without a search: on the dual's rotation lists, each
dart gets a weight (:func:`_side_weights`) such that the weights of a cycle's darts add up to
the number of triangles on one side of it, modulo the 2n - 4 triangles of the sphere. A side
of a chordless l-cycle with i vertices inside is a disc of 2i + l - 2 triangles.
"""

import numpy as np

from grainclass._kernels.validate import _reverse_darts
from grainclass._numba import njit


@njit(inline="always")
def split_type(n, side):
    """The split type k of a 4-belt of a triangulation with n vertices that leaves ``side`` of
    the other n - 4 vertices on one of its sides: the smaller side's count (split k:m, m =
    n - 4 - k)."""
    return min(side, n - 4 - side)


@njit(inline="always")
def belt_penalty(n, k):
    """A 4-belt's share of the penalty: n k (n - 4 - k) for split type k; a grain's penalty is
    the sum over its 4-belts."""
    return n * k * (n - 4 - k)


@njit
def _previous_darts(n, off):
    """The dart before each dart in its face's list, cyclically."""
    prev = np.empty(off[n], np.int64)
    for v in range(n):
        for i in range(off[v], off[v + 1]):
            prev[i] = i - 1
        prev[off[v]] = off[v + 1] - 1
    return prev


@njit
def _side_weights(n, off, rot, rev):
    """Weights of the darts of a triangulation with counter-clockwise rotation lists ``rot``
    (``rev``: each dart's reverse) such that ``w[rev[d]] = -w[d]`` and the darts of every
    triangle but one add up to 1 (those of the last to 1 - (2n - 4)).

    The triangle of dart a -> b is (a, b, c) with c after b around a; its darts are a -> b,
    b -> c, c -> a, each the one before the reverse of the last. The triangles form a tree by a
    search of the dual from triangle 0; the dart by which a triangle was reached, on its side,
    weighs as many triangles as its subtree holds, its reverse as many less, every other dart
    nothing. So the darts of a closed walk along a cycle add up, modulo 2n - 4, to the
    triangles on the side whose triangles hold those darts. O(n + E).
    """
    m = off[n]
    prev = _previous_darts(n, off)
    face = np.full(m, -1, np.int64)
    faces = 0
    for d in range(m):
        if face[d] < 0:
            e = d
            while face[e] < 0:
                face[e] = faces
                e = prev[rev[e]]
            faces += 1
    first = np.empty(faces, np.int64)  # a dart of each triangle
    for d in range(m):
        first[face[d]] = d
    parent_dart = np.full(faces, -1, np.int64)  # the dart on the triangle's side it came by
    order = np.empty(faces, np.int64)
    reached = np.zeros(faces, np.bool_)
    reached[0] = True
    order[0] = 0
    head, tail = 0, 1
    while head < tail:
        f = order[head]
        head += 1
        e = first[f]
        for _ in range(3):
            g = face[rev[e]]
            if not reached[g]:
                reached[g] = True
                parent_dart[g] = rev[e]
                order[tail] = g
                tail += 1
            e = prev[rev[e]]
    size = np.ones(faces, np.int64)
    w = np.zeros(m, np.int64)
    for t in range(faces - 1, 0, -1):
        g = order[t]
        d = parent_dart[g]
        size[face[rev[d]]] += size[g]
        w[d] = size[g]
        w[rev[d]] = -size[g]
    return w


@njit(inline="always")
def side_vertices(n, weight, length):
    """Vertices on the side of a chordless cycle of ``length`` whose darts weigh ``weight``
    (:func:`_side_weights`) in a triangulation with n vertices."""
    faces = 2 * n - 4
    inside = weight % faces  # Python's modulo: in 0..faces-1
    return (inside - length + 2) // 2


@njit
def _four_belts(n, off, rot, out):
    """Split type, number of 4-belts and penalty of a flag triangulation with counter-clockwise
    rotation lists ``rot``.

    Writes ``out = (split_k, belts, penalty)``: the largest :func:`split_type` of its belts,
    their number and the sum of their :func:`belt_penalty`, or -1 where that sum passes
    2^63 - 1 (from about 8,000 faces on). In a triangulation a chordless 4-cycle always leaves
    two non-empty sides.

    Each belt is found once, from its diagonal (a, c) through its smallest vertex a: the paths
    a -> b -> c with b, c > a and c not a neighbour of a, grouped by c. Two neighbours b, d of
    a are adjacent in a flag triangulation iff they are consecutive around a (a triangle on
    them is a face), and the belt's sides come from its paths' weights. O(n + sum over b of
    deg(b) times b's smaller neighbours) plus O(1) a belt: O(k^2) for the k-gonal prism, which
    has about k^2 / 2 belts.
    """
    rev = _reverse_darts(n, off, rot)
    w = _side_weights(n, off, rot, rev)
    m = off[n]
    position = np.empty(n, np.int64)  # of each neighbour of a around a
    near = np.full(n, -1, np.int64)  # a, for a and its neighbours
    group = np.full(n, -1, np.int64)  # a, for the ends c of paths from a
    head = np.empty(n, np.int64)  # c's latest path
    ends = np.empty(n, np.int64)
    via = np.empty(m, np.int64)  # a path's middle vertex b
    weight = np.empty(m, np.int64)
    after = np.empty(m, np.int64)  # the path before it to the same c
    split_k, belts, penalty = 0, 0, 0
    largest = np.iinfo(np.int64).max
    for a in range(n):
        deg_a = off[a + 1] - off[a]
        near[a] = a
        for i in range(off[a], off[a + 1]):
            near[rot[i]] = a
            position[rot[i]] = i - off[a]
        paths, n_ends = 0, 0
        for i in range(off[a], off[a + 1]):
            b = rot[i]
            if b < a:
                continue
            for j in range(off[b], off[b + 1]):
                c = rot[j]
                if c < a or near[c] == a:
                    continue
                if group[c] != a:
                    group[c] = a
                    head[c] = -1
                    ends[n_ends] = c
                    n_ends += 1
                via[paths], weight[paths], after[paths] = b, w[i] + w[j], head[c]
                head[c] = paths
                paths += 1
        for t in range(n_ends):
            p = head[ends[t]]
            while p >= 0:
                q = after[p]
                while q >= 0:
                    gap = abs(position[via[p]] - position[via[q]])
                    if gap != 1 and gap != deg_a - 1:  # b and d not adjacent: a belt
                        k = split_type(n, side_vertices(n, weight[p] - weight[q], 4))
                        belts += 1
                        share = belt_penalty(n, k)
                        penalty = penalty + share if 0 <= penalty <= largest - share else -1
                        split_k = max(split_k, k)
                    q = after[q]
                p = after[p]
    out[0], out[1], out[2] = split_k, belts, penalty
