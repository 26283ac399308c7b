"""The paper's tables that the reproduce scripts and the tests compare with.

Transcribed by hand from Lutz, Mason, Lazar and MacPherson, *Roundness of grains in cellular
microstructures* (the LaTeX source, tables named by their labels below), never produced by
grainclass. The scripts import this module from beside them; the tests import it too (pytest's
``pythonpath`` in pyproject.toml holds ``scripts``), so that neither depends on the other.
"""

from __future__ import annotations

# tbl:few_vertices_I, rows n = 6..12: n -> all, min. deg. >= 4, flag
TABLE_I = {
    6: (2, 1, 1),
    7: (5, 1, 1),
    8: (14, 2, 2),
    9: (50, 5, 4),
    10: (233, 12, 10),
    11: (1249, 34, 25),
    12: (7595, 130, 87),
}
# tbl:few_vertices_II: n -> all, stacked, flag, flag+1, flag+1+1, flag+2, flag>=3, sc, sc+1, sc>=2
TABLE_II = {
    4: (1, 1, 0, 0, 0, 0, 0, 0, 0, 0),
    5: (1, 1, 0, 0, 0, 0, 0, 0, 0, 0),
    6: (2, 1, 1, 0, 0, 0, 0, 0, 0, 0),
    7: (5, 3, 1, 1, 0, 0, 0, 0, 0, 0),
    8: (14, 7, 2, 1, 3, 1, 0, 0, 0, 0),
    9: (50, 24, 4, 3, 5, 2, 11, 1, 0, 0),
    10: (233, 93, 10, 13, 19, 7, 86, 2, 3, 0),
    11: (1249, 434, 25, 47, 78, 30, 590, 9, 16, 20),
    12: (7595, 2110, 87, 217, 354, 127, 4301, 43, 99, 257),
    13: (49566, 11002, 313, 1041, 1799, 608, 30938, 212, 650, 3003),
    14: (339722, 58713, 1357, 5288, 9780, 3016, 224839, 1115, 3997, 31617),
}
# The columns of TABLE_II, as grainclass summarize names them.
CLASS_COLUMNS = ["all", "stacked", "flag", "flag+1", "flag+1+1", "flag+2", "flag>=3"]
CLASS_COLUMNS += ["sc", "sc+1", "sc>=2"]

# tbl:flag_few_vertices: n -> {k: number of flag triangulations of split type k:(n-4-k)}
SPLIT = {
    6: {1: 1},
    7: {1: 1},
    8: {2: 2},
    9: {1: 1, 2: 3},
    10: {1: 2, 2: 1, 3: 7},
    11: {1: 3, 2: 6, 3: 16},
    12: {0: 1, 1: 9, 2: 15, 3: 16, 4: 46},
    13: {1: 28, 2: 52, 3: 62, 4: 171},
    14: {0: 1, 1: 97, 2: 209, 3: 235, 4: 261, 5: 554},
}

# tbl:distribution, rows all*_{n=13} and all*_{n=14} (percent): round0, round<=1..6, sc
ROUND_ALL = {
    13: (0.63, 2.73, 7.59, 15.19, 25.63, 37.82, 51.59, 7.80),
    14: (0.40, 1.96, 5.72, 12.04, 20.81, 31.36, 43.11, 10.81),
}
# The columns of ROUND_ALL, as grainclass summarize names them.
ROUND_COLUMNS = ["round0"] + [f"round<={k}" for k in range(1, 7)] + ["sc"]

# The Poisson-Voronoi data set V-268402: its grains, and tbl:distribution_V_data, total row.
V_GRAINS = 268_402
V_CLASSES = {
    "stacked": 1902,
    "flag": 27810,
    "flag+1": 59715,
    "flag+1+1": 60760,
    "flag+2": 6530,
    "flag>=3": 108422,
    "sc": 315,
    "sc+1": 743,
    "sc>=2": 2205,
}
# tbl:distribution, row V-268402 (percent).
V_ROUND = {
    "round0": 10.36,
    "round<=1": 32.61,
    "round<=2": 57.71,
    "round<=3": 77.17,
    "round<=4": 88.85,
    "round<=5": 94.75,
    "round<=6": 97.32,
    "sc": 1.22,
}
