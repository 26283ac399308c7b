"""The ``weinberg``, ``symmetry`` and ``chirality`` columns: the Weinberg walks of the ok grains
(``_kernels/weinberg.py``), on dense tables for grains of up to ``DENSE_FACES`` faces and on
tables of darts for larger ones."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import pyarrow as pa

from grainclass._kernels import codes
from grainclass.arrow import string_array
from grainclass.batch import GrainBatch
from grainclass.memory import each_grain

if TYPE_CHECKING:
    from grainclass.classified import Classified


@dataclass(frozen=True)
class Types:
    """Weinberg vectors (grain g's at ``weinberg[code_offsets[g]:code_offsets[g + 1]]``),
    symmetry orders and chirality, for the grains in ``computed``."""

    computed: np.ndarray
    code_offsets: np.ndarray
    weinberg: np.ndarray
    symmetry: np.ndarray
    chirality: np.ndarray


def weinberg_types(batch: GrainBatch, out: Classified, types: bool) -> Types:
    """The Weinberg walks for the ok grains (for none unless ``types``). A grain refused
    memory for them is invalid in ``out`` (E_MEMORY), and has none."""
    from grainclass._kernels.weinberg import (
        DENSE_FACES,
        _rotations,
        _weinberg_batch,
        _weinberg_large_batch,
    )

    g = len(batch)
    n_faces = batch.n_faces
    ok = out.status == codes.OK
    computed = ok & types
    code_offsets = np.zeros(g + 1, np.int64)
    np.cumsum(np.where(computed, 6 * n_faces - 11, 0), out=code_offsets[1:])
    result = Types(
        computed=computed,
        code_offsets=code_offsets,
        weinberg=np.zeros(int(code_offsets[-1]), np.int32),
        symmetry=np.zeros(g, np.int32),
        chirality=np.zeros(g, np.int8),
    )
    if types:
        rotations = batch.neighbors
        csr = (batch.face_offsets, batch.nbr_offsets, batch.neighbors)
        unoriented = np.flatnonzero(ok & ~out.consistent)
        if len(unoriented):
            rotations = batch.neighbors.copy()
            each_grain(_rotations, unoriented, (*csr, rotations), out)
        ok &= out.status == codes.OK
        small = ok & (n_faces <= DENSE_FACES)
        arrays = (*csr[:2], rotations, code_offsets, result.weinberg, result.symmetry,
                  result.chirality)  # fmt: skip
        each_grain(_weinberg_batch, np.flatnonzero(small), arrays, out)
        each_grain(_weinberg_large_batch, np.flatnonzero(ok & ~small), arrays, out)
        computed &= out.status == codes.OK
    return result


def weinberg_strings(types: Types) -> pa.Array:
    """The Weinberg vectors as VoroTop writes them, null where none was computed."""
    from grainclass._kernels.columns import _code_strings

    computed = types.computed
    return string_array(*_code_strings(types.weinberg, types.code_offsets, computed), computed)
