"""Numbered lines to entries: a vertex's coordinates, an edge's ends and marks, a facet's or a
body's list of signed ids, into the rows of :class:`Entries`.

The tokenizer hands each function the line's tokens (:class:`~.lexing.LineTokens`) and the
entry's row ``n``; numbers the kernel leaves to Python's float() are noted in
:class:`SlowNumbers`.
"""

from typing import NamedTuple

import numpy as np

from grainclass._kernels.evolver.codes import ENTRY_BAD, ENTRY_SLOW, SLOW_VOLUME
from grainclass._kernels.evolver.lexing import MINUS, PLUS, STAR, UNDERSCORE, _lower, _word_is
from grainclass._kernels.evolver.numbers import _is_decimal, _parse_float, _parse_int
from grainclass._numba import njit, njit_leaf

_W_VOLUME = np.frombuffer(b"volume", np.uint8)


class Entries(NamedTuple):
    """The entries of all files in order, one per numbered line, and the ids that facets and
    bodies list."""

    kind: np.ndarray
    """int8[n]: VERTEX, EDGE, FACET or BODY"""
    id: np.ndarray
    """int64[n]: the number the line starts with"""
    line: np.ndarray
    """int64[n]: its line in the file (from 1)"""
    status: np.ndarray
    """int8[n]: ENTRY_OK, ENTRY_BAD or ENTRY_SLOW"""
    first: np.ndarray
    """int64[n]: an edge's tail id; where a facet's or body's ids start in ``ids``"""
    last: np.ndarray
    """int64[n]: an edge's head id; where a facet's or body's ids end"""
    xyz: np.ndarray
    """float64[n, 3]: a vertex's coordinates; a body's volume in column 0 (nan: none)"""
    wraps: np.ndarray
    """int8[n, 3]: an edge's wrap marks, -1, 0 or 1"""
    flag: np.ndarray
    """int8[n]: an edge on a triple line; a body that gives its volume"""
    ids: np.ndarray
    """int64[m]: the signed ids of facets' edges and bodies' facets"""


class SlowNumbers(NamedTuple):
    """Numbers left to Python's float(), each a token ``buf[start:end]``."""

    entry: np.ndarray
    """int64[k]: the entry (a file, for a period) the number belongs to"""
    slot: np.ndarray
    """int8[k]: where it goes: a coordinate 0-2, SLOW_VOLUME, SLOW_PERIOD + 0-8"""
    start: np.ndarray
    """int64[k]"""
    end: np.ndarray
    """int64[k]"""
    count: np.ndarray
    """int64[1]: how many there are"""


class TripleMarker(NamedTuple):
    """The lower-case words that mark a triple edge (``color``, ``red``), one after another."""

    letters: np.ndarray
    """uint8[:]"""
    ends: np.ndarray
    """int64[words]: where each word ends in ``letters``"""


@njit(inline="always")
def _new_entries(n, m):
    """Room for ``n`` entries and ``m`` listed ids."""
    return Entries(
        np.empty(n, np.int8),
        np.empty(n, np.int64),
        np.empty(n, np.int64),
        np.empty(n, np.int8),
        np.empty(n, np.int64),
        np.empty(n, np.int64),
        np.empty((n, 3), np.float64),
        np.zeros((n, 3), np.int8),
        np.zeros(n, np.int8),
        np.empty(m, np.int64),
    )


@njit(inline="always")
def _first_entries(entries, n, m):
    """The first ``n`` entries and ``m`` ids."""
    return Entries(
        entries.kind[:n],
        entries.id[:n],
        entries.line[:n],
        entries.status[:n],
        entries.first[:n],
        entries.last[:n],
        entries.xyz[:n],
        entries.wraps[:n],
        entries.flag[:n],
        entries.ids[:m],
    )


@njit(inline="always")
def _new_slow_numbers(n):
    return SlowNumbers(
        np.empty(n, np.int64),
        np.empty(n, np.int8),
        np.empty(n, np.int64),
        np.empty(n, np.int64),
        np.zeros(1, np.int64),
    )


@njit(inline="always")
def _noted(slow):
    """The slow numbers noted so far."""
    k = slow.count[0]
    return SlowNumbers(slow.entry[:k], slow.slot[:k], slow.start[:k], slow.end[:k], slow.count)


@njit
def _slow_number(slow, entry, slot, s, e):
    """Note a number left to Python's float(): token ``buf[s:e]``, for ``slot`` of ``entry``
    (``slow``: a :class:`SlowNumbers`' arrays, in its order)."""
    entry_of, slot_of, start, end, count = slow
    k = count[0]
    entry_of[k], slot_of[k], start[k], end[k] = entry, slot, s, e
    count[0] = k + 1


