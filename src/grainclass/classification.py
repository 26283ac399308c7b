"""`classify`: one batch of grains in, one Arrow table of per-grain results out."""

from __future__ import annotations

import numpy as np
import pyarrow as pa

from grainclass import schema, vocabulary
from grainclass._kernels import codes
from grainclass._kernels.bits import MAX_BITSET_FACES
from grainclass.arrow import (
    booleans,
    floats,
    numbers,
    repeated_string,
    string_array,
    strings,
    strings_from_codes,
)
from grainclass.batch import GrainBatch
from grainclass.belt_columns import belt_lists, belt_profile
from grainclass.classified import Classified, GrainCodes
from grainclass.memory import each_grain, grain_memory_limit
from grainclass.messages import error_messages
from grainclass.parallel import run_ranges
from grainclass.weinberg_columns import Types, weinberg_strings, weinberg_types


def _floats(values: np.ndarray | None, length: int) -> pa.Array:
    return pa.nulls(length, pa.float64()) if values is None else floats(values)


def _counts(values: np.ndarray | None, length: int) -> pa.Array:
    """Counts as int64, null where missing (None, or a negative entry)."""
    if values is None:
        return pa.nulls(length, pa.int64())
    return numbers(np.asarray(values, np.int64), pa.int64(), np.asarray(values) >= 0)


def _classify_csr(
    batch: GrainBatch, max_small: int, strings: bool, limit: int | None = None
) -> Classified:
    """The fast path over the batch, then the general validation over the grains it left,
    then the general classification over the ok ones of more than ``max_small`` faces. A grain
    may take ``limit`` bytes on the general path (:func:`grain_memory_limit` by default)."""
    from grainclass._kernels.batch import _classify_batch

    limit = grain_memory_limit() if limit is None else limit
    out = Classified.empty(batch, strings)
    run_ranges(
        _classify_batch,
        len(batch),
        *_csr(batch),
        out.parsed,
        max_small,
        strings,
        out.status,
        out.consistent,
        out.err,
        *out.rows,
        *out.forests,
    )
    pending = np.flatnonzero(out.status == codes.PENDING)
    if len(pending):
        _validate_pending(batch, out, pending, max_small, strings, limit)
        pending = pending[out.status[pending] == codes.PENDING]
    if len(pending):
        _classify_general(batch, out, pending, strings, limit)
    return out


def _csr(batch: GrainBatch) -> tuple[np.ndarray, ...]:
    return (batch.face_offsets, batch.nbr_offsets, batch.neighbors)


def _validate_pending(
    batch: GrainBatch,
    out: Classified,
    pending: np.ndarray,
    max_small: int,
    strings: bool,
    limit: int | None = None,
) -> None:
    """The general validation of the grains ``pending`` (int64 indices) that the fast path
    left, into ``out``; those of at most ``max_small`` faces found ok are classified too. A
    grain may take ``limit`` bytes (:func:`grain_memory_limit` by default)."""
    from grainclass._kernels.batch import _validate_pending_batch

    limit = grain_memory_limit() if limit is None else limit
    arrays = (
        *_csr(batch),
        max_small,
        strings,
        limit,
        out.status,
        out.consistent,
        out.err,
        *out.rows,
        *out.forests,
    )
    each_grain(_validate_pending_batch, pending, arrays, out)


def _classify_general(
    batch: GrainBatch,
    out: Classified,
    pending: np.ndarray,
    strings: bool,
    limit: int | None = None,
) -> None:
    """The general classification of the grains ``pending`` (int64 indices), validated and too
    large for the fast path, into ``out`` (``limit`` as for :func:`_validate_pending`)."""
    from grainclass._kernels.batch import _classify_general_batch

    limit = grain_memory_limit() if limit is None else limit
    arrays = (*_csr(batch), strings, limit, out.status, out.err, *out.rows, *out.forests)
    each_grain(_classify_general_batch, pending, arrays, out)


def grain_codes(batch: GrainBatch, belt_length: int = 4) -> GrainCodes:
    """Classify a batch for counting only: no truncation-forest strings, no types; the split
    type that of the ``belt_length``-belts."""
    out = _classify_csr(batch, MAX_BITSET_FACES, strings=False)
    return _csr_grain_codes(batch, out, _splits(batch, out, belt_length))


