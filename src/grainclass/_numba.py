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
without numba's reference counting (NRT). With it, every array passed in was counted up on
entry and down on exit, each an atomic instruction: those two took over a third of the samples
of the classification kernel at n = 16, most for the truncation forests' nine scratch arrays,
and 4% without it; the kernel with forest strings took a sixth less time (505-668 ns a grain
against 639-883, the best of five passes in each of six alternated runs). numba refuses to
compile an allocation in such a kernel.
"""


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
