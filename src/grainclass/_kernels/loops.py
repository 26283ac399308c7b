"""Face adjacency from the corner loops of a grain's faces (Voro++, Neper, mesh codes).

Two faces are adjacent where they share an edge (two consecutive corners of both loops); walking
a face's loop gives its neighbours in cyclic order. A corner on only two faces (an edge split in
two) does not start a new neighbour. Corners are numbered 0..k-1 within a grain here; tables
indexed by pairs of corners are allocated once per call and cleared after each grain.
"""

import numpy as np

from grainclass._numba import borrowed, njit, njit_leaf

# Flags per grain.
BAD_CORNER = 1  # a corner not on exactly three faces
OPEN = 2  # an edge not on exactly two faces: the loops do not close into a surface
PINCHED = 4  # a closed surface, but not a sphere: V - E + F is not 2


@njit
def _tables(size):
    """Scratch for grains with up to ``size`` corners: the first and second face on each edge,
    the faces on it, the faces at each corner (the first three) and their number."""
    return (
        np.full(size * size, -1, np.int32),
        np.full(size * size, -1, np.int32),
        np.zeros(size * size, np.int32),
        np.zeros((size, 3), np.int32),
        np.zeros(size, np.int32),
    )


@njit(inline="always")
def _borrowed_tables(tables):
    """:func:`_tables`'s arrays as :func:`~grainclass._numba.borrowed` views."""
    first, second, count, corner_faces, on_faces = tables
    return (
        borrowed(first), borrowed(second), borrowed(count), borrowed(corner_faces),
        borrowed(on_faces),
    )  # fmt: skip


@njit_leaf
def _grain_adjacency(f0, f1, loop_offsets, corners, size, tables, nbr_offsets, neighbors, m, bad):
    """Neighbour lists of faces ``f0:f1`` (face f has the corners
    ``corners[loop_offsets[f]:loop_offsets[f + 1]]``, all below ``size``), written to
    ``neighbors`` from ``m`` as local face indices, with ``nbr_offsets[f + 1]``.

    Returns ``(m, flags)``. For the first edge not on exactly two faces, ``bad`` gets (position
    in ``corners`` of its first corner, of its second, faces on it). The tables stay filled for
    the caller (``tables[3]``, ``tables[4]``: faces at each corner), until :func:`_clear`.
    """
    first, second, count, corner_faces, on_faces = tables
    flag = 0
    for f in range(f0, f1):
        a, b = loop_offsets[f], loop_offsets[f + 1]
        for i in range(a, b):
            j = i + 1 if i + 1 < b else a
            u, v = corners[i], corners[j]
            key = min(u, v) * size + max(u, v)
            if first[key] < 0:
                first[key] = f - f0
            elif second[key] < 0:
                second[key] = f - f0
            count[key] += 1
            if on_faces[u] < 3:
                corner_faces[u, on_faces[u]] = f
            on_faces[u] += 1
    for f in range(f0, f1):
        a, b = loop_offsets[f], loop_offsets[f + 1]
        start = m
        for i in range(a, b):
            j = i + 1 if i + 1 < b else a
            u, v = corners[i], corners[j]
            key = min(u, v) * size + max(u, v)
            other = second[key] if first[key] == f - f0 else first[key]
            if count[key] != 2 or other < 0 or other == f - f0:
                if not flag & OPEN:
                    bad[0], bad[1], bad[2] = i, j, count[key]
                flag |= OPEN
            neighbors[m] = other
            m += 1
        # Drop an edge to the same face as the edge before it across a corner on two faces.
        kept = start
        length = m - start
        for k in range(length):
            i = loop_offsets[f] + k
            previous = neighbors[start + (k - 1) % length]
            if neighbors[start + k] != previous or on_faces[corners[i]] > 2:
                neighbors[kept] = neighbors[start + k]
                kept += 1
        if kept == start and length:
            kept = start + 1  # every edge to one face: one neighbour
        m = kept
        nbr_offsets[f + 1] = m
    for f in range(f0, f1):
        for i in range(loop_offsets[f], loop_offsets[f + 1]):
            if on_faces[corners[i]] != 3:
                flag |= BAD_CORNER
    return m, flag


@njit_leaf
def _clear(f0, f1, loop_offsets, corners, size, tables):
    """Reset what :func:`_grain_adjacency` wrote for faces ``f0:f1``."""
    first, second, count, _, on_faces = tables
    for f in range(f0, f1):
        a, b = loop_offsets[f], loop_offsets[f + 1]
        for i in range(a, b):
            u, v = corners[i], corners[i + 1 if i + 1 < b else a]
            key = min(u, v) * size + max(u, v)
            first[key] = second[key] = -1
            count[key] = 0
            on_faces[u] = 0


@njit
def _adjacency_from_loops(
    face_offsets, loop_offsets, loop_corners, nbr_offsets, neighbors, flags, bad, clockwise
):
    """:func:`_grain_adjacency` for every grain g (faces ``face_offsets[g]:face_offsets[g+1]``),
    its corner ids (any integers) numbered 0..k-1 first. ``bad`` is int64[G, 3] (corner ids of
    a bad edge and the faces on it, or for PINCHED (0, 0, V - E + F)); ``neighbors`` has room
    for one entry per loop corner. Each face's neighbours come in its loop's sense, or the
    other way round if ``clockwise`` (loops that turn clockwise seen from outside, as Voro++'s:
    the lists then turn counter-clockwise, as every reader with geometry gives them).

    A closed surface whose V - E + F is not 2 is flagged PINCHED: two corners given one id (the
    surface touches itself there) leave a face adjacency that can pass for a simple grain's,
    and a grain with a handle is no polytope either."""
    size = 16
    tables = _tables(size)
    local = np.empty(loop_corners.shape[0], np.int64)
    where = np.empty(3, np.int64)
    m = 0
    nbr_offsets[0] = 0
    for g in range(face_offsets.shape[0] - 1):
        f0, f1 = face_offsets[g], face_offsets[g + 1]
        a, b = loop_offsets[f0], loop_offsets[f1]
        ids = np.unique(loop_corners[a:b])
        local[a:b] = np.searchsorted(ids, loop_corners[a:b])
        if ids.shape[0] > size:
            size = ids.shape[0]
            tables = _tables(size)
        where[:] = -1
        m, flags[g] = _grain_adjacency(
            f0, f1, borrowed(loop_offsets), borrowed(local), size, _borrowed_tables(tables),
            borrowed(nbr_offsets), borrowed(neighbors), m, borrowed(where),
        )  # fmt: skip
        if clockwise:
            for f in range(f0, f1):
                i, j = nbr_offsets[f], nbr_offsets[f + 1] - 1
                while i < j:
                    neighbors[i], neighbors[j] = neighbors[j], neighbors[i]
                    i += 1
                    j -= 1
        if where[0] >= 0:
            bad[g, 0], bad[g, 1], bad[g, 2] = (
                loop_corners[where[0]],
                loop_corners[where[1]],
                where[2],
            )
        elif f1 > f0:  # every edge on two loops: E is half the loops' corners
            euler = ids.shape[0] - (b - a) // 2 + (f1 - f0)
            if euler != 2:
                flags[g] |= PINCHED
                bad[g, 0], bad[g, 1], bad[g, 2] = 0, 0, euler
        _clear(f0, f1, borrowed(loop_offsets), borrowed(local), size, _borrowed_tables(tables))
    return m
