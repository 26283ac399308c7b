"""`summarize`: per-grain rows in, the paper's tables out. Aggregation only, no formatting."""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np
import pandas as pd
import pyarrow as pa
import pyarrow.compute as pc

from grainclass import schema, vocabulary
from grainclass._kernels import codes as kernel_codes

if TYPE_CHECKING:
    from grainclass.batch import GrainBatch
    from grainclass.classified import GrainCodes
    from grainclass.readers.planar_code import PlanarCodeRecords

KEYS = [
    schema.STATUS,
    schema.N_FACES,
    schema.FAMILY,
    schema.CLASS,
    schema.ROUND_K,
    schema.SPLIT_K,
]
COLUMNS = [*KEYS, schema.N_TRIANGLES, schema.WEINBERG, schema.ISOPERIMETRIC, schema.BOUNDARY]
ROUND_LEVELS = range(7)
COUNT, TRIANGLES = "count", "triangles"
Q_COUNT, Q_SUM, Q_SQUARES = "q_count", "q_sum", "q_squares"
SUMS = [COUNT, TRIANGLES, Q_COUNT, Q_SUM, Q_SQUARES]


@dataclass(frozen=True)
class Summary:
    """The headline figures and the three tables of :func:`summarize`."""

    headline: dict[str, float | int | None]
    classes: pd.DataFrame
    round: pd.DataFrame
    split: pd.DataFrame
    geometry: pd.DataFrame

    def table(self, name: str) -> pd.DataFrame:
        """One of ``classes``, ``round``, ``split``, ``geometry``."""
        return getattr(self, name)


@dataclass(frozen=True)
class Tally:
    """A batch of grains reduced to what the tables need: grain counts (with their triangles and
    isoperimetric sums) by (status, n_faces, family, class, round_k, split_k), the 64-bit hashes
    of its distinct Weinberg vectors, whether those are all its ok grains' (``typed``: else the
    distinct types of a summary are unknown), and how many grains were left out as cut by a
    boundary.
    """

    counts: pd.DataFrame
    grains: int
    type_hashes: np.ndarray = field(default_factory=lambda: np.zeros(0, np.uint64))
    boundary_excluded: int = 0
    typed: bool = False

    def __len__(self) -> int:
        return self.grains


def tally_table(grains: pa.Table, include_boundary: bool = False, belt_length: int = 4) -> Tally:
    """A :class:`Tally` of per-grain rows (as ``grainclass classify`` writes them); with a
    ``belt_length`` other than 4, flag grains by the split type of their l-belts (from the
    ``splits`` column). The rows are read back into the codes a raw batch is classified into,
    and counted as a raw batch is (:func:`tally_batch`)."""
    from grainclass.classified import GrainCodes

    split = _codes(grains.column(schema.SPLIT_K))
    if belt_length != 4:
        from_belts = pc.list_element(grains.column(schema.SPLITS).combine_chunks(), belt_length - 3)
        split = np.where(split >= 0, _codes(from_belts), -1)
    codes = GrainCodes(
        n_faces=_codes(grains.column(schema.N_FACES)),
        status=_word_codes(grains.column(schema.STATUS), vocabulary.STATUSES),
        family=_word_codes(grains.column(schema.FAMILY), vocabulary.FAMILIES),
        truncations=np.full(len(grains), -1, np.int64),  # counted by class, not by number
        class_code=_word_codes(grains.column(schema.CLASS), vocabulary.CLASSES),
        round_k=_codes(grains.column(schema.ROUND_K)),
        split_k=split,
        triangles=_codes(grains.column(schema.N_TRIANGLES), missing=0),
    )
    q = grains.column(schema.ISOPERIMETRIC).to_numpy(zero_copy_only=False).astype(np.float64)
    keep = uncut(grains, include_boundary)
    kept = grains if keep is None else grains.filter(pa.array(keep))
    return _tally_codes(
        codes, q, keep, type_hashes(kept.column(schema.WEINBERG)), untyped_grains(kept) == 0
    )


def _codes(column: pa.ChunkedArray | pa.Array, missing: int = -1) -> np.ndarray:
    """An integer column as int64 codes, ``missing`` where null."""
    return pc.fill_null(column, missing).to_numpy(zero_copy_only=False).astype(np.int64)


def _word_codes(column: pa.ChunkedArray | pa.Array, words: tuple[str, ...]) -> np.ndarray:
    """A column of words as their index in ``words``, -1 where null."""
    return _codes(pc.index_in(column, value_set=pa.array(words)))


