"""Tokens to numbers: ids as integers, coordinates and volumes as Python's float() reads them.

Each function reads one token, ``buf[s:e]``, and returns a status with the value; a number the
kernel cannot be sure to read as float() does is left to Python (ENTRY_SLOW).
"""

import numpy as np

from grainclass._kernels.evolver.codes import ENTRY_BAD, ENTRY_OK, ENTRY_SLOW
from grainclass._kernels.evolver.lexing import (
    DOT,
    MINUS,
    NINE,
    PLUS,
    UNDERSCORE,
    ZERO,
    _lower,
    _word_is,
)
from grainclass._numba import njit, njit_leaf

LONGEST_ID = 18  # decimal digits: past them an id does not fit int64

_W_INF = np.frombuffer(b"inf", np.uint8)
_W_INFINITY = np.frombuffer(b"infinity", np.uint8)
_W_NAN = np.frombuffer(b"nan", np.uint8)
_POWERS = np.array([10.0**k for k in range(23)])  # exact in float64


@njit_leaf
def _is_decimal(buf, s, e):
    p = s
    while p < e and ZERO <= buf[p] <= NINE:
        p += 1
    return e > s and p == e


@njit_leaf
def _parse_int(buf, s, e):
    """``(ok, value)`` of an integer token: a sign, then 1 to 18 ASCII digits."""
    p = s
    negative = False
    if p < e and (buf[p] == PLUS or buf[p] == MINUS):
        negative = buf[p] == MINUS
        p += 1
    if p == e or e - p > LONGEST_ID:
        return False, 0
    value = 0
    for q in range(p, e):
        c = buf[q]
        if not ZERO <= c <= NINE:
            return False, 0
        value = value * 10 + (int(c) - ZERO)
    return True, -value if negative else value


# A call of its own, not compiled into the tokenizer's loop: inlined at its two places there
# it took twice as long to compile (28 s against 14) for 3% less time tokenizing.
@njit
def _parse_float(buf, s, e):
    """``(status, value)`` of a number token, as Python's float() reads it: ENTRY_OK where the
    value is certain to be float()'s (a sign, digits with a point, an exponent, up to 19
    significant digits and a power of ten within 22: one correctly rounded operation; inf,
    infinity, nan), ENTRY_BAD where float() would refuse the token, ENTRY_SLOW otherwise
    (more digits, underscores, other characters float() may take) for float() itself."""
    p = s
    negative = False
    if p < e and (buf[p] == PLUS or buf[p] == MINUS):
        negative = buf[p] == MINUS
        p += 1
    if p == e:
        return ENTRY_BAD, 0.0
    sign = -1.0 if negative else 1.0
    c = _lower(buf[p])
    if c == 105 or c == 110:  # i, n
        if _word_is(buf, p, e, _W_INF) or _word_is(buf, p, e, _W_INFINITY):
            return ENTRY_OK, sign * np.inf
        if _word_is(buf, p, e, _W_NAN):
            return ENTRY_OK, np.nan
        return ENTRY_BAD, 0.0
    mantissa = 0
    digits = 0
    exponent = 0
    seen = False
    while p < e and ZERO <= buf[p] <= NINE:
        seen = True
        if mantissa or buf[p] != ZERO:
            if digits == 19:
                return ENTRY_SLOW, 0.0
            mantissa = mantissa * 10 + (int(buf[p]) - ZERO)
            digits += 1
        p += 1
    if p < e and buf[p] == DOT:
        p += 1
        while p < e and ZERO <= buf[p] <= NINE:
            seen = True
            if mantissa or buf[p] != ZERO:
                if digits == 19:
                    return ENTRY_SLOW, 0.0
                mantissa = mantissa * 10 + (int(buf[p]) - ZERO)
                digits += 1
            exponent -= 1
            p += 1
    if not seen:
        return (ENTRY_SLOW if p < e and (buf[p] == UNDERSCORE or buf[p] >= 128) else ENTRY_BAD), 0.0
    if p < e and _lower(buf[p]) == 101:  # e
        p += 1
        exp_negative = False
        if p < e and (buf[p] == PLUS or buf[p] == MINUS):
            exp_negative = buf[p] == MINUS
            p += 1
        if p == e:
            return ENTRY_BAD, 0.0
        given = 0
        while p < e and ZERO <= buf[p] <= NINE:
            if given < 100000:
                given = given * 10 + (int(buf[p]) - ZERO)
            p += 1
        exponent += -given if exp_negative else given
    if p < e:
        return (ENTRY_SLOW if buf[p] == UNDERSCORE or buf[p] >= 128 else ENTRY_BAD), 0.0
    if mantissa == 0:
        return ENTRY_OK, sign * 0.0
    if mantissa > 2**53 or exponent > 22 or exponent < -22:
        return ENTRY_SLOW, 0.0
    if exponent >= 0:
        return ENTRY_OK, sign * (float(mantissa) * _POWERS[exponent])
    return ENTRY_OK, sign * (float(mantissa) / _POWERS[-exponent])


@njit
def _is_number(buf, s, e):
    """What the periods rows must be: ``[-+]?(\\d+\\.?\\d*|\\.\\d+)([eE][-+]?\\d+)?``."""
    p = s
    if p < e and (buf[p] == PLUS or buf[p] == MINUS):
        p += 1
    before = 0
    while p < e and ZERO <= buf[p] <= NINE:
        p += 1
        before += 1
    after = 0
    if p < e and buf[p] == DOT:
        p += 1
        while p < e and ZERO <= buf[p] <= NINE:
            p += 1
            after += 1
    if before == 0 and after == 0:
        return False
    if p < e and _lower(buf[p]) == 101:
        p += 1
        if p < e and (buf[p] == PLUS or buf[p] == MINUS):
            p += 1
        if p == e:
            return False
        while p < e and ZERO <= buf[p] <= NINE:
            p += 1
    return p == e
