"""Edge flips (T1 moves) in the dual triangulation of a grain, for ``grainclass perturb``.

Edge A-B of the dual lies on the triangles A-B-C and B-A-D; its flip replaces it by C-D: A and
B lose a neighbour (their faces a side), C and D gain one. The flip is admissible when A and B
have at least four neighbours and C and D are not adjacent already, so that the result is again
the dual of a simple grain (Lutz et al., Sec. "Grain Classes and Error Analysis").

A grain is worked on in ``rows``: face v's neighbours at ``rows[start[v]:start[v] + deg[v]]``,
in cyclic order, with room behind them for as many neighbours more as the flips can add. C and D
are the neighbours before and after B in A's list whichever way the list turns, and D goes in
between A and B in C's list, C in between A and B in D's: each list keeps its sense, so lists
that turn one way still do after a flip. A grain of at most 64 faces also keeps each face's
neighbours as a bitset, ``bits[v]``, so that whether C and D meet is one bit, not a search
through C's list.

Each grain's random choices come from its own stream, a SplitMix64 sequence started from the
run's key and the grain's position in the input, so that they do not depend on how the input is
cut into batches or threads.
"""

import numpy as np

from grainclass._kernels.bits import MAX_BITSET_FACES, ONE, ZERO, bit
from grainclass._kernels.codes import INVALID, OK, PENDING
from grainclass._kernels.small import CORNERS, _validate_small, next_stamp
from grainclass._kernels.validate import _validate, grain_lists
from grainclass._numba import njit

GOLDEN = np.uint64(0x9E3779B97F4A7C15)