def uncut(grains: pa.Table | GrainBatch, include_boundary: bool) -> np.ndarray | None:
    """Which grains count, as the boundary rule has it: all of them with ``include_boundary``
    or when none is known to be cut, else those not cut by a sample boundary (a grain whose
    boundary is unknown counts). None for all; else a boolean mask."""
    if include_boundary:
        return None
    if isinstance(grains, pa.Table):
        if schema.BOUNDARY not in grains.column_names:
            return None
        cut = pc.fill_null(grains.column(schema.BOUNDARY), False)
        return None if not pc.any(cut).as_py() else ~cut.to_numpy(zero_copy_only=False)
    boundary = grains.boundary
    return None if boundary is None else boundary != 1


def untyped_grains(grains: pa.Table) -> int:
    """The ok grains of per-grain rows without their Weinberg vector (classified with
    ``--no-types``); 0 also for no ok grain at all."""
    ok = pc.equal(grains.column(schema.STATUS), "ok")
    return pc.sum(pc.and_(ok, pc.is_null(grains.column(schema.WEINBERG)))).as_py() or 0


def _names(codes: np.ndarray, names: tuple[str, ...]) -> np.ndarray:
    """Words for codes, None for -1."""
    return np.array([None, *names], dtype=object)[codes.astype(np.int64) + 1]


