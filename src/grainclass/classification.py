"""`classify`: one batch of grains in, one Arrow table of per-grain results out."""

from __future__ import annotations

import numpy as np
import pyarrow as pa

from grainclass import schema
from grainclass._kernels import codes
from grainclass.batch import GrainBatch

_FAMILY_NAMES = np.array(codes.FAMILY_NAMES, dtype=object)
_STATUS_NAMES = np.array(codes.STATUS_NAMES, dtype=object)

_MESSAGES = {
    codes.E_TOO_FEW_FACES: "{a} faces; a grain needs at least 4",
    codes.E_INDEX_RANGE: "face {a} lists face {b}, but the faces are numbered 0..{last}",
    codes.E_SELF: "face {a} lists itself as a neighbour",
    codes.E_ASYMMETRIC: "asymmetric adjacency: face {a} lists face {b}, "
    "but face {b} does not list face {a} as often",
    codes.E_FEW_NEIGHBOURS: "face {a} has {b} neighbour(s); a face needs at least 2",
    codes.E_TWO_GON: "degenerate: face {a} is a 2-gon",
    codes.E_SHARED_EDGES: "degenerate: faces {a} and {b} share more than one edge",
    codes.E_DISCONNECTED: "not connected: face {a} cannot be reached from face 0",
    codes.E_TOO_MANY_EDGES: "not a sphere: {a} adjacencies, but a grain with {n} faces "
    "has at most 3n-6 = {b}",
    codes.E_EULER: "not a sphere: the neighbour lists, read as cyclic orders, "
    "describe a surface of Euler characteristic {a}",
    codes.E_UNORDERED: "not a simple grain ({a} adjacencies, 3n-6 = {b}) and the neighbour "
    "lists are not in cyclic order, so the corners cannot be recovered",
    codes.E_NOT_SPHERE: "not a sphere: {edges} adjacencies, but the triangles around "
    "faces {a} and {b} do not close up into a sphere",
    codes.E_NON_SIMPLE: "non-simple: a corner where {a} faces meet (face {b} is one of them)",
}


def _where(batch: GrainBatch, g: int) -> str:
    if batch.location_kind == "line":
        return f"{batch.source}:{batch.location[g]}"
    return f"{batch.source}: record {batch.location[g]}"


def _error_messages(batch: GrainBatch, status: np.ndarray, err: np.ndarray) -> list[str | None]:
    messages: list[str | None] = [None] * len(batch)
    n_faces = batch.n_faces
    for g in np.flatnonzero(status != codes.OK):
        code, a, b = (int(x) for x in err[g])
        if code == codes.E_PARSE:
            what = batch.parse_error[g] or "unreadable record"
        else:
            n = int(n_faces[g])
            what = _MESSAGES[code].format(a=a, b=b, n=n, last=n - 1, edges=3 * n - 6)
        messages[g] = f"{_where(batch, g)}: {what}"
    return messages


def _nullable(values: np.ndarray, valid: np.ndarray, type_: pa.DataType) -> pa.Array:
    return pa.array(values, type=type_, mask=~valid)


def _p_vectors(batch: GrainBatch, ok: np.ndarray) -> tuple[pa.Array, np.ndarray]:
    """p-vectors (faces with 3, 4, ... sides up to the largest) and triangle counts per grain."""
    n_faces = batch.n_faces
    degree = np.diff(batch.nbr_offsets)
    grain_of_face = np.repeat(np.arange(len(batch)), n_faces)
    face_ok = ok[grain_of_face]
    largest = np.zeros(len(batch), np.int64)
    np.maximum.at(largest, grain_of_face[face_ok], degree[face_ok])
    lengths = np.where(ok, largest - 2, 0)
    list_offsets = np.concatenate([[0], np.cumsum(lengths)])
    slot = list_offsets[grain_of_face[face_ok]] + degree[face_ok] - 3
    counts = np.bincount(slot, minlength=int(list_offsets[-1])).astype(np.int32)
    p_vector = pa.ListArray.from_arrays(
        pa.array(list_offsets.astype(np.int32)), pa.array(counts), mask=pa.array(~ok)
    )
    triangles = np.bincount(grain_of_face[face_ok & (degree == 3)], minlength=len(batch))
    return p_vector, triangles


def _trees_column(
    offsets: np.ndarray, data: np.ndarray, length: np.ndarray, valid: np.ndarray
) -> pa.Array:
    """Compact the kernel's fixed-size slots into an Arrow string array."""
    size = np.diff(offsets)
    local = np.arange(int(offsets[-1])) - np.repeat(offsets[:-1], size)
    keep = local < np.repeat(length, size)
    string_offsets = np.concatenate([[0], np.cumsum(length)]).astype(np.int32)
    validity = pa.py_buffer(np.packbits(valid, bitorder="little"))
    return pa.Array.from_buffers(
        pa.string(),
        len(length),
        [validity, pa.py_buffer(string_offsets), pa.py_buffer(data[keep])],
    )