@njit_leaf
def _vertex_entry(buf, starts, ends, ntok, n, status, xyz, slow):
    """A vertex line's coordinates (tokens 1 to 3) into ``xyz[n]``."""
    if ntok < 4:
        status[n] = ENTRY_BAD
        return
    for k in range(3):
        s, e = starts[k + 1], ends[k + 1]
        code, value = _parse_float(buf, s, e)
        xyz[n, k] = value
        if code == ENTRY_BAD:
            status[n] = ENTRY_BAD
        elif code == ENTRY_SLOW and status[n] != ENTRY_BAD:
            status[n] = ENTRY_SLOW
            _slow_number(slow, n, k, s, e)


@njit_leaf
def _edge_entry(buf, starts, ends, ntok, n, periodic, marker, status, first, last, wraps, flag):
    """An edge line: tail and head ids into ``first`` and ``last``, three wrap marks (a
    periodic file's), the triple-line mark (``marker``'s words among the attributes)."""
    ok_t, tail = _parse_int(buf, starts[1], ends[1]) if ntok > 1 else (False, 0)
    ok_h, head = _parse_int(buf, starts[2], ends[2]) if ntok > 2 else (False, 0)
    first[n], last[n] = tail, head
    wraps[n, 0] = wraps[n, 1] = wraps[n, 2] = 0
    if not (ok_t and ok_h):
        status[n] = ENTRY_BAD
    elif periodic and ntok >= 6 and _wrap_mark(buf, starts[3], ends[3]) < 2:
        for k in range(3):
            mark = _wrap_mark(buf, starts[3 + k], ends[3 + k])
            if mark == 2:
                status[n] = ENTRY_BAD
            else:
                wraps[n, k] = mark
    words = marker[1].shape[0]
    if ntok > 4 and words > 0:
        for t in range(3, ntok - words + 1):
            if _words_at(buf, starts, ends, t, marker):
                flag[n] = 1
                break


@njit_leaf
def _list_entry(buf, starts, ends, ntok, n, body, status, first, last, xyz, flag, ids, m, slow):
    """A facet's line, or a body's if ``body``: its signed ids into ``ids[m:]`` (three or more
    for a facet, one or more for a body), and a body's ``volume``. Returns ``m`` after the
    ids."""
    first[n] = m
    ok, m = _leading_ids(buf, starts, ends, ntok, ids, m)
    last[n] = m
    if not ok or m - first[n] < (1 if body else 3):
        status[n] = ENTRY_BAD
    if not body:
        return m
    xyz[n, 0] = np.nan
    for t in range(1, ntok):
        if _word_is(buf, starts[t], ends[t], _W_VOLUME):
            if t + 1 >= ntok:
                status[n] = ENTRY_BAD
                break
            code, value = _parse_float(buf, starts[t + 1], ends[t + 1])
            if code == ENTRY_BAD:
                # An expression (`volume 2*pi*rad^3/3`), which Surface Evolver evaluates and
                # grainclass does not: the volume is computed from the geometry instead.
                break
            xyz[n, 0] = value
            flag[n] = 1
            if code == ENTRY_SLOW and status[n] != ENTRY_BAD:
                status[n] = ENTRY_SLOW
                # An int64, as at the other calls: a literal slot would compile _slow_number
                # once more.
                _slow_number(slow, n, np.int64(SLOW_VOLUME), starts[t + 1], ends[t + 1])
            break
    return m


@njit_leaf
def _leading_ids(buf, starts, ends, ntok, ids, m):
    """The signed ids at the start of tokens 1.. of an entry into ``ids`` from ``m``: ``(ok,
    m after them)``. What follows them must be an attribute's name; a token that is neither
    (``13.0``, ``+``, ``x7`` is a name) makes the line unreadable."""
    for t in range(1, ntok):
        s, e = starts[t], ends[t]
        ok, value = _parse_int(buf, s, e)
        if ok:
            ids[m] = value
            m += 1
            continue
        p = s
        while p < e and (buf[p] == PLUS or buf[p] == MINUS):
            p += 1
        if _is_decimal(buf, p, e):
            return False, m  # a damaged or overlong id
        c = buf[s]
        if (65 <= c <= 90) or (97 <= c <= 122) or c == UNDERSCORE or c >= 128:
            return True, m  # attributes follow the ids
        return False, m
    return True, m


@njit_leaf
def _wrap_mark(buf, s, e):
    """A wrap mark's value: ``*`` 0, ``+`` 1, ``-`` -1; 2 for any other token."""
    if e - s != 1:
        return 2
    c = buf[s]
    if c == STAR:
        return 0
    if c == PLUS:
        return 1
    if c == MINUS:
        return -1
    return 2


@njit_leaf
def _words_at(buf, starts, ends, t, marker):
    """Whether tokens ``t, t + 1, ...`` are the marker's words, in any case (``marker``: a
    :class:`TripleMarker`'s arrays)."""
    letters, word_ends = marker
    begin = 0
    for w in range(word_ends.shape[0]):
        s, e = starts[t + w], ends[t + w]
        if e - s != word_ends[w] - begin:
            return False
        for i in range(e - s):
            if _lower(buf[s + i]) != letters[begin + i]:
                return False
        begin = word_ends[w]
    return True
