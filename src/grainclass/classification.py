"""`classify`: one batch of grains in, one Arrow table of per-grain results out."""

from __future__ import annotations

from dataclasses import dataclass

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
from grainclass.parallel import run_ranges

_MESSAGES = {
    codes.E_TOO_FEW_FACES: "{a} faces; a grain needs at least 4",
    codes.E_INDEX_RANGE: "face {a} lists face {b}, but the faces are numbered 0..{last}",
    codes.E_SELF: "face {a} lists itself as a neighbour",
    codes.E_ASYMMETRIC: "asymmetric adjacency: face {a} lists face {b}{ab}, but face {b} {ba}",
    codes.E_FEW_NEIGHBOURS: "face {a} has {b} neighbour(s); a face needs at least 2",
    codes.E_TWO_GON: "degenerate: face {a} is a 2-gon",
    codes.E_SHARED_EDGES: "degenerate: faces {a} and {b} share more than one edge",
    codes.E_DISCONNECTED: "not connected: face {a} cannot be reached from face {first}",
    codes.E_TOO_MANY_EDGES: "not a sphere: {a} adjacencies, but a grain with {n} faces "
    "has at most 3n-6 = {b}",
    codes.E_EULER: "not a sphere: the neighbour lists, read as cyclic orders, "
    "describe a surface of Euler characteristic {a} (or they are in no cyclic order)",
    codes.E_UNORDERED: "not a simple grain ({a} adjacencies, 3n-6 = {b}) and the neighbour "
    "lists are not in cyclic order, so the corners cannot be recovered",
    codes.E_NOT_SPHERE: "not a sphere: {edges} adjacencies, but the triangles around "
    "faces {a} and {b} do not close up into a sphere",
    codes.E_NON_SIMPLE: "non-simple: a corner where {a} faces meet (face {b} is one of them)",
    codes.E_TOO_LARGE: "too large: {n} faces and {darts} neighbour entries could need {a_mb} "
    "of memory, more than the {b_mb} a grain may take (GRAINCLASS_GRAIN_MEMORY, in MB)",
    codes.E_FOREST_TOO_LARGE: "too large: the strings of its truncation forest would take "
    "{a_mb}, more than the {b_mb} a grain may take (GRAINCLASS_GRAIN_MEMORY, in MB)",
    codes.E_MEMORY: "out of memory: the system refused the memory that classifying "
    "this grain of {n} faces needed",
}

GRAIN_MEMORY_MB = 2048
"""The memory a grain may take on the general path by default, in MB
(``GRAINCLASS_GRAIN_MEMORY`` sets another): a grain that could need more is a row of status
``invalid`` that says so, not a run that fails."""


def grain_memory_limit() -> int:
    """The bytes a grain may take: ``GRAINCLASS_GRAIN_MEMORY`` MB, else :data:`GRAIN_MEMORY_MB`."""
    import os

    value = os.environ.get("GRAINCLASS_GRAIN_MEMORY", "")
    try:
        mb = float(value) if value.strip() else GRAIN_MEMORY_MB
    except ValueError:
        mb = GRAIN_MEMORY_MB
    return max(0, int(mb * 2**20))


def _mb(size: int) -> str:
    return f"{size / 2**20:,.1f} MB"


def _where(batch: GrainBatch, g: int) -> str:
    source = batch.source if isinstance(batch.source, str) else batch.source[g]
    if batch.location_kind == "line":
        return f"{source}:{batch.location[g]}"
    return f"{source}: record {batch.location[g]}"


# The parameters of a message that are faces of the grain, named by the input's face ids
# where it has them (GrainBatch.face_labels).
_FACE_PARAMETERS = {
    codes.E_SELF: "a",
    codes.E_ASYMMETRIC: "ab",
    codes.E_FEW_NEIGHBOURS: "a",
    codes.E_TWO_GON: "a",
    codes.E_SHARED_EDGES: "ab",
    codes.E_DISCONNECTED: "a",
    codes.E_NOT_SPHERE: "ab",
    codes.E_NON_SIMPLE: "b",
}


def _face_name(batch: GrainBatch, g: int, face: int) -> int:
    """Face ``face`` of grain ``g`` as the input names it."""
    labels, start = batch.face_labels, int(batch.face_offsets[g])
    if labels is None or not 0 <= face < int(batch.face_offsets[g + 1]) - start:
        return face
    return int(labels[start + face])


