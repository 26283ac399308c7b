"""The faces field of adjacency text (``1 2 3;0 4 5 2;...``), parsed for a whole chunk at once."""

import numpy as np

from grainclass._numba import njit

SPACE, TAB, SEMICOLON, ZERO, NINE = 32, 9, 59, 48, 57
LARGEST = 2**31 - 1


@njit
def _parse_faces(buf, starts, ends, n_faces, degrees, neighbors):
    """Parse each field ``buf[starts[g]:ends[g]]`` into faces of neighbour indices.

    Fills ``n_faces[g]``, then per face its degree and neighbours (sized for the worst case,
    ``len(buf)``); returns ``(faces, entries, bad)`` with ``bad[g]`` True for a field with a
    character other than digits, blanks and ``;`` or with an empty face (a trailing ``;`` is
    allowed): those get no faces, and the caller reads them again for the message.
    """
    n = starts.shape[0]
    bad = np.zeros(n, np.bool_)
    f = 0
    m = 0
    for g in range(n):
        f0, m0 = f, m
        value, in_number, degree = 0, False, 0
        for p in range(starts[g], ends[g] + 1):
            c = (
                int(buf[p]) if p < ends[g] else SEMICOLON
            )  # the end closes a face; int(): no uint8 wrap
            if ZERO <= c <= NINE:
                # Clamped: an index past int32 is out of range for any grain, as validation says.
                value = min(value * 10 + (c - ZERO), LARGEST)
                in_number = True
                continue
            if in_number:
                neighbors[m] = value
                m += 1
                degree += 1
                value, in_number = 0, False
            if c == SEMICOLON:
                if degree > 0:
                    degrees[f] = degree
                    f += 1
                elif p < ends[g] or f == f0:  # an empty face, or no face at all
                    bad[g] = True
                    break
                degree = 0
            elif c != SPACE and c != TAB:
                bad[g] = True
                break
        if bad[g]:
            f, m = f0, m0
        n_faces[g] = f - f0
    return f, m, bad
