"""uint64 bitset helpers for grains with at most 64 faces.

``popcount`` and ``lowest`` compile to single LLVM instructions (ctpop, cttz); as plain Python
(``NUMBA_DISABLE_JIT=1``) they fall back to ``int`` arithmetic.
"""

import numpy as np
from llvmlite import ir
from numba.core import cgutils, types
from numba.cpython.unsafe.numbers import trailing_zeros
from numba.extending import intrinsic, overload

from grainclass._numba import njit

MAX_BITSET_FACES = 64
ONE = np.uint64(1)
ZERO = np.uint64(0)


def popcount(x):
    """Number of set bits."""
    return bin(int(x)).count("1")


def lowest(x):
    """Index of the lowest set bit (x must not be 0)."""
    x = int(x)
    return (x & -x).bit_length() - 1


@intrinsic
def _ctpop(typingctx, x):
    if not isinstance(x, types.Integer):
        return None

    def codegen(context, builder, signature, args):
        fnty = ir.FunctionType(args[0].type, [args[0].type])
        fn = cgutils.get_or_insert_function(builder.module, fnty, f"llvm.ctpop.i{x.bitwidth}")
        return builder.call(fn, [args[0]])

    return x(x), codegen


@overload(popcount, jit_options={"cache": True})
def _popcount_jit(x):
    return lambda x: _ctpop(x)


@overload(lowest, jit_options={"cache": True})
def _lowest_jit(x):
    return lambda x: trailing_zeros(x)


@njit(inline="always")  # called with int32, int64 and uint64: inlined, compiled for none
def bit(i):
    """The bitset holding only ``i``."""
    return ONE << np.uint64(i)


@njit
def full(n):
    """The bitset {0, ..., n-1}."""
    return ~ZERO if n == 64 else (ONE << np.uint64(n)) - ONE
