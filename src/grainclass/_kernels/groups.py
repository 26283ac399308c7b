"""Grouping equal keys in one pass with a hash table, where ``np.unique`` would sort.

A batch of a census has tens of thousands of grains but only a few hundred distinct
(status, n, family, class, round, split) keys: hashing them is linear, sorting is not. Keys are
non-negative int64; the table is open addressing, doubled whenever it is half full, with a row
of int64 values per slot (a group's index, or its running sums).
"""

import numpy as np

from grainclass._numba import njit

EMPTY = -1  # a free slot of the table
FIRST_SLOTS = 1024


@njit(inline="always")
def slot(table, key):
    """Where ``key`` is in ``table``, or the free slot where it goes."""
    mask = table.size - 1
    # Fibonacci hashing: the top bits of key * 2**64 / phi spread consecutive keys apart.
    s = np.int64((np.uint64(key) * np.uint64(11400714819323198485)) >> np.uint64(32)) & mask
    while table[s] != EMPTY and table[s] != key:
        s = (s + 1) & mask
    return s


@njit
def doubled(table, values):
    """``table`` and its ``values`` (one row per slot) rehashed into twice the slots."""
    bigger = np.full(2 * table.size, EMPTY, np.int64)
    moved = np.zeros((2 * table.size, values.shape[1]), np.int64)
    for s in range(table.size):
        if table[s] != EMPTY:
            t = slot(bigger, table[s])
            bigger[t] = table[s]
            # Element by element: a row assignment (moved[t] = values[s]) compiles numba's
            # broadcasting, with its shape-mismatch error, into a first run.
            for c in range(values.shape[1]):
                moved[t, c] = values[s, c]
    return bigger, moved


@njit(inline="always")
def insert(table, values, groups, key):
    """``(table, values, groups, s)``: ``key``'s slot s, taken if the key is new (``groups``,
    the number of keys, then grows by one, and the table doubles once it is half full)."""
    s = slot(table, key)
    if table[s] == EMPTY:
        table[s] = key
        groups += 1
        if 2 * groups > table.size:
            table, values = doubled(table, values)
            s = slot(table, key)
    return table, values, groups, s


@njit
def _group_keys(keys):
    """``(first, group)`` for int64 ``keys``: the first row of each distinct key, in order of
    first appearance, and each row's index into ``first``."""
    n = keys.shape[0]
    table = np.full(FIRST_SLOTS, EMPTY, np.int64)
    index = np.empty((FIRST_SLOTS, 1), np.int64)  # each key's group
    first = np.empty(n, np.int64)
    group = np.empty(n, np.int64)
    groups = 0
    for i in range(n):
        known = groups
        table, index, groups, s = insert(table, index, groups, keys[i])
        if groups > known:
            index[s, 0] = known
            first[known] = i
        group[i] = index[s, 0]
    return first[:groups].copy(), group
