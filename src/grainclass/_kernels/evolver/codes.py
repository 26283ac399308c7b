"""The codes that the Evolver kernels write and ``readers/evolver.py`` turns into messages: entry
kinds and statuses, where a number left to Python goes, a file's status, a grain's code."""

# Entry kinds, as the sections of a datafile: vertices, edges, facets (or faces), bodies.
VERTEX, EDGE, FACET, BODY = 0, 1, 2, 3

# Entry status: read, not readable, or a number the kernel leaves to Python's float().
ENTRY_OK, ENTRY_BAD, ENTRY_SLOW = 0, 1, 2

# Where a slow number goes: a vertex's coordinate 0-2, a body's volume, a file's period 0-8.
SLOW_VOLUME = 3
SLOW_PERIOD = 4

# File status from the tokenizer (the file is one invalid row unless FILE_OK).
FILE_OK = 0
FILE_LONG_ID = 1  # aux: entry kind, token start, token end
FILE_PERIODS = 2  # periods without three rows of three numbers
FILE_2D = 3  # space_dimension 2 (aux0: 1 for a string model)
FILE_STRING = 4  # string model in 3-space
FILE_SPACE = 5  # space_dimension other than 2 or 3 (aux0)
FILE_SIMPLEX = 6  # simplex_representation: facets given by vertices
FILE_SYMMETRY = 7  # symmetry_group: a quotient space

# Grain codes from the assembly; params in the order the reader's messages use them.
GRAIN_OK = 0
GRAIN_BODY_LINE = 1  # the body's line cannot be read
GRAIN_UNDEFINED = 2  # (kind, id, user kind, user id, line of an unreadable definition or 0)
GRAIN_TWICE = 3  # (facet id,): a non-periodic body lists a facet twice
GRAIN_TWICE_SAME = 4  # (facet id, times, sign): a periodic body lists it twice one way, or more
GRAIN_FACET_OPEN = 5  # (facet id, edge id): a facet's edges do not join up
GRAIN_FACET_WRAPS = 6  # (facet id,): a facet's wrap marks do not add up to nothing
GRAIN_NOT_CLOSED = 7  # (edge id, uses)
GRAIN_ORIENTATION = 8  # (facet id, facet id, edge id): both run along the edge the same way
GRAIN_UNPAIRED = 9  # (edge id, uses): the patches around an edge do not pair off
GRAIN_AROUND = 10  # (edge id,): the surface does not close once unwrapped
GRAIN_EULER = 11  # (V - E + F,)
GRAIN_PIECES = 12
GRAIN_NO_TRIPLE = 13
GRAIN_NOT_DISC = 14  # (face,)
GRAIN_NO_BODIES = 15  # (facets line or 0, kind of the first unreadable entry or -1, its line)
GRAIN_FILE = 16  # the file's status is not FILE_OK
GRAIN_POINT_EDGE = 17  # (edge id, uses): an edge the body uses more than twice has no length

# Users of an undefined id, for GRAIN_UNDEFINED.
USER_LIST, USER_FACET, USER_EDGE = 0, 1, 2
