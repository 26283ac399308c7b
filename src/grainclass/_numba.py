"""The one place where numba's compilation flags are set; :func:`at`, the kernels' index;
:func:`borrowed`, the view a per-grain kernel is handed; and the listener that tells
:mod:`grainclass.compilation` when numba compiles one of the kernels.

The kernels do exact combinatorics, so ``fastmath`` stays off; ``cache=True`` keeps shell
pipelines from recompiling on every run; ``nogil=True`` lets :mod:`grainclass.parallel` run a
batch kernel on several grain ranges in threads at once (numba's own ``parallel=True`` would
cost many seconds more compilation at a first run). Only numba's documented options and
extension API are used (``inline``, ``numba.extending.intrinsic``, ``numba.carray``, the
event API of ``numba.core.event``).
"""

import functools

import numba
import numpy as np
from numba import types
from numba.core import cgutils
from numba.core import event as numba_event
from numba.extending import intrinsic, overload

from grainclass import compilation

JIT = {"cache": True, "nogil": True, "fastmath": False}

njit = functools.partial(numba.njit, **JIT)
"""``@njit``: a serial kernel with the project's flags."""


def njit_leaf(function):
    """``@njit_leaf``: a kernel called once or more per grain, inlined where it is called
    (numba's ``inline="always"``, at the level of numba's IR). As a call of its own, numba's
    reference counting (NRT) would count each array argument up on entry and down on exit, an
    atomic instruction each, which dominates the per-grain cost of a kernel that hands many
    scratch arrays on; inlined, the counting is the caller's, on the caller's variables, and a
    :func:`borrowed` view handed in is counted not at all (see docs/performance.md). Takes no
    options: every leaf kernel is compiled alike."""
    return numba.njit(function, inline="always", **JIT)


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


def borrowed(array):
    """``array`` itself as plain Python; compiled, a view of its data that owns nothing
    (``numba.carray`` of its address), whose reference counting is a test of a null pointer
    that the compiler removes. For a C-contiguous array handed to an :func:`njit_leaf` kernel
    in a per-grain loop, while ``array`` itself stays alive: the view must not outlive it."""
    return array


@intrinsic
def _first_element(typingctx, array):
    """The address of a C-contiguous array's first element, as a typed pointer."""
    if not isinstance(array, types.Array) or array.layout != "C":
        return None

    def codegen(context, builder, signature, args):
        # A struct proxy reads a member of numba's native value, as the extension docs do.
        return cgutils.create_struct_proxy(signature.args[0])(context, builder, args[0]).data

    return types.CPointer(array.dtype)(array), codegen


@overload(borrowed, inline="always", jit_options=JIT)
def _borrowed_jit(array):
    return lambda array: numba.carray(_first_element(array), array.shape)


class _KernelCompiles(numba_event.Listener):
    """numba's ``numba:compile`` events (a kernel compiled, not loaded from the cache) for
    grainclass's kernels, passed on to :func:`grainclass.compilation.kernel_compiling`."""

    def on_start(self, event: numba_event.Event) -> None:
        # Any other code compiling in the process (a user's own kernels, numba's) is not
        # ours, and a function made without a module must not break its compilation.
        module = getattr(event.data["dispatcher"].py_func, "__module__", None) or ""
        if module.startswith("grainclass."):
            compilation.kernel_compiling()

    def on_end(self, event: numba_event.Event) -> None:
        pass


numba_event.register("numba:compile", _KernelCompiles())
