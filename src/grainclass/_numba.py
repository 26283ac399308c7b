"""The one place where numba's compilation flags are set.

The kernels do exact combinatorics, so ``fastmath`` stays off; ``cache=True``
keeps shell pipelines from recompiling on every run.
"""

import functools

import numba

JIT = {"cache": True, "nogil": True, "fastmath": False}

njit = functools.partial(numba.njit, **JIT)
"""``@njit``: a serial kernel with the project's flags."""

njit_parallel = functools.partial(numba.njit, parallel=True, **JIT)
"""``@njit_parallel``: a batch kernel whose outer loop is a ``prange`` over grains."""