def grain_codes_and_type_hashes(
    batch: GrainBatch, belt_length: int = 4
) -> tuple[GrainCodes, np.ndarray]:
    """:func:`grain_codes` of a CSR batch, with the 64-bit hash of the Weinberg vector that
    ``classify`` would write for each ok grain (:func:`grainclass.summary.type_hashes` of it;
    0 where not ok): what ``summarize --types`` counts, without the vectors' strings."""
    from grainclass._kernels.columns import _code_hashes

    out = _classify_csr(batch, MAX_BITSET_FACES, strings=False)
    split = _splits(batch, out, belt_length)
    types = weinberg_types(batch, out, True)
    with np.errstate(over="ignore"):  # FNV wraps modulo 2**64 on purpose (seen without the JIT)
        hashes = _code_hashes(types.weinberg, types.code_offsets, types.computed)
    return _csr_grain_codes(batch, out, split), hashes


def _splits(batch: GrainBatch, out: Classified, belt_length: int) -> np.ndarray:
    """Per grain, the k of the split type of its ``belt_length``-belts: the 4-belts'
    from the classification, other lengths' from :func:`belt_profile`."""
    if belt_length == 4:
        return out.belts[:, 0]
    return belt_profile(batch, out, belt_length)[:, belt_length - 3, 1]


def _csr_grain_codes(
    batch: GrainBatch, out: Classified, split: np.ndarray, triangles: np.ndarray | None = None
) -> GrainCodes:
    """:class:`GrainCodes` of a classified CSR batch, ``split`` the k of each grain's split
    type; ``triangles`` (per grain) are counted here unless the caller has them."""
    from grainclass._kernels.columns import _triangle_counts

    if triangles is None:
        triangles = _triangle_counts(batch.face_offsets, batch.nbr_offsets, out.status == codes.OK)
    from grainclass._kernels.batch import _grain_codes

    g = len(batch)
    n_faces = np.where(out.parsed, batch.n_faces, -1)
    grain = GrainCodes(
        n_faces=n_faces,
        status=out.status,
        family=out.family,
        truncations=np.empty(g, np.int64),
        class_code=np.empty(g, np.int8),
        round_k=np.empty(g, np.int64),
        split_k=np.empty(g, np.int64),
        triangles=triangles,
    )
    _grain_codes(
        out.status, n_faces, out.family, out.fundamental, out.n_trees,
        np.ascontiguousarray(split, np.int64), grain.truncations, grain.class_code,
        grain.round_k, grain.split_k,
    )  # fmt: skip
    return grain


