"""The words grainclass reads and writes: statuses, families, classes, formats and tables.

Plain tuples in a module that imports nothing, so that the command line offers them as choices
without loading numpy, pyarrow or numba (``grainclass --help`` stays fast), and every module
that names them takes them from here.
"""

# The ``status`` column; a status code of ``_kernels.codes`` indexes this.
STATUSES = ("ok", "degenerate", "non_simple", "invalid")

# The ``family`` column; a family code of ``_kernels.codes`` indexes this.
FAMILIES = ("stacked", "flag", "sc")

# The ``class`` column: the columns of the paper's Tables II, V, R and E, in their order
# (``_kernels.codes.CLASS_OF`` gives the index).
CLASSES = ("stacked", "flag", "flag+1", "flag+1+1", "flag+2", "flag>=3", "sc", "sc+1", "sc>=2")

# Formats of grain inputs (sniffed when not named).
INPUT_FORMATS = (
    "adjacency",
    "planar_code",
    "evolver",
    "voro",
    "neper",
    "loops",
    "npy",
    "tiff",
    "dream3d",
    "vti",
    "spparks",
    "tesr",
)

# Formats of summaries and type tables.
OUTPUT_FORMATS = ("text", "csv", "markdown", "latex", "json", "parquet")

# The summary tables printed by default, in order; "geometry" only on request.
TABLES = ("classes", "round", "split")
ALL_TABLES = (*TABLES, "geometry")

# Kinds of `grainclass plot`: the paper's figures.
PLOT_KINDS = (
    "round",
    "classes",
    "faces-q",
    "round-q",
    "penalty",
    "ranks",
    "evolution",
    "edge-errors",
)

# Candidate penalties of flag types (``grainclass penalties``, ``plot penalty --penalty``).
PENALTIES = ("P4", "P4..L", "P4/sym", "P4..L/sym", "sym", "(1+P4)*sym", "(1+P4..L)*sym")

# Named grains that `grainclass plot evolution --series` follows beside the classes.
NAMED_SERIES = ("tetrahedron", "cube", "dodecahedron", "0:m", "triangles")

# What `grainclass draw` writes in each face: its number of sides, its id, or nothing.
FACE_LABELS = ("sides", "ids", "none")

# What flipping an edge gives (`grainclass draw --flips`): another type, the same, or no grain.
FLIP_RESULTS = ("other", "same", "none")


def plural(count: int, word: str, words: str | None = None) -> str:
    """``count`` and ``word``, in the plural (``words``, else ``word + "s"``) unless one.

    >>> plural(1, "grain"), plural(2_000, "grain"), plural(3, "body", "bodies")
    ('1 grain', '2000 grains', '3 bodies')
    """
    return f"{count} {word if count == 1 else words or word + 's'}"
