"""The batch kernel: one compiled call classifies every grain of a :class:`GrainBatch`."""

import numpy as np
from numba import prange

from grainclass._kernels.belts import _four_belts
from grainclass._kernels.codes import E_PARSE, FLAG, INVALID, OK, SC, STACKED
from grainclass._kernels.reduce import _has_empty_triangle, _reduce
from grainclass._kernels.trees import _truncation_forest
from grainclass._kernels.validate import _validate
from grainclass._numba import njit_parallel


@njit_parallel
def _classify_batch(
    face_offsets,
    nbr_offsets,
    neighbors,
    parsed,
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
    """Classify grains ``g`` in parallel; each output row ``g`` is written by iteration ``g`` only.

    Layout: grain g has faces ``face_offsets[g]:face_offsets[g+1]``; face f has the local
    neighbour indices ``neighbors[nbr_offsets[f]:nbr_offsets[f+1]]``. ``err`` is int64[G, 3]
    (code, a, b), ``belts`` int64[G, 3] (split_k, count, weight), ``tree_bytes`` holds 3n bytes per
    grain from ``tree_offsets[g]``. Family is -1 for grains that are not ok.
    """
    for g in prange(face_offsets.shape[0] - 1):
        family[g] = -1
        if not parsed[g]:
            status[g] = INVALID
            err[g, 0] = E_PARSE
            continue
        f0 = face_offsets[g]
        n = face_offsets[g + 1] - f0
        off = nbr_offsets[f0 : f0 + n + 1] - nbr_offsets[f0]
        nb = neighbors[nbr_offsets[f0] : nbr_offsets[f0 + n]]
        adj = np.zeros((n, n), np.uint8)
        status[g] = _validate(n, off, nb, adj, err[g])
        if status[g] != OK:
            continue
        alive = np.empty(n, np.bool_)
        removed_round = np.empty(n, np.int32)
        link = np.empty((n, 3), np.int32)
        fundamental[g] = _reduce(n, off, nb, alive, removed_round, link)
        if fundamental[g] == 4:
            family[g] = STACKED
            continue
        family[g] = SC if _has_empty_triangle(n, off, nb, adj, alive) else FLAG
        if fundamental[g] < n:
            out = tree_bytes[tree_offsets[g] : tree_offsets[g + 1]]
            trees_count[g], depth[g], tree_length[g] = _truncation_forest(
                n, alive, removed_round, link, out
            )
        else:
            depth[g] = 0
            if family[g] == FLAG:
                _four_belts(n, off, nb, adj, belts[g])
