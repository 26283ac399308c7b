"""Grouping equal keys in one pass with a hash table, where ``np.unique`` would sort.

A batch of a census has tens of thousands of grains but only a few hundred distinct
(status, n, family, class, round, split) keys: hashing them is linear, sorting is not.
"""

import numpy as np

from grainclass._numba import njit

_EMPTY = -1


@njit
def _group_keys(keys):
    """``(first, group)`` for int64 ``keys``: the first row of each distinct key, in order of
    first appearance, and each row's index into ``first``. Open addressing, the table doubled
    whenever it is half full."""
    n = keys.shape[0]
    size = 1024
    slots = np.full(size, _EMPTY, np.int64)  # a group's index, or _EMPTY
    first = np.empty(n, np.int64)
    group = np.empty(n, np.int64)
    groups = 0
    for i in range(n):
        key = keys[i]
        # Fibonacci hashing: the top bits of key * 2**64 / phi spread consecutive keys apart.
        h = np.int64((np.uint64(key) * np.uint64(11400714819323198485)) >> np.uint64(32))
        mask = size - 1
        s = h & mask
        while slots[s] != _EMPTY and keys[first[slots[s]]] != key:
            s = (s + 1) & mask
        if slots[s] == _EMPTY:
            slots[s] = groups
            first[groups] = i
            groups += 1
            if 2 * groups > size:
                size *= 2
                slots = np.full(size, _EMPTY, np.int64)
                mask = size - 1
                for g in range(groups):
                    hg = np.uint64(keys[first[g]]) * np.uint64(11400714819323198485)
                    t = np.int64(hg >> np.uint64(32)) & mask
                    while slots[t] != _EMPTY:
                        t = (t + 1) & mask
                    slots[t] = g
            group[i] = groups - 1
        else:
            group[i] = slots[s]
    return first[:groups].copy(), group
