"""The triangulation constraint on a label image's junctions: the edits that undo voxel
artefacts where the triple lines and quadruple points that :func:`grainclass.voxels.image_topology`
reads off the blocks cannot be those of simple polytopes (docs/voxels.md, "The triangulation
constraint"). Each edit is made once for all the grains it concerns, so neighbours agree.
"""

from __future__ import annotations

from itertools import combinations

import numpy as np

SPURIOUS_FACE_CONTACTS = 1
"""A small triangular face whose two grains share at most this many voxel faces ..."""
SPURIOUS_FACE_PIECES = 21
"""... and whose three triple lines are at most this many simplices of the blocks' meshes is
taken for a short triple line seen flipped (docs/voxels.md)."""


def settle(
    pairs: np.ndarray,
    pair_faces: np.ndarray,
    triples: np.ndarray,
    triple_weight: np.ndarray,
    quads: np.ndarray,
    quad_weight: np.ndarray,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The triple lines and quadruple points with two kinds of voxel artefacts undone.

    *Odd triple lines*: in a triangulation every triple line is on two quadruple points. A
    quadruple point each of whose four triple lines is on an odd number (one or three) is
    removed, which leaves each on none or two; so is a pair sharing a triple line, each on three
    odd ones. A *lens* is one such: x and y touch at one spot between u and v, a face of two
    sides for both ({x, y, u} and {x, y, v} on {x, y, u, v} alone, {x, u, v} and {y, u, v} on
    three).
    A *tiny triangle*: a pair d, e on exactly three quadruple points {d, e, a, b}, {d, e, b, c},
    {d, e, c, a} (a triangular face for both), sharing at most
    :data:`SPURIOUS_FACE_CONTACTS` voxel faces, its triple lines at most
    :data:`SPURIOUS_FACE_PIECES` simplices: flipped into the short triple line {a, b, c}
    between {a, b, c, d} and {a, b, c, e}. Both keep every grain's graph consistent with the
    others'."""
    n = int(max(quads.max(initial=-1), triples.max(initial=-1), pairs.max(initial=-1))) + 1
    # Only quadruple points near a pair on one of them, or on three and few voxel faces, can be
    # edited: the dictionaries below hold those with three labels among the labels of theirs,
    # complete for every pair and triple line they are asked about.
    pair_of = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)]
    pair_keys = np.stack([quads[:, a] * n + quads[:, b] for a, b in pair_of], axis=1)
    keys, counts = np.unique(pair_keys, return_counts=True)
    contact_keys = pairs[:, 0] * n + pairs[:, 1]
    order = np.argsort(contact_keys)
    at = np.searchsorted(contact_keys[order], keys)
    found = at < len(order)
    found[found] = contact_keys[order][at[found]] == keys[found]
    faces_of_key = np.where(found, pair_faces[order][np.minimum(at, len(order) - 1)], 0)
    candidate = (counts == 1) | ((counts == 3) & (faces_of_key <= SPURIOUS_FACE_CONTACTS))
    near = np.isin(pair_keys, keys[candidate]).any(axis=1)
    # Quadruple points on a triple line that is on an odd number of them.
    triple_of = [(0, 1, 2), (0, 1, 3), (0, 2, 3), (1, 2, 3)]
    triple_keys = np.stack(
        [(quads[:, a] * n + quads[:, b]) * n + quads[:, c] for a, b, c in triple_of], axis=1
    )
    t_keys, t_counts = np.unique(triple_keys, return_counts=True)
    odd = np.isin(triple_keys, t_keys[t_counts % 2 == 1])
    near |= odd.any(axis=1)
    involved = np.zeros(n, bool)
    involved[quads[near].ravel()] = True
    subset = involved[quads].sum(axis=1) >= 3
    inside = involved[triples].all(axis=1) if len(triples) else np.zeros(0, bool)

    tw = {
        tuple(t): int(w)
        for t, w in zip(triples[inside].tolist(), triple_weight[inside].tolist(), strict=True)
    }
    qw = {
        tuple(q): int(w)
        for q, w in zip(quads[subset].tolist(), quad_weight[subset].tolist(), strict=True)
    }
    loose = set(tw)  # triples with no quadruple point stay as they are
    pair_quads: dict[tuple[int, ...], set[tuple[int, ...]]] = {}
    triple_quads: dict[tuple[int, ...], set[tuple[int, ...]]] = {}

    def add(q: tuple[int, ...], weight: int) -> None:
        qw[q] = weight
        for p in combinations(q, 2):
            pair_quads.setdefault(p, set()).add(q)
        for t in combinations(q, 3):
            triple_quads.setdefault(t, set()).add(q)
            tw.setdefault(t, 0)

    def remove(q: tuple[int, ...]) -> None:
        del qw[q]
        for p in combinations(q, 2):
            pair_quads[p].discard(q)
        for t in combinations(q, 3):
            triple_quads[t].discard(q)
            if not triple_quads[t]:
                tw.pop(t, None)

    for q, weight in list(qw.items()):
        add(q, weight)
    loose -= set(triple_quads)

    # Odd triple lines: a quadruple point each of whose triple lines is on an odd number of
    # them is removed (every one of them is then on 0 or 2), and so is a pair of quadruple
    # points sharing a triple line, each on three odd ones.
    def odd_triples(q: tuple[int, ...]) -> list[tuple[int, ...]]:
        return [t for t in combinations(q, 3) if len(triple_quads[t]) % 2 == 1]

    suspects = sorted(tuple(q) for q in quads[odd.any(axis=1)].tolist())
    for q in suspects:
        if q in qw and len(odd_triples(q)) == 4:
            remove(q)
    for q in suspects:
        if q not in qw or len(odd_triples(q)) != 3:
            continue
        (shared,) = [t for t in combinations(q, 3) if len(triple_quads[t]) % 2 == 0]
        if len(triple_quads[shared]) != 2:
            continue
        (other,) = triple_quads[shared] - {q}
        if len(odd_triples(other)) == 3:
            remove(q)
            remove(other)
    triangles = [
        (int(f), int(k // n), int(k % n))
        for k, f, c in zip(keys, faces_of_key, counts, strict=True)
        if c == 3 and f <= SPURIOUS_FACE_CONTACTS
    ]
    for _, d, e in sorted(triangles):
        around = pair_quads[(d, e)]
        if len(around) != 3:
            continue
        others = sorted({x for q in around for x in q} - {d, e})
        if len(others) != 3 or triple_quads.get(tuple(others)):
            continue
        pieces = sum(tw.get(tuple(sorted((d, e, x))), 0) for x in others)
        two = (tuple(sorted((*others, d))), tuple(sorted((*others, e))))
        if pieces > SPURIOUS_FACE_PIECES or two[0] in qw or two[1] in qw:
            continue
        weight = min(qw[q] for q in around)
        for q in list(around):
            remove(q)
        for q in two:
            add(q, weight)
    kept = sorted(t for t in set(tw) | loose if all(involved[list(t)]))
    near_triples = np.array(kept, np.int64).reshape(-1, 3)
    near_weight = np.array([tw.get(t, 0) for t in kept], np.int64)
    kept_quads = sorted(qw)
    all_triples = np.concatenate([triples[~inside], near_triples])
    all_weight = np.concatenate([triple_weight[~inside], near_weight])
    all_quads = np.concatenate([quads[~subset], np.array(kept_quads, np.int64).reshape(-1, 4)])
    all_quad_weight = np.concatenate(
        [quad_weight[~subset], np.array([qw[q] for q in kept_quads], np.int64)]
    )
    t_order = np.lexsort(all_triples.T[::-1])
    q_order = np.lexsort(all_quads.T[::-1])
    return (
        all_triples[t_order],
        all_weight[t_order],
        all_quads[q_order],
        all_quad_weight[q_order],
    )
