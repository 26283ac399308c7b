"""`type_frequencies`: how often each combinatorial type (Weinberg vector) occurs."""

from __future__ import annotations

import itertools
from collections.abc import Iterable, Sequence

import numpy as np
import pandas as pd
import pyarrow as pa
import pyarrow.compute as pc

from grainclass import schema
from grainclass.summary import uncut

COLUMNS = [
    schema.STATUS,
    schema.WEINBERG,
    schema.N_FACES,
    schema.P_VECTOR,
    schema.CLASS,
    schema.SPLIT_K,
    schema.SPLIT_M,
    schema.PENALTY,
    schema.SYMMETRY,
    schema.CHIRALITY,
    schema.BOUNDARY,
]
FIRST = [schema.N_FACES, schema.P_VECTOR, schema.CLASS, schema.SPLIT_K, schema.SPLIT_M]
FIRST += [schema.PENALTY, schema.SYMMETRY]
CHIRAL_COUNTS = {"left": -1, "achiral": 0, "right": 1}
# The columns of type_frequencies, in order.
OUTPUT = [schema.WEINBERG, schema.N_FACES, schema.P_VECTOR, schema.CLASS, "split"]
OUTPUT += [schema.PENALTY, schema.SYMMETRY, "count", *CHIRAL_COUNTS, "fraction"]


def _count_types(
    grains: pa.Table,
    n_faces: int | None,
    class_name: str | None,
    include_boundary: bool,
    belt_length: int = 4,
) -> tuple[pd.DataFrame, int]:
    """The types of one table, and how many grains that would count were left out as cut by
    the sample boundary. For a ``belt_length`` other than 4 the split type is that of the
    l-belts, from the ``splits`` column."""
    keep = pc.equal(grains.column(schema.STATUS), "ok")
    if n_faces is not None:
        keep = pc.and_(keep, pc.equal(grains.column(schema.N_FACES), n_faces))
    if class_name is not None:
        keep = pc.and_(keep, pc.equal(grains.column(schema.CLASS), class_name))
    keep = np.asarray(pc.fill_null(keep, False))
    counted = uncut(grains, include_boundary)
    excluded = 0 if counted is None else int(np.count_nonzero(keep & ~counted))
    kept = grains.filter(pa.array(keep if counted is None else keep & counted))
    frame = kept.select(COLUMNS).to_pandas()
    if belt_length != 4:
        flag = frame[schema.SPLIT_K].notna()
        index = belt_length - 3
        splits = [s[index] if s is not None and index < len(s) else None for s in
                  kept.column(schema.SPLITS).to_pylist()]  # fmt: skip
        frame[schema.SPLIT_K] = pd.Series(splits, index=frame.index, dtype="Int64").where(flag)
        frame[schema.SPLIT_M] = frame[schema.N_FACES] - belt_length - frame[schema.SPLIT_K]
    frame[schema.P_VECTOR] = [f"({','.join(map(str, p))})" for p in frame[schema.P_VECTOR]]
    for name, sign in CHIRAL_COUNTS.items():
        frame[name] = (frame[schema.CHIRALITY] == sign).astype("int64")
    grouped = frame.groupby(schema.WEINBERG, sort=False, dropna=False)
    counts = grouped[FIRST].first()
    counts["count"] = grouped.size()
    counts[list(CHIRAL_COUNTS)] = grouped[list(CHIRAL_COUNTS)].sum()
    return counts, excluded


def type_frequencies(
    grains: pa.Table | Iterable[pa.Table],
    n_faces: int | None = None,
    class_name: str | None = None,
    include_boundary: bool = False,
    belt_length: int = 4,
) -> pd.DataFrame:
    """A frequency table of grain types, most frequent first.

    Parameters
    ----------
    grains : pyarrow.Table or iterable of pyarrow.Table
        Classified grains (at least the columns in ``COLUMNS``); only ok grains count.
    n_faces, class_name : optional
        Keep only grains with this number of faces, or of this class.
    include_boundary : bool
        Count grains cut by a sample boundary too (as ``summarize`` leaves them out).
    belt_length : int
        The split type of l-belts for this l (``k:l:m``; the tables need the ``splits``
        column), rather than the paper's 4-belts (``k:m``).

    Returns
    -------
    pandas.DataFrame
        Columns ``weinberg, n_faces, p_vector, class, split, penalty, symmetry, count, left,
        achiral, right, fraction`` (:data:`OUTPUT`; also for no input at all): ``split`` is
        ``k:m`` for flag grains, ``left, achiral, right`` the counts by chirality, ``fraction``
        of all grains counted. ``attrs["boundary_excluded"]`` is the number of ok grains (of
        the ``n_faces`` and class asked for) left out as cut by the sample boundary.
    """
    tables = [grains] if isinstance(grains, pa.Table) else grains
    parts = []
    excluded = 0
    for table in tables:
        part, cut = _count_types(table, n_faces, class_name, include_boundary, belt_length)
        parts.append(part)
        excluded += cut
    if not parts:
        return _with_excluded(pd.DataFrame(columns=OUTPUT), excluded)
    both = pd.concat(parts)
    grouped = both.groupby(level=0, sort=False)
    table = grouped[FIRST].first()
    table[["count", *CHIRAL_COUNTS]] = grouped[["count", *CHIRAL_COUNTS]].sum()
    table["fraction"] = table["count"] / table["count"].sum()
    split = table[schema.SPLIT_K].astype("Int64").astype(str) + ":"
    if belt_length != 4:
        split += f"{belt_length}:"
    split += table[schema.SPLIT_M].astype("Int64").astype(str)
    table.insert(3, "split", split.where(table[schema.SPLIT_K].notna(), None))
    table = table.drop(columns=[schema.SPLIT_K, schema.SPLIT_M])
    table[[schema.PENALTY, schema.SYMMETRY]] = table[[schema.PENALTY, schema.SYMMETRY]].astype(
        "Int64"
    )
    table = table.reset_index()[OUTPUT].sort_values(
        ["count", schema.WEINBERG], ascending=[False, True], kind="stable"
    )
    return _with_excluded(table.reset_index(drop=True), excluded)


