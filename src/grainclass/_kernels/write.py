"""Grains written back as bytes: adjacency text lines and planar_code records."""

import numpy as np

from grainclass._kernels.columns import _digits, _write_digits
from grainclass._numba import at, njit


@njit
def _faces_length(face_offsets, nbr_offsets, neighbors, g):
    """Bytes of grain g's faces field (``1 2 3;0 4 5 2;...``)."""
    a, b = face_offsets[g], face_offsets[g + 1]
    size = max(b - a - 1, 0)  # the ";"s
    for f in range(a, b):
        size += max(nbr_offsets[f + 1] - nbr_offsets[f] - 1, 0)  # the spaces
        for i in range(nbr_offsets[f], nbr_offsets[f + 1]):
            size += _digits(neighbors[at(i)])
    return size


@njit
def _adjacency_text(
    id_offsets, id_bytes, face_offsets, nbr_offsets, neighbors, field_offsets, field_bytes
):
    """Adjacency text, a line per grain: its id (``id_bytes[id_offsets[g]:id_offsets[g + 1]]``),
    a TAB, its faces, its fields (for each row c of ``field_offsets``, int64[C, G + 1], the
    bytes ``field_bytes[field_offsets[c, g]:field_offsets[c, g + 1]]``: ``<TAB>key=value`` or
    nothing) and a newline, as one uint8 array."""
    n_grains = face_offsets.shape[0] - 1
    n_fields = field_offsets.shape[0]
    ends = np.zeros(n_grains + 1, np.int64)
    for g in range(n_grains):
        size = id_offsets[g + 1] - id_offsets[g] + 2  # the TAB and the newline
        size += _faces_length(face_offsets, nbr_offsets, neighbors, g)
        for c in range(n_fields):
            size += field_offsets[c, g + 1] - field_offsets[c, g]
        ends[g + 1] = ends[g] + size
    data = np.empty(ends[n_grains], np.uint8)
    for g in range(n_grains):
        p = ends[g]
        for i in range(id_offsets[g], id_offsets[g + 1]):
            data[at(p)] = id_bytes[at(i)]
            p += 1
        data[at(p)] = 9  # TAB
        p += 1
        for f in range(face_offsets[g], face_offsets[g + 1]):
            if f > face_offsets[g]:
                data[at(p)] = 59  # ";"
                p += 1
            for i in range(nbr_offsets[f], nbr_offsets[f + 1]):
                if i > nbr_offsets[f]:
                    data[at(p)] = 32  # " "
                    p += 1
                p = _write_digits(data, p, neighbors[at(i)])
        for c in range(n_fields):
            for i in range(field_offsets[c, g], field_offsets[c, g + 1]):
                data[at(p)] = field_bytes[at(i)]
                p += 1
        data[at(p)] = 10  # newline
    return data


@njit
def _planar_code(face_offsets, nbr_offsets, neighbors):
    """plantri's planar_code records of the grains (without a header): n, then each face's
    neighbours 1-based and a 0, in 1-byte entries; a grain of more than 255 faces, or one
    that lists a face numbered past 255 from 1, in 2-byte entries (little-endian, as after the
    header ``>>planar_code<<`` or ``>>planar_code le<<``) after a 0 byte."""
    n_grains = face_offsets.shape[0] - 1
    ends = np.zeros(n_grains + 1, np.int64)
    wide = np.zeros(n_grains, np.bool_)
    for g in range(n_grains):
        a, b = face_offsets[g], face_offsets[g + 1]
        largest = b - a
        for i in range(nbr_offsets[a], nbr_offsets[b]):
            largest = max(largest, neighbors[at(i)] + 1)
        wide[g] = largest > 255
        entries = 1 + (nbr_offsets[b] - nbr_offsets[a]) + (b - a)
        ends[g + 1] = ends[g] + (1 + 2 * entries if wide[g] else entries)
    data = np.empty(ends[n_grains], np.uint8)
    for g in range(n_grains):
        a, b = face_offsets[g], face_offsets[g + 1]
        p = ends[g]
        if wide[g]:
            data[p] = 0
            p += 1
            p = _entry2(data, p, b - a)
            for f in range(a, b):
                for i in range(nbr_offsets[f], nbr_offsets[f + 1]):
                    p = _entry2(data, p, neighbors[i] + 1)
                p = _entry2(data, p, 0)
        else:
            data[p] = b - a
            p += 1
            for f in range(a, b):
                for i in range(nbr_offsets[f], nbr_offsets[f + 1]):
                    data[at(p)] = neighbors[at(i)] + 1
                    p += 1
                data[at(p)] = 0
                p += 1
    return data


@njit(inline="always")
def _entry2(data, p, value):
    """A 2-byte little-endian entry at ``data[p:]``; returns the end."""
    data[p] = value & 255
    data[p + 1] = (value >> 8) & 255
    return p + 2
