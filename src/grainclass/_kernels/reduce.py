"""Reverse truncations: reduce a triangulation to its fundamental polytope (Lutz et al., App. B).

A degree-3 vertex of the dual triangulation is a triangular face of the grain; removing it undoes
one truncation. For n >= 5 degree-3 vertices are never adjacent, so a whole round of them can be
removed at once, and the result does not depend on the order (the paper's uniqueness lemma).
"""

import numpy as np

from grainclass._numba import njit


@njit
def _reduce(n, off, nb, alive, removed_round, link):
    """Remove degree-3 vertices round by round; stop at the tetrahedron or when none is left.

    ``alive`` (bool[n]) ends as the fundamental vertex set; ``removed_round`` (int32[n]) is the
    round in which a vertex went (0 if it stayed) and ``link`` (int32[n, 3]) its three
    neighbours at that moment. Returns the number of fundamental vertices. O(n * rounds * deg).
    """
    degree = np.empty(n, np.int32)
    for v in range(n):
        alive[v] = True
        removed_round[v] = 0
        degree[v] = off[v + 1] - off[v]
    n_alive = n
    candidates = np.empty(n, np.int32)
    rnd = 0
    while n_alive > 4:
        n_cand = 0
        for v in range(n):
            if alive[v] and degree[v] == 3:
                candidates[n_cand] = v
                n_cand += 1
        if n_cand == 0:
            break
        rnd += 1
        for c in range(n_cand):
            if n_alive == 4:  # the bipyramid has two: keep the tetrahedron
                break
            v = candidates[c]
            alive[v] = False
            removed_round[v] = rnd
            n_alive -= 1
            k = 0
            for i in range(off[v], off[v + 1]):
                x = nb[i]
                if alive[x]:
                    degree[x] -= 1
                    link[v, k] = x
                    k += 1
    return n_alive


@njit
def _has_empty_triangle(n, off, nb, adj, alive):
    """True if the fundamental triangulation has a 3-cycle that is not a face (it is then sc).

    Each edge of a triangulation lies on exactly two faces, so an edge with a third common
    neighbour closes an empty triangle. O(E * deg).
    """
    for u in range(n):
        if not alive[u]:
            continue
        for i in range(off[u], off[u + 1]):
            v = nb[i]
            if v <= u or not alive[v]:
                continue
            common = 0
            for j in range(off[u], off[u + 1]):
                x = nb[j]
                if alive[x] and adj[v, x]:
                    common += 1
            if common > 2:
                return True
    return False
