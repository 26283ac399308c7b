"""Is a grain's face adjacency the dual of a simple 3-polytope (a triangulation of the sphere)?

A grain with ``n`` faces is held as local CSR lists: ``nb[off[v]:off[v+1]]`` are the faces
that share an edge with face ``v``, ideally in cyclic order. Orientation may differ from face
to face, and the order may be missing altogether; since a triangulation of the sphere is
3-connected it has one embedding (Whitney), which :func:`_embed_triangulation` recovers.
"""

import numpy as np

from grainclass._kernels.codes import (
    DEGENERATE,
    E_ASYMMETRIC,
    E_DISCONNECTED,
    E_EULER,
    E_FEW_NEIGHBOURS,
    E_INDEX_RANGE,
    E_NON_SIMPLE,
    E_NOT_SPHERE,
    E_SELF,
    E_SHARED_EDGES,
    E_TOO_FEW_FACES,
    E_TOO_MANY_EDGES,
    E_TWO_GON,
    E_UNORDERED,
    INVALID,
    NON_SIMPLE,
    OK,
)
from grainclass._numba import njit


@njit(inline="always")
def grain_lists(g, face_offsets, nbr_offsets, neighbors):
    """``(n, off, nb)``: grain g of a CSR batch as local lists (see above), its offsets
    rebased to 0 and its neighbours a view."""
    f0, n = face_offsets[g], face_offsets[g + 1] - face_offsets[g]
    off = nbr_offsets[f0 : f0 + n + 1] - nbr_offsets[f0]
    return n, off, neighbors[nbr_offsets[f0] : nbr_offsets[f0 + n]]


@njit
def _count(off, nb, v, x):
    """How often face ``x`` appears in the list of face ``v``."""
    c = 0
    for i in range(off[v], off[v + 1]):
        if nb[i] == x:
            c += 1
    return c


@njit
def _position(off, nb, v, x):
    """Offset of ``x`` within the list of ``v`` (0-based), or -1 if absent."""
    for i in range(off[v], off[v + 1]):
        if nb[i] == x:
            return i - off[v]
    return -1


@njit
def _check_lists(n, off, nb, err):
    """Index range, self-reference, symmetry, 2-gons and doubly shared edges; returns a status."""
    for v in range(n):
        for i in range(off[v], off[v + 1]):
            x = nb[i]
            if x < 0 or x >= n:
                err[0], err[1], err[2] = E_INDEX_RANGE, v, x
                return INVALID
            if x == v:
                err[0], err[1], err[2] = E_SELF, v, v
                return INVALID
    for v in range(n):
        for i in range(off[v], off[v + 1]):
            # int64 like v, as everywhere _count is called: each mix of scalar types would be
            # compiled again (here and in the other kernels of the general path), lengthening
            # a first run.
            x = np.int64(nb[i])
            if _count(off, nb, v, x) != _count(off, nb, x, v):
                err[0], err[1], err[2] = E_ASYMMETRIC, v, x
                return INVALID
    for v in range(n):
        d = off[v + 1] - off[v]
        if d < 2:
            err[0], err[1], err[2] = E_FEW_NEIGHBOURS, v, d
            return INVALID
    # Degenerate grains (the paper's Sec. IV) are data, not errors.
    for v in range(n):
        if off[v + 1] - off[v] == 2:
            err[0], err[1], err[2] = E_TWO_GON, v, 2
            return DEGENERATE
    for v in range(n):
        for i in range(off[v], off[v + 1]):
            c = _count(off, nb, v, np.int64(nb[i]))
            if c > 1:
                err[0], err[1], err[2] = E_SHARED_EDGES, v, nb[i]
                return DEGENERATE
    if n < 4:
        err[0], err[1], err[2] = E_TOO_FEW_FACES, n, 0
        return INVALID
    return OK


@njit
def _first_unreached(n, off, nb, skip):
    """Breadth-first search avoiding faces with ``skip[v]``; the first face not reached, or -1.

    ``skip`` is left unchanged. O(n + E).
    """
    seen = skip.copy()
    queue = np.empty(n, np.int32)
    start = -1
    for v in range(n):
        if not seen[v]:
            start = v
            break
    if start < 0:
        return -1
    seen[start] = True
    queue[0] = start
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
    for v in range(n):
        if not seen[v]:
            return v
    return -1


