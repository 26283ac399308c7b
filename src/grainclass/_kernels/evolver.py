"""Surface Evolver datafiles read over their bytes: :func:`_tokenize` splits files into numbered
entries (vertices, edges, facets, bodies), :func:`_assemble` turns each body into a grain.

No Python object is made per vertex, edge or facet; what the kernels cannot settle they return
as codes, which ``readers/evolver.py`` turns into messages. The rules are those of the reader's
docstring; the kernels' docstrings say how they are carried out.

A body's surface is built from *patches*, one per entry of its list of facets: in a periodic
file a body may list a facet twice, once each way, where the cell meets its own image across
it. Each patch sits at a lattice translation of its facet's own frame (the facet unwrapped
along its edges' wrap marks); the translations follow from the patches' common edges, which
pair the patches' edge uses off, and the cell's corners are (vertex, translation) pairs.
"""

import math

import numpy as np

from grainclass._numba import at, njit, njit_leaf

# Entry kinds, as the sections of a datafile: vertices, edges, facets (or faces), bodies.
VERTEX, EDGE, FACET, BODY = 0, 1, 2, 3

# Entry status: read, not readable, or a number the kernel leaves to Python's float().
ENTRY_OK, ENTRY_BAD, ENTRY_SLOW = 0, 1, 2

# Where a slow number goes: a vertex's coordinate 0-2, a body's volume, a file's period 0-8.
SLOW_VOLUME = 3
SLOW_PERIOD = 4

# File status from the tokenizer (the file is one invalid row unless FILE_OK).
FILE_OK = 0
FILE_LONG_ID = 1  # aux: entry kind, token start, token end
FILE_PERIODS = 2  # periods without three rows of three numbers
FILE_2D = 3  # space_dimension 2 (aux0: 1 for a string model)
FILE_STRING = 4  # string model in 3-space
FILE_SPACE = 5  # space_dimension other than 2 or 3 (aux0)
FILE_SIMPLEX = 6  # simplex_representation: facets given by vertices
FILE_SYMMETRY = 7  # symmetry_group: a quotient space

# Grain codes from the assembly; params in the order the reader's messages use them.
GRAIN_OK = 0
GRAIN_BODY_LINE = 1  # the body's line cannot be read
GRAIN_UNDEFINED = 2  # (kind, id, user kind, user id, line of an unreadable definition or 0)
GRAIN_TWICE = 3  # (facet id,): a non-periodic body lists a facet twice
GRAIN_TWICE_SAME = 4  # (facet id, times, sign): a periodic body lists it twice one way, or more
GRAIN_FACET_OPEN = 5  # (facet id, edge id): a facet's edges do not join up
GRAIN_FACET_WRAPS = 6  # (facet id,): a facet's wrap marks do not add up to nothing
GRAIN_NOT_CLOSED = 7  # (edge id, uses)
GRAIN_ORIENTATION = 8  # (facet id, facet id, edge id): both run along the edge the same way
GRAIN_UNPAIRED = 9  # (edge id, uses): the patches around an edge do not pair off
GRAIN_AROUND = 10  # (edge id,): the surface does not close once unwrapped
GRAIN_EULER = 11  # (V - E + F,)
GRAIN_PIECES = 12
GRAIN_NO_TRIPLE = 13
GRAIN_NOT_DISC = 14  # (face,)
GRAIN_NO_BODIES = 15  # (facets line or 0, kind of the first unreadable entry or -1, its line)
GRAIN_FILE = 16  # the file's status is not FILE_OK

# Users of an undefined id, for GRAIN_UNDEFINED.
USER_LIST, USER_FACET, USER_EDGE = 0, 1, 2

SPACE, TAB, NEWLINE, RETURN, HASH, SLASH, STAR, BACKSLASH = 32, 9, 10, 13, 35, 47, 42, 92
PLUS, MINUS, DOT, UNDERSCORE, ZERO, NINE, COLON = 43, 45, 46, 95, 48, 57, 58
LONGEST_ID = 18  # decimal digits: past them an id does not fit int64

_W_VERTICES = np.frombuffer(b"vertices", np.uint8)
_W_EDGES = np.frombuffer(b"edges", np.uint8)
_W_FACES = np.frombuffer(b"faces", np.uint8)
_W_FACETS = np.frombuffer(b"facets", np.uint8)
_W_BODIES = np.frombuffer(b"bodies", np.uint8)
_W_PERIODS = np.frombuffer(b"periods", np.uint8)
_W_READ = np.frombuffer(b"read", np.uint8)
_W_VOLUME = np.frombuffer(b"volume", np.uint8)
_W_STRING = np.frombuffer(b"string", np.uint8)
_W_SPACE_DIMENSION = np.frombuffer(b"space_dimension", np.uint8)
_W_SURFACE_DIMENSION = np.frombuffer(b"surface_dimension", np.uint8)
_W_SIMPLEX = np.frombuffer(b"simplex_representation", np.uint8)
_W_SYMMETRY = np.frombuffer(b"symmetry_group", np.uint8)
_W_INF = np.frombuffer(b"inf", np.uint8)
_W_INFINITY = np.frombuffer(b"infinity", np.uint8)
_W_NAN = np.frombuffer(b"nan", np.uint8)
_POWERS = np.array([10.0**k for k in range(23)])  # exact in float64


# What each byte is to the lexer: part of a token (``#`` too, but at the start of a line, where
# it makes the line a directive), a byte that may start a comment or join two lines, a blank
# between tokens or a line break (as str.split() and str.splitlines() read ASCII).
C_TOKEN, C_HASH, C_SLASH, C_BACKSLASH, C_BLANK, C_BREAK = 0, 1, 2, 3, 4, 5
_CLASS = np.zeros(256, np.uint8)
_CLASS[[SPACE, TAB, 31]] = C_BLANK
_CLASS[[NEWLINE, 11, 12, RETURN, 28, 29, 30]] = C_BREAK
_CLASS[SLASH], _CLASS[BACKSLASH], _CLASS[HASH] = C_SLASH, C_BACKSLASH, C_HASH


@njit_leaf
def _lower(c):
    return c + 32 if 65 <= c <= 90 else c


@njit_leaf
def _word_is(buf, s, e, word):
    """Whether ``buf[s:e]`` is ``word`` (lower case) in any case."""
    if e - s != word.shape[0]:
        return False
    i = 0
    while i < e - s and _lower(buf[s + i]) == word[i]:
        i += 1
    return i == e - s


@njit_leaf
def _after_break(buf, p, end):
    """The position after the line break at ``p`` (\\r\\n is one break)."""
    if buf[p] == RETURN and p + 1 < end and buf[p + 1] == NEWLINE:
        return p + 2
    return p + 1


@njit_leaf
def _line_end(buf, p, end):
    """The first line break from ``p`` on (or ``end``)."""
    while p < end and _CLASS[buf[p]] != C_BREAK:
        p += 1
    return p


@njit_leaf
def _continues(buf, p, end):
    """Whether a backslash before ``p`` continues its line: only blanks, or a // comment, follow
    it on the line."""
    while p < end and _CLASS[buf[p]] == C_BLANK:
        p += 1
    if p >= end or _CLASS[buf[p]] == C_BREAK:
        return True
    return buf[p] == SLASH and p + 1 < end and buf[p + 1] == SLASH


@njit_leaf
def _comment_at(buf, p, end, last_close):
    """Whether a comment starts at ``p``: ``//``, or a ``/*`` that closes."""
    if p + 1 >= end or buf[p] != SLASH:
        return False
    return buf[p + 1] == SLASH or (buf[p + 1] == STAR and p + 2 <= last_close)


@njit_leaf
def _special(buf, p, end, last_close):
    """Whether the byte at ``p`` is not part of a token: a blank, a line break, a comment's
    start, or a backslash that joins its line to the next."""
    k = _CLASS[buf[p]]
    if k <= C_HASH:
        return False
    if k == C_SLASH:
        return _comment_at(buf, p, end, last_close)
    if k == C_BACKSLASH:
        return _continues(buf, p + 1, end)
    return True


