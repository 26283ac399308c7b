"""What the classification gives per grain, as integer arrays: the kernels' outputs
(:class:`Classified`) and the codes that rows and summaries are made from (:class:`GrainCodes`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from grainclass.batch import GrainBatch


@dataclass(frozen=True)
class GrainCodes:
    """A grain's classification as integer arrays (no strings, no Arrow): what the summaries
    count, and what the per-grain table's class, round and split columns are written from.

    ``status`` and ``family`` are codes of :mod:`grainclass._kernels.codes`, ``class_code`` an
    index into :data:`grainclass.vocabulary.CLASSES`; ``truncations`` and ``class_code`` are -1
    when the grain is not ok, ``round_k`` also for sc, ``split_k`` unless the grain is fundamental
    flag; ``n_faces`` is -1 for an unreadable record. The per-grain table's columns take their
    nulls from these -1s. The rules of class, round<=k and split type are those of
    ``_kernels/batch.py: grain_fields``, which the census reads too.
    """

    n_faces: np.ndarray
    status: np.ndarray
    family: np.ndarray
    truncations: np.ndarray
    class_code: np.ndarray
    round_k: np.ndarray
    split_k: np.ndarray
    triangles: np.ndarray


@dataclass(frozen=True)
class Classified:
    """The classification kernels' per-grain outputs (see ``_kernels/batch.py``), and which
    grains the reader could parse."""

    parsed: np.ndarray
    status: np.ndarray
    consistent: np.ndarray
    err: np.ndarray
    family: np.ndarray
    fundamental: np.ndarray
    n_trees: np.ndarray
    depth: np.ndarray
    belts: np.ndarray
    tree_offsets: np.ndarray
    tree_bytes: np.ndarray
    tree_length: np.ndarray

    @property
    def rows(self) -> tuple[np.ndarray, ...]:
        """The per-grain classification, as the batch kernels take it."""
        return (self.family, self.fundamental, self.n_trees, self.depth, self.belts)

    @property
    def forests(self) -> tuple[np.ndarray, ...]:
        """The truncation-forest strings, as the batch kernels take them."""
        return (self.tree_offsets, self.tree_bytes, self.tree_length)

    @classmethod
    def empty(cls, batch: GrainBatch, strings: bool) -> Classified:
        """Output arrays for the kernels, sized for ``batch`` (3n bytes of tree string per
        grain when ``strings``)."""
        g = len(batch)
        parsed = np.ones(g, np.bool_)
        parsed[list(batch.parse_errors)] = False
        tree_offsets = np.zeros(g + 1, np.int64)
        if strings:
            np.cumsum(3 * batch.n_faces, out=tree_offsets[1:])
        return cls(
            parsed=parsed,
            status=np.zeros(g, np.int8),
            consistent=np.zeros(g, np.bool_),
            err=np.zeros((g, 3), np.int64),
            family=np.full(g, -1, np.int8),
            fundamental=np.zeros(g, np.int32),
            n_trees=np.zeros(g, np.int32),
            depth=np.zeros(g, np.int32),
            belts=np.zeros((g, 3), np.int64),
            tree_offsets=tree_offsets,
            tree_bytes=np.empty(int(tree_offsets[-1]), np.uint8),
            tree_length=np.zeros(g, np.int64),
        )