@njit
def _orient(n, off, nb, adj, sign):
    """Choose a direction (+1/-1) for every face's list so that triangles turn one way.

    Around a triangle (v, x, y) of a consistently oriented triangulation, ``next_v(x) = y``
    implies ``next_x(y) = v``; that fixes ``sign[x]`` relative to ``sign[v]``. Corners that are
    not triangles impose nothing. Returns False when the constraints contradict each other.
    """
    sign[:] = 0
    queue = np.empty(n, np.int32)
    for root in range(n):
        if sign[root] != 0:
            continue
        sign[root] = 1
        queue[0] = root
        head, tail = 0, 1
        while head < tail:
            v = queue[head]
            head += 1
            d = off[v + 1] - off[v]
            for i in range(d):
                x = nb[off[v] + i]
                y = nb[off[v] + (i + sign[v] + d) % d]
                if not adj[x, y]:
                    continue
                dx = off[x + 1] - off[x]
                p = _position(off, nb, x, y)
                if nb[off[x] + (p + 1) % dx] == v:
                    s = 1
                elif nb[off[x] + (p - 1 + dx) % dx] == v:
                    s = -1
                else:
                    continue
                # A triangle only if y's list has v and x side by side too: in a grain with a
                # corner of four faces, two of them adjacent elsewhere look like one from v and
                # x alone, and would impose a wrong sign.
                dy = off[y + 1] - off[y]
                q = _position(off, nb, y, v)
                if nb[off[y] + (q + 1) % dy] != x and nb[off[y] + (q - 1 + dy) % dy] != x:
                    continue
                if sign[x] == 0:
                    sign[x] = s
                    queue[tail] = x
                    tail += 1
                elif sign[x] != s:
                    return False
    return True


@njit
def _trace_faces(n, off, nb, sign, out):
    """Trace the corners of the grain (faces of the dual map) given by the oriented lists.

    A corner is a pair (face v, neighbour x); the next corner around the same grain corner is
    (next_v(x), v). Writes into ``out`` the longest cycle length and one face on it; returns the
    number of cycles. O(E * max degree).
    """
    m = off[n]
    owner = np.empty(m, np.int32)
    for v in range(n):
        for i in range(off[v], off[v + 1]):
            owner[i] = v
    visited = np.zeros(m, np.bool_)
    cycles = 0
    out[0], out[1] = 0, -1
    for start in range(m):
        if visited[start]:
            continue
        cycles += 1
        length = 0
        cur = start
        while not visited[cur]:
            visited[cur] = True
            length += 1
            a = owner[cur]
            da = off[a + 1] - off[a]
            c = nb[off[a] + (cur - off[a] + sign[a] + da) % da]
            cur = off[c] + _position(off, nb, c, a)
        if length > out[0]:
            out[0], out[1] = length, owner[start]
    return cycles


@njit
def _add_facial(third, a, b, c, err):
    """Record the facial triangle abc on edge ab; False if ab already lies on two."""
    for s in range(2):
        if third[a, b, s] < 0:
            third[a, b, s] = c
            third[b, a, s] = c
            return True
    err[0], err[1], err[2] = E_NOT_SPHERE, a, b
    return False


@njit
def _embed_triangulation(n, off, nb, adj, err, third):
    """Recover the embedding of a graph with 3n - 6 edges from its graph alone.

    In a triangulation of the sphere the faces are exactly the triangles whose removal leaves
    the graph connected. The graph is a sphere triangulation iff those triangles cover every
    edge twice and close up into one cycle around every vertex (then F = 2n - 4 and the
    Euler characteristic is 2). ``third[u, v]`` (int32[n, n, 2], filled with -1) gets the third
    vertices of the two faces on edge u-v. O(T * E) for T triangles: used only when the lists
    are not in cyclic order.
    """
    skip = np.zeros(n, np.bool_)
    for u in range(n):
        for i in range(off[u], off[u + 1]):
            v = np.int64(nb[i])  # int64 like u: one compiled _add_facial, not three
            if v <= u:
                continue
            for j in range(off[v], off[v + 1]):
                w = np.int64(nb[j])
                if w <= v or not adj[u, w]:
                    continue
                skip[u] = skip[v] = skip[w] = True
                facial = _first_unreached(n, off, nb, skip) < 0
                skip[u] = skip[v] = skip[w] = False
                if not facial:
                    continue
                if not (
                    _add_facial(third, u, v, w, err)
                    and _add_facial(third, v, w, u, err)
                    and _add_facial(third, w, u, v, err)
                ):
                    return False
    for v in range(n):
        d = off[v + 1] - off[v]
        x0 = nb[off[v]]
        prev, cur, steps = -1, x0, 0
        while True:
            if third[v, cur, 1] < 0:  # edge v-cur lies on fewer than two facial triangles
                err[0], err[1], err[2] = E_NOT_SPHERE, v, cur
                return False
            nxt = third[v, cur, 0] if third[v, cur, 0] != prev else third[v, cur, 1]
            prev, cur = cur, nxt
            steps += 1
            if cur == x0 or steps > d:
                break
        if steps != d:  # the triangles around v do not form one disc
            err[0], err[1], err[2] = E_NOT_SPHERE, v, x0
            return False
    return True


