"""The per-grain output table: column names and Arrow types, in one place."""

import pyarrow as pa

from grainclass import __version__

SCHEMA_VERSION = "6"

GRAIN_ID = "grain_id"
SOURCE = "source"
BOUNDARY = "boundary"
STATUS = "status"
ERROR = "error"
N_FACES = "n_faces"
N_TRIANGLES = "n_triangles"
P_VECTOR = "p_vector"
FAMILY = "family"
CLASS = "class"
TRUNCATIONS = "truncations"
FUNDAMENTAL_FACES = "fundamental_faces"
TREES = "trees"
DEPTH = "depth"
ROUND_K = "round_k"
SPLIT_K = "split_k"
SPLIT_M = "split_m"
BELTS4 = "belts4"
PENALTY = "penalty"
BELTS = "belts"
SPLITS = "splits"
BELT_PENALTIES = "belt_penalties"
WEINBERG = "weinberg"
SYMMETRY = "symmetry"
CHIRALITY = "chirality"
VOLUME = "volume"
AREA = "area"
ISOPERIMETRIC = "isoperimetric"
VOXELS = "voxels"
SHORTEST_TRIPLE_LINE = "shortest_triple_line"

GRAIN_SCHEMA = pa.schema(
    [
        (GRAIN_ID, pa.string()),
        (SOURCE, pa.string()),
        (BOUNDARY, pa.bool_()),
        (STATUS, pa.string()),
        (ERROR, pa.string()),
        (N_FACES, pa.int32()),
        (N_TRIANGLES, pa.int32()),
        (P_VECTOR, pa.list_(pa.int32())),
        (FAMILY, pa.string()),
        (CLASS, pa.string()),
        (TRUNCATIONS, pa.int32()),
        (FUNDAMENTAL_FACES, pa.int32()),
        (TREES, pa.string()),
        (DEPTH, pa.int32()),
        (ROUND_K, pa.int32()),
        (SPLIT_K, pa.int32()),
        (SPLIT_M, pa.int32()),
        (BELTS4, pa.int32()),
        (PENALTY, pa.int64()),
        (BELTS, pa.list_(pa.int64())),
        (SPLITS, pa.list_(pa.int32())),
        (BELT_PENALTIES, pa.list_(pa.int64())),
        (WEINBERG, pa.string()),
        (SYMMETRY, pa.int32()),
        (CHIRALITY, pa.int8()),
        (VOLUME, pa.float64()),
        (AREA, pa.float64()),
        (ISOPERIMETRIC, pa.float64()),
        (VOXELS, pa.int64()),
        (SHORTEST_TRIPLE_LINE, pa.int64()),
    ],
    metadata={"grainclass.schema_version": SCHEMA_VERSION, "grainclass.version": __version__},
)

COLUMNS = frozenset(GRAIN_SCHEMA.names)