@njit(inline="always")
def mix(z):
    """SplitMix64's finalizer: a bijection of uint64 that scatters every input bit."""
    z = (z ^ (z >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)
    z = (z ^ (z >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)
    return z ^ (z >> np.uint64(31))


@njit(inline="always")
def stream_start(key, position):
    """The first state of the stream of the grain at ``position`` (0-based, in the input)."""
    return mix(key ^ mix(np.uint64(position) * GOLDEN + GOLDEN))


@njit(inline="always")
def below(state, m):
    """``(r, state)``: r uniform in 0..m-1 (m >= 1), by rejection of the draws below
    2^64 mod m, so that every r is exactly as likely."""
    um = np.uint64(m)
    threshold = (ZERO - um) % um  # 2^64 mod m
    while True:
        state += GOLDEN
        x = mix(state)
        if x >= threshold:
            return np.int64(x % um), state


@njit
def _check_batch(first, last, face_offsets, nbr_offsets, neighbors, parsed, status, one_way):
    """The fast path's validation (``small._validate_small``) of grains ``first:last``: OK for
    a grain of at most 64 faces whose lists are a simple grain's, turning one way (``one_way``);
    INVALID for a grain the reader could not parse; PENDING for every other, left to
    :func:`_check_pending_batch`."""
    adj = np.empty(MAX_BITSET_FACES, np.uint64)
    following = np.zeros(CORNERS, np.uint16)
    stamp = 0
    for g in range(first, last):
        one_way[g] = False
        if not parsed[g]:
            status[g] = INVALID
            continue
        f0 = face_offsets[g]
        n = face_offsets[g + 1] - f0
        stamp = next_stamp(following, stamp)
        fast = False
        if n <= MAX_BITSET_FACES:
            fast, _ = _validate_small(n, nbr_offsets, neighbors, f0, adj, following, stamp)
        status[g] = OK if fast else PENDING
        one_way[g] = fast


@njit
def _check_pending_batch(
    first, last, grains, face_offsets, nbr_offsets, neighbors, status, one_way, err
):
    """The general validation (``validate._validate``) of the grains ``grains[first:last]``
    that the fast path left: their status, whether an ok one's lists turn one way as given,
    and why one is not ok (``err``, int64[G, 3])."""
    for i in range(first, last):
        g = grains[i]
        n, off, nb = grain_lists(g, face_offsets, nbr_offsets, neighbors)
        status[g], one_way[g] = _validate(n, off, nb, err[g])


@njit(inline="always")
def _load(f0, n, nbr_offsets, lists, room, start, deg, rows, bits):
    """Grain (faces from ``f0``) into ``rows``, ``room`` free slots behind each list, and,
    for at most 64 faces, its neighbour bitsets into ``bits``."""
    p = 0
    small = n <= MAX_BITSET_FACES
    for v in range(n):
        a, b = nbr_offsets[f0 + v], nbr_offsets[f0 + v + 1]
        start[v] = p
        deg[v] = b - a
        row = ZERO
        for i in range(a, b):
            x = lists[i]
            rows[p + i - a] = x
            row |= bit(x & 63)
        if small:
            bits[v] = row
        p += b - a + room


@njit(inline="always")
def _store(f0, n, base, start, deg, rows, out_offsets, out_lists):
    """The grain in ``rows`` as CSR lists from ``base``: ``out_offsets[f0 + 1:f0 + n + 1]``
    (the entry at ``f0`` is the previous grain's end, or 0) and its neighbours."""
    p = base
    for v in range(n):
        for i in range(deg[v]):
            out_lists[p + i] = rows[start[v] + i]
        p += deg[v]
        out_offsets[f0 + v + 1] = p


@njit(inline="always")
def _copy(f0, n, nbr_offsets, lists, out_offsets, out_lists):
    """The grain's lists as they are."""
    for v in range(n):
        out_offsets[f0 + v + 1] = nbr_offsets[f0 + v + 1]
    for i in range(nbr_offsets[f0], nbr_offsets[f0 + n]):
        out_lists[i] = lists[i]


@njit(inline="always")
def _position(rows, s, d, x):
    """Where ``x`` is in the list ``rows[s:s + d]``, or -1."""
    for i in range(d):
        if rows[s + i] == x:
            return i
    return -1


@njit(inline="always")
def _apexes(rows, s, d, i):
    """C and D: the neighbours before and after the one at ``i`` in the list at ``s``."""
    return rows[s + (i - 1 if i > 0 else d - 1)], rows[s + (i + 1 if i + 1 < d else 0)]


@njit(inline="always")
def _meet(n, start, deg, rows, bits, c, d):
    """Whether faces c and d meet: a bit of c's bitset, or (past 64 faces) d in c's list."""
    if n <= MAX_BITSET_FACES:
        return (bits[c] >> np.uint64(d)) & ONE != ZERO
    return _position(rows, start[c], deg[c], d) >= 0


@njit
def _admissible(n, start, deg, rows, bits, ends, slots):
    """The admissible edges of the grain in ``rows``, each A-B with A < B as (A, B's slot in
    A's list) into ``ends`` and ``slots``, by A, then B's slot; returns their number."""
    m = 0
    for a in range(n):
        da = deg[a]
        if da < 4:
            continue
        sa = start[a]
        for i in range(da):
            b = rows[sa + i]
            if b <= a or deg[b] < 4:
                continue
            c, d = _apexes(rows, sa, da, i)
            if not _meet(n, start, deg, rows, bits, c, d):
                ends[m] = a
                slots[m] = i
                m += 1
    return m


@njit(inline="always")
def _remove(rows, s, d, i):
    """Take the entry at ``i`` out of the list at ``s`` of ``d`` entries."""
    for k in range(i, d - 1):
        rows[s + k] = rows[s + k + 1]


@njit(inline="always")
def _insert_between(rows, s, d, x, y, z):
    """Put ``z`` between ``x`` and ``y``, neighbours in the cyclic list at ``s`` of ``d``
    entries (room for one more behind it)."""
    i = _position(rows, s, d, x)
    j = _position(rows, s, d, y)
    at = max(i, j) if abs(i - j) == 1 else d  # the pair wraps around: z goes last
    for k in range(d, at, -1):
        rows[s + k] = rows[s + k - 1]
    rows[s + at] = z


@njit
def _flip(n, start, deg, rows, bits, a, i, edge):
    """Flip A-B, B at slot ``i`` of A's list; ``edge`` gets (A, B, C, D)."""
    sa, da = start[a], deg[a]
    b = rows[sa + i]
    c, d = _apexes(rows, sa, da, i)
    _remove(rows, sa, da, i)
    deg[a] -= 1
    _remove(rows, start[b], deg[b], _position(rows, start[b], deg[b], a))
    deg[b] -= 1
    _insert_between(rows, start[c], deg[c], a, b, d)
    deg[c] += 1
    _insert_between(rows, start[d], deg[d], a, b, c)
    deg[d] += 1
    if n <= MAX_BITSET_FACES:
        bits[a] &= ~bit(b)
        bits[b] &= ~bit(a)
        bits[c] |= bit(d)
        bits[d] |= bit(c)
    edge[0], edge[1], edge[2], edge[3] = a, b, c, d


@njit
def _flip_batch(
    first,
    last,
    face_offsets,
    nbr_offsets,
    neighbors,
    lists,
    status,
    flips,
    key,
    first_position,
    max_faces,
    max_entries,
    out_offsets,
    out_lists,
    done,
):
    """Up to ``flips`` random admissible flips of each ok grain of ``first:last``, one after
    another, each edge drawn uniformly among those admissible then; every other grain copied.

    ``neighbors`` are the grains' lists as read, ``lists`` the same with an ok grain's lists
    turning one way (``weinberg._rotations``) where they did not. The output CSR lists
    (``out_offsets``, ``out_lists``, of the input's sizes: a flip keeps the number of
    neighbours) are written for grain g's rows only, so ranges can run in threads at once; a
    grain that is not ok, or that no flip changed, keeps its lists as read. ``done[g]`` is the
    number of flips made: fewer than ``flips`` when no edge was admissible any more. Grain g's
    draws come from ``stream_start(key, first_position + g)``.
    """
    room = min(flips, max_faces)  # a face gains at most a neighbour a flip, and has fewer than n
    start = np.empty(max_faces, np.int64)
    deg = np.empty(max_faces, np.int64)
    rows = np.empty(max_entries + room * max_faces, np.int32)
    bits = np.empty(MAX_BITSET_FACES, np.uint64)
    ends = np.empty(3 * max_faces, np.int64)
    slots = np.empty(3 * max_faces, np.int64)
    edge = np.empty(4, np.int64)
    for g in range(first, last):
        f0 = face_offsets[g]
        n = face_offsets[g + 1] - f0
        done[g] = 0
        base = nbr_offsets[f0]
        if status[g] == OK:
            _load(f0, n, nbr_offsets, lists, room, start, deg, rows, bits)
            state = stream_start(key, first_position + g)
            for _ in range(flips):
                m = _admissible(n, start, deg, rows, bits, ends, slots)
                if m == 0:
                    break
                r, state = below(state, m)
                _flip(n, start, deg, rows, bits, ends[r], slots[r], edge)
                done[g] += 1
        if done[g]:
            _store(f0, n, base, start, deg, rows, out_offsets, out_lists)
        else:
            _copy(f0, n, nbr_offsets, neighbors, out_offsets, out_lists)


@njit
def _count_admissible(
    first, last, face_offsets, nbr_offsets, lists, status, max_faces, max_entries, counts
):
    """The number of admissible edges of each ok grain of ``first:last`` (0 for the others)."""
    start = np.empty(max_faces, np.int64)
    deg = np.empty(max_faces, np.int64)
    rows = np.empty(max_entries + max_faces, np.int32)
    bits = np.empty(MAX_BITSET_FACES, np.uint64)
    ends = np.empty(3 * max_faces, np.int64)
    slots = np.empty(3 * max_faces, np.int64)
    for g in range(first, last):
        counts[g] = 0
        if status[g] != OK:
            continue
        f0 = face_offsets[g]
        n = face_offsets[g + 1] - f0
        _load(f0, n, nbr_offsets, lists, 1, start, deg, rows, bits)
        counts[g] = _admissible(n, start, deg, rows, bits, ends, slots)


@njit
def _all_flips_batch(
    first,
    last,
    face_offsets,
    nbr_offsets,
    lists,
    status,
    max_faces,
    max_entries,
    out_first,
    out_face_offsets,
    out_bases,
    out_offsets,
    out_lists,
    edges,
):
    """Every grain one admissible flip makes of each ok grain of ``first:last``: grain g's go
    to the output grains ``out_first[g]:out_first[g + 1]``, in the order of
    :func:`_admissible`, each with the lists of ``lists`` but for the flip, and its flipped edge
    and new edge, (A, B, C, D), in ``edges`` (int64[M, 4]). Output grain o has its faces from
    ``out_face_offsets[o]`` and its neighbours from ``out_bases[o]``, set beforehand, as is
    ``out_offsets[0]``."""
    start = np.empty(max_faces, np.int64)
    deg = np.empty(max_faces, np.int64)
    rows = np.empty(max_entries + max_faces, np.int32)
    bits = np.empty(MAX_BITSET_FACES, np.uint64)
    ends = np.empty(3 * max_faces, np.int64)
    slots = np.empty(3 * max_faces, np.int64)
    for g in range(first, last):
        if status[g] != OK or out_first[g] == out_first[g + 1]:
            continue
        f0 = face_offsets[g]
        n = face_offsets[g + 1] - f0
        _load(f0, n, nbr_offsets, lists, 1, start, deg, rows, bits)
        m = _admissible(n, start, deg, rows, bits, ends, slots)
        for j in range(m):
            o = out_first[g] + j
            if j:  # the grain as it was before the last flip
                _load(f0, n, nbr_offsets, lists, 1, start, deg, rows, bits)
            _flip(n, start, deg, rows, bits, ends[j], slots[j], edges[o])
            _store(out_face_offsets[o], n, out_bases[o], start, deg, rows, out_offsets, out_lists)
