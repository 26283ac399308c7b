"""Weinberg vectors of grains, as VoroTop writes them (Weinberg 1965; Lazar et al. 2015).

The walk runs on the grain's own edge graph: its vertices are the grain's corners (the triangles
of the dual triangulation), three edges at each. From a start edge a -> b and an orientation:
label vertices in order of first arrival and write the label of every vertex reached; at a new
vertex turn right (take the next edge around it, in the walk's rotational direction); at an old
vertex go back along the reverse edge if that is unused, else take the next unused edge around
it in the same direction; stop when every directed edge is used. A code has 2E + 1 entries.
The canonical vector is the smallest code, as integer sequences, over all 2E start edges and
both orientations; a walk is abandoned as soon as it exceeds the best so far.

The edge graph is never built: it is read off the dual's rotation table. With ``sigma(a, b)``
the face after b around face a (counter-clockwise), the dart a -> b of the dual names the corner
(a, b, sigma(a, b)) together with the edge leaving it across its side a-b: the corner's three
edges, counter-clockwise, are its darts a -> b, b -> c and c -> a (c = sigma(a, b)), and the
edge back from the corner across is the reverse dart b -> a. Labels, and what a walk has used,
are kept per dart in one table. Both tables are indexed by ``a << shift | b``, rows a power of
two wide (at least n), not by ``a * n + b``: a walk's every step computes three such indices
from the face it has just loaded, and a multiplication's latency would hold up the next load
(the tables are at most four times n * n; see docs/performance.md). A grain of more than
DENSE_FACES faces, whose tables of n * n would grow with the square of its size, names its darts
by their place in its rotation lists instead, and keeps per dart the three darts of the corner
across it and sigma (:func:`_crossings`): tables of 4E entries, E = 6n - 12
(:func:`_weinberg_large_batch`, a kernel of its own, compiled only for such a grain).

Orientation +1 turns right with the faces seen from outside, taking the input's neighbour lists
as counter-clockwise seen from outside (the orientation of face 0's list for text input).
"""

import numpy as np

from grainclass._kernels.validate import _reverse_darts, _rotation, grain_lists
from grainclass._numba import at, borrowed, njit, njit_leaf

# Stamps count walks within one kernel call; the table is cleared before they could overflow.
_MAX_STAMP = 1 << 30
_USED = np.int64(1) << 31  # the walk has left along this dart
_LABEL = _USED - 1

# Grains of up to this many faces name their darts by their ends, in tables of at most
# 4 n^2 entries (256 kB of sigma); larger ones by their place in the lists, in tables of 4E.
DENSE_FACES = 256


@njit_leaf
def _walk(shift, sigma, length, a, b, turn, best, state, gen, seen, code):
    """The first ``length`` entries of the Weinberg walk that leaves corner (a, b, sigma(a, b))
    along its edge a -> b, turning by ``turn`` in counter-clockwise steps around a corner seen
    from outside: +1 takes the edge after the one arrived by, a right turn; -1 a left turn.
    Compares with ``best`` as it goes: returns -1 if the code is smaller (``code`` then holds
    it), 0 if equal, +1 as soon as it is larger.

    ``seen`` holds, per dart, ``gen`` (the walk's stamp) in its high half, so nothing is reset
    per walk, the label of the dart's corner in its low bits and USED once the walk has left
    along the dart: one load tells whether a corner is new, its label and whether the edge
    back is free.
    """
    stamp = np.int64(gen) << 32
    c = sigma[at(a << shift | b)]
    for dart in (a << shift | b, b << shift | c, c << shift | a):
        seen[at(dart)] = stamp | 1
    next_label = 2
    code[0] = 1
    cmp = state
    for step in range(1, length):
        seen[at(a << shift | b)] |= _USED
        # Across to corner (b, a, r): back is its edge b -> a, ahead (a -> r) and behind
        # (r -> b) its others, counter-clockwise.
        back = b << shift | a
        r = sigma[at(back)]
        ahead, behind = a << shift | r, r << shift | b
        mark = seen[at(back)]
        if mark < stamp:  # a corner not seen yet in this walk
            seen[at(back)] = seen[at(ahead)] = seen[at(behind)] = stamp | next_label
            code[at(step)] = next_label
            next_label += 1
            go = turn  # +1 ahead, -1 behind, 0 back
        else:
            code[at(step)] = mark & _LABEL
            if not mark & _USED:
                go = 0
            else:
                go = turn if not seen[at(ahead if turn > 0 else behind)] & _USED else -turn
        if go == 0:
            a, b = b, a
        elif go > 0:
            b = r
        else:
            a = r
        if cmp == 0:
            if code[at(step)] > best[at(step)]:
                return 1
            if code[at(step)] < best[at(step)]:
                cmp = -1
    return cmp


