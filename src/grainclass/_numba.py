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

njit_leaf = functools.partial(numba.njit, _nrt=False, **JIT)
"""``@njit_leaf``: a kernel that allocates nothing, called once or more per grain, compiled
without numba's reference counting (NRT): counting every array argument up on entry and down
on exit, each an atomic instruction, dominates the per-grain cost of a kernel that hands many
scratch arrays on (see docs/performance.md). numba refuses to compile an allocation in such a
kernel.
"""


@njit(inline="always")
def at(i):
    """``i``, known to be >= 0, as an array index: ``a[at(i)]``.

    numba lets a negative index count from the end, which costs every access through a signed
    integer a compare and a select; LLVM can rarely prove an index non-negative. An unsigned
    index skips that fix-up, which counts in tight loops of loads and stores (the planar_code
    fill, the Weinberg walks, the per-grain table), not where mispredicted branches take the
    time (the validation loops); see docs/performance.md.
    """
    return np.uint64(i)
