"""plantri's planar_code, parsed from a byte buffer in two compiled passes (count, then fill).

A record is the vertex count n followed, for each vertex 1..n, by its neighbours (1-based, in
rotational order) and a 0. Counts below 256 use 1-byte entries; otherwise the record starts with
a 0 byte and every entry, n included, is 2 bytes in the stream's byte order.
"""

import numpy as np

from grainclass._kernels.bits import popcount
from grainclass._numba import at, njit

_LOW7 = np.uint64(0x7F7F7F7F7F7F7F7F)
_HIGH = np.uint64(0x8080808080808080)
_ALL = np.uint64(0xFFFFFFFFFFFFFFFF)


@njit
def _entry(buf, p, wide, big_endian):
    # int(): uint8 arithmetic would wrap at 256 when run as plain Python (NUMBA_DISABLE_JIT).
    if not wide:
        return int(buf[p])
    if big_endian:
        return int(buf[p]) * 256 + int(buf[p + 1])
    return int(buf[p]) + int(buf[p + 1]) * 256


@njit
def _zero_bytes(words, a, b):
    """The number of 0 bytes among bytes a..b-1 (a < b) of little-endian ``words``.

    Eight at a time: in ((w & 0x7F..) + 0x7F..) | w the high bit of a byte is set exactly when
    the byte is not 0, and no carry crosses into the next byte. Bytes outside a..b-1 in the
    first and last word are set to 0xFF first.
    """
    first, last = a >> 3, (b - 1) >> 3
    zeros = 0
    for k in range(first, last + 1):
        w = words[k]
        if k == first:
            w |= _ALL >> np.uint64(64 - 8 * (a & 7)) if a & 7 else np.uint64(0)
        if k == last and b & 7:
            w |= _ALL << np.uint64(8 * (b & 7))
        zeros += 8 - popcount((((w & _LOW7) + _LOW7) | w) & _HIGH)
    return zeros


@njit
def _scan(buf, words, offset, big_endian, max_records, starts):
    """Count complete records from the start of ``buf``; record r starts at ``starts[r]``
    (int64[max_records + 1]; the entry after the last record is where it ends).

    ``words`` are the bytes of ``buf``, from ``offset`` bytes before its start, as little-endian
    uint64 (empty if there are none such): where a triangulation's record would end, its
    bytes' zeros are counted eight at a time.

    Returns ``(records, vertices, entries, consumed)``: entries counts neighbours, and
    ``consumed`` is the number of bytes of complete records (a cut-off record is left unread).
    """
    size = buf.shape[0]
    p = 0
    records = vertices = entries = 0
    starts[0] = 0
    while p < size and records < max_records:
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
            if (
                n >= 3
                and offset + end <= 8 * words.shape[0]
                and buf[end - 1] == 0
                and _zero_bytes(words, offset + q, offset + end) == n
            ):
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