def _asymmetry(batch: GrainBatch, g: int, a: int, b: int) -> tuple[str, str]:
    """How often face a lists face b, and what face b's list does about face a, in words."""

    def listed(v: int, x: int) -> int:
        face = batch.face_offsets[g] + v
        lst = batch.neighbors[batch.nbr_offsets[face] : batch.nbr_offsets[face + 1]]
        return int((lst == x).sum())

    def times(k: int) -> str:
        return {1: "once", 2: "twice"}.get(k, f"{k} times")

    back = listed(b, a)
    return (
        f" {times(listed(a, b))}",
        f"lists face {_face_name(batch, g, a)} {times(back)}"
        if back
        else f"does not list face {_face_name(batch, g, a)}",
    )


def _error_messages(batch: GrainBatch, status: np.ndarray, err: np.ndarray) -> list[str | None]:
    messages: list[str | None] = [None] * len(batch)
    n_faces = batch.n_faces
    for g in np.flatnonzero(status != codes.OK):
        code, a, b = (int(x) for x in err[g])
        if code == codes.E_PARSE:
            what = batch.parse_errors.get(int(g), "unreadable record")
        else:
            n = int(n_faces[g])
            ab, ba = _asymmetry(batch, int(g), a, b) if code == codes.E_ASYMMETRIC else ("", "")
            darts = int(batch.nbr_offsets[batch.face_offsets[g + 1]])
            darts -= int(batch.nbr_offsets[batch.face_offsets[g]])
            faces = _FACE_PARAMETERS.get(code, "")
            what = _MESSAGES[code].format(
                a=_face_name(batch, int(g), a) if "a" in faces else a,
                b=_face_name(batch, int(g), b) if "b" in faces else b,
                first=_face_name(batch, int(g), 0), n=n, last=n - 1, edges=3 * n - 6,
                ab=ab, ba=ba, darts=darts, a_mb=_mb(a), b_mb=_mb(b),
            )  # fmt: skip
        messages[g] = f"{_where(batch, g)}: {what}"
    return messages


def _class_codes(family: np.ndarray, truncations: np.ndarray, n_trees: np.ndarray) -> np.ndarray:
    """Index into ``vocabulary.CLASSES`` per grain (``codes.CLASS_OF``), -1 when not ok."""
    ok = family >= 0
    by_family = codes.CLASS_OF[
        np.where(ok, family, 0), np.clip(truncations, 0, 3), (n_trees == 2).view(np.int8)
    ]
    return np.where(ok, by_family, -1)


def _floats(values: np.ndarray | None, length: int) -> pa.Array:
    return pa.nulls(length, pa.float64()) if values is None else floats(values)


@dataclass(frozen=True)
class GrainCodes:
    """A grain's classification as integer arrays (no strings, no Arrow): what the summaries
    count, and what the per-grain table's class, round and split columns are written from.

    ``status`` and ``family`` are codes of :mod:`grainclass._kernels.codes`, ``class_code`` an
    index into :data:`grainclass.vocabulary.CLASSES`; ``truncations`` and ``class_code`` are -1
    when the grain is not ok, ``round_k`` also for sc, ``split_k`` unless the grain is fundamental
    flag; ``n_faces`` is -1 for an unreadable record. The per-grain table's columns take their
    nulls from these -1s, so that the rules of round<=k and of the split type are written once
    for rows and summaries (the census kernel's ``census_key`` is their compiled twin).
    """

    n_faces: np.ndarray
    status: np.ndarray
    family: np.ndarray
    truncations: np.ndarray
    class_code: np.ndarray
    round_k: np.ndarray
    split_k: np.ndarray
    triangles: np.ndarray


