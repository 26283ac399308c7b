"""Integer codes that the kernels write and the Python wrappers turn into words.

Kept as plain module-level ints (and one constant array) so that numba folds them as constants.
"""

import numpy as np

# Grain status, an index into ``vocabulary.STATUSES``; PENDING only between the fast and the
# general path.
PENDING = -1
OK = 0
DEGENERATE = 1
NON_SIMPLE = 2
INVALID = 3

# What is wrong with a grain; the kernels also write two integers (a, b) of detail. A grain's
# row of codes starts as zeros: 0 is no code.
E_PARSE = 1  # the reader could not parse the record (message comes from the reader)
E_TOO_FEW_FACES = 2  # a = number of faces
E_INDEX_RANGE = 3  # face a lists face b, which does not exist
E_SELF = 4  # face a lists itself
E_ASYMMETRIC = 5  # face a lists face b, but face b does not list face a as often
E_FEW_NEIGHBOURS = 6  # face a has b < 2 neighbours
E_TWO_GON = 7  # face a has only two neighbours (degenerate)
E_SHARED_EDGES = 8  # faces a and b share b > 1 edges (degenerate)
E_DISCONNECTED = 9  # face a cannot be reached from face 0
E_TOO_MANY_EDGES = 10  # a adjacencies, but a sphere with n faces has at most b = 3n - 6
E_EULER = 11  # the neighbour lists describe a surface of Euler characteristic a, not 2
E_UNORDERED = 12  # not a triangulation and the lists are not cyclic: cannot embed
E_NOT_SPHERE = 13  # 3n - 6 adjacencies but no sphere (the triangle at face a is wrong)
E_NON_SIMPLE = 14  # a corner where a > 3 faces meet, one of them face b
E_TOO_LARGE = 15  # the general path could need a bytes for the grain, more than the limit b
E_FOREST_TOO_LARGE = 16  # its truncation forest's strings would take a bytes, more than b
E_MEMORY = 17  # the system refused memory that the grain needed (a, b: 0)

# Families, an index into ``vocabulary.FAMILIES``; -1 when the grain is not ok.
STACKED = 0
FLAG = 1
SC = 2

# A grain's class (an index into ``vocabulary.CLASSES``) by [family, min(truncations, 3), whether it
# has two truncation trees]: the kernels that count read it per grain, the Python wrappers with
# numpy's indexing, so the classes are defined once.
CLASS_OF = np.array(
    [
        [[0, 0], [0, 0], [0, 0], [0, 0]],  # stacked
        [[1, 1], [2, 2], [4, 3], [5, 5]],  # flag, flag+1, flag+2 (one tree) or flag+1+1, flag>=3
        [[6, 6], [7, 7], [8, 8], [8, 8]],  # sc, sc+1, sc>=2
    ],
    np.int8,
)
