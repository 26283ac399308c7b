"""The batch kernels: one compiled call classifies every grain of a batch.

Grains with at most 64 faces whose lists pass the fast check run on bitsets with per-call
scratch (``small.py``); the fast kernels mark every other grain PENDING. Those go to
:func:`_validate_pending_batch`, which allocates per grain but diagnoses anything
(``validate.py``) and classifies the ok ones on bitsets, and the ok ones of more than 64 faces
on to :func:`_classify_general_batch` (``reduce.py``, ``belts.py``, ``trees.py``). They are
kernels of their own so that each is compiled only when some input needs it (together they are
most of the compilation). Two layouts come in: CSR arrays
(:func:`_classify_batch`, any reader) and plantri's planar_code bytes, validated in place and
counted by group without a row per grain (:func:`_tally_records`, the census).
"""

import numpy as np

from grainclass._kernels.belts import _four_belts
from grainclass._kernels.bits import MAX_BITSET_FACES, ONE, ZERO, bit, lowest, popcount
from grainclass._kernels.codes import (
    CLASS_OF,
    E_FOREST_TOO_LARGE,
    E_PARSE,
    E_TOO_LARGE,
    FLAG,
    INVALID,
    OK,
    PENDING,
    SC,
    STACKED,
)
from grainclass._kernels.groups import EMPTY, FIRST_SLOTS, insert
from grainclass._kernels.reduce import _has_empty_triangle, _reduce
from grainclass._kernels.small import (
    CORNERS,
    _four_belts_small,
    _has_empty_triangle_small,
    _reduce_small,
    _validate_record,
    _validate_small,
    next_stamp,
)
from grainclass._kernels.trees import (
    _borrowed_forest,
    _by_round,
    _forest_bytes,
    _forest_scratch,
    _forest_string,
    _forest_string_small,
    _parents_from_links,
)
from grainclass._kernels.validate import _rotation, _validate, grain_lists
from grainclass._numba import borrowed, njit, njit_leaf


@njit
def _work():
    """Scratch for the fast path, allocated once per kernel call."""
    return (
        np.empty(MAX_BITSET_FACES, np.uint64),  # adjacency bitsets
        np.zeros(CORNERS, np.uint16),  # corners (small.next_stamp)
        np.empty(MAX_BITSET_FACES, np.uint64),  # link of each removed face
        np.empty(MAX_BITSET_FACES, np.int32),  # round it was removed in
        # not literals: compiled once, for int64
        _forest_scratch(np.int64(MAX_BITSET_FACES), np.int64(MAX_BITSET_FACES * 65 + 1)),
    )


# Upper bounds on the general path's arrays, counted from its kernels: about sixteen int64
# arrays of E entries at once (belts' paths, weights, reverse darts, incoming darts) and as
# many of n.
BYTES_PER_DART = 128
BYTES_PER_FACE = 256


@njit(inline="always")
def grain_bytes(n, darts):
    """What the general path may hold at once for a grain of n faces and ``darts`` neighbour
    entries, in bytes: a bound on its arrays of n and of E entries (validation, reduction,
    belts, rotation lists, the Weinberg walks' tables), without the truncation forest's
    strings (:func:`trees._forest_bytes`), which are weighed once the forest is known."""
    return BYTES_PER_DART * darts + BYTES_PER_FACE * n


@njit
def _classify_ok_general(n, off, nb, strings, out, at, result, belts, limit):
    """Classify an ok grain (validated by :func:`_validate_pending_batch`) without bitsets.
    ``result`` gets (family, fundamental, trees, depth, tree length); without ``strings`` only
    the number of trees. Returns the bytes its truncation forest's strings would need if they
    are more than ``limit`` (nothing is written then), else 0."""
    alive = np.empty(n, np.bool_)
    removed_round = np.empty(n, np.int32)
    link = np.empty((n, 3), np.int32)
    result[1] = _reduce(n, off, nb, alive, removed_round, link)
    if result[1] == 4:
        result[0] = STACKED
        return 0
    result[0] = SC if _has_empty_triangle(n, off, nb, alive) else FLAG
    if result[1] < n:
        parent = np.empty(n, np.int32)
        _parents_from_links(n, alive, removed_round, link, parent)
        if strings:
            order = _by_round(n, removed_round)
            need = _forest_bytes(n, order, parent)
            if need > limit:
                return need
            result[2], result[3], result[4] = _forest_string(
                n, order, parent, out, at, _forest_scratch(n, need)
            )
        else:
            result[2] = np.sum((parent < 0) & ~alive)
    elif result[0] == FLAG:
        rot = np.empty(off[n], np.int64)
        _rotation(n, off, nb, rot)
        _four_belts(n, off, rot, belts)
    return 0