@dataclass(frozen=True)
class _Classified:
    """The classification kernels' per-grain outputs (see ``_kernels/batch.py``), and which
    grains the reader could parse."""

    parsed: np.ndarray
    status: np.ndarray
    consistent: np.ndarray
    err: np.ndarray
    family: np.ndarray
    fundamental: np.ndarray
    n_trees: np.ndarray
    depth: np.ndarray
    belts: np.ndarray
    tree_offsets: np.ndarray
    tree_bytes: np.ndarray
    tree_length: np.ndarray

    @property
    def rows(self) -> tuple[np.ndarray, ...]:
        """The per-grain classification, as the batch kernels take it."""
        return (self.family, self.fundamental, self.n_trees, self.depth, self.belts)

    @property
    def forests(self) -> tuple[np.ndarray, ...]:
        """The truncation-forest strings, as the batch kernels take them."""
        return (self.tree_offsets, self.tree_bytes, self.tree_length)

    @classmethod
    def empty(cls, batch: GrainBatch, strings: bool) -> _Classified:
        """Output arrays for the kernels, sized for ``batch`` (3n bytes of tree string per
        grain when ``strings``)."""
        g = len(batch)
        parsed = np.ones(g, np.bool_)
        parsed[list(batch.parse_errors)] = False
        tree_offsets = np.zeros(g + 1, np.int64)
        if strings:
            np.cumsum(3 * batch.n_faces, out=tree_offsets[1:])
        return cls(
            parsed=parsed,
            status=np.zeros(g, np.int8),
            consistent=np.zeros(g, np.bool_),
            err=np.zeros((g, 3), np.int64),
            family=np.full(g, -1, np.int8),
            fundamental=np.zeros(g, np.int32),
            n_trees=np.zeros(g, np.int32),
            depth=np.zeros(g, np.int32),
            belts=np.zeros((g, 3), np.int64),
            tree_offsets=tree_offsets,
            tree_bytes=np.empty(int(tree_offsets[-1]), np.uint8),
            tree_length=np.zeros(g, np.int64),
        )


def _classify_csr(
    batch: GrainBatch, max_small: int, strings: bool, limit: int | None = None
) -> _Classified:
    """The fast path over the batch, then the general validation over the grains it left,
    then the general classification over the ok ones of more than ``max_small`` faces. A grain
    may take ``limit`` bytes on the general path (:func:`grain_memory_limit` by default)."""
    from grainclass._kernels.batch import _classify_batch

    limit = grain_memory_limit() if limit is None else limit
    out = _Classified.empty(batch, strings)
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


def _refuse(out: _Classified, g: int) -> None:
    """Grain g could not be had memory for: invalid, saying so (E_MEMORY)."""
    out.status[g] = codes.INVALID
    out.err[g] = (codes.E_MEMORY, 0, 0)
    out.family[g] = -1


def _each_grain(kernel, grains: np.ndarray, arrays: tuple, refuse) -> None:
    """``kernel`` over the grains ``grains`` in ranges; if the system refuses it memory, again
    one grain at a time, and ``refuse(g)`` for each grain that it still refuses: one grain
    that cannot be had memory for does not cost the others their rows."""
    try:
        run_ranges(kernel, len(grains), grains, *arrays)
    except MemoryError:
        for i in range(len(grains)):
            try:
                kernel(i, i + 1, grains, *arrays)
            except MemoryError:
                refuse(int(grains[i]))


