"""Is a grain's face adjacency the dual of a simple 3-polytope (a triangulation of the sphere)?

A grain with ``n`` faces is held as local CSR lists: ``nb[off[v]:off[v+1]]`` are the faces
that share an edge with face ``v``, ideally in cyclic order. Orientation may differ from face
to face, and the order may be missing altogether; since a triangulation of the sphere is
3-connected it has one embedding (Whitney), which :func:`_embed_triangulation` recovers.

Entry ``i`` of the lists is the dart ``v -> nb[i]``. Everything here works on darts, with arrays
of length n or E (the number of darts), never a table of n x n: memory and, unless the lists
are out of cyclic order, time grow linearly with the grain. The dart back along an edge,
``rev[i]``, comes from :func:`_reverse_darts` once the lists are known to be symmetric.
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
def _incoming(n, off, nb):
    """``(in_off, darts)``: the darts into each face, ``darts[in_off[x]:in_off[x + 1]]`` those
    of face x, by a counting sort. O(n + E)."""
    in_off = np.zeros(n + 1, np.int64)
    for i in range(off[n]):
        in_off[nb[i] + 1] += 1
    for x in range(n):
        in_off[x + 1] += in_off[x]
    fill = in_off[:n].copy()
    darts = np.empty(off[n], np.int64)
    for v in range(n):
        for i in range(off[v], off[v + 1]):
            x = nb[i]
            darts[fill[x]] = i
            fill[x] += 1
    return in_off, darts


@njit
def _owners(n, off):
    """The face each dart leaves from."""
    owner = np.empty(off[n], np.int64)
    for v in range(n):
        for i in range(off[v], off[v + 1]):
            owner[i] = v
    return owner


@njit
def _check_lists(n, off, nb, err):
    """Index range, self-reference, symmetry, 2-gons and doubly shared edges; returns a status.

    The first face (in order) whose list holds a face a different number of times than that
    face's list holds it is reported, as a count per pair would find it; the counts come from
    marks in an array of n, set and cleared per face: O(n + E)."""
    for v in range(n):
        for i in range(off[v], off[v + 1]):
            x = nb[i]
            if x < 0 or x >= n:
                err[0], err[1], err[2] = E_INDEX_RANGE, v, x
                return INVALID
            if x == v:
                err[0], err[1], err[2] = E_SELF, v, v
                return INVALID
    in_off, darts = _incoming(n, off, nb)
    owner = _owners(n, off)
    balance = np.zeros(n, np.int64)  # times v lists x, less times x lists v
    for v in range(n):
        for i in range(off[v], off[v + 1]):
            balance[nb[i]] += 1
        for j in range(in_off[v], in_off[v + 1]):
            balance[owner[darts[j]]] -= 1
        bad = -1
        for i in range(off[v], off[v + 1]):
            if bad < 0 and balance[nb[i]] != 0:
                bad = nb[i]
        for i in range(off[v], off[v + 1]):
            balance[nb[i]] = 0
        for j in range(in_off[v], in_off[v + 1]):
            balance[owner[darts[j]]] = 0
        if bad >= 0:
            err[0], err[1], err[2] = E_ASYMMETRIC, v, bad
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
            balance[nb[i]] += 1
        bad = -1
        for i in range(off[v], off[v + 1]):
            if bad < 0 and balance[nb[i]] > 1:
                bad = nb[i]
        for i in range(off[v], off[v + 1]):
            balance[nb[i]] = 0
        if bad >= 0:
            err[0], err[1], err[2] = E_SHARED_EDGES, v, bad
            return DEGENERATE
    if n < 4:
        err[0], err[1], err[2] = E_TOO_FEW_FACES, n, 0
        return INVALID
    return OK


@njit
def _reverse_darts(n, off, nb):
    """``rev``: the dart x -> v of each dart v -> x, for symmetric lists without repeats (as
    :func:`_check_lists` passes them). O(n + E)."""
    in_off, darts = _incoming(n, off, nb)
    owner = _owners(n, off)
    at_x = np.empty(n, np.int64)  # where each neighbour of x is in x's list
    rev = np.empty(off[n], np.int64)
    for x in range(n):
        for j in range(off[x], off[x + 1]):
            at_x[nb[j]] = j
        for k in range(in_off[x], in_off[x + 1]):
            i = darts[k]
            rev[i] = at_x[owner[i]]
    return rev


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
def _orient(n, off, nb, rev, sign):
    """Choose a direction (+1/-1) for every face's list so that triangles turn one way.

    Around a triangle (v, x, y) of a consistently oriented triangulation, ``next_v(x) = y``
    implies ``next_x(y) = v``; that fixes ``sign[x]`` relative to ``sign[v]``. Corners that are
    not triangles impose nothing. Returns False when the constraints contradict each other.
    Where v is in x's list is ``rev`` of the dart v -> x: O(n + E).
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
                f = off[v] + (i + sign[v] + d) % d  # the dart v -> y
                y = nb[f]
                dx = off[x + 1] - off[x]
                p = rev[off[v] + i] - off[x]  # v in x's list
                if nb[off[x] + (p - 1 + dx) % dx] == y:  # y, then v, around x
                    s = 1
                elif nb[off[x] + (p + 1) % dx] == y:
                    s = -1
                else:
                    continue
                # A triangle only if y's list has v and x side by side too: in a grain with a
                # corner of four faces, two of them adjacent elsewhere look like one from v and
                # x alone, and would impose a wrong sign.
                dy = off[y + 1] - off[y]
                q = rev[f] - off[y]
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
def _trace_faces(n, off, nb, rev, sign, out):
    """Trace the corners of the grain (faces of the dual map) given by the oriented lists.

    A corner is a pair (face v, neighbour x); the next corner around the same grain corner is
    (next_v(x), v). Writes into ``out`` the longest cycle length and one face on it; returns the
    number of cycles. O(n + E).
    """
    m = off[n]
    owner = _owners(n, off)
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
            cur = rev[off[a] + (cur - off[a] + sign[a] + da) % da]
        if length > out[0]:
            out[0], out[1] = length, owner[start]
    return cycles