@njit_leaf
def _weinberg(n, shift, rot, off, sigma, faces, best, gen, seen, code, walks, keys, smallest_faces):
    """Canonical code into ``best``; returns (symmetry, chirality, the last stamp used).
    ``rot[off[v]:off[v + 1]]`` is face v's counter-clockwise list, ``sigma`` its table (rows
    ``1 << shift`` wide) and ``faces[v]`` its size; ``walks`` and ``keys`` (int64[12n - 24],
    two per dart) and ``smallest_faces`` (int64[n]) are scratch.

    The three faces at the start corner fix how a walk's code begins. It goes round the face on
    its turning side first (s sides: 1, 2, ..., s, then 1 again), back one edge (s), round the
    face opposite its first edge (m sides: m - 2 new labels, then 1), back one edge, and round
    the other face of its first edge (q sides: q - 3 new labels, then 2). Two faces of a simple
    polytope share at most an edge, so those labels are new, and a smaller face writes its 1 or
    2 where a larger one writes a new label: only starts with the least (s, m, q) can give the
    smallest code. That leaves few walks a grain beyond the one that gives the smallest code:
    each is walked to its end or until it exceeds the best so far. The least s is found first,
    so that only the edges of the smallest faces are looked at, not every start. Then every
    start is weighed and stored, its edge and turn packed in one integer (one store a start,
    not three), and those of the least weight are moved down, without a branch (see
    docs/performance.md).
    """
    t = 2 * n - 4
    length = 3 * t + 1  # 2E + 1 with E = 3t/2
    sizes = t + 1  # a face has at most t corners
    smallest = faces[0]
    for v in range(1, n):
        smallest = min(smallest, faces[v])
    n_smallest = 0
    for v in range(n):
        smallest_faces[at(n_smallest)] = v
        n_smallest += faces[v] == smallest
    least = sizes * sizes
    starts = 0
    for k in range(n_smallest):
        v = smallest_faces[at(k)]
        # The walks that go round face v first: along v -> x turning right (face v is right of
        # that edge), along x -> v turning left (face v is left of it). Either way the other
        # face of the first edge is x, and the opposite face is the third face at the start.
        for i in range(off[v], off[v + 1]):
            x = int(rot[at(i)])  # packed below into 64 bits, also without the JIT
            key_right = faces[at(sigma[at(v << shift | x)])] * sizes + faces[at(x)]
            key_left = faces[at(sigma[at(x << shift | v)])] * sizes + faces[at(x)]
            # a start packed in one integer: its edge a -> b and its turn, 1 right, 0 left
            walks[at(starts)], keys[at(starts)] = (v << 32) | (x << 1) | 1, key_right
            walks[at(starts + 1)], keys[at(starts + 1)] = (x << 32) | (v << 1), key_left
            starts += 2
            least = min(least, key_right, key_left)
    count = 0
    for j in range(starts):  # count never passes j
        walks[at(count)] = walks[at(j)]
        count += keys[at(j)] == least
    best[0] = -1  # nothing yet: the first walk wins
    kept = 0
    for j in range(count):  # kept ones are moved down: kept never passes j
        gen += 1
        state = -1 if best[0] < 0 else 0
        start = walks[j]
        a, b, turn = start >> 32, (start >> 1) & _LABEL, 1 if start & 1 else -1
        result = _walk(shift, sigma, length, a, b, turn, best, state, gen, seen, code)
        if result < 0:
            for i in range(length):
                best[i] = code[i]
            kept = 0
        if result <= 0:
            walks[kept] = start
            kept += 1
    # The walks giving the smallest code: one per symmetry (reflections included). Chirality
    # as VoroTop numbers it: -1 when only walks turning right reach the code, +1 only left.
    left = 0
    for j in range(kept):
        left += not walks[j] & 1
    right = kept - left
    chirality = 0 if right and left else (-1 if right else 1)
    return kept, chirality, gen


