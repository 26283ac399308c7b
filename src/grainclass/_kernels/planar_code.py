"""plantri's planar_code, parsed from a byte buffer in two compiled passes (count, then fill).

A record is the vertex count n followed, for each vertex 1..n, by its neighbours (1-based, in
rotational order) and a 0. Counts below 256 use 1-byte entries; otherwise the record starts with
a 0 byte and every entry, n included, is 2 bytes in the stream's byte order.
"""

from grainclass._numba import njit


@njit
def _entry(buf, p, wide, big_endian):
    # int(): uint8 arithmetic would wrap at 256 when run as plain Python (NUMBA_DISABLE_JIT).
    if not wide:
        return int(buf[p])
    if big_endian:
        return int(buf[p]) * 256 + int(buf[p + 1])
    return int(buf[p]) + int(buf[p + 1]) * 256


@njit
def _scan(buf, big_endian, max_records, starts):
    """Count complete records from the start of ``buf``; record r starts at ``starts[r]``
    (int64[max_records + 1]; the entry after the last record is where it ends).

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
        else:  # plantri's usual records: count the 0 bytes, no branch per entry
            start = q
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
def _fill(buf, big_endian, records, face_offsets, nbr_offsets, neighbors):
    """Fill CSR arrays for the first ``records`` records (sized by :func:`_scan`).

    Neighbours become 0-based; an entry larger than n stays out of range for validation to flag.
    """
    p = 0
    f = 0
    m = 0
    face_offsets[0] = 0
    nbr_offsets[0] = 0
    for r in range(records):
        wide = buf[p] == 0
        width = 2 if wide else 1
        q = p + 1 if wide else p
        n = _entry(buf, q, wide, big_endian)
        q += width
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
        p = q
