"""Kernels that lay out output columns as Arrow buffers, so no Python loop runs per grain."""

import numpy as np

from grainclass._numba import at, njit


@njit
def _p_vectors(face_offsets, nbr_offsets, ok):
    """p-vectors as a list column: (offsets int32[G+1], counts int32[...], triangles int32[G]).

    Grain g's list has one count per face size 3 .. its largest (empty when not ok).
    """
    n_grains = face_offsets.shape[0] - 1
    offsets = np.zeros(n_grains + 1, np.int32)
    triangles = np.zeros(n_grains, np.int32)
    for g in range(n_grains):
        largest = 2
        if ok[g]:
            for f in range(face_offsets[g], face_offsets[g + 1]):
                largest = max(largest, nbr_offsets[at(f + 1)] - nbr_offsets[at(f)])
        offsets[g + 1] = offsets[g] + largest - 2
    counts = np.zeros(offsets[n_grains], np.int32)
    for g in range(n_grains):
        if ok[g]:
            for f in range(face_offsets[g], face_offsets[g + 1]):
                size = nbr_offsets[at(f + 1)] - nbr_offsets[at(f)]
                counts[at(offsets[g] + size - 3)] += 1
                if size == 3:
                    triangles[g] += 1
    return offsets, counts, triangles


@njit
def _triangle_counts(face_offsets, nbr_offsets, ok):
    """Triangular faces per grain (int32[G]; 0 when not ok)."""
    n_grains = face_offsets.shape[0] - 1
    triangles = np.zeros(n_grains, np.int32)
    for g in range(n_grains):
        if ok[g]:
            for f in range(face_offsets[g], face_offsets[g + 1]):
                triangles[g] += nbr_offsets[f + 1] - nbr_offsets[f] == 3
    return triangles


@njit
def _compact(slot_offsets, data, lengths):
    """Strings written at ``data[slot_offsets[g]:]`` with ``lengths[g]`` bytes, packed tightly.

    Returns Arrow string buffers (offsets int32[G+1], bytes).
    """
    n = lengths.shape[0]
    offsets = np.zeros(n + 1, np.int32)
    for g in range(n):
        offsets[g + 1] = offsets[g] + lengths[g]
    packed = np.empty(offsets[n], np.uint8)
    for g in range(n):
        for i in range(lengths[g]):
            packed[at(offsets[g] + i)] = data[at(slot_offsets[g] + i)]
    return offsets, packed


@njit
def _strings_from_codes(codes, names, name_offsets):
    """Arrow string buffers for ``names[codes[g]]``; a negative code gives an empty string."""
    n = codes.shape[0]
    offsets = np.zeros(n + 1, np.int32)
    for g in range(n):
        c = codes[g]
        offsets[g + 1] = offsets[g] + (name_offsets[c + 1] - name_offsets[c] if c >= 0 else 0)
    data = np.empty(offsets[n], np.uint8)
    for g in range(n):
        c = codes[g]
        if c >= 0:
            for i in range(offsets[g + 1] - offsets[g]):
                data[offsets[g] + i] = names[name_offsets[c] + i]
    return offsets, data


# Called with int32 and int64 positions and values: inlined where they are called, so that
# numba compiles no version of them for each mix of types.
@njit(inline="always")
def _digits(v):
    """Decimal digits of a non-negative integer."""
    digits = 1
    while v >= 10:
        v //= 10
        digits += 1
    return digits


@njit(inline="always")
def _write_digits(data, p, v):
    """Write the non-negative integer v in decimal at ``data[p:]``; returns the end."""
    end = p + _digits(v)
    for k in range(end - 1, p - 1, -1):
        data[k] = 48 + v % 10
        v //= 10
    return end