@njit_leaf
def _roots_small(alive, n, link):
    """Number of truncation trees: removed faces whose link holds no removed face."""
    removed = ~alive & ((ONE << np.uint64(n)) - ONE if n < 64 else ~ZERO)
    roots = 0
    m = removed
    while m:
        v = lowest(m)
        m &= m - ONE
        roots += (link[v] & removed) == ZERO
    return roots


@njit(inline="always")
def _classify_small(g, n, triangular, adj, link, removed_round, family, fundamental, belts):
    """Classify grain g, validated by the fast path (its bitsets in ``adj``, its triangular
    faces in the bitset ``triangular``; ``link`` and ``removed_round`` as
    :func:`small._reduce_small` fills them); returns the fundamental faces as a bitset. The
    truncation trees are left to the caller: the census only counts them, and a kernel that
    never writes their strings is compiled without them.
    """
    alive = _reduce_small(n, adj, triangular, removed_round, link)
    fundamental[g] = popcount(alive)
    if fundamental[g] == 4:
        family[g] = STACKED
    elif _has_empty_triangle_small(adj, alive):
        family[g] = SC
    else:
        family[g] = FLAG
        if fundamental[g] == n:
            _four_belts_small(n, adj, belts[g])
    return alive


@njit(inline="always")
def _classify_ok_small(
    g, n, triangular, adj, link, removed_round, forest, strings, family, fundamental,
    trees_count, depth, belts, tree_offsets, tree_bytes, tree_length,
):  # fmt: skip
    """Classify ok grain g of at most 64 faces (``adj`` to ``removed_round`` as for
    :func:`_classify_small`; ``forest``, the scratch of the truncation-tree strings) into the
    outputs of :func:`_classify_batch` (which writes these steps out itself)."""
    alive = _classify_small(g, n, triangular, adj, link, removed_round, family, fundamental, belts)
    if 4 < fundamental[g] < n:
        if strings:
            trees_count[g], depth[g], tree_length[g] = _forest_string_small(
                n, alive, removed_round, link, tree_bytes, tree_offsets[g], forest
            )
        else:
            trees_count[g] = _roots_small(alive, n, link)


@njit
def _classify_batch(
    first,
    last,
    face_offsets,
    nbr_offsets,
    neighbors,
    parsed,
    max_small,
    strings,
    status,
    consistent,
    err,
    family,
    fundamental,
    trees_count,
    depth,
    belts,
    tree_offsets,
    tree_bytes,
    tree_length,
):
    """Classify grains ``first:last`` of a CSR batch by the fast path, marking the others
    PENDING; row ``g`` of every output is written for grain ``g`` only, so disjoint ranges can
    run in threads at once (see :mod:`grainclass.parallel`).

    Layout: grain g has faces ``face_offsets[g]:face_offsets[g+1]``; face f has the local
    neighbour indices ``neighbors[nbr_offsets[f]:nbr_offsets[f+1]]``. ``err`` is int64[G, 3]
    (code, a, b), ``consistent`` marks grains whose lists were already oriented one way,
    ``belts`` int64[G, 3] (split_k, count, penalty), ``tree_bytes`` holds 3n bytes per grain from
    ``tree_offsets[g]``. Family is -1 for grains that are not ok, depth 0 for fundamental ones.
    Grains with more than ``max_small`` faces skip the fast path. Without ``strings`` the
    truncation forests are only counted (trees_count; depth and tree bytes are left alone).
    """
    adj, following, link, removed_round, forest = _work()
    stamp = 0
    for g in range(first, last):
        family[g] = -1
        depth[g] = 0
        if not parsed[g]:
            status[g] = INVALID
            err[g, 0] = E_PARSE
            continue
        f0 = face_offsets[g]
        n = face_offsets[g + 1] - f0
        stamp = next_stamp(following, stamp)
        fast, triangular = False, ZERO
        if n <= max_small:
            fast, triangular = _validate_small(
                n, borrowed(nbr_offsets), borrowed(neighbors), f0, borrowed(adj),
                borrowed(following), stamp,
            )  # fmt: skip
        if fast:
            status[g] = OK
            consistent[g] = True
            # _classify_ok_small written out, its arrays borrowed: otherwise each is counted
            # up and down at every grain (see docs/performance.md).
            alive = _classify_small(
                g, n, triangular, borrowed(adj), borrowed(link), borrowed(removed_round),
                family, fundamental, belts,
            )  # fmt: skip
            if 4 < fundamental[g] < n:
                if strings:
                    trees_count[g], depth[g], tree_length[g] = _forest_string_small(
                        n, alive, borrowed(removed_round), borrowed(link), borrowed(tree_bytes),
                        tree_offsets[g], _borrowed_forest(forest),
                    )  # fmt: skip
                else:
                    trees_count[g] = _roots_small(alive, n, borrowed(link))
        else:
            status[g] = PENDING