@njit
def _rotation(n, off, nb, rot):
    """Counter-clockwise rotation lists of an ok grain into ``rot`` (same layout as ``nb``),
    oriented like face 0's list where the lists are cyclic, else recovered from the graph."""
    adj = np.zeros((n, n), np.uint8)
    for v in range(n):
        for i in range(off[v], off[v + 1]):
            adj[v, nb[i]] = 1
    sign = np.zeros(n, np.int64)
    longest = np.empty(2, np.int64)
    source = nb.copy()  # of nb's type: one compiled _orient and _trace_faces for both
    if not (
        _orient(n, off, nb, adj, sign) and _trace_faces(n, off, nb, sign, longest) == 2 * n - 4
    ):
        third = np.full((n, n, 2), -1, np.int32)
        _embed_triangulation(n, off, nb, adj, np.zeros(3, np.int64), third)
        for v in range(n):  # walk the link of v: its neighbours in cyclic order
            prev, cur = -1, nb[off[v]]
            for i in range(off[v], off[v + 1]):
                rot[i] = cur
                nxt = third[v, cur, 0] if third[v, cur, 0] != prev else third[v, cur, 1]
                prev, cur = cur, nxt
        for i in range(off[n]):
            source[i] = rot[i]
        _orient(n, off, source, adj, sign)
    for v in range(n):
        d = off[v + 1] - off[v]
        for i in range(d):
            rot[off[v] + i] = source[off[v] + (i if sign[v] > 0 else d - 1 - i)]


@njit
def _validate(n, off, nb, adj, err):
    """``(status, one_way)`` of one grain, with the reason in ``err``; fills the n x n matrix
    ``adj``. ``one_way``: an ok grain's lists are cyclic and turn one way as given, so that
    they are its rotation lists (:func:`_rotation` would give them back unchanged)."""
    status = _check_lists(n, off, nb, err)
    if status != OK:
        return status, False
    skip = np.zeros(n, np.bool_)
    lost = _first_unreached(n, off, nb, skip)
    if lost >= 0:
        err[0], err[1], err[2] = E_DISCONNECTED, lost, 0
        return INVALID, False
    edges = off[n] // 2
    if edges > 3 * n - 6:
        err[0], err[1], err[2] = E_TOO_MANY_EDGES, edges, 3 * n - 6
        return INVALID, False
    adj[:, :] = 0
    for v in range(n):
        for i in range(off[v], off[v + 1]):
            adj[v, nb[i]] = 1
    sign = np.zeros(n, np.int64)
    consistent = _orient(n, off, nb, adj, sign)
    chi = 0
    if consistent:
        longest = np.empty(2, np.int64)
        chi = n - edges + _trace_faces(n, off, nb, sign, longest)
        if chi == 2:
            if edges == 3 * n - 6:
                return OK, bool(np.all(sign > 0))
            err[0], err[1], err[2] = E_NON_SIMPLE, longest[0], longest[1]
            return NON_SIMPLE, False
    if edges == 3 * n - 6:
        if _embed_triangulation(n, off, nb, adj, err, np.full((n, n, 2), -1, np.int32)):
            return OK, False
        return INVALID, False
    if consistent:
        err[0], err[1], err[2] = E_EULER, chi, 0
    else:
        err[0], err[1], err[2] = E_UNORDERED, edges, 3 * n - 6
    return INVALID, False