@njit
def _decimal_strings(values):
    """Arrow string buffers for the decimal digits of non-negative integers."""
    n = values.shape[0]
    offsets = np.zeros(n + 1, np.int32)
    for g in range(n):
        offsets[g + 1] = offsets[g] + _digits(values[g])
    data = np.empty(offsets[n], np.uint8)
    for g in range(n):
        _write_digits(data, offsets[g], values[g])
    return offsets, data


@njit
def _code_strings(codes, code_offsets, ok):
    """Arrow string buffers for Weinberg codes written as ``(1,2,3,...)``; empty when not ok.

    Codes whose labels all have one or two digits (those of grains up to 51 faces) are written
    without a loop per digit, whose varying length a branch predictor misses: that loop costs
    nearly as much as the Weinberg walks themselves.
    """
    n = ok.shape[0]
    offsets = np.zeros(n + 1, np.int32)
    small = np.zeros(n, np.bool_)
    for g in range(n):
        size = 0
        if ok[g]:
            a, b = code_offsets[g], code_offsets[g + 1]
            two, top = 0, 0
            for i in range(a, b):
                two += codes[at(i)] >= 10
                top = max(top, codes[at(i)])
            small[g] = top < 100
            size = 2 * (b - a) + 1 + two  # "(" or "," before each label, ")" after
            if not small[g]:
                for i in range(a, b):
                    size += _digits(codes[i]) - 1 - (codes[i] >= 10)
        offsets[g + 1] = offsets[g] + size
    data = np.empty(offsets[n], np.uint8)
    for g in range(n):
        if not ok[g]:
            continue
        a, b = code_offsets[g], code_offsets[g + 1]
        p = offsets[g]
        data[p] = 40  # "("
        if small[g]:
            for i in range(a, b):
                v = np.uint32(codes[at(i)])
                tens = v // np.uint32(10)
                units = v - tens * np.uint32(10)
                # A single digit is written twice: the "," or ")" that follows comes over it.
                data[at(p + 1)] = 48 + (tens if tens else units)
                data[at(p + 2)] = 48 + units
                p += 2 + (tens > 0)
                data[at(p)] = 44  # ","
        else:
            for i in range(a, b):
                p = _write_digits(data, p + 1, codes[i])
                data[p] = 44
        data[p] = 41  # ")", over the last ","
    return offsets, data


_FNV_BASIS = np.uint64(14695981039346656037)
_FNV_PRIME = np.uint64(1099511628211)


@njit(inline="always")
def _fnv_byte(h, byte):
    return (h ^ np.uint64(byte)) * _FNV_PRIME


@njit
def _code_hashes(codes, code_offsets, ok):
    """:func:`_fnv1a` of the strings :func:`_code_strings` would write, without writing them
    (``summarize --types`` only counts distinct codes): 0 where not ok."""
    n = ok.shape[0]
    out = np.zeros(n, np.uint64)
    digits = np.empty(20, np.uint8)
    for g in range(n):
        if not ok[g]:
            continue
        h = _fnv_byte(_FNV_BASIS, 40)  # "("
        for i in range(code_offsets[g], code_offsets[g + 1]):
            if i > code_offsets[g]:
                h = _fnv_byte(h, 44)  # ","
            v = codes[at(i)]
            if v < 10:
                h = _fnv_byte(h, 48 + v)
            elif v < 100:
                tens = v // 10
                h = _fnv_byte(_fnv_byte(h, 48 + tens), 48 + v - 10 * tens)
            else:
                end = _write_digits(digits, 0, v)
                for k in range(end):
                    h = _fnv_byte(h, digits[k])
        out[g] = _fnv_byte(h, 41)  # ")"
    return out


@njit
def _fnv1a(offsets, data):
    """64-bit FNV-1a hash of each string of an Arrow string array (offsets, bytes)."""
    n = offsets.shape[0] - 1
    out = np.empty(n, np.uint64)
    for g in range(n):
        h = _FNV_BASIS
        for i in range(offsets[g], offsets[g + 1]):
            h = _fnv_byte(h, data[at(i)])
        out[g] = h
    return out
