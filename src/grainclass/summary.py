"""`summarize`: per-grain rows in, the paper's tables out. Aggregation only, no formatting."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd
import pyarrow as pa

from grainclass import schema

COLUMNS = [
    schema.STATUS,
    schema.N_FACES,
    schema.N_TRIANGLES,
    schema.FAMILY,
    schema.CLASS,
    schema.ROUND_K,
    schema.SPLIT_K,
]
ROUND_LEVELS = range(7)
TABLES = ("classes", "round", "split")


@dataclass(frozen=True)
class Summary:
    """The headline figures and the three tables of :func:`summarize`."""

    headline: dict[str, float | int]
    classes: pd.DataFrame
    round: pd.DataFrame
    split: pd.DataFrame

    def table(self, name: str) -> pd.DataFrame:
        """One of ``classes``, ``round``, ``split``."""
        return {"classes": self.classes, "round": self.round, "split": self.split}[name]


def _headline(grains: pd.DataFrame) -> dict[str, float | int]:
    ok = grains[grains[schema.STATUS] == "ok"]
    counts = grains[schema.STATUS].value_counts()
    faces = int(ok[schema.N_FACES].sum())
    return {
        "grains": len(grains),
        **{status: int(counts.get(status, 0)) for status in schema.STATUSES},
        "mean_faces": float(ok[schema.N_FACES].mean()) if len(ok) else float("nan"),
        "triangle_faces_percent": (
            100.0 * float(ok[schema.N_TRIANGLES].sum()) / faces if faces else float("nan")
        ),
    }


def class_counts(grains: pd.DataFrame) -> pd.DataFrame:
    """Counts of ok grains per number of faces and class: the paper's Tables II, V, R and E.

    Returns a frame with columns ``n, all, stacked, flag, ..., sc>=2`` and a final ``total`` row.
    """
    ok = grains[grains[schema.STATUS] == "ok"]
    table = pd.crosstab(ok[schema.N_FACES], ok[schema.CLASS])
    table = table.reindex(columns=list(schema.CLASSES), fill_value=0)
    table.insert(0, "all", table.sum(axis=1))
    table.index = table.index.astype(str)
    table.loc["total"] = table.sum(axis=0)
    table.index.name = "n"
    table.columns.name = None
    return table.reset_index().astype({c: "int64" for c in ["all", *schema.CLASSES]})


def round_percentages(grains: pd.DataFrame, n_values: tuple[int, ...] = ()) -> pd.DataFrame:
    """Percentages of ok grains in round<=k (k = 0..6) and in the sc family: the paper's Table
    ``tbl:distribution``, for all grains and for each requested number of faces.
    """
    ok = grains[grains[schema.STATUS] == "ok"]
    groups = [("all", ok)] + [(f"n={n}", ok[ok[schema.N_FACES] == n]) for n in n_values]
    rows = []
    for label, part in groups:
        total = len(part)
        round_k = part[schema.ROUND_K]
        row: dict[str, object] = {"grains": label, "count": total}
        for k in ROUND_LEVELS:
            hits = int((round_k <= k).sum())
            row["round0" if k == 0 else f"round<={k}"] = (
                round(100.0 * hits / total, 2) if total else np.nan
            )
        sc = int((part[schema.FAMILY] == "sc").sum())
        row["sc"] = round(100.0 * sc / total, 2) if total else np.nan
        rows.append(row)
    return pd.DataFrame(rows)


def split_counts(grains: pd.DataFrame) -> pd.DataFrame:
    """Counts of ``flag`` grains by number of faces (rows) and split type k (columns).

    The split type is k:m with m = n - 4 - k. The paper's Table ``tbl:flag_few_vertices``.
    """
    flag = grains[(grains[schema.STATUS] == "ok") & (grains[schema.CLASS] == "flag")]
    table = pd.crosstab(flag[schema.N_FACES], flag[schema.SPLIT_K].astype("int64"))
    if len(table.columns):
        table = table.reindex(columns=range(int(table.columns.max()) + 1), fill_value=0)
    table.index.name = "n"
    table.columns = [str(k) for k in table.columns]
    return table.reset_index().astype("int64")


def summarize(grains: pa.Table | pd.DataFrame, n_values: tuple[int, ...] = ()) -> Summary:
    """Summarize classified grains into the paper's tables.

    Parameters
    ----------
    grains : pyarrow.Table or pandas.DataFrame
        Rows as written by ``grainclass classify`` (at least the columns in ``COLUMNS``).
    n_values : tuple of int
        Numbers of faces for which the round table gets a row of its own.

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
    if isinstance(grains, pa.Table):
        grains = grains.select(COLUMNS).to_pandas()
    return Summary(
        headline=_headline(grains),
        classes=class_counts(grains),
        round=round_percentages(grains, tuple(n_values)),
        split=split_counts(grains),
    )