def group_rows(columns: Sequence[np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    """Distinct rows of equal-length, non-negative integer columns: ``(first, group)``, the
    first row of each distinct row in order of first appearance, and each row's group.

    Rows are packed into one int64 each when the column maxima allow and grouped by hashing, in
    one pass (:func:`grainclass._kernels.groups._group_keys`); otherwise they are compared whole.
    """
    from grainclass._kernels.groups import _group_keys

    length = len(columns[0])
    radices = [int(c.max()) + 1 if length else 1 for c in columns]
    if float(np.prod([float(r) for r in radices])) < 2.0**62:
        keys = np.zeros(length, np.int64)
        for column, radix in zip(columns, radices, strict=True):
            keys *= radix
            keys += column
        with np.errstate(over="ignore"):  # the hash wraps modulo 2**64 (seen without the JIT)
            return _group_keys(keys)
    rows = np.stack(columns, axis=1).astype(np.int64)
    _, first, inverse = np.unique(rows, axis=0, return_index=True, return_inverse=True)
    order = np.argsort(first)
    rank = np.empty_like(order)
    rank[order] = np.arange(len(order))
    return first[order], rank[inverse.reshape(-1)]


def tally_batch(
    batch: GrainBatch | PlanarCodeRecords,
    include_boundary: bool = False,
    types: bool = False,
    belt_length: int = 4,
) -> Tally:
    """A :class:`Tally` of raw grains, classified for counting only (no per-grain rows, no
    truncation-tree strings): the census path of ``summarize``. With ``types`` (a CSR batch
    only) the Weinberg vectors are computed too, for the distinct types; with a
    ``belt_length`` other than 4 (a CSR batch only), flag grains are counted by the split type
    of their l-belts."""
    from grainclass.classification import grain_codes, grain_codes_and_type_hashes
    from grainclass.readers.planar_code import PlanarCodeRecords

    if isinstance(batch, PlanarCodeRecords) and not types:
        return _tally_records(batch)
    code_hashes = None
    if types:
        codes, code_hashes = grain_codes_and_type_hashes(batch, belt_length)
    else:
        codes = grain_codes(batch, belt_length)
    keep = uncut(batch, include_boundary)
    hashes = np.zeros(0, np.uint64)
    if code_hashes is not None:  # the distinct types of the kept ok grains
        ok = codes.status == kernel_codes.OK
        hashes = np.unique(code_hashes[ok if keep is None else ok & keep])
    return _tally_codes(codes, batch.isoperimetric, keep, hashes, typed=types)


def _tally_codes(
    codes: GrainCodes,
    q: np.ndarray | None,
    keep: np.ndarray | None,
    hashes: np.ndarray,
    typed: bool,
) -> Tally:
    """A :class:`Tally` of grains given by their codes: those of ``keep`` (None: all) grouped
    by (status, family, class, n_faces, round_k, split_k), with their triangles and the count,
    sum and sum of squares of their isoperimetric quotients ``q`` (NaN or None: none) where ok.
    """
    keys = [
        codes.status,
        codes.family,
        codes.class_code,
        codes.n_faces,
        codes.round_k,
        codes.split_k,
    ]
    triangles = codes.triangles
    if q is not None:
        q = np.where(codes.status == kernel_codes.OK, q, np.nan)
    grains = len(codes.status)
    if keep is not None:
        keys = [column[keep] for column in keys]
        triangles = triangles[keep]
        q = None if q is None else q[keep]
    # Codes shifted to be >= 0 (-1 is null), one row per kept grain.
    shifted = [keys[0].astype(np.int64), *(np.add(c, 1, dtype=np.int64) for c in keys[1:])]
    first, group = group_rows(shifted)
    groups = len(first)
    kept = len(group)

    def sums(weights: np.ndarray) -> np.ndarray:
        return np.bincount(group, weights, minlength=groups)

    q_sums = None
    if q is not None:
        has_q = ~np.isnan(q)
        q_sums = (
            sums(has_q).astype(np.int64),
            sums(np.where(has_q, q, 0.0)),
            sums(np.where(has_q, q * q, 0.0)),
        )
    rows = [column[first] for column in keys]
    counts = _counts(
        *rows, sums(triangles).astype(np.int64), np.bincount(group, minlength=groups), q_sums
    )
    return Tally(counts, kept, hashes, boundary_excluded=grains - kept, typed=typed)


def _tally_records(batch: PlanarCodeRecords) -> Tally:
    """:func:`tally_batch` of planar_code records: counted in the kernel as they are classified
    (``_kernels.batch._tally_records``); the records it leaves (not on the fast path) are read
    as CSR lists and counted as any other batch."""
    from grainclass._kernels.batch import _tally_records as tally_kernel
    from grainclass._kernels.batch import census_fields
    from grainclass._kernels.groups import EMPTY

    with np.errstate(over="ignore"):  # the hash wraps modulo 2**64 (seen without the JIT)
        table, sums, pending = tally_kernel(batch.buf, batch.starts)
    used = table != EMPTY
    family, class_code, n_faces, round_k, split_k = census_fields(table[used])
    status = np.full(len(family), kernel_codes.OK)
    grains, triangles = sums[used, 0], sums[used, 1]
    counts = _counts(status, family, class_code, n_faces, round_k, split_k, triangles, grains)
    if len(pending):
        rest = tally_batch(batch.as_csr(pending)).counts
        counts = pd.concat([counts, rest], ignore_index=True) if len(counts) else rest
    return Tally(counts, len(batch))


def _counts(
    status: np.ndarray,
    family: np.ndarray,
    class_code: np.ndarray,
    n_faces: np.ndarray,
    round_k: np.ndarray,
    split_k: np.ndarray,
    triangles: np.ndarray,
    count: np.ndarray,
    q_sums: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None,
) -> pd.DataFrame:
    """A tally's rows from the codes of its groups (-1 for null), their sums of triangular faces
    and grains and, where grains have an isoperimetric quotient, its count, sum and sum of
    squares."""
    groups = len(count)
    if q_sums is None:  # no geometry: every grain's q is null
        q_sums = np.zeros(groups, np.int64), np.zeros(groups), np.zeros(groups)
    return pd.DataFrame(
        {
            schema.STATUS: _names(status, vocabulary.STATUSES),
            schema.N_FACES: np.where(n_faces >= 0, n_faces, np.nan),
            schema.FAMILY: _names(family, vocabulary.FAMILIES),
            schema.CLASS: _names(class_code, vocabulary.CLASSES),
            schema.ROUND_K: np.where(round_k >= 0, round_k, np.nan),
            schema.SPLIT_K: np.where(split_k >= 0, split_k, np.nan),
            TRIANGLES: triangles,
            COUNT: count,
            Q_COUNT: q_sums[0],
            Q_SUM: q_sums[1],
            Q_SQUARES: q_sums[2],
        }
    )


def _distinct(hashes: list[np.ndarray]) -> int:
    """Distinct values among the hash arrays, which are emptied."""
    return len(_deduplicated(hashes))


def _deduplicated(hashes: list[np.ndarray]) -> np.ndarray:
    """The distinct values among the hash arrays, which are emptied (they can hold a 64-bit
    hash per grain of a whole enumeration: joined and sorted in place, never copied twice)."""
    joined = np.empty(sum(h.size for h in hashes), np.uint64)
    if not joined.size:
        return joined
    at = 0
    hashes.reverse()
    while hashes:
        part = hashes.pop()
        joined[at : at + part.size] = part
        at += part.size
    joined.sort()
    first = np.empty(joined.size, bool)
    first[0] = True
    np.not_equal(joined[1:], joined[:-1], out=first[1:])
    return joined[first]


MERGE_EVERY = 64  # tallies (and arrays of type hashes) held before they are merged


def merge_tallies(tallies: list[pd.DataFrame]) -> pd.DataFrame:
    """One tally from several (same groups added up)."""
    if not tallies:
        return _counts(*[np.zeros(0, np.int64)] * 8)
    both = pd.concat(tallies, ignore_index=True)
    return both.groupby(KEYS, dropna=False, as_index=False)[SUMS].sum(min_count=0)


def _ok(counts: pd.DataFrame) -> pd.DataFrame:
    return counts[counts[schema.STATUS] == "ok"]


def type_hashes(weinberg: pa.Array | pa.ChunkedArray) -> np.ndarray:
    """64-bit hashes of the distinct Weinberg codes of a column (uint64)."""
    from grainclass._kernels.columns import _fnv1a

    if isinstance(weinberg, pa.ChunkedArray):
        weinberg = weinberg.combine_chunks()
    codes = pc.unique(weinberg.drop_null())
    if not len(codes):
        return np.zeros(0, np.uint64)
    codes = codes.cast(pa.string())
    _, offsets, data = codes.buffers()
    starts = np.frombuffer(offsets, np.int32, len(codes) + 1, codes.offset * 4)
    with np.errstate(over="ignore"):  # FNV wraps modulo 2**64 on purpose (seen without the JIT)
        return _fnv1a(starts, np.frombuffer(data, np.uint8))


def _headline(counts: pd.DataFrame, distinct_types: int | None) -> dict[str, float | int | None]:
    ok = _ok(counts)
    by_status = counts.groupby(schema.STATUS)[COUNT].sum()
    grains = int(ok[COUNT].sum())
    faces = float((ok[schema.N_FACES] * ok[COUNT]).sum())
    return {
        "grains": int(counts[COUNT].sum()),
        **{status: int(by_status.get(status, 0)) for status in vocabulary.STATUSES},
        "mean_faces": faces / grains if grains else float("nan"),
        "triangle_faces_percent": (
            100.0 * float(ok[TRIANGLES].sum()) / faces if faces else float("nan")
        ),
        "types": distinct_types,
    }


def class_counts(counts: pd.DataFrame) -> pd.DataFrame:
    """Counts of ok grains per number of faces and class: the paper's Tables II, V, R and E.

    Returns a frame with columns ``n, all, stacked, flag, ..., sc>=2`` and a final ``total`` row.
    """
    ok = _ok(counts)
    table = ok.pivot_table(
        index=schema.N_FACES, columns=schema.CLASS, values=COUNT, aggfunc="sum", fill_value=0
    )
    table = table.reindex(columns=list(vocabulary.CLASSES), fill_value=0)
    table.insert(0, "all", table.sum(axis=1))
    table.index = table.index.astype("int64").astype(str)
    table.loc["total"] = table.sum(axis=0)
    table.index.name = "n"
    table.columns.name = None
    return table.reset_index().astype({c: "int64" for c in ["all", *vocabulary.CLASSES]})


def round_percentages(counts: pd.DataFrame, n_values: tuple[int, ...] = ()) -> pd.DataFrame:
    """Percentages of ok grains in round<=k (k = 0..6) and in the sc family: the paper's Table
    ``tbl:distribution``, for all grains and for each requested number of faces.
    """
    ok = _ok(counts)
    groups = [("all", ok)] + [(f"n={n}", ok[ok[schema.N_FACES] == n]) for n in n_values]
    rows = []
    for label, part in groups:
        total = int(part[COUNT].sum())
        row: dict[str, object] = {"grains": label, "count": total}
        for k in ROUND_LEVELS:
            hits = int(part.loc[part[schema.ROUND_K] <= k, COUNT].sum())
            # Unrounded: text, Markdown and LaTeX show two decimals, CSV, JSON and Parquet keep
            # what a census of millions needs (0.004% is 0.00).
            row["round0" if k == 0 else f"round<={k}"] = 100.0 * hits / total if total else np.nan
        sc = int(part.loc[part[schema.FAMILY] == "sc", COUNT].sum())
        row["sc"] = 100.0 * sc / total if total else np.nan
        rows.append(row)
    return pd.DataFrame(rows)


def split_counts(counts: pd.DataFrame, belt_length: int = 4) -> pd.DataFrame:
    """Counts of ``flag`` grains by number of faces (rows) and split type k (columns).

    The split type is k:m with m = n - 4 - k. The paper's Table ``tbl:flag_few_vertices``. For
    l-belts (the counts tallied so), k:l:m with m = n - l - k: ``attrs["belt_length"]`` is l.
    """
    flag = _ok(counts)[_ok(counts)[schema.CLASS] == "flag"]
    table = flag.pivot_table(
        index=schema.N_FACES, columns=schema.SPLIT_K, values=COUNT, aggfunc="sum", fill_value=0
    )
    if len(table.columns):
        table = table.reindex(columns=range(int(table.columns.max()) + 1), fill_value=0)
    table.index = table.index.astype("int64")
    table.index.name = "n"
    table.columns = [str(int(k)) for k in table.columns]
    table = table.reset_index().astype("int64")
    table.attrs["belt_length"] = belt_length
    return table


def geometry_table(counts: pd.DataFrame) -> pd.DataFrame:
    """Mean isoperimetric quotient Q = 36 pi V^2 / S^3 of ok grains, with its standard error,
    per number of faces and per round_k (the paper's figures on isoperimetricity)."""
    ok = _ok(counts).copy()
    ok["round"] = (
        ok[schema.ROUND_K].astype("Int64").astype(str).where(ok[schema.FAMILY] != "sc", "sc")
    )
    ok[schema.N_FACES] = ok[schema.N_FACES].astype("int64")  # float where a tally had nulls
    rows = []
    for by, column in ((schema.N_FACES, schema.N_FACES), (schema.ROUND_K, "round")):
        sums = ok.groupby(column)[[Q_COUNT, Q_SUM, Q_SQUARES]].sum()
        order = sorted(sums.index, key=lambda v: (str(v) == "sc", int(v) if str(v) != "sc" else 0))
        for value, (count, total, squares) in sums.loc[order].iterrows():
            if count == 0:
                continue
            mean = total / count
            variance = (squares - count * mean**2) / (count - 1) if count > 1 else np.nan
            rows.append(
                {
                    "by": by,
                    "value": str(value),
                    "grains": int(count),
                    "mean_Q": mean,
                    "se_Q": float(np.sqrt(max(variance, 0.0) / count)),
                }
            )
    return pd.DataFrame(rows, columns=["by", "value", "grains", "mean_Q", "se_Q"])


def summarize(
    grains: pa.Table | Iterable[pa.Table | Tally],
    n_values: tuple[int, ...] = (),
    include_boundary: bool = False,
    belt_length: int = 4,
) -> Summary:
    """Summarize classified grains into the paper's tables.

    Parameters
    ----------
    grains : pyarrow.Table, or iterable of pyarrow.Table or Tally
        Rows as written by ``grainclass classify`` (at least the columns in ``COLUMNS``), or
        batches already tallied (:func:`tally_batch`); an iterable is consumed one item at a
        time, so a stream of batches needs little memory.
    n_values : tuple of int
        Numbers of faces for which the round table gets a row of its own.
    include_boundary : bool
        Count grains cut by a sample boundary too (they are left out by default: their faces
        there are cuts, not grain boundaries). Tallies carry their own choice.
    belt_length : int
        The split table by the split type of l-belts (k:l:m) rather than 4-belts: tables
        need the ``splits`` column, tallies must have been made with the same l.

    Returns
    -------
    Summary

    Examples
    --------
    >>> from grainclass import GrainBatch, classify
    >>> cube = [[1, 2, 3, 4], [0, 4, 5, 2], [0, 1, 5, 3], [0, 2, 5, 4], [0, 3, 5, 1], [1, 4, 3, 2]]
    >>> s = summarize(classify(GrainBatch.from_lists([cube])))
    >>> s.classes[["n", "all", "flag"]].values.tolist()
    [['6', 1, 1], ['total', 1, 1]]
    """
    items = [grains] if isinstance(grains, pa.Table) else grains
    frames, hashes, excluded, typed = [], [], 0, True
    held = 0  # hashes held, the distinct ones of the last merge included
    for item in items:
        part = item if isinstance(item, Tally) else tally_table(item, include_boundary, belt_length)
        frames.append(part.counts)
        hashes.append(part.type_hashes)
        held += part.type_hashes.size
        excluded += part.boundary_excluded
        typed &= part.typed
        # A long stream (a data set of millions of grains in thousands of row groups) is held
        # as its tallies so far and its distinct hashes, not as every batch's.
        if len(frames) >= MERGE_EVERY:
            frames = [merge_tallies(frames)]
        if len(hashes) >= MERGE_EVERY and held > hashes[0].size * 5 // 4:
            hashes = [_deduplicated(hashes)]
            held = hashes[0].size
    counts = merge_tallies(frames)
    # Distinct types are known only if every part knows its grains' types: a count over some
    # would pass for the whole.
    headline = _headline(counts, _distinct(hashes) if typed else None)
    headline["boundary_excluded"] = excluded
    return Summary(
        headline=headline,
        classes=class_counts(counts),
        round=round_percentages(counts, tuple(dict.fromkeys(n_values))),  # a row per n, once
        split=split_counts(counts, belt_length),
        geometry=geometry_table(counts),
    )