def _class_names(family: np.ndarray, truncations: np.ndarray, n_trees: np.ndarray) -> np.ndarray:
    names = np.full(len(family), None, dtype=object)
    flag = family == codes.FLAG
    sc = family == codes.SC
    names[family == codes.STACKED] = "stacked"
    names[flag & (truncations == 0)] = "flag"
    names[flag & (truncations == 1)] = "flag+1"
    names[flag & (truncations == 2) & (n_trees == 2)] = "flag+1+1"
    names[flag & (truncations == 2) & (n_trees == 1)] = "flag+2"
    names[flag & (truncations >= 3)] = "flag>=3"
    names[sc & (truncations == 0)] = "sc"
    names[sc & (truncations == 1)] = "sc+1"
    names[sc & (truncations >= 2)] = "sc>=2"
    return names


def classify(batch: GrainBatch) -> pa.Table:
    """Classify every grain of a batch (Lutz et al., Secs. II-III and App. B).

    Parameters
    ----------
    batch : GrainBatch
        Grains as flat face-adjacency arrays, as the readers produce them.

    Returns
    -------
    pyarrow.Table
        One row per grain, in input order, with the columns of
        :data:`grainclass.schema.GRAIN_SCHEMA` followed by any extra string attributes of the
        input. Grains that are not simple polytopes keep their row: their status says why and
        their classification is null.

    Examples
    --------
    >>> cube = [[1, 2, 3, 4], [0, 4, 5, 2], [0, 1, 5, 3], [0, 2, 5, 4], [0, 3, 5, 1], [1, 4, 3, 2]]
    >>> row = classify(GrainBatch.from_lists([cube])).to_pylist()[0]
    >>> row["class"], row["split_k"], row["split_m"], row["penalty"]
    ('flag', 1, 1, 18)
    """
    from grainclass._kernels.batch import _classify_batch

    g = len(batch)
    n_faces = batch.n_faces
    parsed = np.array([e is None for e in batch.parse_error], dtype=np.bool_)
    status = np.zeros(g, np.int8)
    err = np.zeros((g, 3), np.int64)
    family = np.full(g, -1, np.int8)
    fundamental = np.zeros(g, np.int32)
    n_trees = np.zeros(g, np.int32)
    depth = np.zeros(g, np.int32)
    belts = np.zeros((g, 3), np.int64)
    tree_offsets = np.concatenate([[0], np.cumsum(3 * n_faces)]).astype(np.int64)
    tree_bytes = np.zeros(int(tree_offsets[-1]), np.uint8)
    tree_length = np.zeros(g, np.int64)
    _classify_batch(
        batch.face_offsets,
        batch.nbr_offsets,
        batch.neighbors,
        parsed,
        status,
        err,
        family,
        fundamental,
        n_trees,
        depth,
        belts,
        tree_offsets,
        tree_bytes,
        tree_length,
    )

    ok = status == codes.OK
    truncations = n_faces - fundamental
    stacked = family == codes.STACKED
    flag_family = family == codes.FLAG
    has_trees = ok & ~stacked
    is_flag = flag_family & (truncations == 0)
    p_vector, triangles = _p_vectors(batch, ok)
    split_k = belts[:, 0]
    volume = batch.volume if batch.volume is not None else np.full(g, np.nan)
    area = batch.area if batch.area is not None else np.full(g, np.nan)
    with np.errstate(divide="ignore", invalid="ignore"):
        isoperimetric = 36 * np.pi * volume**2 / area**3

    columns = {
        schema.GRAIN_ID: pa.array(batch.grain_id, pa.string()),
        schema.SOURCE: pa.array([batch.source] * g, pa.string()),
        schema.STATUS: pa.array(_STATUS_NAMES[status], pa.string()),
        schema.ERROR: pa.array(_error_messages(batch, status, err), pa.string()),
        schema.N_FACES: _nullable(n_faces, parsed, pa.int32()),
        schema.N_TRIANGLES: _nullable(triangles, ok, pa.int32()),
        schema.P_VECTOR: p_vector,
        schema.FAMILY: pa.array(_FAMILY_NAMES[np.where(ok, family, 0)], pa.string(), mask=~ok),
        schema.CLASS: pa.array(_class_names(family, truncations, n_trees), pa.string()),
        schema.TRUNCATIONS: _nullable(truncations, ok, pa.int32()),
        schema.FUNDAMENTAL_FACES: _nullable(fundamental, ok, pa.int32()),
        schema.TREES: _trees_column(tree_offsets, tree_bytes, tree_length, has_trees),
        schema.DEPTH: _nullable(depth, has_trees, pa.int32()),
        schema.ROUND_K: _nullable(truncations, ok & (stacked | flag_family), pa.int32()),
        schema.SPLIT_K: _nullable(split_k, is_flag, pa.int32()),
        schema.SPLIT_M: _nullable(n_faces - 4 - split_k, is_flag, pa.int32()),
        schema.BELTS4: _nullable(belts[:, 1], is_flag, pa.int32()),
        schema.PENALTY: _nullable(n_faces * belts[:, 2], is_flag, pa.int64()),
        schema.VOLUME: pa.array(volume, pa.float64(), from_pandas=True),
        schema.AREA: pa.array(area, pa.float64(), from_pandas=True),
        schema.ISOPERIMETRIC: pa.array(isoperimetric, pa.float64(), from_pandas=True),
    }
    table = pa.table(columns, schema=schema.GRAIN_SCHEMA)
    for key, values in batch.attributes.items():
        if key not in schema.COLUMNS:  # an input field may not overwrite a result column
            table = table.append_column(pa.field(key, pa.string()), pa.array(values, pa.string()))
    return table