def _with_excluded(table: pd.DataFrame, excluded: int) -> pd.DataFrame:
    table.attrs["boundary_excluded"] = int(excluded)
    return table


def vorotop_distribution(types: pd.DataFrame, sources: Sequence[str]) -> str:
    r"""What VoroTop's ``-d`` writes (its ``.distribution`` file) for the types counted in
    ``types``, from the inputs named ``sources``.

    Parameters
    ----------
    types : pandas.DataFrame
        A table of :func:`type_frequencies` (at least ``weinberg``, ``count`` and the counts by
        chirality, ``left``, ``achiral``, ``right``).
    sources : sequence of str
        The inputs the types were counted from, as named to the program.

    Returns
    -------
    str
        VoroTop's four ``#`` lines: the inputs (VoroTop names its one input file), the grains
        counted, the types, and the columns. Then a row per type,
        ``(code)<TAB>total<TAB>left<TAB>achiral<TAB>right``, left counting chirality -1, by
        count descending, then by the vector's integers in lexicographic order (VoroTop sorts
        its codes as ``std::vector<int>``: label 10 after 9, not after 1).

    Examples
    --------
    >>> cube = "(1,2,3,4,1,4,5,6,1,6,7,2,7,8,3,8,5,8,7,6,5,4,3,2,1)"
    >>> types = pd.DataFrame(
    ...     {"weinberg": [cube], "count": [2], "left": [0], "achiral": [2], "right": [0]}
    ... )
    >>> text = vorotop_distribution(types, ["cubes.txt"]).splitlines()
    >>> text[0]
    '#\tDISTRIBUTION CREATED FROM cubes.txt'
    >>> text[1:3]
    ['#\tTotal particles sampled: 2', '#\tTotal Voronoi topologies observed: 1']
    >>> text[4]
    '(1,2,3,4,1,4,5,6,1,6,7,2,7,8,3,8,5,8,7,6,5,4,3,2,1)\t2\t0\t2\t0'
    """
    codes = types[schema.WEINBERG].tolist()
    counts = types[["count", "left", "achiral", "right"]].to_numpy(np.int64).tolist()
    keys = _label_bytes(codes)
    order = sorted(range(len(codes)), key=lambda i: (-counts[i][0], keys[i]))
    lines = [
        f"#\tDISTRIBUTION CREATED FROM {' '.join(sources)}",
        f"#\tTotal particles sampled: {sum(row[0] for row in counts)}",
        f"#\tTotal Voronoi topologies observed: {len(codes)}",
        "#\tColumns indicate: Voronoi topology vector, total count, left-handed, non-chiral, "
        "and right-handed types",
    ]
    lines += ["\t".join([codes[i], *map(str, counts[i])]) for i in order]
    return "\n".join(lines) + "\n"


def _label_bytes(codes: list[str], chunk: int = 4096) -> list[bytes]:
    """Each vector ``(1,2,...)``'s labels as big-endian 32-bit integers: bytes that compare as
    VoroTop compares its vectors, lexicographically by the integers, a prefix first. Parsed by
    Arrow ``chunk`` vectors at a time (not label by label in Python, nor all at once: a split
    of every vector would hold each label as a string)."""
    keys: list[bytes] = []
    for start in range(0, len(codes), chunk):
        inner = pc.utf8_slice_codeunits(pa.array(codes[start : start + chunk], pa.string()), 1, -1)
        labels = pc.cast(pc.split_pattern(inner, ","), pa.list_(pa.int32()))
        data = labels.flatten().to_numpy().astype(">u4").tobytes()
        ends = (labels.offsets.to_numpy() * 4).tolist()
        keys += [data[a:b] for a, b in itertools.pairwise(ends)]
    return keys
