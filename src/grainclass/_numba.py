"""The one place where numba's compilation flags are set.

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
    integer a compare and a select; LLVM can rarely prove an index non-negative, and in the
    byte loops this doubled the time. An unsigned index skips that fix-up.
    """
    return np.uint64(i)
