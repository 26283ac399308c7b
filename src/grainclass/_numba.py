"""The one place where numba's compilation flags are set, and :func:`at`, the kernels' index.

The kernels do exact combinatorics, so ``fastmath`` stays off; ``cache=True`` keeps shell
pipelines from recompiling on every run; ``nogil=True`` lets :mod:`grainclass.parallel` run a
batch kernel on several grain ranges in threads at once (numba's own ``parallel=True`` would
cost many seconds more compilation at the first run).
"""

import functools

import numba
import numpy as np

JIT = {"cache": True, "nogil": True, "fastmath": False}

njit = functools.partial(numba.njit, **JIT)
"""``@njit``: a serial kernel with the project's flags."""


@njit(inline="always")
def at(i):
    """``i``, known to be >= 0, as an array index: ``a[at(i)]``.

    numba lets a negative index count from the end, which costs every access through a signed
    integer a compare and a select; LLVM can rarely prove an index non-negative. An unsigned
    index skips that fix-up. It pays in tight loops of loads and stores (the planar_code fill
    took half the time, the Weinberg walks a quarter less, the per-grain table two fifths less);
    where mispredicted branches take the time (the validation loops) it measured nothing.
    """
    return np.uint64(i)