@njit
def _validate_pending_batch(
    first,
    last,
    grains,
    face_offsets,
    nbr_offsets,
    neighbors,
    max_small,
    strings,
    limit,
    status,
    consistent,
    err,
    family,
    fundamental,
    trees_count,
    depth,
    belts,
    tree_offsets,
    tree_bytes,
    tree_length,
):
    """The grains ``grains[first:last]`` that the fast path left (outputs as in
    :func:`_classify_batch`; ``consistent`` marks those whose lists turn one way as given, as a
    grain of more than 64 faces may): each is validated with its diagnosis (``validate.py``),
    unless the general path could hold more than ``limit`` bytes for it (:func:`grain_bytes`:
    it is then invalid, E_TOO_LARGE, before anything is allocated),
    and an ok one of at most ``max_small`` faces, whose lists were only out of the fast path's
    order (turning both ways, or in no cyclic order), is classified on bitsets as by the fast path.
    Larger ok grains stay PENDING, for :func:`_classify_general_batch`. A kernel of its own, so
    that the general classification (``reduce.py``, ``belts.py``, ``trees._forest_string``) is
    compiled only once a grain of more than 64 faces needs it: a first run on a simulation's
    grains, a few of them degenerate, compiled it for them all the same."""
    bits, _, link, removed_round, forest = _work()
    for i in range(first, last):
        g = grains[i]
        n, off, nb = grain_lists(g, face_offsets, nbr_offsets, neighbors)
        need = grain_bytes(n, off[n])
        if need > limit:
            status[g] = INVALID
            err[g, 0], err[g, 1], err[g, 2] = E_TOO_LARGE, need, limit
            continue
        status[g], consistent[g] = _validate(n, off, nb, err[g])
        if status[g] != OK:
            continue
        if n > max_small:
            status[g] = PENDING
            continue
        triangular = ZERO
        for v in range(n):
            row = ZERO
            for k in range(off[v], off[v + 1]):
                row |= bit(nb[k])
            bits[v] = row
            triangular |= bit(v) if off[v + 1] - off[v] == 3 else ZERO
        _classify_ok_small(
            g, n, triangular, bits, link, removed_round, forest, strings, family, fundamental,
            trees_count, depth, belts, tree_offsets, tree_bytes, tree_length,
        )  # fmt: skip


@njit
def _classify_general_batch(
    first,
    last,
    grains,
    face_offsets,
    nbr_offsets,
    neighbors,
    strings,
    limit,
    status,
    err,
    family,
    fundamental,
    trees_count,
    depth,
    belts,
    tree_offsets,
    tree_bytes,
    tree_length,
):
    """The general path for the ok grains ``grains[first:last]`` of a CSR batch, which
    :func:`_validate_pending_batch` left PENDING, classified without bitsets (outputs as in
    :func:`_classify_batch`): those of more than 64 faces, and every grain when the tests
    compare the two paths. They are not validated again: that would lengthen its
    compilation. A grain whose truncation forest's strings would take more than ``limit``
    bytes is invalid (E_FOREST_TOO_LARGE)."""
    result = np.empty(5, np.int64)
    for i in range(first, last):
        g = grains[i]
        n, off, nb = grain_lists(g, face_offsets, nbr_offsets, neighbors)
        at = tree_offsets[g] if strings else 0
        result[:] = -1
        need = _classify_ok_general(n, off, nb, strings, tree_bytes, at, result, belts[g], limit)
        if need:
            status[g] = INVALID
            err[g, 0], err[g, 1], err[g, 2] = E_FOREST_TOO_LARGE, need, limit
            continue
        status[g] = OK
        family[g], fundamental[g] = result[0], result[1]
        if result[2] >= 0:
            trees_count[g] = result[2]
            if strings:  # else they were not computed (-1): left alone, as by the fast path
                depth[g], tree_length[g] = result[3], result[4]


@njit(inline="always")
def _small_record(buf, p, end):
    """The vertex count n of the planar_code record at ``buf[p:end]`` if the fast path can
    validate it in place (:func:`small._validate_record`): a triangulation's worth of 1-byte
    entries, n + (6n - 12) + n zeros, with at most 64 vertices; else 0. It returns n alone:
    one helper that also read the record for its verdict and bitset slows the census kernel.
    """
    n = int(buf[p])  # a record of 2-byte entries starts with a 0
    return n if 0 < n <= MAX_BITSET_FACES and end - p == 1 + 7 * n - 12 else 0


