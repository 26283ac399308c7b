"""The memory a grain may take, and the grains refused it: one that could need more than the
limit (the kernels weigh it: E_TOO_LARGE, E_FOREST_TOO_LARGE), or for which the system refuses
memory (E_MEMORY, :func:`each_grain`), is an ``invalid`` row that says so, and the others are
classified."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

import numpy as np

from grainclass._kernels import codes
from grainclass.parallel import run_ranges

if TYPE_CHECKING:
    from grainclass.classified import Classified

GRAIN_MEMORY_MB = 2048
"""The memory a grain may take on the general path by default, in MB
(``GRAINCLASS_GRAIN_MEMORY`` sets another): a grain that could need more is a row of status
``invalid`` that says so, not a run that fails."""


def grain_memory_limit() -> int:
    """The bytes a grain may take: ``GRAINCLASS_GRAIN_MEMORY`` MB, else :data:`GRAIN_MEMORY_MB`."""
    import os

    value = os.environ.get("GRAINCLASS_GRAIN_MEMORY", "")
    try:
        mb = float(value) if value.strip() else GRAIN_MEMORY_MB
    except ValueError:
        mb = GRAIN_MEMORY_MB
    return max(0, int(mb * 2**20))


def each_grain(
    kernel: Callable[..., object], grains: np.ndarray, arrays: tuple, out: Classified
) -> None:
    """``kernel(first, last, grains, *arrays)`` over the grains ``grains`` (int64 indices) in
    ranges; if the system refuses it memory, again one grain at a time, and each grain that it
    still refuses is invalid in ``out``, saying so (E_MEMORY): one grain that cannot be had
    memory for does not cost the others their rows. Every kernel that allocates per grain or
    for the largest grain of its range runs through here."""
    try:
        run_ranges(kernel, len(grains), grains, *arrays)
    except MemoryError:
        for i in range(len(grains)):
            try:
                kernel(i, i + 1, grains, *arrays)
            except MemoryError:
                g = int(grains[i])
                out.status[g] = codes.INVALID
                out.err[g] = (codes.E_MEMORY, 0, 0)
                out.family[g] = -1
