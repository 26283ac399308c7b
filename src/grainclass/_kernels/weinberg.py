"""Weinberg vectors of grains, as VoroTop writes them (Weinberg 1965; Lazar et al. 2015).

The walk runs on the grain's own edge graph: its vertices are the grain's corners (the triangles
of the dual triangulation), three edges at each. From a start edge a -> b and an orientation:
label vertices in order of first arrival and write the label of every vertex reached; at a new
vertex turn right (take the next edge around it, in the walk's rotational direction); at an old
vertex go back along the reverse edge if that is unused, else take the next unused edge around
it in the same direction; stop when every directed edge is used. A code has 2E + 1 entries.
The canonical vector is the smallest code, as integer sequences, over all 2E start edges and
both orientations; a walk is abandoned as soon as it exceeds the best so far.

Orientation +1 turns right with the faces seen from outside, taking the input's neighbour lists
as counter-clockwise seen from outside (the orientation of face 0's list for text input).
"""

import numpy as np

from grainclass._kernels.validate import _rotation
from grainclass._numba import njit


@njit
def _corners(n, off, rot, pos, corner, least, corner_nbr, corner_back, left_face):
    """The grain's edge graph: ``corner_nbr[T]`` = the 3 corners next to corner T, in
    counter-clockwise order, ``corner_back[T, k]`` the index of the edge back from
    ``corner_nbr[T, k]`` to T, and ``left_face[T, k]`` the size of the grain face on the left of
    the edge T -> corner_nbr[T, k] (the face on its right is the left face of edge k + 1).
    Corners are the dual's triangles; returns their number.

    ``rot`` holds the counter-clockwise rotation lists (``nb``'s layout); ``pos`` (n x n),
    ``corner`` (one per dart) and ``least`` (one more than there are corners) are scratch.
    Loops choose with selects where they can: which of a triangle's faces is least, or which
    edge leads back, is data that no branch predictor guesses.
    """
    for v in range(n):
        for i in range(off[v], off[v + 1]):
            pos[v, rot[i]] = i - off[v]
    # Dart i of face v, with x = rot[i] and y = rot[next], is corner (v, x, y). Its id is made
    # at the triangle's least face, which comes first in this loop; the other two darts copy
    # it from there. ``least[t]`` is corner t's dart at its least face.
    count = 0
    for v in range(n):
        s, e = off[v], off[v + 1]
        for i in range(s, e):
            x = rot[i]
            y = rot[i + 1] if i + 1 < e else rot[s]
            least_here = (v < x) & (v < y)
            source = off[x] + pos[x, y] if (x < v) & (x < y) else off[y] + pos[y, v]
            copied = corner[source]  # read before it is set when least_here: not used then
            corner[i] = count if least_here else copied
            least[count] = i
            count += least_here
    v = 0
    for t in range(count):  # corners in the order of their darts, face by face
        i = least[t]
        while i >= off[v + 1]:
            v += 1
        s, e = off[v], off[v + 1]
        x = rot[i]
        y = rot[i + 1] if i + 1 < e else rot[s]
        sx, ex = off[x], off[x + 1]
        before_y = sx + pos[x, y] - 1
        # Corner t is the counter-clockwise triangle (v, x, y); leaving it across its side
        # a -> b (in that order), face a lies on the left and face b on the right.
        corner_nbr[t, 0] = corner[i - 1 if i > s else e - 1]  # across side v-x
        corner_nbr[t, 1] = corner[before_y if before_y >= sx else ex - 1]  # across x-y
        corner_nbr[t, 2] = corner[i + 1 if i + 1 < e else s]  # across side y-v
        left_face[t, 0] = e - s
        left_face[t, 1] = ex - sx
        left_face[t, 2] = off[y + 1] - off[y]
    for t in range(count):  # once per edge here, not once per step of every walk
        for k in range(3):
            nxt = corner_nbr[t, k]
            # The edge graph is simple: exactly one of nxt's three edges leads back to t.
            corner_back[t, k] = (corner_nbr[nxt, 1] == t) + 2 * (corner_nbr[nxt, 2] == t)
    return count


