"""Ids to slots: each distinct id of a file's vertices, edges, facets or bodies gets a slot, a
row of that file's tables, counting up from 0 in the order the ids first come.

An :class:`IdMap` holds one kind's slots; :func:`_slot` looks an id up (or inserts it), and
:func:`_defined` says which entry defines each slot.
"""

from typing import NamedTuple

import numpy as np

from grainclass._kernels.evolver.codes import ENTRY_OK
from grainclass._numba import borrowed, njit, njit_leaf


class IdMap(NamedTuple):
    """Ids to slots. Ids from 0 to ``direct.shape[0] - 1`` (the usual 1, 2, 3, ... of a
    datafile) go straight to ``direct[id]``, others through open addressing in ``keys`` and
    ``slots`` (-1: free)."""

    keys: np.ndarray
    """int64[size]: the id in each used cell of the hash table"""
    slots: np.ndarray
    """int64[size]: its slot"""
    count: np.ndarray
    """int64[1]: slots given so far"""
    direct: np.ndarray
    """int64[most + 1]: the slot of each small id (-1: none yet)"""


class Defined(NamedTuple):
    """Per slot: its id and the lines that define it."""

    id: np.ndarray
    """int64[n]"""
    entry: np.ndarray
    """int64[n]: the entry of its last readable line (-1: none)"""
    bad: np.ndarray
    """int64[n]: the line of its last unreadable one (0: none)"""


@njit_leaf
def _hash(x, mask):
    h = np.uint64(x) * np.uint64(0x9E3779B97F4A7C15)
    return np.int64((h ^ (h >> np.uint64(31))) & np.uint64(mask))


@njit(inline="always")
def _new_map(n, most):
    """An empty map of up to ``n`` ids, ids up to ``most`` held directly (when ``most`` is not
    far beyond ``n``)."""
    size = 16
    while size < 2 * n:
        size *= 2
    direct = np.full(most + 1 if 0 <= most <= 4 * n + 64 else 0, -1, np.int64)
    return IdMap(
        np.empty(size, np.int64), np.full(size, -1, np.int64), np.zeros(1, np.int64), direct
    )


@njit_leaf
def _slot(table, x, insert):
    """The slot of id ``x``, or -1 if it has none and ``insert`` is False."""
    keys, slots, count, direct = table
    return _slot_at(keys, slots, count, direct, x, insert)


@njit_leaf
def _slot_at(keys, slots, count, direct, x, insert):
    """:func:`_slot` on an :class:`IdMap`'s arrays one by one: a loop over ids hands them as
    borrowed views (see ``tables._fill_sides``)."""
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


@njit
def _slots(ids, room):
    """A map with a slot for each distinct id of ``ids``, with room for ``room`` ids in all,
    and the slot of each."""
    most = -1
    for i in range(ids.shape[0]):
        most = max(most, ids[i])
    table = _new_map(room, most)
    slot = np.empty(ids.shape[0], np.int64)
    keys, slots, count = borrowed(table.keys), borrowed(table.slots), borrowed(table.count)
    direct = borrowed(table.direct)
    for i in range(ids.shape[0]):
        slot[i] = _slot_at(keys, slots, count, direct, ids[i], True)
    return table, slot


@njit
def _defined(rows, slot, n, entries):
    """For ``n`` slots, of which entries ``rows`` fill ``slot``: each slot's id and the lines
    that define it."""
    slot_id = np.empty(n, np.int64)
    entry = np.full(n, -1, np.int64)
    bad = np.zeros(n, np.int64)
    for j in range(rows.shape[0]):
        i = rows[j]
        slot_id[slot[j]] = entries.id[i]
        if entries.status[i] == ENTRY_OK:
            entry[slot[j]] = i
        else:
            bad[slot[j]] = entries.line[i]
    return Defined(slot_id, entry, bad)
