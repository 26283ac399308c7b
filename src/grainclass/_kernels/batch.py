"""The batch kernel: one compiled call classifies every grain of a :class:`GrainBatch`.

Grains with at most 64 faces whose lists pass the fast check run on bitsets with per-block
scratch (``small.py``); every other grain takes the general path, which allocates per grain but
diagnoses anything (``validate.py``, ``reduce.py``, ``belts.py``).
"""

import numpy as np

from grainclass._kernels.belts import _four_belts
from grainclass._kernels.bits import MAX_BITSET_FACES, popcount
from grainclass._kernels.codes import E_PARSE, FLAG, INVALID, OK, SC, STACKED
from grainclass._kernels.reduce import _has_empty_triangle, _reduce
from grainclass._kernels.small import (
    _four_belts_small,
    _has_empty_triangle_small,
    _parents_small,
    _reduce_small,
    _validate_small,
)
from grainclass._kernels.trees import _forest_scratch, _forest_string, _parents_from_links
from grainclass._kernels.validate import _validate
from grainclass._numba import njit


@njit
def _classify_general(n, off, nb, err, out, at, result, belts):
    """Any grain: validate with diagnosis, then classify. ``result`` gets (status, family,
    fundamental, trees, depth, tree length)."""
    adj = np.zeros((n, n), np.uint8)
    result[0] = _validate(n, off, nb, adj, err)
    if result[0] != OK:
        return
    alive = np.empty(n, np.bool_)
    removed_round = np.empty(n, np.int32)
    link = np.empty((n, 3), np.int32)
    result[2] = _reduce(n, off, nb, alive, removed_round, link)
    if result[2] == 4:
        result[1] = STACKED
        return
    result[1] = SC if _has_empty_triangle(n, off, nb, adj, alive) else FLAG
    if result[2] < n:
        parent = np.empty(n, np.int32)
        _parents_from_links(n, alive, removed_round, link, parent)
        result[3], result[4], result[5] = _forest_string(
            n, removed_round, parent, out, at, _forest_scratch(n)
        )
    elif result[1] == FLAG:
        _four_belts(n, off, nb, adj, belts)


@njit
def _classify_batch(
    first,
    last,
    face_offsets,
    nbr_offsets,
    neighbors,
    parsed,
    max_small,
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
    """Classify grains ``first:last``; row ``g`` of every output is written for grain ``g`` only,
    so disjoint ranges can run in threads at once (see :mod:`grainclass.parallel`).

    Layout: grain g has faces ``face_offsets[g]:face_offsets[g+1]``; face f has the local
    neighbour indices ``neighbors[nbr_offsets[f]:nbr_offsets[f+1]]``. ``err`` is int64[G, 3]
    (code, a, b), ``consistent`` marks grains whose lists were already oriented one way,
    ``belts`` int64[G, 3] (split_k, count, weight), ``tree_bytes`` holds 3n bytes
    per grain from ``tree_offsets[g]``. Family is -1 for grains that are not ok, depth 0 for
    fundamental ones. Grains with more than ``max_small`` faces skip the fast path; the fast
    path's scratch arrays are allocated once per call.
    """
    adj = np.empty(MAX_BITSET_FACES, np.uint64)
    following = np.empty(MAX_BITSET_FACES * MAX_BITSET_FACES, np.uint8)
    link = np.empty(MAX_BITSET_FACES, np.uint64)
    removed_round = np.empty(MAX_BITSET_FACES, np.int32)
    parent = np.empty(MAX_BITSET_FACES, np.int32)
    scratch = _forest_scratch(MAX_BITSET_FACES)
    result = np.zeros(6, np.int64)
    for g in range(first, last):
        family[g] = -1
        depth[g] = 0
        if not parsed[g]:
            status[g] = INVALID
            err[g, 0] = E_PARSE
            continue
        f0 = face_offsets[g]
        n = face_offsets[g + 1] - f0
        if n <= max_small and _validate_small(n, nbr_offsets, neighbors, f0, adj, following):
            status[g] = OK
            consistent[g] = True
            alive = _reduce_small(n, adj, removed_round, link)
            fundamental[g] = popcount(alive)
            if fundamental[g] == 4:
                family[g] = STACKED
            elif fundamental[g] < n:
                family[g] = SC if _has_empty_triangle_small(adj, alive) else FLAG
                _parents_small(n, alive, removed_round, link, parent)
                trees_count[g], depth[g], tree_length[g] = _forest_string(
                    n, removed_round, parent, tree_bytes, tree_offsets[g], scratch
                )
            elif _has_empty_triangle_small(adj, alive):
                family[g] = SC
            else:
                family[g] = FLAG
                _four_belts_small(n, adj, belts[g])
            continue
        off = nbr_offsets[f0 : f0 + n + 1] - nbr_offsets[f0]
        nb = neighbors[nbr_offsets[f0] : nbr_offsets[f0 + n]]
        result[:] = -1
        _classify_general(n, off, nb, err[g], tree_bytes, tree_offsets[g], result, belts[g])
        status[g] = result[0]
        if result[0] == OK:
            family[g], fundamental[g] = result[1], result[2]
            if result[3] >= 0:
                trees_count[g], depth[g], tree_length[g] = result[3], result[4], result[5]
