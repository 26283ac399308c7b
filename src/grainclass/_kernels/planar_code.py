"""plantri's planar_code, parsed from a byte buffer in two compiled passes (count, then fill).

A record is the vertex count n followed, for each vertex 1..n, by its neighbours (1-based, in
rotational order) and a 0. Counts below 256 use 1-byte entries; otherwise the record starts with
a 0 byte and every entry, n included, is 2 bytes in the stream's byte order.
"""

import numpy as np

from grainclass._numba import at, njit

_HEADER = np.frombuffer(b">>planar_code", np.uint8)


@njit
def _entry(buf, p, wide, big_endian):
    # int(): uint8 arithmetic would wrap at 256 when run as plain Python (NUMBA_DISABLE_JIT).
    if not wide:
        return int(buf[p])
    if big_endian:
        return int(buf[p]) * 256 + int(buf[p + 1])
    return int(buf[p]) + int(buf[p + 1]) * 256


@njit
def header_length(buf, p):
    """The length of a planar_code header (``>>planar_code<<``, ``... le<<``, ``... be<<``) at
    ``buf[p]``, or 0. Streams written one after another (``cat a.pc b.pc``) have one in the
    middle, where a record would start; no record can start so: n would be 62 ('>') and its
    first list hold 112 ('p')."""
    size = buf.shape[0]
    if p + 15 > size:
        return 0
    for i in range(13):
        if buf[p + i] != _HEADER[i]:
            return 0
    if buf[p + 13] == 60 and buf[p + 14] == 60:  # "<<"
        return 15
    if p + 18 > size or buf[p + 13] != 32 or buf[p + 16] != 60 or buf[p + 17] != 60:
        return 0
    endian = (buf[p + 14], buf[p + 15])
    return 18 if endian == (108, 101) or endian == (98, 101) else 0  # "le", "be"


@njit(inline="always")
def _zero_count(buf, a, b):
    """The number of 0 bytes among ``buf[a:b]``: a plain loop, which LLVM vectorizes, many bytes
    a step; it is faster than counting eight bytes at a time in uint64 words, which would also
    need the buffer on an 8-byte boundary."""
    zeros = 0
    for i in range(a, b):
        zeros += buf[at(i)] == 0
    return zeros


@njit
def _scan(buf, big_endian, max_records, starts):
    """Count complete records from the start of ``buf``; record r starts at ``starts[r]``
    (int64[max_records + 1]; the entry after the last record is where it ends).

    Returns ``(records, vertices, entries, consumed)``: entries counts neighbours, and
    ``consumed`` is the number of bytes of complete records (a cut-off record is left unread).
    The scan stops before a header (:func:`header_length`): the caller reads it.
    """
    size = buf.shape[0]
    p = np.int64(0)  # not the literal 0, for which numba would compile header_length again
    records = vertices = entries = 0
    starts[0] = 0
    while p < size and records < max_records:
        if buf[p] == 62 and header_length(buf, p):
            break
        wide = buf[p] == 0
        width = 2 if wide else 1
        q = p + 1 if wide else p
        if q + width > size:
            break
        n = _entry(buf, q, wide, big_endian)
        q += width
        seen = 0
        nbrs = 0
        if wide:
            while seen < n and q + width <= size:
                x = _entry(buf, q, wide, big_endian)
                q += width
                if x == 0:
                    seen += 1
                else:
                    nbrs += 1
        else:
            start = q
            # A triangulation's n lists hold 6n - 12 neighbours and n zeros. If the bytes up to
            # there hold n zeros, the last of them 0, the n-th zero is that last byte.
            end = q + 7 * n - 12
            if n >= 3 and end <= size and buf[end - 1] == 0 and _zero_count(buf, q, end) == n:
                seen, q = n, end
            else:  # count the 0 bytes one by one, no branch per entry
                while seen < n and q < size:
                    seen += buf[q] == 0
                    q += 1
            nbrs = q - start - seen
        if seen < n:
            break
        records += 1
        vertices += n
        entries += nbrs
        p = q
        starts[records] = p
    return records, vertices, entries, p


@njit
def _fill(buf, big_endian, records, starts, face_offsets, nbr_offsets, neighbors):
    """Fill CSR arrays for the first ``records`` records (found and sized by :func:`_scan`,
    which put their starts in ``starts``); ``neighbors`` has one slot to spare.

    Neighbours become 0-based; an entry larger than n stays out of range for validation to flag.
    """
    f = 0
    m = 0
    face_offsets[0] = 0
    nbr_offsets[0] = 0
    for r in range(records):
        p = starts[r]
        wide = buf[p] == 0
        width = 2 if wide else 1
        q = p + 1 if wide else p
        n = _entry(buf, q, wide, big_endian)
        q += width
        if not wide:
            # Every byte is stored, a 0 as -1 in the slot the next neighbour takes (at the end,
            # the spare one), and the list's end is written until its 0 comes: no branch per
            # byte, where a loop per list would mispredict at each list's end.
            for i in range(q, starts[r + 1]):
                x = int(buf[at(i)])
                neighbors[at(m)] = x - 1
                m += x != 0
                nbr_offsets[at(f + 1)] = m
                f += x == 0
        else:
            for _ in range(n):
                x = _entry(buf, q, wide, big_endian)
                q += width
                while x != 0:
                    neighbors[m] = x - 1
                    m += 1
                    x = _entry(buf, q, wide, big_endian)
                    q += width
                f += 1
                nbr_offsets[f] = m
        face_offsets[r + 1] = f
