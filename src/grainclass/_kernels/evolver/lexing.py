"""Bytes to tokens: the logical lines of a datafile, each as its tokens' spans in a
:class:`LineTokens`, with comments, directives and joined lines taken out.

The tokenizer lexes one line at a time (:func:`_lex_line`) and reads the spans it leaves in
``LineTokens.starts`` and ``LineTokens.ends``; nothing is copied out of the file's bytes.
"""

from typing import NamedTuple

import numpy as np

from grainclass._numba import at, njit, njit_leaf

SPACE, TAB, NEWLINE, RETURN, HASH, SLASH, STAR, BACKSLASH = 32, 9, 10, 13, 35, 47, 42, 92
PLUS, MINUS, DOT, UNDERSCORE, ZERO, NINE, COLON = 43, 45, 46, 95, 48, 57, 58

# What each byte is to the lexer: part of a token (``#`` too, but at the start of a line, where
# it makes the line a directive), a byte that may start a comment or join two lines, a blank
# between tokens or a line break (as str.split() and str.splitlines() read ASCII).
C_TOKEN, C_HASH, C_SLASH, C_BACKSLASH, C_BLANK, C_BREAK = 0, 1, 2, 3, 4, 5
_CLASS = np.zeros(256, np.uint8)
_CLASS[[SPACE, TAB, 31]] = C_BLANK
_CLASS[[NEWLINE, 11, 12, RETURN, 28, 29, 30]] = C_BREAK
_CLASS[SLASH], _CLASS[BACKSLASH], _CLASS[HASH] = C_SLASH, C_BACKSLASH, C_HASH


class LineTokens(NamedTuple):
    """The tokens of the line last lexed, and the physical line reached."""

    starts: np.ndarray
    """int64[longest // 2 + 2]: where each token starts in the file's bytes"""
    ends: np.ndarray
    """int64[longest // 2 + 2]: where it ends"""
    line: np.ndarray
    """int64[1]: the number of the physical line reached (from 1)"""


@njit
def _lower(c):
    return c + 32 if 65 <= c <= 90 else c


@njit
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


@njit
def _line_end(buf, p, end):
    """The first line break from ``p`` on (or ``end``)."""
    while p < end and _CLASS[buf[p]] != C_BREAK:
        p += 1
    return p


@njit
def _continues(buf, p, end):
    """Whether a backslash before ``p`` continues its line: only blanks, or a // comment, follow
    it on the line."""
    while p < end and _CLASS[buf[p]] == C_BLANK:
        p += 1
    if p >= end or _CLASS[buf[p]] == C_BREAK:
        return True
    return buf[p] == SLASH and p + 1 < end and buf[p + 1] == SLASH


@njit
def _comment_at(buf, p, end, last_close):
    """Whether a comment starts at ``p``: ``//``, or a ``/*`` that closes."""
    if p + 1 >= end or buf[p] != SLASH:
        return False
    return buf[p + 1] == SLASH or (buf[p + 1] == STAR and p + 2 <= last_close)


@njit
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
def _lex_line(buf, p, end, last_close, starts, ends, line):
    """The tokens of the logical line at ``p`` into ``starts`` and ``ends`` (a
    :class:`LineTokens`' arrays): ``(p after it, tokens, its first line number, at end of
    file)``; ``line[0]`` counts physical lines.

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
            starts[ntok] = start
            ends[ntok] = p
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


@njit
def _last_close(buf, start, end):
    """Where the last ``*/`` of ``buf[start:end]`` starts (``start - 1`` if none)."""
    for p in range(end - 2, start - 1, -1):
        if buf[p] == STAR and buf[p + 1] == SLASH:
            return p
    return start - 1


@njit
def _count_breaks(buf, start, end):
    n = 0
    for p in range(start, end):
        if _CLASS[buf[p]] == C_BREAK:
            n += 1
    return n