@njit
def _rotations(first, last, grains, face_offsets, nbr_offsets, neighbors, rotations):
    """Counter-clockwise rotation lists (``validate._rotation``) of the ok grains
    ``grains[first:last]`` whose lists do not turn one way, written over their lists in
    ``rotations`` (a copy of ``neighbors``). A kernel of its own: compiled only when an input
    needs it."""
    for i in range(first, last):
        g = grains[i]
        n, off, nb = grain_lists(g, face_offsets, nbr_offsets, neighbors)
        rot = np.empty(nb.shape[0], np.int64)
        _rotation(n, off, nb, rot)
        a = nbr_offsets[face_offsets[g]]
        for k in range(rot.shape[0]):
            rotations[a + k] = rot[k]


@njit
def _weinberg_batch(
    first,
    last,
    grains,
    face_offsets,
    nbr_offsets,
    rotations,
    code_offsets,
    codes,
    symmetry,
    chirality,
):
    """Weinberg vectors of the ok grains ``grains[first:last]`` of at most DENSE_FACES faces:
    grain g's code goes to ``codes[code_offsets[g]:]`` (6n - 11 entries), with its symmetry
    (automorphisms, reflections included) and chirality. Rows of different ranges are
    disjoint: ranges can run in threads.

    ``rotations`` are the neighbour lists turning one way, counter-clockwise (as the fast path
    found them, or from :func:`_rotations`). Scratch arrays for the largest of these grains
    (the rotation table, int32, and the walks' table, int64, each with rows and columns the
    least power of two >= its faces) are allocated once per call: a call for one grain
    allocates for that grain alone.

    The rotation table is filled in one pass over the grain's darts without a branch: each
    list's first dart is marked beforehand with the list's last face, which comes before it
    (a loop per list would be mispredicted at each list's end).
    """
    max_faces = 0
    for j in range(first, last):
        max_faces = max(max_faces, face_offsets[grains[j] + 1] - face_offsets[grains[j]])
    stride = 1
    while stride < max_faces:
        stride *= 2
    size = stride * stride
    sigma = np.empty(size, np.int32)
    seen = np.zeros(size, np.int64)
    faces = np.empty(max(max_faces, 1), np.int64)
    wrap = np.full(6 * max(max_faces, 1), -1, np.int64)  # per dart: -1, or a list's last face
    code = np.empty(max(6 * max_faces - 11, 1), np.int32)
    walks = np.empty(max(12 * max_faces - 24, 1), np.int64)
    keys = np.empty(max(12 * max_faces - 24, 1), np.int64)
    smallest_faces = np.empty(max(max_faces, 1), np.int64)
    # Not the literal 0: numba would compile _weinberg once for a literal 0 and once for int64.
    gen = np.int64(0)
    for j in range(first, last):
        g = grains[j]
        f0 = face_offsets[g]
        n = face_offsets[g + 1] - f0
        off = nbr_offsets[f0 : f0 + n + 1]
        begin = off[0]
        for v in range(n):
            faces[v] = off[v + 1] - off[v]
            wrap[at(off[v] - begin)] = rotations[at(off[v + 1] - 1)]
        shift = 0
        while (1 << shift) < n:
            shift += 1
        row = -(1 << shift)  # face v's row of sigma, v << shift
        before = 0
        for i in range(begin, off[n]):
            last_face = wrap[at(i - begin)]
            first = last_face >= 0
            row += (1 << shift) if first else 0
            before = last_face if first else before
            sigma[at(row + before)] = rotations[at(i)]
            before = int(rotations[at(i)])
            wrap[at(i - begin)] = -1
        if gen > _MAX_STAMP:  # a grain makes at most 12n walks: far from overflowing
            seen[:] = 0
            gen = np.int64(0)
        best = codes[code_offsets[g] : code_offsets[g] + 6 * n - 11]
        symmetry[g], chirality[g], gen = _weinberg(
            n,
            shift,
            borrowed(rotations),
            borrowed(off),
            borrowed(sigma),
            borrowed(faces),
            borrowed(best),
            gen,
            borrowed(seen),
            borrowed(code),
            borrowed(walks),
            borrowed(keys),
            borrowed(smallest_faces),
        )