@njit_leaf
def _lex_line(buf, p, end, last_close, tok_s, tok_e, line):
    """The tokens of the logical line at ``p`` into ``tok_s``/``tok_e``: ``(p after it, tokens,
    its first line number, at end of file)``; ``line[0]`` counts physical lines.

    Comments are left out: ``/* ... */`` (one that closes: its ``*/`` is at ``last_close`` or
    before), whose line breaks still end lines; ``//`` to the end of the line; a line that
    starts with ``#`` (a directive). A comment separates tokens. A backslash ending a line joins
    the next one to it.
    """
    ntok = 0
    first = line[0]
    line_start = True
    while p < end:
        k = _CLASS[buf[at(p)]]
        if k == C_BLANK:
            p += 1
        elif k == C_BREAK:
            line[0] += 1
            return _after_break(buf, p, end), ntok, first, False
        elif k == C_HASH and line_start:  # a directive
            p = _line_end(buf, p, end)
        elif k <= C_HASH or not _special(buf, p, end, last_close):
            start = p
            p += 1
            while p < end:
                k = _CLASS[buf[at(p)]]
                if k >= C_BLANK or (k >= C_SLASH and _special(buf, p, end, last_close)):
                    break
                p += 1
            tok_s[ntok] = start
            tok_e[ntok] = p
            ntok += 1
        elif k == C_SLASH and buf[p + 1] == SLASH:  # a // comment
            p = _line_end(buf, p, end)
        elif k == C_SLASH:  # a /* ... */ comment
            q = p + 2
            breaks = 0
            while not (buf[q] == STAR and buf[q + 1] == SLASH):
                if _CLASS[buf[q]] == C_BREAK:
                    q = _after_break(buf, q, end)
                    breaks += 1
                else:
                    q += 1
            p = q + 2
            if breaks:  # the comment's line breaks end the line
                line[0] += breaks
                return p, ntok, first, False
        else:  # a backslash that joins the next line to this one
            p = _line_end(buf, p, end)
            if p < end:
                p = _after_break(buf, p, end)
                line[0] += 1
                line_start = True
                continue
        line_start = False
    return p, ntok, first, True


@njit_leaf
def _last_close(buf, start, end):
    """Where the last ``*/`` of ``buf[start:end]`` starts (``start - 1`` if none)."""
    for p in range(end - 2, start - 1, -1):
        if buf[p] == STAR and buf[p + 1] == SLASH:
            return p
    return start - 1


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


@njit_leaf
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


@njit_leaf
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


@njit_leaf
def _leading_ids(buf, tok_s, tok_e, ntok, ids, m):
    """The signed ids at the start of tokens 1.. of an entry into ``ids`` from ``m``: ``(ok,
    m after them)``. What follows them must be an attribute's name; a token that is neither
    (``13.0``, ``+``, ``x7`` is a name) makes the line unreadable."""
    for t in range(1, ntok):
        s, e = tok_s[t], tok_e[t]
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
def _count_breaks(buf, start, end):
    n = 0
    for p in range(start, end):
        if _CLASS[buf[p]] == C_BREAK:
            n += 1
    return n


