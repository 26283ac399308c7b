"""Truncation trees (Lutz et al. Sec. II.B) written as one canonical string per grain.

A removed vertex w was stacked onto the triangle formed by its three neighbours at removal time.
That triangle was created by the most recently stacked of them, i.e. by the one removed earliest:
that vertex is w's parent; a w whose link is all fundamental is a root. Neighbours in a link are
adjacent, and adjacent degree-3 vertices never go in the same round, so the parent is unique.

Canonical form: a tree is ``(`` + its children's strings in ascending byte order + ``)``; the
forest is its trees sorted by (length, string) joined by ``+``.
"""

import numpy as np

from grainclass._kernels.bits import ONE, ZERO, bit, full, lowest
from grainclass._numba import borrowed, njit, njit_leaf

OPEN, CLOSE, PLUS = 40, 41, 43  # "(", ")", "+"


@njit(inline="always")
def _copy(source, at, count, target, to):
    """Copy ``count`` bytes from ``source[at:]`` to ``target[to:]``; returns the end in target.

    A loop, not a slice assignment: that would compile shape checks with formatted error
    messages, seconds of first-run compilation for nothing.
    """
    for i in range(count):
        target[to + i] = source[at + i]
    return to + count


@njit(inline="always")
def _less(buf, a_start, a_len, b_start, b_len):
    """Byte-wise lexicographic ``buf[a] < buf[b]`` for two slices of one buffer."""
    for i in range(min(a_len, b_len)):
        if buf[a_start + i] != buf[b_start + i]:
            return buf[a_start + i] < buf[b_start + i]
    return a_len < b_len


@njit(inline="always")
def _sort_slices(items, count, buf, start, length, by_length_first):
    """Insertion sort of node ids ``items[:count]`` by their strings in ``buf``."""
    for i in range(1, count):
        item = items[i]
        j = i - 1
        while j >= 0:
            other = items[j]
            if by_length_first and length[other] != length[item]:
                greater = length[other] > length[item]
            else:
                greater = _less(buf, start[item], length[item], start[other], length[other])
            if not greater:
                break
            items[j + 1] = other
            j -= 1
        items[j + 1] = item


@njit
def _parents_from_links(n, alive, removed_round, link, parent):
    """Parent of each removed vertex: the vertex of its link that was removed first, else -1."""
    for v in range(n):
        parent[v] = -1
        if alive[v]:
            continue
        for k in range(3):
            x = link[v, k]
            if not alive[x] and (parent[v] < 0 or removed_round[x] < removed_round[parent[v]]):
                parent[v] = x


@njit
def _forest_scratch(n, string_bytes):
    """Scratch arrays for :func:`_forest_string` and :func:`_forest_string_small` on up to n
    vertices whose subtrees' strings take up to ``string_bytes`` (:func:`_forest_bytes`)."""
    return (
        np.empty(max(n, 1), np.int32),  # first child of each vertex (-1: a leaf)
        np.empty(max(n, 1), np.int32),  # next sibling
        np.empty(max(n, 1), np.int32),  # the children of one vertex, to sort
        np.empty(max(string_bytes, 1), np.uint8),  # strings of the subtrees
        np.empty(max(n, 1), np.int64),  # start of each subtree's string
        np.empty(max(n, 1), np.int64),  # its length
        np.empty(max(n, 1), np.int32),  # subtree height
        np.empty(max(n, 1), np.int32),  # roots
        np.empty(n + 1, np.uint64),  # removed vertices by round (bitset path)
    )


@njit(inline="always")
def _borrowed_forest(scratch):
    """:func:`_forest_scratch`'s arrays as :func:`~grainclass._numba.borrowed` views."""
    first_child, next_sibling, kids, buf, start, length, height, roots, by_round = scratch
    return (
        borrowed(first_child), borrowed(next_sibling), borrowed(kids), borrowed(buf),
        borrowed(start), borrowed(length), borrowed(height), borrowed(roots), borrowed(by_round),
    )  # fmt: skip


@njit
def _by_round(n, removed_round):
    """The removed vertices (``removed_round > 0``) in the order of their rounds, by a
    counting sort: children come before their parents. O(n + rounds)."""
    last = 0
    for v in range(n):
        last = max(last, removed_round[v])
    start = np.zeros(last + 2, np.int64)
    for v in range(n):
        start[removed_round[v] + 1] += 1
    for r in range(last + 1):
        start[r + 1] += start[r]
    kept = start[1]  # vertices of round 0
    order = np.empty(n, np.int64)
    for v in range(n):
        order[start[removed_round[v]]] = v
        start[removed_round[v]] += 1
    return order[kept:]


