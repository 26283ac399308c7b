"""Each connected piece of a label as a grain of its own (``--components``), with
connected-components-3d (``cc3d``), the pieces joined across the sides of the image that wrap.

cc3d labels an array held in memory and wraps all three axes or none (its
``periodic_boundary``, for 6-connected pieces), so the whole image is read, the pieces are
found without wrapping, and those that meet across a side that wraps are joined here.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from grainclass.errors import MissingDependencyError


def connected_pieces(
    labels: np.ndarray, periodic: tuple[int, int, int], background: Sequence[int] = ()
) -> tuple[np.ndarray, np.ndarray]:
    """``(pieces, original)``: ``labels`` (indexed [z, y, x]) with each connected piece of a
    label (voxels joined through faces, across the sides that wrap too: ``periodic`` for x, y,
    z) numbered 1, 2, ... in the order cc3d meets them, the background 0; and the label of each
    piece (``original[piece]``)."""
    try:
        import cc3d
    except ImportError:
        raise MissingDependencyError(
            "--components needs connected-components-3d: pip install 'grainclass[images]'"
        ) from None
    labels = labels.astype(np.int64)
    shifted = labels + 1
    for b in background:
        shifted[labels == b] = 0
    pieces = cc3d.connected_components(shifted, connectivity=6, out_dtype=np.uint64)
    pieces = pieces.astype(np.int64)
    n = int(pieces.max()) + 1
    parent = np.arange(n)

    def root(x: int) -> int:
        while parent[x] != x:
            parent[x] = parent[parent[x]]
            x = int(parent[x])
        return x

    for axis, wraps in zip((2, 1, 0), periodic, strict=True):
        if not wraps:
            continue
        first = np.take(pieces, 0, axis=axis).ravel()
        last = np.take(pieces, -1, axis=axis).ravel()
        same = (first > 0) & (
            np.take(shifted, 0, axis=axis).ravel() == np.take(shifted, -1, axis=axis).ravel()
        )
        for a, b in set(zip(first[same].tolist(), last[same].tolist(), strict=True)):
            ra, rb = root(a), root(b)
            if ra != rb:
                parent[max(ra, rb)] = min(ra, rb)
    roots = np.array([root(x) for x in range(n)])
    kept = np.unique(roots[1:]) if n > 1 else np.zeros(0, np.int64)
    renumber = np.zeros(n, np.int64)
    renumber[kept] = np.arange(1, len(kept) + 1)
    new = renumber[roots][pieces]
    original = np.zeros(len(kept) + 1, np.int64)
    original[new.ravel()] = labels.ravel()
    return new, original
