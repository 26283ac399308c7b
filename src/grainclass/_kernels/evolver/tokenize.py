"""Files to entries: :func:`_tokenize` reads the bytes of many datafiles at once into one
:class:`Tokens`, the entries of all files in order (:class:`~.entries.Entries`), the numbers
left to Python (:class:`~.entries.SlowNumbers`) and each file's status, periods and range of
entries (:class:`Files`).

A file is read line by line (:func:`_tokenize_file`): a numbered line in a section is an entry
(``entries.py``), any other line a keyword: a section's name, ``periods`` and its rows, ``read``
(the end of the data) or one of the header's words that say the file is not a 3D surface.
"""

from typing import NamedTuple

import numpy as np

from grainclass._kernels.evolver.codes import (
    BODY,
    EDGE,
    ENTRY_OK,
    ENTRY_SLOW,
    FACET,
    FILE_2D,
    FILE_LONG_ID,
    FILE_OK,
    FILE_PERIODS,
    FILE_SIMPLEX,
    FILE_SPACE,
    FILE_STRING,
    FILE_SYMMETRY,
    SLOW_PERIOD,
    VERTEX,
)
from grainclass._kernels.evolver.entries import (
    Entries,
    SlowNumbers,
    _edge_entry,
    _first_entries,
    _list_entry,
    _new_entries,
    _new_slow_numbers,
    _noted,
    _slow_number,
    _vertex_entry,
)
from grainclass._kernels.evolver.lexing import (
    COLON,
    LineTokens,
    _count_breaks,
    _last_close,
    _lex_line,
    _word_is,
)
from grainclass._kernels.evolver.numbers import (
    LONGEST_ID,
    _is_decimal,
    _is_number,
    _parse_float,
    _parse_int,
)
from grainclass._numba import borrowed, njit

# The keywords a line may start with: a section's (the kind of its entries), then the others.
KEY_OTHER, KEY_PERIODS, KEY_READ, KEY_STRING, KEY_SIMPLEX, KEY_SYMMETRY = -1, 4, 5, 6, 7, 8
KEY_SPACE_DIMENSION, KEY_SURFACE_DIMENSION = 9, 10

_W_VERTICES = np.frombuffer(b"vertices", np.uint8)
_W_EDGES = np.frombuffer(b"edges", np.uint8)
_W_FACES = np.frombuffer(b"faces", np.uint8)
_W_FACETS = np.frombuffer(b"facets", np.uint8)
_W_BODIES = np.frombuffer(b"bodies", np.uint8)
_W_PERIODS = np.frombuffer(b"periods", np.uint8)
_W_READ = np.frombuffer(b"read", np.uint8)
_W_STRING = np.frombuffer(b"string", np.uint8)
_W_SPACE_DIMENSION = np.frombuffer(b"space_dimension", np.uint8)
_W_SURFACE_DIMENSION = np.frombuffer(b"surface_dimension", np.uint8)
_W_SIMPLEX = np.frombuffer(b"simplex_representation", np.uint8)
_W_SYMMETRY = np.frombuffer(b"symmetry_group", np.uint8)


class Files(NamedTuple):
    """Per file: how it was read, and where its entries are."""

    status: np.ndarray
    """int8[F]: FILE_OK, or why the file is not read"""
    line: np.ndarray
    """int64[F]: the line the status concerns"""
    aux: np.ndarray
    """int64[F, 3]: more about the status (see the FILE_ codes)"""
    periodic: np.ndarray
    """bool[F]: the file has periods"""
    periods: np.ndarray
    """float64[F, 3, 3]: its periods, one per row"""
    entry_start: np.ndarray
    """int64[F]: its entries are ``entry_start[f]:entry_end[f]``"""
    entry_end: np.ndarray
    """int64[F]"""
    facets_line: np.ndarray
    """int64[F]: the line of its facets section (0: none)"""


class Tokens(NamedTuple):
    """What :func:`_tokenize` reads from a group of files."""

    entries: Entries
    slow: SlowNumbers
    files: Files


class Header(NamedTuple):
    """What a file's header says of its space: the lines that say it (0: none) and the
    dimensions."""

    string_line: int
    space_dim: int
    space_line: int
    surface_dim: int
    surface_line: int
    simplex_line: int
    symmetry_line: int


