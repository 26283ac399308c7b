"""Adjacency text parsed for a whole chunk at once: its plain lines split into id and faces
spans, and the faces fields (``1 2 3;0 4 5 2;...``) into neighbour lists."""

import numpy as np

from grainclass._numba import njit

SPACE, TAB, SEMICOLON, ZERO, NINE = 32, 9, 59, 48, 57
NEWLINE, RETURN, HASH = 10, 13, 35
LARGEST = 2**31 - 1


@njit
def _parse_faces(buf, starts, ends, n_faces, degrees, neighbors):
    """Parse each field ``buf[starts[g]:ends[g]]`` into faces of neighbour indices.

    Fills ``n_faces[g]``, then per face its degree and neighbours (sized for the worst case,
    ``len(buf)``); returns ``(faces, entries, bad)`` with ``bad[g]`` True for a field with a
    character other than digits, blanks and ``;`` or with an empty face (a trailing ``;`` is
    allowed) or with an index past int32: those get no faces, and the caller reads them again
    for the message.
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
                value = value * 10 + (c - ZERO)
                in_number = True
                if value > LARGEST:
                    bad[g] = True
                    break
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


@njit
def _blank(c):
    """True for the ASCII characters Python's str.strip takes away (\\t-\\r, \\x1c-\\x1f, space)."""
    return (9 <= c <= 13) | (28 <= c <= 32)


@njit
def _plain_lines(buf, id_starts, id_ends, faces_starts, faces_ends):
    """Split ``buf``, whole lines of text, into plain grain lines, ``id<TAB>faces``: for line g,
    the span of its id, stripped as ``str.strip`` strips, and of its faces field, up to the
    line's end less trailing CR and LF. Returns the number of lines, or -1 as soon as a line is
    not plain (a byte outside ASCII, no tab or two, an empty id or one starting with ``#``,
    which makes the line a comment): the caller then reads the lines one by one.
    """
    size = buf.shape[0]
    g = 0
    p = 0
    while p < size:
        start, tab = p, -1
        while p < size and buf[p] != NEWLINE:
            c = buf[p]
            if c >= 128 or (c == TAB and tab >= 0):
                return -1
            if c == TAB:
                tab = p
            p += 1
        end = p
        p += 1
        while end > start and buf[end - 1] == RETURN:
            end -= 1
        if tab < 0 or tab >= end:
            return -1
        a, b = start, tab
        while a < b and _blank(buf[a]):
            a += 1
        while b > a and _blank(buf[b - 1]):
            b -= 1
        if a == b or buf[a] == HASH:
            return -1
        id_starts[g], id_ends[g] = a, b
        faces_starts[g], faces_ends[g] = tab + 1, end
        g += 1
    return g