@njit
def _turned(k, turn):
    """Edge index k moved one step by turn (+1/-1) around a corner of three (no modulo)."""
    k += turn
    return k - 3 if k > 2 else (k + 3 if k < 0 else k)


@njit
def _walk(
    corner_nbr, corner_back, length, start, first, turn, best, state, stamp, gen, label, used, code
):
    """The first ``length`` entries of the Weinberg walk from ``start`` along its edge
    ``first``, turning by ``turn`` (-1 right, +1 left, in counter-clockwise index steps).
    Compares with ``best`` as it goes: returns -1 if the code is smaller (``code`` then holds
    it), 0 if equal, +1 as soon as it is larger. ``stamp``/``used`` hold ``gen`` for what this
    walk has seen, so nothing is reset per walk.
    """
    cmp = state
    stamp[start] = gen
    label[start] = 1
    next_label = 2
    code[0] = 1
    cur, k = start, first
    for step in range(1, length):
        used[cur, k] = gen
        nxt = corner_nbr[cur, k]
        back = corner_back[cur, k]
        if stamp[nxt] != gen:
            stamp[nxt] = gen
            label[nxt] = next_label
            next_label += 1
            k = _turned(back, turn)
        elif used[nxt, back] != gen:
            k = back
        else:
            k = _turned(back, turn)
            if used[nxt, k] == gen:
                k = _turned(k, turn)
        code[step] = label[nxt]
        if cmp == 0:
            if code[step] > best[step]:
                return 1
            if code[step] < best[step]:
                cmp = -1
        cur = nxt
    return cmp


@njit
def _smallest_walks(corner_nbr, corner_back, walks, count, length, best, scratch):
    """Walk each of ``walks[:count]`` (``6 start + 2 first + (turn > 0)``), the smallest code
    into ``best``; the walks that give it are moved to the front of ``walks``. Returns their
    number."""
    stamp, label, used, code = scratch
    best[0] = -1  # nothing yet: the first walk wins
    kept = 0
    gen = 1  # the caller zeroed stamp and used
    for j in range(count):  # kept ones are moved down: kept never passes j
        walk = walks[j]
        start, first, turn = walk // 6, walk % 6 // 2, 1 if walk & 1 else -1
        state = -1 if best[0] < 0 else 0
        result = _walk(
            corner_nbr,
            corner_back,
            length,
            start,
            first,
            turn,
            best,
            state,
            stamp,
            gen,
            label,
            used,
            code,
        )
        gen += 1
        if result < 0:
            for i in range(length):
                best[i] = code[i]
            kept = 0
        if result <= 0:
            walks[kept] = walk
            kept += 1
    return kept


@njit
def _weinberg(corner_nbr, corner_back, left_face, t, best, stamp, label, used, code, walks):
    """Canonical code into ``best``; returns (symmetry, chirality). ``walks`` (6t entries) is
    scratch.

    The three faces at the start corner fix how a walk's code begins. It goes round the face on
    its turning side first (s sides: 1, 2, ..., s, then 1 again), back one edge (s), round the
    face opposite its first edge (m sides: m - 2 new labels, then 1), back one edge, and round
    the other face of its first edge (q sides: q - 3 new labels, then 2). Two faces of a simple
    polytope share at most an edge, so those labels are new, and a smaller face writes its 1 or
    2 where a larger one writes a new label: only starts with the least (s, m, q) can give the
    smallest code. That leaves 1.4 walks a grain at n = 16, where 1.0 give the smallest code:
    each is walked to its end or until it exceeds the best so far.
    """
    length = 3 * t + 1  # 2E + 1 with E = 3t/2
    sizes = t + 1  # a face has at most t corners
    least = -1
    count = 0
    for start in range(t):
        for first in range(3):
            opposite = left_face[start, (first + 2) % 3]
            for turn in (-1, 1):
                # Turning right, the walk goes round the face right of edge ``first`` (the left
                # face of the next edge); turning left, the face left of it.
                side = (first + 1) % 3 if turn < 0 else first
                other = first if turn < 0 else (first + 1) % 3
                key = (left_face[start, side] * sizes + opposite) * sizes + left_face[start, other]
                if least < 0 or key < least:
                    least, count = key, 0
                if key == least:
                    walks[count] = 6 * start + 2 * first + (turn > 0)
                    count += 1
    scratch = (stamp, label, used, code)
    count = _smallest_walks(corner_nbr, corner_back, walks, count, length, best, scratch)
    # The walks giving the smallest code: one per symmetry (reflections included).
    right = 0
    for j in range(count):
        right += (walks[j] & 1) == 0
    left = count - right
    chirality = 0 if right and left else (1 if right else -1)
    return count, chirality


