"""`penalty_correlations`: how well candidate penalties rank the frequencies of flag types.

For the flag grains of a data set (fundamental, no truncations), grouped by type (Weinberg
vector), each candidate penalty is a number per type that should be larger the rarer the type;
its Spearman rank correlation with the types' counts, per number of faces n, says how well it
ranks them (-1: perfectly, larger penalty always rarer; 0: not at all). Spearman's rho is the
Pearson correlation of the ranks (ties get their average rank), computed here with pandas'
ranks.

The candidates, from the per-grain columns ``belt_penalties`` (l = 3..L) and ``symmetry``:

- ``P4``: the paper's penalty, n times the sum over 4-belts of k (n - 4 - k);
- ``P4..L``: the same summed over the l-belts of every length l = 4..L;
- ``P4/sym``, ``P4..L/sym``: each divided by the symmetry order;
- ``sym``: the symmetry order alone; ``(1+P4)*sym``, ``(1+P4..L)*sym``: each (plus one, so
  that types without belts are told apart too) times it, as a type's frequency among the cells
  of a random tessellation falls with its symmetry order.
"""

from __future__ import annotations

from collections.abc import Iterable

import numpy as np
import pandas as pd
import pyarrow as pa
import pyarrow.compute as pc

from grainclass import schema
from grainclass.errors import DataError, Remedy
from grainclass.summary import uncut
from grainclass.vocabulary import PENALTIES

COLUMNS = [
    schema.STATUS,
    schema.CLASS,
    schema.N_FACES,
    schema.WEINBERG,
    schema.SYMMETRY,
    schema.BELT_PENALTIES,
    schema.BOUNDARY,
]


def spearman(x: pd.Series, y: pd.Series) -> float:
    """Spearman's rank correlation of two series (NaN where either is constant)."""
    rx, ry = x.rank(), y.rank()
    if rx.nunique() < 2 or ry.nunique() < 2:
        return float("nan")
    return float(np.corrcoef(rx.to_numpy(float), ry.to_numpy(float))[0, 1])


def flag_types(
    grains: pa.Table | Iterable[pa.Table], include_boundary: bool = False
) -> pd.DataFrame:
    """The flag types of per-grain tables with their belt penalties: one row per Weinberg
    vector, with ``n_faces``, ``symmetry``, ``count`` and one column per l of
    ``belt_penalties`` (``P3``, ``P4``, ...); ``attrs["ok_grains"]`` is the number of ok
    grains counted (all classes), for frequencies among them."""
    tables = [grains] if isinstance(grains, pa.Table) else grains
    parts = []
    ok_grains = 0
    for table in tables:
        ok = pc.equal(table.column(schema.STATUS), "ok")
        counted = uncut(table, include_boundary)
        if counted is not None:
            ok = pc.and_(ok, pa.array(counted))
        ok_grains += pc.sum(ok).as_py() or 0
        keep = pc.and_(ok, pc.equal(table.column(schema.CLASS), "flag"))
        kept = table.select(COLUMNS).filter(keep)
        if pc.any(pc.is_null(kept.column(schema.BELT_PENALTIES))).as_py():
            raise DataError("flag grains without belt penalties", Remedy("belt_length", 6, True))
        frame = kept.select([schema.WEINBERG, schema.N_FACES, schema.SYMMETRY]).to_pandas()
        penalties = kept.column(schema.BELT_PENALTIES).to_pylist()
        width = max((len(p) for p in penalties), default=0)
        for i in range(width):
            frame[f"P{i + 3}"] = [p[i] if i < len(p) else np.nan for p in penalties]
        parts.append(frame)
    if not parts or not sum(len(p) for p in parts):
        types = pd.DataFrame(columns=[schema.WEINBERG, schema.N_FACES, schema.SYMMETRY, "count"])
    else:
        frame = pd.concat(parts, ignore_index=True)
        grouped = frame.groupby(schema.WEINBERG, sort=False)
        types = grouped.first()
        types["count"] = grouped.size()
        types = types.reset_index()
    types.attrs["ok_grains"] = ok_grains
    return types


def candidates(types: pd.DataFrame, longest: int) -> pd.DataFrame:
    """The candidate penalties (:data:`PENALTIES`) of each type, l up to ``longest``."""
    sym = types[schema.SYMMETRY].astype(float)
    p4 = types["P4"].astype(float)
    total = sum(types[f"P{length}"].astype(float) for length in range(4, longest + 1))
    return pd.DataFrame(
        {
            "P4": p4,
            "P4..L": total,
            "P4/sym": p4 / sym,
            "P4..L/sym": total / sym,
            "sym": sym,
            "(1+P4)*sym": (1 + p4) * sym,
            "(1+P4..L)*sym": (1 + total) * sym,
        }
    )


def penalty_correlations(
    grains: pa.Table | Iterable[pa.Table],
    n_values: Iterable[int] | None = None,
    include_boundary: bool = False,
    longest: int = 6,
) -> pd.DataFrame:
    """Spearman's rho per n between the flag types' counts and each candidate penalty.

    Returns a frame with columns ``n``, ``types``, ``grains`` and one per candidate (of
    :data:`PENALTIES`, summed over l = 4..``longest``), a row per n that has at least three
    flag types (or per n of ``n_values``).
    """
    types = flag_types(grains, include_boundary)
    lengths = [int(c[1:]) for c in types.columns if c.startswith("P") and c[1:].isdigit()]
    if len(types) and max(lengths, default=0) < longest:
        raise DataError(
            f"flag grains without belt penalties up to l = {longest}",
            Remedy("belt_length", longest, reclassify=True),
        )
    values = candidates(types, longest) if len(types) else pd.DataFrame(columns=PENALTIES)
    rows = []
    wanted = sorted(set(n_values)) if n_values else sorted(types[schema.N_FACES].unique())
    for n in wanted:
        at_n = types[schema.N_FACES] == n
        count = types.loc[at_n, "count"]
        if not n_values and len(count) < 3:
            continue
        row = {"n": int(n), "types": int(at_n.sum()), "grains": int(count.sum())}
        for name in PENALTIES:
            row[name] = spearman(count, values.loc[at_n, name])
        rows.append(row)
    return pd.DataFrame(rows, columns=["n", "types", "grains", *PENALTIES])