def classify(
    batch: GrainBatch,
    max_bitset_faces: int = MAX_BITSET_FACES,
    types: bool = True,
    grain_memory: int | None = None,
    belts: int = 0,
) -> pa.Table:
    """Classify every grain of a batch (Lutz et al., Secs. II-III and App. B).

    Parameters
    ----------
    batch : GrainBatch
        Grains as flat face-adjacency arrays, as the readers produce them.
    max_bitset_faces : int
        Grains with at most this many faces (64 at most) may take the fast bitset path; 0 sends
        every grain through the general path (the tests compare the two).
    types : bool
        Compute the ``weinberg``, ``symmetry`` and ``chirality`` columns (null when False):
        the Weinberg walks cost several times the rest of the classification.
    grain_memory : int, optional
        The bytes a grain may take (:func:`grain_memory_limit` by default): a grain that could
        need more is invalid, with a message that says so, and the others are classified.
    belts : int
        The longest belts to count (3 to 10): the ``belts``, ``splits`` and ``belt_penalties``
        columns for l = 3..belts (null when 0, the default: they cost more than the rest).

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
    out = _classify_csr(batch, max_bitset_faces, strings=True, limit=grain_memory)
    # The belts before the walks: a grain refused memory for its belts is not walked.
    profile = belt_profile(batch, out, belts) if belts else None
    return _table(batch, out, weinberg_types(batch, out, types), profile)


def _table(
    batch: GrainBatch, out: Classified, types: Types, profile: np.ndarray | None = None
) -> pa.Table:
    """The per-grain table of :func:`classify` from the kernels' outputs."""
    from grainclass._kernels.columns import _compact, _p_vectors

    g = len(batch)
    n_faces = batch.n_faces
    parsed, status, err, family = out.parsed, out.status, out.err, out.family
    fundamental, depth, belts = out.fundamental, out.depth, out.belts
    ok = status == codes.OK
    has_trees = ok & (family != codes.STACKED)
    p_offsets, p_counts, triangles = _p_vectors(batch.face_offsets, batch.nbr_offsets, ok)
    trees = string_array(*_compact(out.tree_offsets, out.tree_bytes, out.tree_length), has_trees)
    grain = _csr_grain_codes(batch, out, out.belts[:, 0], triangles)
    split_k = grain.split_k
    is_flag = split_k >= 0
    with_type = types.computed
    volume, area = batch.volume, batch.area
    grain_id = batch.grain_id
    if not isinstance(grain_id, pa.Array):
        grain_id = strings(grain_id)

    columns = {
        schema.GRAIN_ID: grain_id,
        schema.SOURCE: (
            repeated_string(batch.source, g)
            if isinstance(batch.source, str)
            else strings(batch.source)
        ),
        schema.BOUNDARY: (
            pa.nulls(g, pa.bool_())
            if batch.boundary is None
            else booleans(batch.boundary == 1, batch.boundary >= 0)
        ),
        schema.STATUS: strings_from_codes(status, vocabulary.STATUSES),
        schema.ERROR: (
            pa.nulls(g, pa.string()) if ok.all() else strings(error_messages(batch, status, err))
        ),
        schema.N_FACES: numbers(n_faces, pa.int32(), parsed),
        schema.N_TRIANGLES: numbers(triangles, pa.int32(), ok),
        schema.P_VECTOR: pa.ListArray.from_arrays(
            numbers(p_offsets, pa.int32()),
            numbers(p_counts, pa.int32()),
            mask=None if ok.all() else booleans(~ok),
        ),
        schema.FAMILY: strings_from_codes(family, vocabulary.FAMILIES),
        schema.CLASS: strings_from_codes(grain.class_code, vocabulary.CLASSES),
        schema.TRUNCATIONS: numbers(grain.truncations, pa.int32(), ok),
        schema.FUNDAMENTAL_FACES: numbers(fundamental, pa.int32(), ok),
        schema.TREES: trees,
        schema.DEPTH: numbers(depth, pa.int32(), has_trees),
        schema.ROUND_K: numbers(grain.round_k, pa.int32(), grain.round_k >= 0),
        schema.SPLIT_K: numbers(split_k, pa.int32(), is_flag),
        schema.SPLIT_M: numbers(n_faces - 4 - split_k, pa.int32(), is_flag),
        schema.BELTS4: numbers(belts[:, 1], pa.int32(), is_flag),
        schema.PENALTY: numbers(belts[:, 2], pa.int64(), is_flag & (belts[:, 2] >= 0)),
        schema.BELTS: belt_lists(profile, 0, ok, pa.int64()),
        schema.SPLITS: belt_lists(profile, 1, ok, pa.int32()),
        schema.BELT_PENALTIES: belt_lists(profile, 2, ok, pa.int64()),
        schema.WEINBERG: weinberg_strings(types),
        schema.SYMMETRY: numbers(types.symmetry, pa.int32(), with_type),
        schema.CHIRALITY: numbers(types.chirality, pa.int8(), with_type),
        schema.VOLUME: _floats(volume, g),
        schema.AREA: _floats(area, g),
        schema.ISOPERIMETRIC: _floats(batch.isoperimetric, g),
        schema.VOXELS: _counts(batch.voxels, g),
        schema.SHORTEST_TRIPLE_LINE: _counts(batch.shortest_triple_line, g),
    }
    table = pa.table(columns, schema=schema.GRAIN_SCHEMA)
    for key, values in batch.attributes.items():
        if key not in schema.COLUMNS:  # an input field may not overwrite a result column
            table = table.append_column(pa.field(key, pa.string()), strings(values))
    return table
