"""uint64 bitset helpers for grains with at most 64 faces.

``popcount`` and ``lowest`` compile to single LLVM instructions (ctpop, cttz); as plain Python
(``NUMBA_DISABLE_JIT=1``) they fall back to ``int`` arithmetic.
"""

import numpy as np
from llvmlite import ir
from numba import types
from numba.extending import intrinsic, overload

from grainclass._numba import JIT, njit

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


# llvmlite's IRBuilder emits LLVM's ctpop and cttz intrinsics, as numba's extension docs build
# an intrinsic's code.
@intrinsic
def _ctpop(typingctx, x):
    if not isinstance(x, types.Integer):
        return None

    def codegen(context, builder, signature, args):
        return builder.ctpop(args[0])

    return x(x), codegen


@intrinsic
def _cttz(typingctx, x):
    if not isinstance(x, types.Integer):
        return None

    def codegen(context, builder, signature, args):
        # Not "undefined at zero": the callers never pass 0, but LLVM's result stays defined.
        return builder.cttz(args[0], ir.Constant(ir.IntType(1), 0))

    return x(x), codegen


@overload(popcount, jit_options=JIT)
def _popcount_jit(x):
    return lambda x: _ctpop(x)


@overload(lowest, jit_options=JIT)
def _lowest_jit(x):
    return lambda x: _cttz(x)


@njit(inline="always")  # called with int32, int64 and uint64: inlined, compiled for none
def bit(i):
    """The bitset holding only ``i``."""
    return ONE << np.uint64(i)


@njit
def full(n):
    """The bitset {0, ..., n-1}."""
    return ~ZERO if n == 64 else (ONE << np.uint64(n)) - ONE