@njit
def _forest_bytes(n, order, parent):
    """Bytes that the strings of every subtree take together: 2 per vertex of each subtree,
    from n (a bush of leaves) to about n^2 (a path). ``order``: :func:`_by_round`'s."""
    size = np.ones(n, np.int64)
    total = 0
    for v in order:
        total += 2 * size[v]
        if parent[v] >= 0:
            size[parent[v]] += size[v]
    return total


@njit(inline="always")
def _subtree(v, first_child, next_sibling, kids, buf, start, length, height, pos):
    """Write the string of v's subtree at ``buf[pos:]`` (its children's strings are there
    already); returns where it ends."""
    start[v] = pos
    c = first_child[v]
    if c < 0:  # a leaf, most of them
        buf[pos] = OPEN
        buf[pos + 1] = CLOSE
        length[v] = 2
        height[v] = 1
        return pos + 2
    count = 0
    tallest = 0
    while c >= 0:
        kids[count] = c
        count += 1
        tallest = max(tallest, height[c])
        c = next_sibling[c]
    _sort_slices(kids, count, buf, start, length, False)
    buf[pos] = OPEN
    pos += 1
    for i in range(count):
        pos = _copy(buf, start[kids[i]], length[kids[i]], buf, pos)
    buf[pos] = CLOSE
    pos += 1
    length[v] = pos - start[v]
    height[v] = tallest + 1
    return pos


@njit(inline="always")
def _write_forest(roots, n_roots, buf, start, length, height, out, at):
    """The trees of ``roots[:n_roots]`` sorted by (length, string) and joined by ``+`` into
    ``out`` from ``at``; returns ``(n_trees, depth, length)``."""
    depth = 0
    for r in range(n_roots):
        depth = max(depth, height[roots[r]])
    _sort_slices(roots, n_roots, buf, start, length, True)
    written = at
    for r in range(n_roots):
        if r > 0:
            out[written] = PLUS
            written += 1
        v = roots[r]
        written = _copy(buf, start[v], length[v], out, written)
    return n_roots, depth, written - at


@njit
def _forest_string(n, order, parent, out, at, scratch):
    """Write the canonical forest string of the removed vertices into ``out`` from ``at``
    (3n bytes suffice; an offset, not a view: a view per grain costs reference counting).

    ``order`` holds the removed vertices by round (:func:`_by_round`); ``parent`` is -1 for
    roots. ``scratch`` comes from :func:`_forest_scratch`, with room for :func:`_forest_bytes`.
    Returns ``(n_trees, depth, length)``: depth is the number of vertices on a longest root
    path. O(n + the subtrees' strings) besides sorting siblings.
    """
    first_child, next_sibling, kids, buf, start, length, height, roots, _ = scratch
    n_roots = 0
    for v in order:
        first_child[v] = -1
    for v in order:
        if parent[v] >= 0:
            next_sibling[v] = first_child[parent[v]]
            first_child[parent[v]] = v
        else:
            roots[n_roots] = v
            n_roots += 1
    # Children are removed in earlier rounds than their parent: build strings round by round.
    pos = 0
    for v in order:
        pos = _subtree(v, first_child, next_sibling, kids, buf, start, length, height, pos)
    return _write_forest(roots, n_roots, buf, start, length, height, out, at)


@njit_leaf
def _forest_string_small(n, alive, removed_round, link, out, at, scratch):
    """:func:`_forest_string` for a grain on bitsets (``small.py``): ``alive`` is the
    fundamental vertex set, ``link[v]`` the bitset of v's neighbours when it went. Parents come
    from the links (module docstring) and only removed vertices are visited."""
    first_child, next_sibling, kids, buf, start, length, height, roots, by_round = scratch
    removed = full(n) & ~alive
    last_round = 0
    m = removed
    while m:
        v = lowest(m)
        m &= m - ONE
        first_child[v] = -1
        last_round = max(last_round, removed_round[v])
    for rnd in range(1, last_round + 1):
        by_round[rnd] = ZERO
    n_roots = 0
    m = removed
    while m:
        v = lowest(m)
        m &= m - ONE
        by_round[removed_round[v]] |= bit(v)
        linked = link[v] & removed
        if linked == ZERO:
            roots[n_roots] = v
            n_roots += 1
            continue
        p = lowest(linked)
        linked &= linked - ONE
        while linked:
            x = lowest(linked)
            linked &= linked - ONE
            if removed_round[x] < removed_round[p]:
                p = x
        next_sibling[v] = first_child[p]
        first_child[p] = v
    pos = 0
    for rnd in range(1, last_round + 1):
        m = by_round[rnd]
        while m:
            v = lowest(m)
            m &= m - ONE
            pos = _subtree(v, first_child, next_sibling, kids, buf, start, length, height, pos)
    return _write_forest(roots, n_roots, buf, start, length, height, out, at)