@njit
def _tokenize(buf, file_starts, marker):
    """Split each file ``buf[file_starts[i]:file_starts[i + 1]]`` into entries (``marker``: the
    words that mark a triple edge). Returns a :class:`Tokens`."""
    n_files = file_starts.shape[0] - 1
    size = file_starts[-1] - file_starts[0]
    lines_bound = _count_breaks(buf, file_starts[0], file_starts[-1]) + n_files
    tokens_bound = size // 2 + n_files + 1
    entries = _new_entries(lines_bound, tokens_bound)
    slow = _new_slow_numbers(4 * lines_bound + 9 * n_files)
    files = Files(
        np.zeros(n_files, np.int8),
        np.zeros(n_files, np.int64),
        np.zeros((n_files, 3), np.int64),
        np.zeros(n_files, np.bool_),
        np.zeros((n_files, 3, 3), np.float64),
        np.zeros(n_files, np.int64),
        np.zeros(n_files, np.int64),
        np.zeros(n_files, np.int64),
    )
    longest = 0
    for f in range(n_files):
        longest = max(longest, file_starts[f + 1] - file_starts[f])
    tokens = LineTokens(
        np.empty(longest // 2 + 2, np.int64),
        np.empty(longest // 2 + 2, np.int64),
        np.ones(1, np.int64),
    )
    # Not the literal 0: numba would compile _tokenize_file once for literal counts and once
    # more for the int64 counts it returns.
    n, m = np.int64(0), np.int64(0)
    for f in range(n_files):
        files.entry_start[f] = n
        n, m, read = _tokenize_file(
            buf, file_starts[f], file_starts[f + 1], marker, tokens, entries, slow, f,
            files.periods[f], n, m,
        )  # fmt: skip
        files.entry_end[f] = n
        files.status[f], files.line[f] = read.status, read.line
        files.aux[f, 0], files.aux[f, 1], files.aux[f, 2] = read.aux
        files.periodic[f], files.facets_line[f] = read.periodic, read.facets_line
    return Tokens(_first_entries(entries, n, m), _noted(slow), files)


class FileRead(NamedTuple):
    """What :func:`_tokenize_file` tells of a file, for :class:`Files`."""

    status: int
    line: int
    aux: tuple[int, int, int]
    periodic: bool
    facets_line: int


@njit
def _tokenize_file(buf, start, end, marker, tokens, entries, slow, f, periods, n, m):
    """File ``f``, ``buf[start:end]``, into ``entries`` from row ``n`` on (its ids from ``m``)
    and ``slow``, its periods into ``periods`` (float64[3, 3]). Returns ``(n, m)`` after its
    entries and ids, and a :class:`FileRead`.

    The steps per line are compiled into it (``njit_leaf``) and handed borrowed views of the
    arrays (:func:`~grainclass._numba.borrowed`), made here, which are not reference-counted:
    a named tuple's arrays, or views handed in as arguments, would be counted up and down on
    every line. Its stores go through those views only: after an inlined ``borrowed()`` numba
    drops dead code, and with it a store through a named tuple's array that nothing reads
    later."""
    text = borrowed(buf)
    starts, ends, line = borrowed(tokens.starts), borrowed(tokens.ends), borrowed(tokens.line)
    kind, ident, line_of = borrowed(entries.kind), borrowed(entries.id), borrowed(entries.line)
    status, flag = borrowed(entries.status), borrowed(entries.flag)
    first, last, ids = borrowed(entries.first), borrowed(entries.last), borrowed(entries.ids)
    xyz, wraps = borrowed(entries.xyz), borrowed(entries.wraps)
    noted = (
        borrowed(slow.entry), borrowed(slow.slot), borrowed(slow.start), borrowed(slow.end),
        borrowed(slow.count),
    )  # fmt: skip
    words = (borrowed(marker.letters), borrowed(marker.ends))
    code, where, aux = FILE_OK, 0, (0, 0, 0)
    periodic = False
    facets_line = 0
    if end - start >= 3 and text[start] == 0xEF and text[start + 1] == 0xBB:
        start += 3 if text[start + 2] == 0xBF else 0
    last_close = _last_close(text, start, end)
    line[0] = 1
    p = start
    section = -1
    header = Header(0, 3, 0, 2, 0, 0, 0)
    header_checked = False
    # The rows after a `periods` line, read here so that _lex_line is compiled at one call
    # only: the next three lines with tokens, whatever they hold, or those up to the end of
    # the file; their first nine tokens are the numbers. A file that ends in blank lines
    # before its third row keeps its numbers but is not made periodic.
    rows_due, values, numbers, periods_line = 0, 0, True, 0
    eof = False
    while not eof:
        p, ntok, number, eof = _lex_line(text, p, end, last_close, starts, ends, line)
        if rows_due > 0:
            if ntok > 0:
                values, numbers = _period_row(
                    text, starts, ends, ntok, f, periods, noted, values, numbers
                )
                rows_due -= 1
            if rows_due == 0 or eof:
                if not (numbers and values == 9):
                    code, where = FILE_PERIODS, periods_line
                    break
                periodic |= ntok > 0
                rows_due = 0
            continue
        if ntok == 0:
            continue
        s0, e0 = starts[0], ends[0]
        if section >= 0 and _is_decimal(text, s0, e0):
            if e0 - s0 > LONGEST_ID:
                code, where, aux = FILE_LONG_ID, number, (section, s0, e0)
                break
            _, value = _parse_int(text, s0, e0)
            kind[n], ident[n], line_of[n] = section, value, number
            status[n], flag[n] = ENTRY_OK, 0
            if section == VERTEX:
                _vertex_entry(text, starts, ends, ntok, n, status, xyz, noted)
            elif section == EDGE:
                _edge_entry(
                    text, starts, ends, ntok, n, periodic, words, status, first, last, wraps,
                    flag,
                )  # fmt: skip
            else:
                m = _list_entry(
                    text, starts, ends, ntok, n, section == BODY, status, first, last, xyz,
                    flag, ids, m, noted,
                )  # fmt: skip
            n += 1
            continue
        word = _keyword(text, s0, e0)
        if 0 <= word <= KEY_PERIODS and not header_checked:
            header_checked = True
            code, where, kept = _header_status(header)
            if code != FILE_OK:
                aux = (kept, 0, 0)
                break
        if word == KEY_PERIODS:
            if eof:
                break
            rows_due, values, numbers, periods_line = 3, 0, True, number
        elif 0 <= word <= BODY:
            section = word
            if section == FACET and facets_line == 0:
                facets_line = number
        elif word == KEY_READ:
            break
        elif not header_checked:
            header = _header_line(header, word, number, text, starts, ends, ntok)
    return n, m, FileRead(code, where, aux, periodic, facets_line)


@njit
def _keyword(buf, s, e):
    """The keyword that token ``buf[s:e]`` is, in any case: a section's (its entries' kind),
    another KEY_, or KEY_OTHER. Surface Evolver takes a section's keyword with a colon too
    (`vertices:`, as in its own sphere.fe)."""
    if e - s > 1 and buf[e - 1] == COLON:
        e -= 1
    if _word_is(buf, s, e, _W_VERTICES):
        return VERTEX
    if _word_is(buf, s, e, _W_EDGES):
        return EDGE
    if _word_is(buf, s, e, _W_FACES) or _word_is(buf, s, e, _W_FACETS):
        return FACET
    if _word_is(buf, s, e, _W_BODIES):
        return BODY
    if _word_is(buf, s, e, _W_PERIODS):
        return KEY_PERIODS
    if _word_is(buf, s, e, _W_READ):
        return KEY_READ
    if _word_is(buf, s, e, _W_STRING):
        return KEY_STRING
    if _word_is(buf, s, e, _W_SIMPLEX):
        return KEY_SIMPLEX
    if _word_is(buf, s, e, _W_SYMMETRY):
        return KEY_SYMMETRY
    if _word_is(buf, s, e, _W_SPACE_DIMENSION):
        return KEY_SPACE_DIMENSION
    if _word_is(buf, s, e, _W_SURFACE_DIMENSION):
        return KEY_SURFACE_DIMENSION
    return KEY_OTHER


@njit
def _period_row(buf, starts, ends, ntok, f, periods, slow, values, numbers):
    """A row of file ``f``'s periods, its tokens up to the ninth number, into ``periods`` (its
    3 x 3) after the ``values`` read before. Returns ``(values, numbers)`` after the row:
    ``numbers`` stays True while every token read is a number."""
    for t in range(min(ntok, 9 - values)):
        s, e = starts[t], ends[t]
        if not _is_number(buf, s, e):
            numbers = False
        else:
            code, value = _parse_float(buf, s, e)
            if code == ENTRY_SLOW:
                _slow_number(slow, f, SLOW_PERIOD + values, s, e)
            periods[values // 3, values % 3] = value
        values += 1
    return values, numbers


@njit
def _header_line(header, word, number, buf, starts, ends, ntok):
    """``header`` with line ``number`` (keyword ``word``, ``ntok`` tokens) taken in."""
    string_line, space_dim, space_line, surface_dim, surface_line, simplex_line, symmetry_line = (
        header
    )
    if word == KEY_STRING:
        string_line = number
    elif word == KEY_SIMPLEX:
        simplex_line = number
    elif word == KEY_SYMMETRY:
        symmetry_line = number
    elif ntok > 1:
        # One call of the inlined _parse_int for both dimensions: one copy compiled.
        ok, value = _parse_int(buf, starts[1], ends[1])
        if ok and word == KEY_SPACE_DIMENSION:
            space_dim, space_line = value, number
        elif ok and word == KEY_SURFACE_DIMENSION:
            surface_dim, surface_line = value, number
    return Header(
        string_line, space_dim, space_line, surface_dim, surface_line, simplex_line, symmetry_line
    )


@njit
def _header_status(header):
    """``(FILE_ code, line, aux)`` of a file's header: FILE_OK for a surface in 3-space."""
    string = header.string_line > 0 or header.surface_dim == 1
    if header.space_dim == 2:
        return FILE_2D, header.space_line, 1 if string else 0
    if header.space_dim != 3:
        return FILE_SPACE, header.space_line, header.space_dim
    if string:
        line = header.string_line if header.string_line > 0 else header.surface_line
        return FILE_STRING, line, 0
    if header.simplex_line > 0:
        return FILE_SIMPLEX, header.simplex_line, 0
    if header.surface_dim != 2:
        return FILE_SPACE, header.surface_line, header.space_dim
    if header.symmetry_line > 0:
        return FILE_SYMMETRY, header.symmetry_line, 0
    return FILE_OK, 0, 0