@njit(inline="always")
def _edge(rev, i):
    """The edge of dart i, as the smaller of its two darts."""
    return min(i, rev[i])


@njit
def _add_facial(third, e, c, a, b, err):
    """Record c as the third vertex of a facial triangle on edge e (between a and b); False if
    e already lies on two."""
    for s in range(2):
        if third[e, s] < 0:
            third[e, s] = c
            return True
    err[0], err[1], err[2] = E_NOT_SPHERE, a, b
    return False


@njit(inline="always")
def _above(deg, v, x):
    """Whether x comes after v in the order by (degree, index)."""
    return deg[x] > deg[v] or (deg[x] == deg[v] and x > v)


@njit
def _triangles(n, off, nb, alive, limit):
    """The triangles of the graph on the faces ``alive`` as darts (u -> v, v -> w, u -> w),
    each once, listed by the degree order (Chiba and Nishizeki): each edge points to its end of
    higher (degree, index), and a triangle is found from its lowest vertex. O(E) for a planar
    graph, whatever its degrees. Returns ``(triangles, count)``; stops with count -1 past
    ``limit`` triangles."""
    deg = np.empty(n, np.int64)
    for v in range(n):
        deg[v] = off[v + 1] - off[v]
    up_off = np.zeros(n + 1, np.int64)
    for v in range(n):
        for i in range(off[v], off[v + 1]):
            x = nb[i]
            up_off[v + 1] += alive[v] and alive[x] and _above(deg, v, x)
    for v in range(n):
        up_off[v + 1] += up_off[v]
    up = np.empty(up_off[n], np.int64)  # darts up
    k = 0
    for v in range(n):
        for i in range(off[v], off[v + 1]):
            x = nb[i]
            if alive[v] and alive[x] and _above(deg, v, x):
                up[k] = i
                k += 1
    mark = np.full(n, -1, np.int64)  # the dart u -> x for x up from u, while u is looked at
    owner_of_mark = np.full(n, -1, np.int64)
    found = np.empty((limit, 3), np.int64)
    count = 0
    for u in range(n):
        for k in range(up_off[u], up_off[u + 1]):
            mark[nb[up[k]]] = up[k]
            owner_of_mark[nb[up[k]]] = u
        for k in range(up_off[u], up_off[u + 1]):
            i = up[k]
            v = nb[i]
            for j in range(up_off[v], up_off[v + 1]):
                w = nb[up[j]]
                if owner_of_mark[w] == u:
                    if count == limit:
                        return found, -1
                    found[count, 0], found[count, 1], found[count, 2] = i, up[j], mark[w]
                    count += 1
    return found, count