@njit
def _crossings(n, off, rot, table):
    """The darts' table of a grain of more than DENSE_FACES faces, darts named by their place
    in its counter-clockwise lists ``rot`` (face v's from ``off[v]``, 0-based): for dart i =
    a -> b, ``table[4 i : 4 i + 4]`` holds the corner across it, back (b -> a), ahead (a -> r,
    the dart before i around a) and behind (r -> b, the reverse of the dart after back around
    b), r = sigma(b, a), and then sigma(a, b), the face after b around a. O(E)."""
    rev = _reverse_darts(n, off, rot)
    for v in range(n):
        d = off[v + 1] - off[v]
        for k in range(d):
            i = off[v] + k
            back = rev[i]
            b = rot[i]
            after_back = off[b] + (back - off[b] + 1) % (off[b + 1] - off[b])
            table[4 * i] = back
            table[4 * i + 1] = off[v] + (k - 1 + d) % d
            table[4 * i + 2] = rev[after_back]
            table[4 * i + 3] = rot[off[v] + (k + 1) % d]


@njit
def _walk_large(table, length, d, turn, best, state, gen, seen, code):
    """:func:`_walk` on a table of :func:`_crossings`, from dart d (its corner's edge along
    which the walk leaves)."""
    stamp = np.int64(gen) << 32
    back = table[4 * d]  # d's corner is the one across its reverse
    for dart in (d, table[4 * back + 1], table[4 * back + 2]):
        seen[dart] = stamp | 1
    next_label = 2
    code[0] = 1
    cmp = state
    for step in range(1, length):
        seen[d] |= _USED
        back, ahead, behind = table[4 * d], table[4 * d + 1], table[4 * d + 2]
        mark = seen[back]
        if mark < stamp:  # a corner not seen yet in this walk
            seen[back] = seen[ahead] = seen[behind] = stamp | next_label
            code[step] = next_label
            next_label += 1
            go = turn  # +1 ahead, -1 behind, 0 back
        else:
            code[step] = mark & _LABEL
            if not mark & _USED:
                go = 0
            else:
                go = turn if not seen[ahead if turn > 0 else behind] & _USED else -turn
        d = back if go == 0 else (ahead if go > 0 else behind)
        if cmp == 0:
            if code[step] > best[step]:
                return 1
            if code[step] < best[step]:
                cmp = -1
    return cmp


@njit
def _weinberg_large_batch(
    first, last, grains, face_offsets, nbr_offsets, rotations, code_offsets, codes, symmetry,
    chirality,
):  # fmt: skip
    """:func:`_weinberg_batch` for the ok grains ``grains[first:last]`` of more than
    DENSE_FACES faces, on tables of :func:`_crossings`, each of 4E entries: memory grows with a
    grain's size, not its square. The starts are chosen as :func:`_weinberg` chooses them."""
    for j in range(first, last):
        g = grains[j]
        n, off, rot = grain_lists(g, face_offsets, nbr_offsets, rotations)
        m = off[n]
        table = np.empty(4 * m, np.int64)
        _crossings(n, off, rot, table)
        seen = np.zeros(m, np.int64)
        code = np.empty(6 * n - 11, np.int32)
        best = codes[code_offsets[g] : code_offsets[g] + 6 * n - 11]
        faces = off[1:] - off[:-1]
        t = 2 * n - 4
        length = 3 * t + 1
        sizes = t + 1
        smallest = faces.min()
        walks = np.empty(2 * m, np.int64)
        keys = np.empty(2 * m, np.int64)
        least = sizes * sizes
        starts = 0
        for v in range(n):
            if faces[v] != smallest:
                continue
            for i in range(off[v], off[v + 1]):
                x = rot[i]
                left = table[4 * i]
                key_right = faces[table[4 * i + 3]] * sizes + faces[x]
                key_left = faces[table[4 * left + 3]] * sizes + faces[x]
                walks[starts], keys[starts] = (i << 1) | 1, key_right
                walks[starts + 1], keys[starts + 1] = left << 1, key_left
                starts += 2
                least = min(least, key_right, key_left)
        best[0] = -1
        kept = 0
        gen = np.int64(0)
        for k in range(starts):
            if keys[k] != least:
                continue
            gen += 1
            state = -1 if best[0] < 0 else 0
            start = walks[k]
            turn = 1 if start & 1 else -1
            result = _walk_large(table, length, start >> 1, turn, best, state, gen, seen, code)
            if result < 0:
                for i in range(length):
                    best[i] = code[i]
                kept = 0
            if result <= 0:
                walks[kept] = start
                kept += 1
        left = 0
        for k in range(kept):
            left += not walks[k] & 1
        right = kept - left
        symmetry[g] = kept
        chirality[g] = 0 if right and left else (-1 if right else 1)
