"""The ``belts``, ``splits`` and ``belt_penalties`` columns: the belts of every length l = 3..L
of the ok grains (``_kernels/lbelts.py``), as a list per grain."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import pyarrow as pa

from grainclass._kernels import codes
from grainclass.arrow import booleans, numbers
from grainclass.batch import GrainBatch
from grainclass.errors import OptionError
from grainclass.memory import each_grain

if TYPE_CHECKING:
    from grainclass.classified import Classified


def belt_profile(batch: GrainBatch, out: Classified, longest: int) -> np.ndarray:
    """The belts of lengths 3..``longest`` of the grains ok in ``out``: per grain and l,
    (belts, split_k, penalty), int64[G, longest - 2, 3] (``_kernels/lbelts.py``); zeros for
    the other grains. A grain refused memory for them is invalid in ``out`` (E_MEMORY)."""
    from grainclass._kernels.lbelts import MAX_BELT_LENGTH, _belts_batch

    if not 3 <= longest <= MAX_BELT_LENGTH:
        raise OptionError(
            "belts", f"belt lengths go from 3 to at most {MAX_BELT_LENGTH}, not {longest}"
        )
    profile = np.zeros((len(batch), longest - 2, 3), np.int64)
    ok = np.flatnonzero(out.status == codes.OK)
    csr = (batch.face_offsets, batch.nbr_offsets, batch.neighbors)
    each_grain(_belts_batch, ok, (*csr, longest, profile), out)
    return profile


def belt_lists(profile: np.ndarray | None, field: int, ok: np.ndarray, kind) -> pa.Array:
    """Column ``field`` (0 belts, 1 split_k, 2 penalty) of the belt profile as a list per ok
    grain, null elsewhere and for every grain without a profile; a split type the grain does
    not have (-1: fewer faces than the belts' length) is a null element."""
    g = len(ok)
    if profile is None:
        return pa.nulls(g, pa.list_(kind))
    width = profile.shape[1]
    offsets = np.arange(0, (g + 1) * width, width, dtype=np.int32)
    column = np.ascontiguousarray(profile[:, :, field]).reshape(-1)
    values = numbers(column, kind, column >= 0 if (column < 0).any() else None)
    return pa.ListArray.from_arrays(
        numbers(offsets, pa.int32()), values, mask=None if ok.all() else booleans(~ok)
    )
