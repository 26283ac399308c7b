"""4-belts and split types of flag grains (Lutz et al. Sec. III.D, Def. of split type and penalty).

A 4-belt is a chordless 4-cycle a-b-c-d of the dual triangulation. Rather than the paper's scan of
all 4-subsets, cycles are built from pairs of non-adjacent vertices (a, c) and pairs of their
common neighbours (b, d) that are non-adjacent too: O(n^2 * deg^2) instead of O(n^4).
"""

import numpy as np

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
def _side_size(n, off, nb, on_belt):
    """Vertices in the component of the graph minus the belt that holds the first free vertex."""
    seen = on_belt.copy()
    queue = np.empty(n, np.int32)
    for v in range(n):
        if not seen[v]:
            seen[v] = True
            queue[0] = v
            break
    head, tail = 0, 1
    while head < tail:
        v = queue[head]
        head += 1
        for i in range(off[v], off[v + 1]):
            x = nb[i]
            if not seen[x]:
                seen[x] = True
                queue[tail] = x
                tail += 1
    return tail


@njit
def _four_belts(n, off, nb, adj, out):
    """Split type, number of 4-belts and penalty of a flag triangulation.

    Writes ``out = (split_k, belts, penalty)``: the largest :func:`split_type` of its belts,
    their number and the sum of their :func:`belt_penalty`. In a triangulation a chordless
    4-cycle always leaves two non-empty sides.
    """
    on_belt = np.zeros(n, np.bool_)
    common = np.empty(n, np.int32)
    split_k, belts, penalty = 0, 0, 0
    for a in range(n):
        for c in range(a + 1, n):
            if adj[a, c]:
                continue
            m = 0
            for i in range(off[a], off[a + 1]):
                if adj[c, nb[i]]:
                    common[m] = nb[i]
                    m += 1
            for i in range(m):
                b = common[i]
                if b < a:  # each belt once: from its diagonal through the smallest vertex
                    continue
                for j in range(i + 1, m):
                    d = common[j]
                    if d < a or adj[b, d]:
                        continue
                    on_belt[a] = on_belt[b] = on_belt[c] = on_belt[d] = True
                    side = _side_size(n, off, nb, on_belt)
                    on_belt[a] = on_belt[b] = on_belt[c] = on_belt[d] = False
                    k = split_type(n, side)
                    belts += 1
                    penalty += belt_penalty(n, k)
                    split_k = max(split_k, k)
    out[0], out[1], out[2] = split_k, belts, penalty
