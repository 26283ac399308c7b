"""Truncation trees (Lutz et al. Sec. II.B) written as one canonical string per grain.

A removed vertex w was stacked onto the triangle formed by its three neighbours at removal time.
That triangle was created by the most recently stacked of them, i.e. by the one removed earliest:
that vertex is w's parent; a w whose link is all fundamental is a root. Neighbours in a link are
adjacent, and adjacent degree-3 vertices never go in the same round, so the parent is unique.

Canonical form: a tree is ``(`` + its children's strings in ascending byte order + ``)``; the
forest is its trees sorted by (length, string) joined by ``+``.
"""

import numpy as np

from grainclass._numba import njit

OPEN, CLOSE, PLUS = 40, 41, 43  # "(", ")", "+"


@njit
def _copy(source, at, count, target, to):
    """Copy ``count`` bytes from ``source[at:]`` to ``target[to:]``; returns the end in target.

    A loop, not a slice assignment: that would compile shape checks with formatted error
    messages, seconds of first-run compilation for nothing.
    """
    for i in range(count):
        target[to + i] = source[at + i]
    return to + count


@njit
def _less(buf, a_start, a_len, b_start, b_len):
    """Byte-wise lexicographic ``buf[a] < buf[b]`` for two slices of one buffer."""
    for i in range(min(a_len, b_len)):
        if buf[a_start + i] != buf[b_start + i]:
            return buf[a_start + i] < buf[b_start + i]
    return a_len < b_len


@njit
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
def _forest_scratch(n):
    """Scratch arrays for :func:`_forest_string` on up to n vertices."""
    return (
        np.empty(n + 1, np.int32),  # child offsets
        np.empty(max(n, 1), np.int32),  # children
        np.empty(n * (n + 1) + 1, np.uint8),  # strings of the subtrees
        np.empty(n, np.int64),  # start of each subtree's string
        np.empty(n, np.int64),  # its length
        np.empty(n, np.int32),  # subtree height
        np.empty(max(n, 1), np.int32),  # roots
    )


@njit
def _forest_string(n, removed_round, parent, out, at, scratch):
    """Write the canonical forest string of the removed vertices into ``out`` from ``at``
    (3n bytes suffice; an offset, not a view: a view per grain costs reference counting).

    Nodes are the vertices with ``removed_round > 0``; ``parent`` is -1 for roots. ``scratch``
    comes from :func:`_forest_scratch`. Returns ``(n_trees, depth, length)``: depth is the number
    of vertices on a longest root path. O(t^2) for t truncations.
    """
    child_off, children, buf, start, length, height, roots = scratch
    last_round = 0
    for v in range(n + 1):
        child_off[v] = 0
    for v in range(n):
        last_round = max(last_round, removed_round[v])
        if removed_round[v] > 0 and parent[v] >= 0:
            child_off[parent[v] + 1] += 1
    for v in range(n):
        child_off[v + 1] += child_off[v]
    for v in range(n):  # place children, advancing each offset to the next one's value ...
        if removed_round[v] > 0 and parent[v] >= 0:
            children[child_off[parent[v]]] = v
            child_off[parent[v]] += 1
    for v in range(n - 1, -1, -1):  # ... and shift them back
        child_off[v + 1] = child_off[v]
    child_off[0] = 0
    # Children are removed in earlier rounds than their parent: build strings round by round.
    pos = 0
    for rnd in range(1, last_round + 1):
        for v in range(n):
            if removed_round[v] != rnd:
                continue
            first, count = child_off[v], child_off[v + 1] - child_off[v]
            kids = children[first : first + count]
            _sort_slices(kids, count, buf, start, length, False)
            start[v] = pos
            buf[pos] = OPEN
            pos += 1
            tallest = 0
            for c in kids:
                pos = _copy(buf, start[c], length[c], buf, pos)
                tallest = max(tallest, height[c])
            buf[pos] = CLOSE
            pos += 1
            length[v] = pos - start[v]
            height[v] = tallest + 1
    n_roots = 0
    depth = 0
    for v in range(n):
        if removed_round[v] > 0 and parent[v] < 0:
            roots[n_roots] = v
            n_roots += 1
            depth = max(depth, height[v])
    _sort_slices(roots, n_roots, buf, start, length, True)
    written = at
    for r in range(n_roots):
        if r > 0:
            out[written] = PLUS
            written += 1
        v = roots[r]
        written = _copy(buf, start[v], length[v], out, written)
    return n_roots, depth, written - at