@njit
def _embed_triangulation(n, off, nb, rev, err, third):
    """Recover the embedding of a graph with 3n - 6 edges from its graph alone.

    In a triangulation of the sphere the faces are exactly the triangles whose removal leaves
    the graph connected: the two triangles on an edge that lies on only two are faces, the
    others are tested by a search. The graph is a sphere triangulation iff the triangles taken
    cover every edge twice and close up into one cycle around every vertex (then F = 2n - 4
    and the Euler characteristic is 2, however they were chosen). ``third[e]`` (int64[E, 2],
    filled with -1, per edge e = :func:`_edge`) gets the third vertices of the two faces on
    it. A sphere has at most 2n - 4 + n - 4 triangles: a graph with more is none. O(n + E)
    plus a search O(E) per triangle none of whose edges lies on two triangles only (the
    separating ones and their neighbours): used only when the lists are not in cyclic order.
    """
    tri, count = _triangles(n, off, nb, np.ones(n, np.bool_), 3 * n)
    if count < 0:
        err[0], err[1], err[2] = E_NOT_SPHERE, nb[tri[0, 0]], nb[tri[0, 1]]
        return False
    owner = _owners(n, off)
    on = np.zeros(off[n], np.int64)  # triangles on each edge
    for t in range(count):
        for s in range(3):
            on[_edge(rev, tri[t, s])] += 1
    skip = np.zeros(n, np.bool_)
    for t in range(count):
        i, j, k = tri[t, 0], tri[t, 1], tri[t, 2]
        u, v, w = owner[i], nb[i], nb[j]
        facial = on[_edge(rev, i)] == 2 or on[_edge(rev, j)] == 2 or on[_edge(rev, k)] == 2
        if not facial:
            skip[u] = skip[v] = skip[w] = True
            facial = _first_unreached(n, off, nb, skip) < 0
            skip[u] = skip[v] = skip[w] = False
        if not facial:
            continue
        if not (
            _add_facial(third, _edge(rev, i), w, u, v, err)
            and _add_facial(third, _edge(rev, j), u, v, w, err)
            and _add_facial(third, _edge(rev, k), v, w, u, err)
        ):
            return False
    at_v = np.empty(n, np.int64)  # the dart v -> x, for the neighbours x of v
    for v in range(n):
        d = off[v + 1] - off[v]
        for i in range(off[v], off[v + 1]):
            at_v[nb[i]] = i
        x0 = nb[off[v]]
        prev, cur, steps = -1, x0, 0
        while True:
            e = _edge(rev, at_v[cur])
            if third[e, 1] < 0:  # edge v-cur lies on fewer than two facial triangles
                err[0], err[1], err[2] = E_NOT_SPHERE, v, cur
                return False
            nxt = third[e, 0] if third[e, 0] != prev else third[e, 1]
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
    rev = _reverse_darts(n, off, nb)
    sign = np.zeros(n, np.int64)
    longest = np.empty(2, np.int64)
    source = nb.copy()  # of nb's type: one compiled _orient and _trace_faces for both
    if not (
        _orient(n, off, nb, rev, sign) and _trace_faces(n, off, nb, rev, sign, longest) == 2 * n - 4
    ):
        third = np.full((off[n], 2), -1, np.int64)
        _embed_triangulation(n, off, nb, rev, np.zeros(3, np.int64), third)
        at_v = np.empty(n, np.int64)
        for v in range(n):  # walk the link of v: its neighbours in cyclic order
            for i in range(off[v], off[v + 1]):
                at_v[nb[i]] = i
            prev, cur = -1, nb[off[v]]
            for i in range(off[v], off[v + 1]):
                rot[i] = cur
                e = _edge(rev, at_v[cur])
                nxt = third[e, 0] if third[e, 0] != prev else third[e, 1]
                prev, cur = cur, nxt
        for i in range(off[n]):
            source[i] = rot[i]
        rev = _reverse_darts(n, off, source)
        _orient(n, off, source, rev, sign)
    for v in range(n):
        d = off[v + 1] - off[v]
        for i in range(d):
            rot[off[v] + i] = source[off[v] + (i if sign[v] > 0 else d - 1 - i)]


@njit
def _validate(n, off, nb, err):
    """``(status, one_way)`` of one grain, with the reason in ``err``. ``one_way``: an ok
    grain's lists are cyclic and turn one way as given, so that they are its rotation lists
    (:func:`_rotation` would give them back unchanged)."""
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
    rev = _reverse_darts(n, off, nb)
    sign = np.zeros(n, np.int64)
    consistent = _orient(n, off, nb, rev, sign)
    chi = 0
    if consistent:
        longest = np.empty(2, np.int64)
        chi = n - edges + _trace_faces(n, off, nb, rev, sign, longest)
        if chi == 2:
            if edges == 3 * n - 6:
                return OK, bool(np.all(sign > 0))
            err[0], err[1], err[2] = E_NON_SIMPLE, longest[0], longest[1]
            return NON_SIMPLE, False
    if edges == 3 * n - 6:
        if _embed_triangulation(n, off, nb, rev, err, np.full((off[n], 2), -1, np.int64)):
            return OK, False
        return INVALID, False
    if consistent:
        err[0], err[1], err[2] = E_EULER, chi, 0
    else:
        err[0], err[1], err[2] = E_UNORDERED, edges, 3 * n - 6
    return INVALID, False