@njit
def _rotations(first, last, grains, face_offsets, nbr_offsets, neighbors, rotations):
    """Counter-clockwise rotation lists (``validate._rotation``) of the ok grains
    ``grains[first:last]`` whose lists do not turn one way, written over their lists in
    ``rotations`` (a copy of ``neighbors``). A kernel of its own: compiled only when an input
    needs it."""
    for i in range(first, last):
        g = grains[i]
        f0, n = face_offsets[g], face_offsets[g + 1] - face_offsets[g]
        a = nbr_offsets[f0]
        rot = np.empty(nbr_offsets[f0 + n] - a, np.int64)
        _rotation(n, nbr_offsets[f0 : f0 + n + 1] - a, neighbors[a : nbr_offsets[f0 + n]], rot)
        for k in range(rot.shape[0]):
            rotations[a + k] = rot[k]


@njit
def _weinberg_batch(
    first,
    last,
    face_offsets,
    nbr_offsets,
    rotations,
    ok,
    max_faces,
    code_offsets,
    codes,
    symmetry,
    chirality,
):
    """Weinberg vectors of the ok grains among ``first:last``: grain g's code goes to
    ``codes[code_offsets[g]:]`` (6n - 11 entries), with its symmetry (automorphisms, reflections
    included) and chirality. Rows of different ranges are disjoint: ranges can run in threads.

    ``rotations`` are the neighbour lists turning one way, counter-clockwise (as the fast path
    found them, or from :func:`_rotations`). Scratch arrays for up to ``max_faces`` faces are
    allocated once per call.
    """
    t_max = max(2 * max_faces - 4, 1)
    darts = max(6 * max_faces - 12, 1)
    pos = np.empty((max_faces, max_faces), np.int64)
    corner = np.empty(darts, np.int64)
    least = np.empty(t_max + 1, np.int64)
    corner_nbr = np.empty((t_max, 3), np.int64)
    corner_back = np.empty((t_max, 3), np.int64)
    left_face = np.empty((t_max, 3), np.int64)
    stamp = np.zeros(t_max, np.int64)
    label = np.empty(t_max, np.int64)
    used = np.zeros((t_max, 3), np.int64)
    code = np.empty(3 * t_max + 1, np.int32)
    walks = np.empty(6 * t_max, np.int64)
    for g in range(first, last):
        if not ok[g]:
            continue
        f0 = face_offsets[g]
        n = face_offsets[g + 1] - f0
        off = nbr_offsets[f0 : f0 + n + 1] - nbr_offsets[f0]
        rot = rotations[nbr_offsets[f0] : nbr_offsets[f0 + n]]
        t = _corners(n, off, rot, pos, corner, least, corner_nbr, corner_back, left_face)
        for c in range(t):
            stamp[c] = 0
            used[c, 0] = used[c, 1] = used[c, 2] = 0
        best = codes[code_offsets[g] : code_offsets[g] + 3 * t + 1]
        symmetry[g], chirality[g] = _weinberg(
            corner_nbr, corner_back, left_face, t, best, stamp, label, used, code, walks
        )