@njit(inline="always")
def grain_fields(family, truncations, trees, split):
    """``(class_code, round_k, split_k)`` of an ok grain of ``family`` that is ``truncations``
    truncations from its fundamental polytope, with ``trees`` truncation trees and belts whose
    split type has ``split`` as its k: the class an index into ``vocabulary.CLASSES``
    (``CLASS_OF``), round_k -1 for sc (never round), split_k -1 unless the grain is
    fundamental flag. The one place these rules are written: the per-grain rows and the
    summaries read them through :func:`_grain_codes`, the census through :func:`census_key`."""
    class_code = CLASS_OF[family, min(truncations, 3), 1 if trees == 2 else 0]
    round_k = -1 if family == SC else truncations
    split_k = split if family == FLAG and truncations == 0 else -1
    return class_code, round_k, split_k


@njit
def _grain_codes(
    status, n_faces, family, fundamental, trees, split, truncations, class_code, round_k, split_k
):
    """Per grain of a batch (inputs as the classification kernels write them, ``split`` the k
    of each grain's split type), its truncations, class, round_k and split_k by
    :func:`grain_fields` into the last four arrays; -1 for each where the grain is not ok."""
    for g in range(status.shape[0]):
        if status[g] == OK:
            truncations[g] = n_faces[g] - fundamental[g]
            class_code[g], round_k[g], split_k[g] = grain_fields(
                family[g], truncations[g], trees[g], split[g]
            )
        else:
            truncations[g] = class_code[g] = round_k[g] = split_k[g] = -1


@njit(inline="always")
def census_key(n, family, truncations, trees, split):
    """The group an ok grain of at most 64 faces is counted in: family, class, faces, round
    (truncations, -1 for sc) and split (-1 unless fundamental flag), by :func:`grain_fields`,
    each shifted to be >= 0, in 8 bits apiece (:func:`census_fields` reads them back)."""
    class_code, round_k, split_k = grain_fields(family, truncations, trees, split)
    key = (int(family) + 1) * 256 + int(class_code) + 1  # int(): no int8 wrap-around without JIT
    return ((key * 256 + int(n)) * 256 + int(round_k) + 1) * 256 + int(split_k) + 1


def census_fields(keys):
    """``(family, class_code, n_faces, round_k, split_k)`` of :func:`census_key` values."""
    keys = np.asarray(keys, np.int64)
    return (
        (keys >> 32) - 1,
        ((keys >> 24) & 255) - 1,
        (keys >> 16) & 255,
        ((keys >> 8) & 255) - 1,
        (keys & 255) - 1,
    )


@njit
def _tally_records(buf, starts):
    """The census of a batch of planar_code records without a row per grain: each record that
    :func:`_small_record` admits and the fast path validates is classified and added to its
    group, ``census_key`` (family, class, faces, round, split; all ok). Returns the hash table
    of keys (``EMPTY`` where free), its sums per slot (grains, triangular faces) and the
    records left for the general path (2-byte entries among them). Nothing per grain is
    written, so nothing is read back: grouping per-grain codes with numpy costs a large share
    of the kernel's time, its passes over the batch finding the arrays out of cache and their
    fresh pages to fault in.
    """
    adj, following, link, removed_round, _ = _work()
    stamp = 0
    family = np.empty(1, np.int8)
    fundamental = np.empty(1, np.int32)
    belts = np.zeros((1, 3), np.int64)
    table = np.full(FIRST_SLOTS, EMPTY, np.int64)
    sums = np.zeros((FIRST_SLOTS, 2), np.int64)
    groups = 0
    pending = np.empty(len(starts) - 1, np.int64)
    n_pending = 0
    for r in range(len(starts) - 1):
        stamp = next_stamp(following, stamp)
        p, end = starts[r], starts[r + 1]
        n = _small_record(buf, p, end)
        fast, triangular = (
            _validate_record(buf, p + 1, end, n, borrowed(adj), borrowed(following), stamp)
            if n
            else (False, ZERO)
        )
        if not fast:
            pending[n_pending] = r
            n_pending += 1
            continue
        alive = _classify_small(
            0, n, triangular, borrowed(adj), borrowed(link), borrowed(removed_round), family,
            fundamental, belts,
        )  # fmt: skip
        trees = _roots_small(alive, n, borrowed(link)) if 4 < fundamental[0] < n else 0
        key = census_key(n, family[0], n - fundamental[0], trees, belts[0, 0])
        table, sums, groups, s = insert(table, sums, groups, key)
        sums[s, 0] += 1
        sums[s, 1] += popcount(triangular)
    return table, sums, pending[:n_pending]