@njit
def _tokenize(buf, file_starts, marker, marker_ends):
    """Split each file ``buf[file_starts[i]:file_starts[i + 1]]`` into entries.

    ``marker`` holds the lower-case words that mark a triple edge (``color``, ``red``),
    ``marker_ends`` where each ends. Returns, for the entries of all files in order: kind,
    id, line, status, ``a``/``b`` (an edge's tail and head ids; a facet's or body's ids
    ``ids[a:b]``), ``xyz`` (a vertex's coordinates; a body's volume in ``xyz[:, 0]``),
    ``wraps`` (an edge's three wrap marks, -1, 0 or 1), ``flag`` (an edge on a triple line; a
    body with a volume); ``ids``; the slow numbers (entry or file, where it goes, token span);
    and per file: status, the line it concerns, three more numbers (see the FILE_ codes),
    periodic, its periods, its entries' range and the line of its facets section (0 if none).
    """
    n_files = file_starts.shape[0] - 1
    size = file_starts[-1] - file_starts[0]
    lines_bound = _count_breaks(buf, file_starts[0], file_starts[-1]) + n_files
    tokens_bound = size // 2 + n_files + 1
    kind = np.empty(lines_bound, np.int8)
    ident = np.empty(lines_bound, np.int64)
    line_of = np.empty(lines_bound, np.int64)
    status = np.empty(lines_bound, np.int8)
    first = np.empty(lines_bound, np.int64)
    last = np.empty(lines_bound, np.int64)
    xyz = np.empty((lines_bound, 3), np.float64)
    wraps = np.zeros((lines_bound, 3), np.int8)
    flag = np.zeros(lines_bound, np.int8)
    ids = np.empty(tokens_bound, np.int64)
    slow_entry = np.empty(4 * lines_bound + 9 * n_files, np.int64)
    slow_slot = np.empty(4 * lines_bound + 9 * n_files, np.int8)
    slow_s = np.empty(4 * lines_bound + 9 * n_files, np.int64)
    slow_e = np.empty(4 * lines_bound + 9 * n_files, np.int64)
    slow = (slow_entry, slow_slot, slow_s, slow_e)
    file_status = np.zeros(n_files, np.int8)
    file_line = np.zeros(n_files, np.int64)
    file_aux = np.zeros((n_files, 3), np.int64)
    periodic = np.zeros(n_files, np.bool_)
    periods = np.zeros((n_files, 3, 3), np.float64)
    entry_start = np.zeros(n_files, np.int64)
    entry_end = np.zeros(n_files, np.int64)
    facets_line = np.zeros(n_files, np.int64)
    longest = 0
    for f in range(n_files):
        longest = max(longest, file_starts[f + 1] - file_starts[f])
    tok_s = np.empty(longest // 2 + 2, np.int64)
    tok_e = np.empty(longest // 2 + 2, np.int64)
    line = np.ones(1, np.int64)
    n = 0
    m = 0
    n_slow = 0
    for f in range(n_files):
        start, end = file_starts[f], file_starts[f + 1]
        if end - start >= 3 and buf[start] == 0xEF and buf[start + 1] == 0xBB:
            start += 3 if buf[start + 2] == 0xBF else 0
        last_close = _last_close(buf, start, end)
        line[0] = 1
        entry_start[f] = n
        p = start
        section = -1
        period_lines = 0  # rows of periods still to read
        period_values = 0
        period_ok = True
        period_line = 0
        header_checked = False
        string_line = 0
        space_dim, space_line = 3, 0
        surface_dim, surface_line = 2, 0
        simplex_line = 0
        symmetry_line = 0
        eof = False
        while not eof:
            p, ntok, number, eof = _lex_line(buf, p, end, last_close, tok_s, tok_e, line)
            if ntok == 0:
                if eof and period_lines > 0:
                    period_lines = 0
                    if period_values < 9 or not period_ok:
                        file_status[f], file_line[f] = FILE_PERIODS, period_line
                        break
                continue
            if period_lines > 0:
                for t in range(ntok):
                    if period_values < 9:
                        s, e = tok_s[t], tok_e[t]
                        if not _is_number(buf, s, e):
                            period_ok = False
                        else:
                            code, value = _parse_float(buf, s, e)
                            if code == ENTRY_SLOW:
                                slot = SLOW_PERIOD + period_values
                                n_slow = _slow_number(slow, n_slow, f, slot, s, e)
                            periods[f, period_values // 3, period_values % 3] = value
                        period_values += 1
                period_lines -= 1
                if period_lines == 0 or eof:
                    period_lines = 0
                    if period_values < 9 or not period_ok:
                        file_status[f], file_line[f] = FILE_PERIODS, period_line
                        break
                    periodic[f] = True
                continue
            s0, e0 = tok_s[0], tok_e[0]
            if section >= 0 and _is_decimal(buf, s0, e0):
                if e0 - s0 > LONGEST_ID:
                    file_status[f], file_line[f] = FILE_LONG_ID, number
                    file_aux[f, 0], file_aux[f, 1], file_aux[f, 2] = section, s0, e0
                    break
                _, value = _parse_int(buf, s0, e0)
                kind[n], ident[n], line_of[n], status[n] = section, value, number, ENTRY_OK
                flag[n] = 0
                if section == VERTEX:
                    n_slow = _vertex_entry(buf, tok_s, tok_e, ntok, n, status, xyz, slow, n_slow)
                elif section == EDGE:
                    _edge_entry(
                        buf,
                        tok_s,
                        tok_e,
                        ntok,
                        n,
                        periodic[f],
                        marker,
                        marker_ends,
                        status,
                        first,
                        last,
                        wraps,
                        flag,
                    )
                else:
                    m, n_slow = _list_entry(
                        buf,
                        tok_s,
                        tok_e,
                        ntok,
                        n,
                        section,
                        ids,
                        m,
                        status,
                        first,
                        last,
                        xyz,
                        flag,
                        slow,
                        n_slow,
                    )
                n += 1
                continue
            # A keyword line. Surface Evolver takes a section's keyword with a colon too
            # (`vertices:`, as in its own sphere.fe).
            if e0 - s0 > 1 and buf[e0 - 1] == COLON:
                e0 -= 1
            is_section = (
                _word_is(buf, s0, e0, _W_VERTICES)
                or _word_is(buf, s0, e0, _W_EDGES)
                or _word_is(buf, s0, e0, _W_FACES)
                or _word_is(buf, s0, e0, _W_FACETS)
                or _word_is(buf, s0, e0, _W_BODIES)
            )
            is_periods = _word_is(buf, s0, e0, _W_PERIODS)
            if (is_section or is_periods) and not header_checked:
                header_checked = True
                code, where, aux = _header_status(
                    string_line,
                    space_dim,
                    space_line,
                    surface_dim,
                    surface_line,
                    simplex_line,
                    symmetry_line,
                )
                if code != FILE_OK:
                    file_status[f], file_line[f], file_aux[f, 0] = code, where, aux
                    break
            if is_periods:
                period_lines, period_values, period_ok, period_line = 3, 0, True, number
            elif is_section:
                if _word_is(buf, s0, e0, _W_VERTICES):
                    section = VERTEX
                elif _word_is(buf, s0, e0, _W_EDGES):
                    section = EDGE
                elif _word_is(buf, s0, e0, _W_BODIES):
                    section = BODY
                else:
                    section = FACET
                    if facets_line[f] == 0:
                        facets_line[f] = number
            elif _word_is(buf, s0, e0, _W_READ):
                break
            elif not header_checked:
                if _word_is(buf, s0, e0, _W_STRING):
                    string_line = number
                elif _word_is(buf, s0, e0, _W_SIMPLEX):
                    simplex_line = number
                elif _word_is(buf, s0, e0, _W_SYMMETRY):
                    symmetry_line = number
                elif ntok > 1 and _word_is(buf, s0, e0, _W_SPACE_DIMENSION):
                    ok, value = _parse_int(buf, tok_s[1], tok_e[1])
                    if ok:
                        space_dim, space_line = value, number
                elif ntok > 1 and _word_is(buf, s0, e0, _W_SURFACE_DIMENSION):
                    ok, value = _parse_int(buf, tok_s[1], tok_e[1])
                    if ok:
                        surface_dim, surface_line = value, number
        entry_end[f] = n
    return (
        kind[:n],
        ident[:n],
        line_of[:n],
        status[:n],
        first[:n],
        last[:n],
        xyz[:n],
        wraps[:n],
        flag[:n],
        ids[:m],
        slow_entry[:n_slow],
        slow_slot[:n_slow],
        slow_s[:n_slow],
        slow_e[:n_slow],
        file_status,
        file_line,
        file_aux,
        periodic,
        periods,
        entry_start,
        entry_end,
        facets_line,
    )


@njit_leaf
def _slow_number(slow, n_slow, entry, slot, s, e):
    """Note a number left to Python's float(): token ``buf[s:e]``, for ``slot`` of ``entry``."""
    slow_entry, slow_slot, slow_s, slow_e = slow
    slow_entry[n_slow], slow_slot[n_slow], slow_s[n_slow], slow_e[n_slow] = entry, slot, s, e
    return n_slow + 1


@njit_leaf
def _vertex_entry(buf, tok_s, tok_e, ntok, n, status, xyz, slow, n_slow):
    """A vertex line's coordinates (tokens 1 to 3) into ``xyz[n]``; returns ``n_slow``."""
    if ntok < 4:
        status[n] = ENTRY_BAD
        return n_slow
    for k in range(3):
        code, value = _parse_float(buf, tok_s[k + 1], tok_e[k + 1])
        xyz[n, k] = value
        if code == ENTRY_BAD:
            status[n] = ENTRY_BAD
        elif code == ENTRY_SLOW and status[n] != ENTRY_BAD:
            status[n] = ENTRY_SLOW
            n_slow = _slow_number(slow, n_slow, n, k, tok_s[k + 1], tok_e[k + 1])
    return n_slow


@njit_leaf
def _edge_entry(
    buf, tok_s, tok_e, ntok, n, periodic, marker, marker_ends, status, first, last, wraps, flag
):
    """An edge line: tail and head ids, three wrap marks (a periodic file's), the triple-line
    mark (``marker``'s words among the attributes)."""
    ok_t, tail = _parse_int(buf, tok_s[1], tok_e[1]) if ntok > 1 else (False, 0)
    ok_h, head = _parse_int(buf, tok_s[2], tok_e[2]) if ntok > 2 else (False, 0)
    first[n], last[n] = tail, head
    wraps[n, 0] = wraps[n, 1] = wraps[n, 2] = 0
    if not (ok_t and ok_h):
        status[n] = ENTRY_BAD
    elif periodic and ntok >= 6 and _wrap_mark(buf, tok_s[3], tok_e[3]) < 2:
        for k in range(3):
            mark = _wrap_mark(buf, tok_s[3 + k], tok_e[3 + k])
            if mark == 2:
                status[n] = ENTRY_BAD
            else:
                wraps[n, k] = mark
    words = marker_ends.shape[0]
    if ntok > 4 and words > 0:
        for t in range(3, ntok - words + 1):
            if _words_at(buf, tok_s, tok_e, t, marker, marker_ends):
                flag[n] = 1
                break


@njit_leaf
def _list_entry(
    buf, tok_s, tok_e, ntok, n, section, ids, m, status, first, last, xyz, flag, slow, n_slow
):
    """A facet's or a body's line: its signed ids into ``ids[m:]`` (three or more for a facet,
    one or more for a body), and a body's ``volume``. Returns ``(m, n_slow)``."""
    first[n] = m
    ok, m = _leading_ids(buf, tok_s, tok_e, ntok, ids, m)
    last[n] = m
    if not ok or m - first[n] < (3 if section == FACET else 1):
        status[n] = ENTRY_BAD
    if section != BODY:
        return m, n_slow
    xyz[n, 0] = np.nan
    for t in range(1, ntok):
        if _word_is(buf, tok_s[t], tok_e[t], _W_VOLUME):
            if t + 1 >= ntok:
                status[n] = ENTRY_BAD
                break
            code, value = _parse_float(buf, tok_s[t + 1], tok_e[t + 1])
            if code == ENTRY_BAD:
                # An expression (`volume 2*pi*rad^3/3`), which Surface Evolver evaluates and
                # grainclass does not: the volume is computed from the geometry instead.
                break
            xyz[n, 0] = value
            flag[n] = 1
            if code == ENTRY_SLOW and status[n] != ENTRY_BAD:
                status[n] = ENTRY_SLOW
                n_slow = _slow_number(slow, n_slow, n, SLOW_VOLUME, tok_s[t + 1], tok_e[t + 1])
            break
    return m, n_slow


@njit_leaf
def _header_status(
    string_line, space_dim, space_line, surface_dim, surface_line, simplex_line, symmetry_line
):
    """``(FILE_ code, line, aux)`` of a file's header: FILE_OK for a surface in 3-space."""
    string = string_line > 0 or surface_dim == 1
    if space_dim == 2:
        return FILE_2D, space_line, 1 if string else 0
    if space_dim != 3:
        return FILE_SPACE, space_line, space_dim
    if string:
        return FILE_STRING, string_line if string_line > 0 else surface_line, 0
    if simplex_line > 0:
        return FILE_SIMPLEX, simplex_line, 0
    if surface_dim != 2:
        return FILE_SPACE, surface_line, space_dim
    if symmetry_line > 0:
        return FILE_SYMMETRY, symmetry_line, 0
    return FILE_OK, 0, 0


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
def _words_at(buf, tok_s, tok_e, t, marker, marker_ends):
    """Whether tokens ``t, t + 1, ...`` are the marker's words, in any case."""
    begin = 0
    for w in range(marker_ends.shape[0]):
        s, e = tok_s[t + w], tok_e[t + w]
        if e - s != marker_ends[w] - begin:
            return False
        for i in range(e - s):
            if _lower(buf[s + i]) != marker[begin + i]:
                return False
        begin = marker_ends[w]
    return True


# --- Ids to slots ---------------------------------------------------------------------------


@njit_leaf
def _hash(x, mask):
    h = np.uint64(x) * np.uint64(0x9E3779B97F4A7C15)
    return np.int64((h ^ (h >> np.uint64(31))) & np.uint64(mask))


@njit(no_cpython_wrapper=True)
def _new_map(n, most):
    """An empty map of up to ``n`` ids to slots: ``(keys, slots, count, direct)``. Ids from 0
    to ``most`` (the usual 1, 2, 3, ... of a datafile) go straight to ``direct[id]``, others
    through open addressing in ``keys`` and ``slots``."""
    size = 16
    while size < 2 * n:
        size *= 2
    direct = np.full(most + 1 if 0 <= most <= 4 * n + 64 else 0, -1, np.int64)
    return np.empty(size, np.int64), np.full(size, -1, np.int64), np.zeros(1, np.int64), direct


@njit_leaf
def _slot(table, x, insert):
    """The slot of id ``x`` (slots count up from 0 in the order ids first come), or -1 if it
    has none and ``insert`` is False."""
    keys, slots, count, direct = table
    if 0 <= x < direct.shape[0]:
        if direct[x] < 0 and insert:
            direct[x] = count[0]
            count[0] += 1
        return direct[x]
    mask = keys.shape[0] - 1
    h = _hash(x, mask)
    while slots[h] >= 0:
        if keys[h] == x:
            return slots[h]
        h = (h + 1) & mask
    if not insert:
        return -1
    keys[h], slots[h] = x, count[0]
    count[0] += 1
    return slots[h]


@njit(no_cpython_wrapper=True)
def _slots(ids, extra):
    """A map with a slot for each distinct id of ``ids`` (room for ``extra`` more), and the
    slot of each."""
    most = -1
    for i in range(ids.shape[0]):
        most = max(most, ids[i])
    table = _new_map(ids.shape[0] + extra, most)
    slot = np.empty(ids.shape[0], np.int64)
    for i in range(ids.shape[0]):
        slot[i] = _slot(table, ids[i], True)
    return table, slot


@njit(no_cpython_wrapper=True)
def _slot_entries(rows, slot, n, ident, status, line_of):
    """For ``n`` slots, of which entries ``rows`` fill ``slot``: each slot's id, its readable
    entry (-1: none) and its last unreadable line (0: none)."""
    slot_id = np.empty(n, np.int64)
    entry = np.full(n, -1, np.int64)
    bad = np.zeros(n, np.int64)
    for j in range(rows.shape[0]):
        i = rows[j]
        slot_id[slot[j]] = ident[i]
        if status[i] == ENTRY_OK:
            entry[slot[j]] = i
        else:
            bad[slot[j]] = line_of[i]
    return slot_id, entry, bad


@njit(no_cpython_wrapper=True)
def _reserve(a, need):
    """``a``, or a copy twice as long, so that it holds ``need`` items."""
    if a.shape[0] >= need:
        return a
    b = np.empty(max(need, 2 * a.shape[0]), a.dtype)
    for i in range(a.shape[0]):
        b[i] = a[i]
    return b


# --- Whole files ----------------------------------------------------------------------------


@njit(no_cpython_wrapper=True)
def _rows_by_kind(kind, f0, f1):
    """The entries of each kind among ``f0:f1``, in order: vertices, edges, facets, bodies."""
    counts = np.zeros(4, np.int64)
    for i in range(f0, f1):
        counts[kind[i]] += 1
    rows = (
        np.empty(counts[VERTEX], np.int64),
        np.empty(counts[EDGE], np.int64),
        np.empty(counts[FACET], np.int64),
        np.empty(counts[BODY], np.int64),
    )
    fill = np.zeros(4, np.int64)
    for i in range(f0, f1):
        k = kind[i]
        if k == VERTEX:
            rows[0][fill[0]] = i
        elif k == EDGE:
            rows[1][fill[1]] = i
        elif k == FACET:
            rows[2][fill[2]] = i
        else:
            rows[3][fill[3]] = i
        fill[k] += 1
    return rows


@njit(no_cpython_wrapper=True)
def _file_tables(f0, f1, kind, ident, line_of, status, first, last, wraps, flag, ids):
    """What the bodies of one file (entries ``f0:f1``) need, by slot (one per distinct id):

    vertices: entry of the last readable line (-1), line of the last unreadable one (0), id;
    keys for vertex ids that edges name and no line defines follow the slots;
    edges: entry, unreadable line, tail and head keys; facets: entry, unreadable line, and for
    each of their edge uses (positions ``pos_start[f]:pos_start[f + 1]``): edge slot (-1: not
    defined), sign, dart tail key in the facet's own direction, the tail's translation ``L`` in
    the facet's frame and ``B``, the translation of the edge's own tail; a facet's state (0, or
    1 + the first bad position: an undefined edge; -1 - position: edges that do not join; -1 -
    uses: wraps that do not add up); uses of each edge by facets; bodies in the order of their
    first line: last entry, any unreadable line.
    """
    v_rows, e_rows, f_rows, b_rows = _rows_by_kind(kind, f0, f1)
    # Vertices (room for the ids that edges name and no line defines), edges.
    v_map, v_slot = _slots(ident[v_rows], 2 * e_rows.shape[0])
    nv = v_map[2][0]
    e_map, e_slot = _slots(ident[e_rows], 0)
    ne = e_map[2][0]
    e_id, e_entry, e_bad = _slot_entries(e_rows, e_slot, ne, ident, status, line_of)
    # Edges may name vertices without a line: they get keys past the vertices' slots.
    e_tail = np.full(ne, -1, np.int64)
    e_head = np.full(ne, -1, np.int64)
    for s in range(ne):
        i = e_entry[s]
        if i >= 0:
            e_tail[s] = _slot(v_map, first[i], True)
            e_head[s] = _slot(v_map, last[i], True)
    vk_id, vk_entry, vk_bad = _slot_entries(v_rows, v_slot, v_map[2][0], ident, status, line_of)
    for h in range(v_map[0].shape[0]):
        if v_map[1][h] >= nv:
            vk_id[v_map[1][h]] = v_map[0][h]
    for h in range(v_map[3].shape[0]):
        if v_map[3][h] >= nv:
            vk_id[v_map[3][h]] = h
    e_wrap = np.zeros((ne, 3), np.int64)
    e_triple = np.zeros(ne, np.bool_)
    marked = False
    for s in range(ne):
        i = e_entry[s]
        if i < 0:
            continue
        for k in range(3):
            e_wrap[s, k] = wraps[i, k]
        e_triple[s] = flag[i] != 0
        marked |= e_triple[s]
    # Facets.
    f_map, f_slot = _slots(ident[f_rows], 0)
    nf = f_map[2][0]
    f_id, f_entry, f_bad = _slot_entries(f_rows, f_slot, nf, ident, status, line_of)
    pos_start = np.zeros(nf + 1, np.int64)
    for s in range(nf):
        i = f_entry[s]
        pos_start[s + 1] = pos_start[s] + (last[i] - first[i] if i >= 0 else 0)
    n_pos = pos_start[nf]
    p_facet = np.empty(n_pos, np.int64)
    p_edge = np.full(n_pos, -1, np.int64)
    p_edge_id = np.empty(n_pos, np.int64)
    p_sign = np.empty(n_pos, np.int64)
    p_tail = np.empty(n_pos, np.int64)
    p_L = np.zeros((n_pos, 3), np.int64)
    p_B = np.zeros((n_pos, 3), np.int64)
    f_state = np.zeros(nf, np.int64)
    e_uses = np.zeros(ne, np.int64)
    for s in range(nf):
        i = f_entry[s]
        if i < 0:
            continue
        a = pos_start[s]
        size = pos_start[s + 1] - a
        for k in range(size):
            signed = ids[first[i] + k]
            p_facet[a + k] = s
            p_edge_id[a + k] = abs(signed)
            p_sign[a + k] = -1 if signed < 0 else 1
            es = _slot(e_map, abs(signed), False)
            if es >= 0 and e_entry[es] >= 0:
                p_edge[a + k] = es
            elif f_state[s] == 0:
                f_state[s] = 1 + k
        if f_state[s] != 0:
            continue
        cx, cy, cz = 0, 0, 0
        for k in range(size):
            es = p_edge[a + k]
            forward = p_sign[a + k] > 0
            p_tail[a + k] = e_tail[es] if forward else e_head[es]
            p_L[a + k, 0], p_L[a + k, 1], p_L[a + k, 2] = cx, cy, cz
            if forward:
                p_B[a + k, 0], p_B[a + k, 1], p_B[a + k, 2] = cx, cy, cz
                cx, cy, cz = cx + e_wrap[es, 0], cy + e_wrap[es, 1], cz + e_wrap[es, 2]
            else:
                cx, cy, cz = cx - e_wrap[es, 0], cy - e_wrap[es, 1], cz - e_wrap[es, 2]
                p_B[a + k, 0], p_B[a + k, 1], p_B[a + k, 2] = cx, cy, cz
        for k in range(size):
            es = p_edge[a + k]
            head = e_head[es] if p_sign[a + k] > 0 else e_tail[es]
            if head != p_tail[a + (k + 1) % size]:
                f_state[s] = -1 - ((k + 1) % size)
                break
        if f_state[s] == 0 and (cx != 0 or cy != 0 or cz != 0):
            f_state[s] = -1 - size
        if f_state[s] == 0:
            for k in range(size):
                e_uses[p_edge[a + k]] += 1
    # Edge uses by facets, for pairing patches around an edge.
    use_start = np.zeros(ne + 1, np.int64)
    for s in range(ne):
        use_start[s + 1] = use_start[s] + e_uses[s]
    uses = np.empty(use_start[ne], np.int64)
    fill_e = use_start[:-1].copy()
    for s in range(nf):
        if f_entry[s] >= 0 and f_state[s] == 0:
            for q in range(pos_start[s], pos_start[s + 1]):
                es = p_edge[q]
                uses[fill_e[es]] = q
                fill_e[es] += 1
    # Bodies, in the order of their first line.
    b_map, b_slot = _slots(ident[b_rows], 0)
    nb = b_map[2][0]
    b_last = np.empty(nb, np.int64)
    b_any_bad = np.zeros(nb, np.bool_)
    for j in range(b_rows.shape[0]):
        s = b_slot[j]
        b_last[s] = b_rows[j]
        if status[b_rows[j]] != ENTRY_OK:
            b_any_bad[s] = True
    # The bodies that list each facet (the first three, and how many times in all).
    f_listed = np.zeros(nf, np.int64)
    f_lister = np.full((nf, 3), -1, np.int64)
    for j in range(nb):
        if b_any_bad[j]:
            continue
        i = b_last[j]
        for q in range(first[i], last[i]):
            s = _slot(f_map, abs(ids[q]), False)
            if s >= 0:
                if f_listed[s] < 3:
                    f_lister[s, f_listed[s]] = j
                f_listed[s] += 1
    return (
        (vk_id, vk_entry, vk_bad),
        (e_id, e_entry, e_bad, e_tail, e_head, e_wrap, e_triple, e_uses, use_start, uses),
        (f_map, f_id, f_entry, f_bad, f_state, f_listed, f_lister),
        e_map,
        (pos_start, p_facet, p_edge, p_edge_id, p_sign, p_tail, p_L, p_B),
        (b_last, b_any_bad),
        marked,
    )


# --- One body -------------------------------------------------------------------------------


@njit_leaf
def _dot3(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


@njit_leaf
def _shifted(xyz, entry, off, periods, out):
    """A vertex's position translated by ``off`` (whole periods) into ``out``."""
    for k in range(3):
        out[k] = (
            xyz[entry, k] + off[0] * periods[0, k] + off[1] * periods[1, k] + off[2] * periods[2, k]
        )


@njit(no_cpython_wrapper=True)
def _pair_around(
    rule,
    stamp,
    darts,
    partner,
    local_edges,
    tables,
    stamps,
    xyz,
    periods,
):
    """Pair off the uses of edges that a body makes more than twice (it meets its own image
    along them), by the geometry around each edge: from a patch, turning about the edge into
    the cell (away from the patch's outward side when ``rule`` is 1, towards it when -1: a
    body that lists its facets inwards), the first facet met is the patch's partner, a patch
    of the same body that runs along the edge the other way.

    Returns ``(ok, local edge that failed, vertex key without coordinates or -1)``."""
    _, d_pos, d_dir, occ_d, occ_sign = darts
    el_slot, el_count, el_start, el_darts = local_edges
    vertices, edges, _, _, positions, _, _ = tables
    vk_entry = vertices[1]
    e_tail, e_head, e_wrap, use_start, uses = edges[3], edges[4], edges[5], edges[8], edges[9]
    pos_start, p_facet, _, _, p_sign, p_tail, p_L, p_B = positions
    fs_stamp, _, fs_plus, fs_minus = stamps[0], stamps[1], stamps[2], stamps[3]
    point = np.empty(3)
    tail = np.empty(3)
    along = np.empty(3)
    centre = np.empty(3)
    nowhere = np.zeros(3, np.int64)
    for local in range(el_slot.shape[0]):
        if el_count[local] <= 2:
            continue
        es = el_slot[local]
        u0, u1 = use_start[es], use_start[es + 1]
        k = u1 - u0
        if vk_entry[e_tail[es]] < 0:
            return False, local, e_tail[es]
        if vk_entry[e_head[es]] < 0:
            return False, local, e_head[es]
        _shifted(xyz, vk_entry[e_tail[es]], nowhere, periods, tail)
        _shifted(xyz, vk_entry[e_head[es]], e_wrap[es], periods, along)
        for x in range(3):
            along[x] -= tail[x]
        along2 = _dot3(along, along)
        # The direction from the edge into each facet that uses it (its centre, in its frame).
        into = np.empty((k, 3))
        for c in range(k):
            q = uses[u0 + c]
            g = p_facet[q]
            a, b = pos_start[g], pos_start[g + 1]
            centre[0] = centre[1] = centre[2] = 0.0
            for r in range(a, b):
                if vk_entry[p_tail[r]] < 0:
                    return False, local, p_tail[r]
                _shifted(xyz, vk_entry[p_tail[r]], p_L[r], periods, point)
                for x in range(3):
                    centre[x] += point[x] / (b - a)
            _shifted(xyz, vk_entry[e_tail[es]], p_B[q], periods, point)
            for x in range(3):
                centre[x] -= point[x]
            height = _dot3(centre, along) / along2
            for x in range(3):
                into[c, x] = centre[x] - height * along[x]
        for w in range(el_start[local], el_start[local + 1]):
            d = el_darts[w]
            mine = -1
            for c in range(k):
                if uses[u0 + c] == d_pos[d]:
                    mine = c
            best, best_angle = -1, 0.0
            for c in range(k):
                if c == mine:
                    continue
                u, v = into[mine], into[c]
                turn = d_dir[d] * (
                    (u[1] * v[2] - u[2] * v[1]) * along[0]
                    + (u[2] * v[0] - u[0] * v[2]) * along[1]
                    + (u[0] * v[1] - u[1] * v[0]) * along[2]
                )
                angle = math.atan2(turn / math.sqrt(along2), _dot3(u, v))
                if angle <= 0.0:
                    angle += 2 * math.pi
                if best < 0 or (angle > best_angle if rule > 0 else angle < best_angle):
                    best, best_angle = c, angle
            if best < 0:
                return False, local, -1
            q = uses[u0 + best]
            g = p_facet[q]
            sign = -d_dir[d] * p_sign[q]
            if fs_stamp[g] != stamp:
                return False, local, -1
            o = fs_plus[g] if sign > 0 else fs_minus[g]
            if o < 0:
                return False, local, -1
            size = pos_start[g + 1] - pos_start[g]
            offset = q - pos_start[g]
            partner[d] = occ_d[o] + (offset if occ_sign[o] > 0 else size - 1 - offset)
        for w in range(el_start[local], el_start[local + 1]):
            d = el_darts[w]
            if partner[partner[d]] != d:
                return False, local, -1
    return True, -1, -1


@njit(no_cpython_wrapper=True)
def _body(
    j, entry, ids, first, last, xyz, periodic, periods, marked, many, tables, stamps, stamp, out
):
    """The grain of body ``j`` of a file (its line is entry ``entry``): returns its GRAIN_
    code, with the code's params in ``out[0]``. For GRAIN_OK, ``out`` holds (params, counts:
    faces, neighbours, corners, corner uses, patches, boundary; each face's neighbour count,
    the neighbours, the corners' positions, the corners of each patch in order (rows of the
    positions), the patches' sizes), each long enough for twice the file's facet edges.

    ``many``: the file has other bodies (a patch shared with none is on the sample's boundary).
    ``stamps``: scratch by facet, edge and vertex key; entries from another body (another
    ``stamp``) count as empty.
    """
    vertices, edges, facets, e_map, positions, _, _ = tables
    vk_entry = vertices[1]
    e_id, _, e_bad, _, _, _, e_triple, e_uses, _, _ = edges
    f_map, f_id, f_entry, f_bad, f_state, f_listed, f_lister = facets
    pos_start, _, p_edge, p_edge_id, p_sign, p_tail, p_L, p_B = positions
    fs_stamp, fs_count, fs_plus, fs_minus, es_stamp, es_local, vk_stamp, vk_first = stamps
    params, counts, nbr_counts, neighbours, position, corners, sizes = out
    for k in range(5):
        params[k] = 0
    a0, m = first[entry], last[entry] - first[entry]
    occ_slot = np.empty(m, np.int64)
    occ_sign = np.empty(m, np.int64)
    for o in range(m):
        signed = ids[a0 + o]
        s = _slot(f_map, abs(signed), False)
        occ_slot[o] = s
        occ_sign[o] = -1 if signed < 0 else 1
        if s >= 0:
            if fs_stamp[s] != stamp:
                fs_stamp[s], fs_count[s], fs_plus[s], fs_minus[s] = stamp, 0, -1, -1
            fs_count[s] += 1
            if occ_sign[o] > 0:
                fs_plus[s] = o
            else:
                fs_minus[s] = o
    # A facet listed more than once: only once each way, and only in a periodic file.
    for o in range(m):
        s = occ_slot[o]
        if s >= 0 and fs_count[s] > 1:
            params[0] = f_id[s]
            if not periodic:
                return GRAIN_TWICE
            if fs_count[s] != 2 or fs_plus[s] < 0 or fs_minus[s] < 0:
                params[1], params[2] = fs_count[s], occ_sign[o]
                return GRAIN_TWICE_SAME
    # Every facet and edge defined, in the order the body names them.
    for o in range(m):
        s = occ_slot[o]
        if s < 0 or f_entry[s] < 0:
            params[0], params[1], params[2] = FACET, abs(ids[a0 + o]), USER_LIST
            params[4] = f_bad[s] if s >= 0 else 0
            return GRAIN_UNDEFINED
        if f_state[s] > 0:
            edge = p_edge_id[pos_start[s] + f_state[s] - 1]
            es = _slot(e_map, edge, False)
            params[0], params[1], params[2], params[3] = EDGE, edge, USER_FACET, f_id[s]
            params[4] = e_bad[es] if es >= 0 else 0
            return GRAIN_UNDEFINED
    for o in range(m):
        s = occ_slot[o]
        if f_state[s] < 0:
            size = pos_start[s + 1] - pos_start[s]
            params[0] = f_id[s]
            if f_state[s] == -1 - size:
                return GRAIN_FACET_WRAPS
            params[1] = p_edge_id[pos_start[s] - 1 - f_state[s]]
            return GRAIN_FACET_OPEN
    # Darts: each patch's edge uses in the patch's direction.
    occ_d = np.empty(m + 1, np.int64)
    n_darts = 0
    for o in range(m):
        occ_d[o] = n_darts
        n_darts += pos_start[occ_slot[o] + 1] - pos_start[occ_slot[o]]
    occ_d[m] = n_darts
    d_occ = np.empty(n_darts, np.int64)
    d_pos = np.empty(n_darts, np.int64)
    d_edge = np.empty(n_darts, np.int64)
    d_dir = np.empty(n_darts, np.int64)
    d_key = np.empty(n_darts, np.int64)
    d_L = np.empty((n_darts, 3), np.int64)
    # The body's edges in the order it first uses them, and their uses; the second use of an
    # edge is the first's partner (undone below where an edge has more).
    n_local = 0
    el_slot = np.empty(n_darts, np.int64)
    el_count = np.zeros(n_darts, np.int64)
    el_first = np.empty(n_darts, np.int64)
    partner = np.full(n_darts, -1, np.int64)
    ambiguous = False
    for o in range(m):
        s = occ_slot[o]
        a = pos_start[s]
        size = pos_start[s + 1] - a
        for i in range(size):
            d = occ_d[o] + i
            k = i if occ_sign[o] > 0 else size - 1 - i
            t = k if occ_sign[o] > 0 else (k + 1) % size
            es = p_edge[a + k]
            d_occ[d], d_pos[d], d_edge[d] = o, a + k, es
            d_dir[d] = occ_sign[o] * p_sign[a + k]
            d_key[d] = p_tail[a + t]
            d_L[d, 0], d_L[d, 1], d_L[d, 2] = p_L[a + t, 0], p_L[a + t, 1], p_L[a + t, 2]
            if es_stamp[es] != stamp:
                es_stamp[es], es_local[es] = stamp, n_local
                el_slot[n_local], el_first[n_local] = es, d
                n_local += 1
            local = es_local[es]
            el_count[local] += 1
            if el_count[local] == 2:
                partner[d], partner[el_first[local]] = el_first[local], d
            elif el_count[local] == 3:
                ambiguous = True
    for local in range(n_local):
        c = el_count[local]
        if c != 2 and (not periodic or c % 2 == 1):
            params[0], params[1] = e_id[el_slot[local]], c
            return GRAIN_NOT_CLOSED
    for local in range(n_local):
        d1 = el_first[local]
        if el_count[local] == 2 and d_dir[d1] == d_dir[partner[d1]]:
            params[0], params[1] = f_id[occ_slot[d_occ[d1]]], f_id[occ_slot[d_occ[partner[d1]]]]
            params[2] = e_id[el_slot[local]]
            return GRAIN_ORIENTATION
    if ambiguous:
        el_slot, el_count = el_slot[:n_local], el_count[:n_local]
        el_start = np.zeros(n_local + 1, np.int64)
        for local in range(n_local):
            el_start[local + 1] = el_start[local] + el_count[local]
        el_darts = np.empty(n_darts, np.int64)
        fill = el_start[:-1].copy()
        for d in range(n_darts):
            local = es_local[d_edge[d]]
            el_darts[fill[local]] = d
            fill[local] += 1
        darts = (d_occ, d_pos, d_dir, occ_d, occ_sign)
        edge_uses = (el_slot, el_count, el_start, el_darts)
        ok, failed, key = False, -1, -1
        for attempt in range(2):  # outward lists, then inward ones
            if attempt == 0 or key < 0:
                rule = 1 - 2 * attempt
                ok, failed, key = _pair_around(
                    rule, stamp, darts, partner, edge_uses, tables, stamps, xyz, periods
                )
            if ok:
                break
        if not ok:
            if key >= 0:
                return _undefined_vertex(key, vertices, edges, d_edge, params)
            params[0], params[1] = e_id[el_slot[failed]], el_count[failed]
            return GRAIN_UNPAIRED
    # Each patch's translation, across the edges it shares with its partners.
    shift = np.zeros((m, 3), np.int64)
    piece = np.full(m, -1, np.int64)
    queue = np.empty(m, np.int64)
    pieces = 0
    for start in range(m):
        if piece[start] >= 0:
            continue
        piece[start] = pieces
        queue[0] = start
        head, tail = 0, 1
        while head < tail:
            o = queue[head]
            head += 1
            for d in range(occ_d[o], occ_d[o + 1]):
                p = partner[d]
                o2 = d_occ[p]
                qa, qb = d_pos[d], d_pos[p]
                same = True
                for k in range(3):
                    want = shift[o, k] + p_B[qa, k] - p_B[qb, k]
                    if piece[o2] < 0:
                        shift[o2, k] = want
                    elif shift[o2, k] != want:
                        same = False
                if piece[o2] < 0:
                    piece[o2] = pieces
                    queue[tail] = o2
                    tail += 1
                elif not same:
                    params[0] = e_id[d_edge[d]]
                    return GRAIN_AROUND
        pieces += 1
    # Corners: (vertex, translation) pairs.
    n_lv = 0
    lv_key = np.empty(n_darts, np.int64)
    lv_off = np.empty((n_darts, 3), np.int64)
    lv_next = np.empty(n_darts, np.int64)
    d_tail = corners  # the corners of each patch in order: the tails of its darts
    off = np.empty(3, np.int64)
    for d in range(n_darts):
        o, key = d_occ[d], d_key[d]
        for k in range(3):
            off[k] = shift[o, k] + d_L[d, k]
        if vk_stamp[key] != stamp:
            vk_stamp[key], vk_first[key] = stamp, -1
        v = vk_first[key]
        while v >= 0 and not (
            lv_off[v, 0] == off[0] and lv_off[v, 1] == off[1] and lv_off[v, 2] == off[2]
        ):
            v = lv_next[v]
        if v < 0:
            v = n_lv
            lv_key[v] = key
            lv_off[v, 0], lv_off[v, 1], lv_off[v, 2] = off[0], off[1], off[2]
            lv_next[v] = vk_first[key]
            vk_first[key] = v
            n_lv += 1
        d_tail[d] = v
    d_head = np.empty(n_darts, np.int64)
    for o in range(m):
        for d in range(occ_d[o], occ_d[o + 1]):
            d_head[d] = d_tail[d + 1 if d + 1 < occ_d[o + 1] else occ_d[o]]
    euler = n_lv - n_darts // 2 + m
    if euler != 2:
        params[0] = euler
        return GRAIN_EULER
    if pieces > 1:
        return GRAIN_PIECES
    for v in range(n_lv):
        key = lv_key[v]
        if vk_entry[key] < 0:
            return _undefined_vertex(key, vertices, edges, d_edge, params)
        _shifted(xyz, vk_entry[key], lv_off[v], periods, position[v])
    # What lies across each patch: the other bodies that list its facet (the body's own image
    # for a facet it lists twice), and whether no other body does (the sample's boundary).
    across = np.full((m, 3), -1, np.int64)
    outside = np.zeros(m, np.bool_)
    for o in range(m):
        s = occ_slot[o]
        others = f_listed[s] - fs_count[s]
        x = 1
        for r in range(min(f_listed[s], 3)):
            if f_lister[s, r] != j and x < 3:
                across[o, x] = f_lister[s, r]
                x += 1
        if fs_count[s] == 2:
            others += 1
            across[o, 2] = across[o, 1]
            across[o, 1] = j
        across[o, 0] = others
        outside[o] = others == 0
    normal = np.zeros((m, 3))
    if not marked:
        for o in range(m):
            for d in range(occ_d[o], occ_d[o + 1]):
                pa, pb = position[d_tail[d]], position[d_head[d]]
                normal[o, 0] += pa[1] * pb[2] - pa[2] * pb[1]
                normal[o, 1] += pa[2] * pb[0] - pa[0] * pb[2]
                normal[o, 2] += pa[0] * pb[1] - pa[1] * pb[0]
            length = math.sqrt(_dot3(normal[o], normal[o]))
            for x in range(3):
                normal[o, x] = normal[o, x] / length if length > 0 else 0.0
    # Faces: patches joined across edges that are not triple lines.
    parent = np.empty(m, np.int64)
    for o in range(m):
        parent[o] = o
    for d in range(n_darts):
        p = partner[d]
        if p < d:
            continue
        o, o2 = d_occ[d], d_occ[p]
        es = d_edge[d]
        if e_triple[es] or e_uses[es] > 2:
            continue
        if across[o, 0] != across[o2, 0] or across[o, 1] != across[o2, 1]:
            continue
        if across[o, 2] != across[o2, 2]:
            continue
        if not marked and outside[o] and _dot3(normal[o], normal[o2]) < 1 - 1e-9:
            continue
        ra, rb = _root(parent, o), _root(parent, o2)
        parent[ra] = rb
    face = np.full(m, -1, np.int64)
    face_of_root = np.full(m, -1, np.int64)
    n_faces = 0
    for o in range(m):
        r = _root(parent, o)
        if face_of_root[r] < 0:
            face_of_root[r] = n_faces
            n_faces += 1
        face[o] = face_of_root[r]
    # Boundary darts of each face, and the corners' numbers of triple lines.
    degree = np.zeros(n_lv, np.int64)
    f_count = np.zeros(n_faces + 1, np.int64)
    separating = 0
    for d in range(n_darts):
        p = partner[d]
        if face[d_occ[d]] != face[d_occ[p]]:
            f_count[face[d_occ[d]] + 1] += 1
            if d < p:
                separating += 1
                degree[d_tail[d]] += 1
                degree[d_head[d]] += 1
    if separating == 0:
        return GRAIN_NO_TRIPLE
    for f in range(n_faces):
        f_count[f + 1] += f_count[f]
    boundary_darts = np.empty(f_count[n_faces], np.int64)
    fill = f_count[:-1].copy()
    for d in range(n_darts):
        if face[d_occ[d]] != face[d_occ[partner[d]]]:
            boundary_darts[fill[face[d_occ[d]]]] = d
            fill[face[d_occ[d]]] += 1
    # Walk each face's boundary from a corner: its neighbours in cyclic order.
    leaving = np.full(n_lv, -1, np.int64)
    leaving_face = np.full(n_lv, -1, np.int64)
    next_leaving = np.empty(n_darts, np.int64)
    used = np.zeros(n_darts, np.bool_)
    loop = np.empty(n_darts, np.int64)
    n_nbrs = 0
    for f in range(n_faces):
        b0, b1 = f_count[f], f_count[f + 1]
        for w in range(b1 - 1, b0 - 1, -1):
            d = boundary_darts[w]
            v = d_tail[d]
            if leaving_face[v] != f:
                leaving_face[v], leaving[v] = f, -1
            next_leaving[d] = leaving[v]
            leaving[v] = d
        start = boundary_darts[b0]
        for w in range(b0, b1):
            if degree[d_tail[boundary_darts[w]]] >= 3:
                start = boundary_darts[w]
                break
        length = 0
        d = start
        while not used[d]:
            used[d] = True
            loop[length] = d
            length += 1
            v = d_head[d]
            nd = leaving[v] if leaving_face[v] == f else -1
            while nd >= 0 and used[nd]:
                nd = next_leaving[nd]
            if nd < 0:
                break
            d = nd
        if length != b1 - b0:
            params[0] = f
            return GRAIN_NOT_DISC
        first_nbr = n_nbrs
        for i in range(length):
            d = loop[i]
            g = face[d_occ[partner[d]]]
            if i == 0 or degree[d_tail[d]] >= 3 or g != neighbours[n_nbrs - 1]:
                neighbours[n_nbrs] = g
                n_nbrs += 1
        if (
            n_nbrs - first_nbr > 1
            and neighbours[first_nbr] == neighbours[n_nbrs - 1]
            and degree[d_tail[loop[0]]] < 3
        ):
            n_nbrs -= 1  # the walk started inside a triple line: its two ends are one
        nbr_counts[f] = n_nbrs - first_nbr
    boundary = -1
    if periodic:
        boundary = 0
    elif many:
        boundary = 0
        for o in range(m):
            if outside[o]:
                boundary = 1
    for o in range(m):
        sizes[o] = occ_d[o + 1] - occ_d[o]
    counts[0], counts[1], counts[2], counts[3] = n_faces, n_nbrs, n_lv, n_darts
    counts[4], counts[5] = m, boundary
    return GRAIN_OK


@njit_leaf
def _root(parent, k):
    while parent[k] != k:
        parent[k] = parent[parent[k]]
        k = parent[k]
    return k


@njit_leaf
def _undefined_vertex(key, vertices, edges, d_edge, params):
    """GRAIN_UNDEFINED for a vertex without coordinates, named with the first edge the body
    uses that ends at it."""
    vk_id, _, vk_bad = vertices
    e_id, e_tail, e_head = edges[0], edges[3], edges[4]
    user = 0
    for d in range(d_edge.shape[0]):
        es = d_edge[d]
        if e_tail[es] == key or e_head[es] == key:
            user = e_id[es]
            break
    params[0], params[1], params[2], params[3] = VERTEX, vk_id[key], USER_EDGE, user
    params[4] = vk_bad[key]
    return GRAIN_UNDEFINED


# --- All files ------------------------------------------------------------------------------


@njit
def _assemble(
    kind,
    ident,
    line_of,
    status,
    first,
    last,
    xyz,
    wraps,
    flag,
    ids,
    file_status,
    periodic,
    periods,
    entry_start,
    entry_end,
    facets_line,
):
    """The grains of every file that :func:`_tokenize` read (its outputs, slow numbers filled
    in): one per body, or one for a file that is not read (GRAIN_FILE, GRAIN_NO_BODIES).

    Returns per grain: file, body id, line, code, params, given volume and whether given, boundary
    (1, 0, -1 unknown), number of faces; per face: neighbour count; the neighbours; per corner
    position (float64[N, 3]); per patch its corners (rows of the positions) and its grain.
    """
    n_files = file_status.shape[0]
    cap = n_files
    for i in range(kind.shape[0]):
        cap += kind[i] == BODY
    g_file = np.empty(cap, np.int64)
    g_body = np.zeros(cap, np.int64)
    g_line = np.ones(cap, np.int64)
    g_code = np.zeros(cap, np.int64)
    g_params = np.zeros((cap, 5), np.int64)
    g_volume = np.full(cap, np.nan)
    g_given = np.zeros(cap, np.bool_)
    g_boundary = np.full(cap, -1, np.int8)
    g_faces = np.zeros(cap, np.int64)
    nbr_counts = np.empty(1024, np.int64)
    neighbours = np.empty(4096, np.int32)
    position = np.empty(3 * 1024, np.float64)  # x, y, z of each corner in turn
    corners = np.empty(4096, np.int64)
    loop_sizes = np.empty(1024, np.int64)
    loop_grain = np.empty(1024, np.int64)
    n_g = n_f = n_nb = n_pos = n_c = n_loops = 0
    for f in range(n_files):
        if file_status[f] != FILE_OK:
            g_file[n_g], g_code[n_g] = f, GRAIN_FILE
            n_g += 1
            continue
        f0, f1 = entry_start[f], entry_end[f]
        tables = _file_tables(f0, f1, kind, ident, line_of, status, first, last, wraps, flag, ids)
        b_last, b_any_bad = tables[5]
        nb = b_last.shape[0]
        if nb == 0:
            g_file[n_g], g_code[n_g] = f, GRAIN_NO_BODIES
            g_params[n_g, 1] = -1
            for i in range(f0, f1):
                if kind[i] == FACET:
                    g_params[n_g, 0] = max(facets_line[f], 1)  # a film: facets, no bodies
                if status[i] != ENTRY_OK and g_params[n_g, 1] < 0:
                    g_params[n_g, 1], g_params[n_g, 2] = kind[i], line_of[i]
            n_g += 1
            continue
        nf = tables[2][1].shape[0]
        ne = tables[1][0].shape[0]
        nk = tables[0][0].shape[0]
        stamps = (
            np.zeros(nf, np.int64),
            np.zeros(nf, np.int64),
            np.zeros(nf, np.int64),
            np.zeros(nf, np.int64),
            np.zeros(ne, np.int64),
            np.zeros(ne, np.int64),
            np.zeros(nk, np.int64),
            np.zeros(nk, np.int64),
        )
        marked = tables[6]
        room = 2 * tables[4][0][nf] + 1
        out = (
            np.zeros(5, np.int64),
            np.zeros(6, np.int64),
            np.empty(room, np.int64),
            np.empty(room, np.int64),
            np.empty((room, 3)),
            np.empty(room, np.int64),
            np.empty(room, np.int64),
        )
        counts = out[1]
        for j in range(nb):
            i = b_last[j]
            g_file[n_g], g_body[n_g], g_line[n_g] = f, ident[i], line_of[i]
            if b_any_bad[j]:
                g_code[n_g] = GRAIN_BODY_LINE
                n_g += 1
                continue
            code = _body(
                j,
                i,
                ids,
                first,
                last,
                xyz,
                periodic[f],
                periods[f],
                marked,
                nb > 1,
                tables,
                stamps,
                j + 1,
                out,
            )
            g_code[n_g] = code
            for k in range(5):
                g_params[n_g, k] = out[0][k]
            if code == GRAIN_OK:
                faces, nbrs, points = counts[0], counts[1], counts[2]
                uses, patches = counts[3], counts[4]
                if flag[i]:
                    g_volume[n_g], g_given[n_g] = xyz[i, 0], True
                g_boundary[n_g] = counts[5]
                g_faces[n_g] = faces
                nbr_counts = _reserve(nbr_counts, n_f + faces)
                for k in range(faces):
                    nbr_counts[n_f + k] = out[2][k]
                n_f += faces
                neighbours = _reserve(neighbours, n_nb + nbrs)
                for k in range(nbrs):
                    neighbours[n_nb + k] = out[3][k]
                n_nb += nbrs
                position = _reserve(position, 3 * (n_pos + points))
                for k in range(points):
                    for x in range(3):
                        position[3 * (n_pos + k) + x] = out[4][k, x]
                corners = _reserve(corners, n_c + uses)
                for k in range(uses):
                    corners[n_c + k] = out[5][k] + n_pos
                n_c += uses
                n_pos += points
                loop_sizes = _reserve(loop_sizes, n_loops + patches)
                loop_grain = _reserve(loop_grain, n_loops + patches)
                for k in range(patches):
                    loop_sizes[n_loops + k] = out[6][k]
                    loop_grain[n_loops + k] = n_g
                n_loops += patches
            n_g += 1
    return (
        g_file[:n_g],
        g_body[:n_g],
        g_line[:n_g],
        g_code[:n_g],
        g_params[:n_g],
        g_volume[:n_g],
        g_given[:n_g],
        g_boundary[:n_g],
        g_faces[:n_g],
        nbr_counts[:n_f],
        neighbours[:n_nb],
        position[: 3 * n_pos].reshape((n_pos, 3)),
        corners[:n_c],
        loop_sizes[:n_loops],
        loop_grain[:n_loops],
    )