def _validate_pending(
    batch: GrainBatch,
    out: _Classified,
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
    _each_grain(_validate_pending_batch, pending, arrays, lambda g: _refuse(out, g))


def _classify_general(
    batch: GrainBatch,
    out: _Classified,
    pending: np.ndarray,
    strings: bool,
    limit: int | None = None,
) -> None:
    """The general classification of the grains ``pending`` (int64 indices), validated and too
    large for the fast path, into ``out`` (``limit`` as for :func:`_validate_pending`)."""
    from grainclass._kernels.batch import _classify_general_batch

    limit = grain_memory_limit() if limit is None else limit
    arrays = (*_csr(batch), strings, limit, out.status, out.err, *out.rows, *out.forests)
    _each_grain(_classify_general_batch, pending, arrays, lambda g: _refuse(out, g))


def grain_codes(batch: GrainBatch) -> GrainCodes:
    """Classify a batch for counting only: no truncation-forest strings, no types."""
    return _csr_grain_codes(batch, _classify_csr(batch, MAX_BITSET_FACES, strings=False))


def grain_codes_and_type_hashes(batch: GrainBatch) -> tuple[GrainCodes, np.ndarray]:
    """:func:`grain_codes` of a CSR batch, with the 64-bit hash of the Weinberg vector that
    ``classify`` would write for each ok grain (:func:`grainclass.summary.type_hashes` of it;
    0 where not ok): what ``summarize --types`` counts, without the vectors' strings."""
    from grainclass._kernels.columns import _code_hashes

    out = _classify_csr(batch, MAX_BITSET_FACES, strings=False)
    types = _types(batch, out, True)
    with np.errstate(over="ignore"):  # FNV wraps modulo 2**64 on purpose (seen without the JIT)
        hashes = _code_hashes(types.weinberg, types.code_offsets, types.computed)
    return _csr_grain_codes(batch, out), hashes


def _csr_grain_codes(
    batch: GrainBatch, out: _Classified, triangles: np.ndarray | None = None
) -> GrainCodes:
    """:class:`GrainCodes` of a classified CSR batch; ``triangles`` (per grain) are counted
    here unless the caller has them."""
    from grainclass._kernels.columns import _triangle_counts

    if triangles is None:
        triangles = _triangle_counts(batch.face_offsets, batch.nbr_offsets, out.status == codes.OK)
    n_faces = np.where(out.parsed, batch.n_faces, -1)
    split = out.belts[:, 0]
    return _grain_codes(
        n_faces, out.status, out.family, out.fundamental, out.n_trees, split, triangles
    )


def _grain_codes(n_faces, status, family, fundamental, n_trees, split, triangles) -> GrainCodes:
    ok = status == codes.OK
    truncations = np.where(ok, n_faces - fundamental, -1)
    is_flag = (family == codes.FLAG) & (truncations == 0)
    return GrainCodes(
        n_faces=n_faces,
        status=status,
        family=family,
        truncations=truncations,
        class_code=_class_codes(family, truncations, n_trees),
        round_k=np.where(family != codes.SC, truncations, -1),
        split_k=np.where(is_flag, split, -1),
        triangles=triangles,
    )


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
    walked = _types(batch, out, types)
    return _table(batch, out, walked, _belts(batch, out, belts))


def _belts(batch: GrainBatch, out: _Classified, longest: int) -> np.ndarray | None:
    """Per ok grain and l = 3..``longest``: (belts, split_k, penalty), int64[G, longest - 2,
    3] (``_kernels/lbelts.py``); None when ``longest`` is 0."""
    if not longest:
        return None
    from grainclass._kernels.lbelts import MAX_BELT_LENGTH, _belts_batch

    if not 3 <= longest <= MAX_BELT_LENGTH:
        raise ValueError(f"belt lengths go from 3 to at most {MAX_BELT_LENGTH}, not {longest}")
    profile = np.zeros((len(batch), longest - 2, 3), np.int64)
    ok = out.status == codes.OK
    arrays = (*_csr(batch), ok, longest, profile)
    try:
        run_ranges(_belts_batch, len(batch), *arrays)
    except MemoryError:
        for g in np.flatnonzero(ok):
            try:
                _belts_batch(g, g + 1, *arrays)
            except MemoryError:
                _refuse(out, int(g))
    return profile


def belt_profile(batch: GrainBatch, status: np.ndarray, longest: int) -> np.ndarray:
    """The belts of lengths 3..``longest`` of the grains of ``status`` ok: per grain and l,
    (belts, split_k, penalty), int64[G, longest - 2, 3] (``_kernels/lbelts.py``)."""
    from grainclass._kernels.lbelts import _belts_batch

    profile = np.zeros((len(batch), longest - 2, 3), np.int64)
    run_ranges(_belts_batch, len(batch), *_csr(batch), status == codes.OK, longest, profile)
    return profile


def _belt_lists(profile: np.ndarray | None, field: int, ok: np.ndarray, kind) -> pa.Array:
    """Column ``field`` (0 belts, 1 split_k, 2 penalty) of the belt profile as a list per ok
    grain, null elsewhere and for every grain without a profile."""
    g = len(ok)
    if profile is None:
        return pa.nulls(g, pa.list_(kind))
    width = profile.shape[1]
    offsets = np.arange(0, (g + 1) * width, width, dtype=np.int32)
    values = numbers(np.ascontiguousarray(profile[:, :, field]).reshape(-1), kind)
    return pa.ListArray.from_arrays(
        numbers(offsets, pa.int32()), values, mask=None if ok.all() else booleans(~ok)
    )


@dataclass(frozen=True)
class _Types:
    """Weinberg vectors (grain g's at ``weinberg[code_offsets[g]:code_offsets[g + 1]]``),
    symmetry orders and chirality, for the grains in ``computed``."""

    computed: np.ndarray
    code_offsets: np.ndarray
    weinberg: np.ndarray
    symmetry: np.ndarray
    chirality: np.ndarray


def _types(batch: GrainBatch, out: _Classified, types: bool) -> _Types:
    """The Weinberg walks for the ok grains (for none unless ``types``)."""
    from grainclass._kernels.weinberg import (
        DENSE_FACES,
        _rotations,
        _weinberg_batch,
        _weinberg_large_batch,
    )

    g = len(batch)
    n_faces = batch.n_faces
    ok = out.status == codes.OK
    computed = ok & types
    code_offsets = np.zeros(g + 1, np.int64)
    np.cumsum(np.where(computed, 6 * n_faces - 11, 0), out=code_offsets[1:])
    result = _Types(
        computed=computed,
        code_offsets=code_offsets,
        weinberg=np.zeros(int(code_offsets[-1]), np.int32),
        symmetry=np.zeros(g, np.int32),
        chirality=np.zeros(g, np.int8),
    )
    if types:
        rotations = batch.neighbors
        csr = (batch.face_offsets, batch.nbr_offsets, batch.neighbors)
        unoriented = np.flatnonzero(ok & ~out.consistent)
        if len(unoriented):
            rotations = batch.neighbors.copy()
            _each_grain(_rotations, unoriented, (*csr, rotations), lambda g: _refuse(out, g))
        ok &= out.status == codes.OK
        small = ok & (n_faces <= DENSE_FACES)
        try:
            run_ranges(
                _weinberg_batch,
                g,
                batch.face_offsets,
                batch.nbr_offsets,
                rotations,
                small,
                int(n_faces[small].max()) if small.any() else 0,
                code_offsets,
                result.weinberg,
                result.symmetry,
                result.chirality,
            )
        except MemoryError:
            for i in np.flatnonzero(small):
                _weinberg_one(_weinberg_batch, out, int(i), batch.face_offsets, batch.nbr_offsets,
                              rotations, small, int(n_faces[i]), code_offsets, result.weinberg,
                              result.symmetry, result.chirality)  # fmt: skip
        large = np.flatnonzero(ok & ~small)
        arrays = (*csr[:2], rotations, code_offsets, result.weinberg, result.symmetry,
                  result.chirality)  # fmt: skip
        _each_grain(_weinberg_large_batch, large, arrays, lambda g: _refuse(out, g))
        computed &= out.status == codes.OK
    return result


def _weinberg_one(kernel, out: _Classified, g: int, *arrays) -> None:
    """The Weinberg walks of grain g alone, with scratch for its own size, where the system
    refused scratch for the largest grain of the batch to all: invalid (E_MEMORY) if it still
    refuses."""
    try:
        kernel(g, g + 1, *arrays)
    except MemoryError:
        _refuse(out, g)


def _weinberg_strings(types: _Types) -> pa.Array:
    """The Weinberg vectors as VoroTop writes them, null where none was computed."""
    from grainclass._kernels.columns import _code_strings

    computed = types.computed
    return string_array(*_code_strings(types.weinberg, types.code_offsets, computed), computed)


def _table(
    batch: GrainBatch, out: _Classified, types: _Types, profile: np.ndarray | None = None
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
    grain = _csr_grain_codes(batch, out, triangles)
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
            pa.nulls(g, pa.string()) if ok.all() else strings(_error_messages(batch, status, err))
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
        schema.BELTS: _belt_lists(profile, 0, ok, pa.int64()),
        schema.SPLITS: _belt_lists(profile, 1, ok, pa.int32()),
        schema.BELT_PENALTIES: _belt_lists(profile, 2, ok, pa.int64()),
        schema.WEINBERG: _weinberg_strings(types),
        schema.SYMMETRY: numbers(types.symmetry, pa.int32(), with_type),
        schema.CHIRALITY: numbers(types.chirality, pa.int8(), with_type),
        schema.VOLUME: _floats(volume, g),
        schema.AREA: _floats(area, g),
        schema.ISOPERIMETRIC: _floats(batch.isoperimetric, g),
    }
    table = pa.table(columns, schema=schema.GRAIN_SCHEMA)
    for key, values in batch.attributes.items():
        if key not in schema.COLUMNS:  # an input field may not overwrite a result column
            table = table.append_column(pa.field(key, pa.string()), strings(values))
    return table
