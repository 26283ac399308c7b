"""Reverse truncations: reduce a triangulation to its fundamental polytope (Lutz et al., App. B).

A degree-3 vertex of the dual triangulation is a triangular face of the grain; removing it undoes
one truncation. For n >= 5 degree-3 vertices are never adjacent, so a whole round of them can be
removed at once, and the result does not depend on the order (the paper's uniqueness lemma).
"""

import numpy as np

from grainclass._kernels.validate import _triangles
from grainclass._numba import njit


@njit
def _reduce(n, off, nb, alive, removed_round, link):
    """Remove degree-3 vertices round by round; stop at the tetrahedron or when none is left.

    ``alive`` (bool[n]) ends as the fundamental vertex set; ``removed_round`` (int32[n]) is the
    round in which a vertex went (0 if it stayed) and ``link`` (int32[n, 3]) its three
    neighbours at that moment. Returns the number of fundamental vertices. A round looks only
    at the neighbours of the vertices the round before removed, in index order (which of the
    bipyramid's two apexes stays depends on it): O(n + E) besides sorting them.
    """
    degree = np.empty(n, np.int32)
    candidates = np.empty(n, np.int64)
    n_cand = 0
    for v in range(n):
        alive[v] = True
        removed_round[v] = 0
        degree[v] = off[v + 1] - off[v]
        if degree[v] == 3:
            candidates[n_cand] = v
            n_cand += 1
    looked = np.full(n, -1, np.int32)  # the round a vertex was last made a candidate for
    touched = np.empty(n, np.int64)
    n_alive = n
    rnd = 0
    while n_alive > 4 and n_cand > 0:
        rnd += 1
        n_touched = 0
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
                    if looked[x] != rnd:
                        looked[x] = rnd
                        touched[n_touched] = x
                        n_touched += 1
        n_cand = 0
        for t in range(n_touched):
            x = touched[t]
            if alive[x] and degree[x] == 3:
                candidates[n_cand] = x
                n_cand += 1
        candidates[:n_cand].sort()
    return n_alive


@njit
def _has_empty_triangle(n, off, nb, alive):
    """True if the fundamental triangulation has a 3-cycle that is not a face (it is then sc).

    A triangulation of the sphere with m vertices has 2m - 4 faces, all triangles: any further
    triangle is empty. The triangles are counted by degree order (``validate._triangles``),
    O(E) for a planar graph.
    """
    m = 0
    for v in range(n):
        m += alive[v]
    _, count = _triangles(n, off, nb, alive, 2 * m - 4)
    return count < 0
