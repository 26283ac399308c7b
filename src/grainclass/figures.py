"""The numbers behind the paper's figures, as tidy tables: one row per point drawn.

Each function takes the data sets to compare (a :class:`Summary` or a type table each) and
returns a frame with columns ``dataset, series, x, y`` (and ``yerr`` where error bars are
drawn): what ``grainclass plot`` draws and ``--data`` writes. Drawing is
:mod:`grainclass.plots`' business.
"""

from __future__ import annotations

import math
import os
import re
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import pandas as pd

from grainclass import schema, vocabulary
from grainclass.errors import DataError
from grainclass.summary import ROUND_LEVELS, Summary

if TYPE_CHECKING:
    from grainclass.options import FigureOptions

COLUMNS = ["dataset", "series", "x", "y"]
ROUND_PEAK = "Round (flag peak)"
WITH_ERRORS = [*COLUMNS, "yerr"]


# Edge errors per grain of fig. combined_cut_types: the first data set of ``edge-errors`` is
# drawn after this many random flips per grain, each.
EEPG = (0, 1, 2, 3)


@dataclass(frozen=True)
class Dataset:
    """One data set of a figure: its label and its summary or type table, or, for
    ``edge-errors``, its grains' counts (:func:`grainclass.summary.merge_tallies`) after
    ``eepg`` random edge flips per grain."""

    label: str
    summary: Summary | None = None
    types: pd.DataFrame | None = None
    counts: pd.DataFrame | None = None
    eepg: int = 0


def _require_ok_grains(dataset: Dataset) -> None:
    if dataset.summary is not None:
        ok = dataset.summary.headline["ok"]
    elif dataset.counts is not None:
        counts = dataset.counts
        ok = int(counts.loc[counts[schema.STATUS] == "ok", "count"].sum())
    else:
        ok = 0 if dataset.types is None else int(dataset.types["count"].sum())
    if not ok:
        raise DataError(f"{dataset.label}: no ok grains to draw")


def _frame(rows: list[dict], columns: list[str]) -> pd.DataFrame:
    return pd.DataFrame(rows, columns=columns)


def round_levels(datasets: Sequence[Dataset], n_values: Sequence[int] = ()) -> pd.DataFrame:
    """Percent of ok grains in round<=k against k = 0..6 (fig. cumulative_all), for all grains
    or, with ``n_values``, for grains with n faces (fig. cumulative_14): the summary's round
    table."""
    rows = []
    for dataset in datasets:
        _require_ok_grains(dataset)
        table = dataset.summary.round
        wanted = [f"n={n}" for n in n_values] or ["all"]
        for label in wanted:
            row = table[table["grains"] == label].iloc[0]
            if not row["count"]:
                raise DataError(f"{dataset.label}: no ok grains with {label[2:]} faces")
            for k in ROUND_LEVELS:
                y = row["round0" if k == 0 else f"round<={k}"]
                rows.append({"dataset": dataset.label, "series": label, "x": k, "y": y})
    return _frame(rows, COLUMNS)


def class_frequencies(datasets: Sequence[Dataset]) -> pd.DataFrame:
    """The fraction of ok grains that have n faces and each class, against n (fig. aggregate),
    and, as series ``all``, the distribution of n: the summary's class table over its total."""
    rows = []
    for dataset in datasets:
        _require_ok_grains(dataset)
        table = dataset.summary.classes
        total = int(table.loc[table["n"] == "total", "all"].iloc[0])
        by_n = table[table["n"] != "total"]
        for series in ("all", *vocabulary.CLASSES):
            for n, count in zip(by_n["n"], by_n[series], strict=True):
                if count:
                    rows.append(
                        {
                            "dataset": dataset.label,
                            "series": series,
                            "x": int(n),
                            "y": count / total,
                        }
                    )
    return _frame(rows, COLUMNS)


def _geometry(datasets: Sequence[Dataset], by: str, kind: str) -> pd.DataFrame:
    rows = []
    for dataset in datasets:
        _require_ok_grains(dataset)
        table = dataset.summary.geometry
        table = table[table["by"] == by]
        if table.empty:
            raise DataError(
                f"{dataset.label}: no ok grain has a volume and an area, which the isoperimetric "
                f"quotient of {kind} needs (inputs with volume= and area=, Evolver, Voro++ or "
                "Neper geometry)"
            )
        for value, mean, se in zip(table["value"], table["mean_Q"], table["se_Q"], strict=True):
            x: int | str = value if value == "sc" else int(value)
            rows.append({"dataset": dataset.label, "series": "Q", "x": x, "y": mean, "yerr": se})
    return _frame(rows, WITH_ERRORS)


def quotient_by_faces(datasets: Sequence[Dataset]) -> pd.DataFrame:
    """Mean isoperimetric quotient of ok grains against n, with its standard error (NaN for a
    single grain): fig. faces_vs_isop."""
    return _geometry(datasets, schema.N_FACES, "faces-q")


def quotient_by_round(datasets: Sequence[Dataset]) -> pd.DataFrame:
    """Mean isoperimetric quotient of round_k grains against k, the sc family last, with its
    standard error (NaN for a single grain): fig. cuts_vs_isop."""
    return _geometry(datasets, schema.ROUND_K, "round-q")


def penalties(datasets: Sequence[Dataset], min_frequency: float = 1e-5) -> pd.DataFrame:
    """Flag types with a frequency among all ok grains of at least ``min_frequency``, against
    their penalty (fig. penalty); the series is the number of faces, ``n=N``."""
    rows = []
    for dataset in datasets:
        _require_ok_grains(dataset)
        types = dataset.types
        flag = types[(types[schema.CLASS] == "flag") & (types["fraction"] >= min_frequency)]
        for n, penalty, fraction in zip(
            flag[schema.N_FACES], flag[schema.PENALTY], flag["fraction"], strict=True
        ):
            x = int(penalty) if float(penalty).is_integer() else float(penalty)
            rows.append({"dataset": dataset.label, "series": f"n={n}", "x": x, "y": fraction})
    return _frame(rows, COLUMNS)


def type_ranks(datasets: Sequence[Dataset]) -> pd.DataFrame:
    """Each type's frequency among ok grains against its rank, most frequent first."""
    rows = []
    for dataset in datasets:
        _require_ok_grains(dataset)
        for rank, fraction in enumerate(dataset.types["fraction"], start=1):
            rows.append({"dataset": dataset.label, "series": "types", "x": rank, "y": fraction})
    return _frame(rows, COLUMNS)


def series_percent(summary: Summary, series: str) -> float:
    """The percentage of ok grains in a class (``flag``, ``sc+1``, ...), or of a named kind:
    ``tetrahedron`` (4 faces), ``cube`` (the flag grain with 6 faces), ``dodecahedron`` (the
    flag grain with 12 faces and split type 0:8), ``0:m`` (flag grains of split type 0:m);
    ``triangles`` is the percentage of the ok grains' faces that are triangles."""
    if series == "triangles":
        return float(summary.headline["triangle_faces_percent"])
    classes = summary.classes
    total = int(classes.loc[classes["n"] == "total", "all"].iloc[0])
    if series in vocabulary.CLASSES:
        count = int(classes.loc[classes["n"] == "total", series].iloc[0])
    elif series in ("tetrahedron", "cube"):
        n, column = ("4", "all") if series == "tetrahedron" else ("6", "flag")
        count = int(classes.loc[classes["n"] == n, column].sum())
    elif series in ("dodecahedron", "0:m"):
        split = summary.split
        rows = split[split["n"] == 12] if series == "dodecahedron" else split
        count = int(rows["0"].sum()) if "0" in split.columns else 0
    else:
        raise AssertionError(f"no series {series!r}: FigureOptions checks its series")
    return 100.0 * count / total if total else math.nan


def steps_from_names(paths: Sequence[str]) -> list[float]:
    """The time step of each input, read from its name: the one number in the file or folder
    name (``dump/21000`` -> 21000, ``step21000.parquet`` -> 21000).

    Raises
    ------
    DataError
        For a name with no number or several, or two inputs with the same step.
    """
    steps = []
    for path in paths:
        name = os.path.basename(os.path.normpath(path))
        stem = name if os.path.isdir(path) else os.path.splitext(name)[0]
        numbers = re.findall(r"\d+(?:\.\d+)?", stem)
        if len(numbers) != 1:
            found = "no number" if not numbers else f"{len(numbers)} numbers"
            raise DataError(
                f"{path}: cannot read a time step from its name ({found} in {stem!r}): "
                "give the steps with --times"
            )
        steps.append(float(numbers[0]))
    _require_distinct(paths, steps)
    return steps


def _require_distinct(paths: Sequence[str], steps: Sequence[float]) -> None:
    seen: dict[float, str] = {}
    for path, step in zip(paths, steps, strict=True):
        if step in seen:
            raise DataError(f"{path}: time step {step:g} is also that of {seen[step]}")
        seen[step] = path


def evolution(
    datasets: Sequence[Dataset], steps: Sequence[float], series: Sequence[str], label: str
) -> pd.DataFrame:
    """The percentage of ok grains in each series against the time step (figs. flag_over_time,
    triangles_over_time, combinatorial_parameters), one input a step, and, as series
    ``Round (flag peak)``, the step where the fraction of flag grains peaks (the Round
    microstructure) when there are several steps."""
    rows = []
    flag = []
    for i in np.argsort(steps, kind="stable"):
        dataset, step = datasets[i], steps[i]
        _require_ok_grains(dataset)
        x = int(step) if float(step).is_integer() else step
        for name in series:
            y = series_percent(dataset.summary, name)
            rows.append({"dataset": label, "series": name, "x": x, "y": y})
        flag.append((series_percent(dataset.summary, "flag"), x))
    if len(flag) > 1:  # a single step has no peak to speak of
        peak, at = max(flag, key=lambda item: item[0])  # the first step of the highest
        rows.append({"dataset": label, "series": ROUND_PEAK, "x": at, "y": peak})
    return _frame(rows, COLUMNS)


def round_k_frequencies(datasets: Sequence[Dataset]) -> pd.DataFrame:
    """Percent of ok grains with round_k = k against k, from 0 to the largest k of any data set,
    then of the sc family (x ``sc``): figs. round_k_cuts and combined_cut_types. The series
    says how many random edge flips per grain the data set's grains had (``0 EEPG``, ``1
    EEPG``, ...)."""
    ok = []
    for dataset in datasets:
        _require_ok_grains(dataset)
        counts = dataset.counts
        ok.append(counts[counts[schema.STATUS] == "ok"])
    largest = max(
        (int(part[schema.ROUND_K].max()) for part in ok if part[schema.ROUND_K].notna().any()),
        default=0,
    )
    rows = []
    for dataset, part in zip(datasets, ok, strict=True):
        total = int(part["count"].sum())
        by_k = part.groupby(schema.ROUND_K)["count"].sum()
        sc = int(part.loc[part[schema.FAMILY] == "sc", "count"].sum())
        series = f"{dataset.eepg} EEPG"
        for k in range(largest + 1):
            y = 100.0 * int(by_k.get(float(k), 0)) / total
            rows.append({"dataset": dataset.label, "series": series, "x": k, "y": y})
        rows.append(
            {"dataset": dataset.label, "series": series, "x": "sc", "y": 100.0 * sc / total}
        )
    return _frame(rows, COLUMNS)


def figure_data(request: FigureOptions, datasets: Sequence[Dataset], label: str) -> pd.DataFrame:
    """The tidy table of the figure ``request.kind`` for ``datasets``; ``evolution`` takes them
    as the time steps of one data set, ``label``, at ``request.steps`` (else read from their
    labels, the inputs' names, by :func:`steps_from_names`).

    Raises
    ------
    DataError
        When the data sets cannot give the figure, or give it no point to draw.
    """
    table = _figure_data(request, datasets, label)
    if table.empty:
        names = ", ".join(dict.fromkeys(d.label for d in datasets))
        what = (
            f"no flag type with a frequency of at least {request.min_frequency:g}"
            if request.kind == "penalty"
            else "no point"
        )
        raise DataError(f"{names}: {what} to draw in the {request.kind} figure")
    return table


def _figure_data(request: FigureOptions, datasets: Sequence[Dataset], label: str) -> pd.DataFrame:
    kind, n_values, steps = request.kind, request.n_values, request.steps
    if kind == "round":
        return round_levels(datasets, n_values)
    if kind == "classes":
        return class_frequencies(datasets)
    if kind == "faces-q":
        return quotient_by_faces(datasets)
    if kind == "round-q":
        return quotient_by_round(datasets)
    if kind == "penalty":
        return penalties(datasets, request.min_frequency)
    if kind == "ranks":
        return type_ranks(datasets)
    if kind == "edge-errors":
        return round_k_frequencies(datasets)
    if kind == "evolution":
        labels = [d.label for d in datasets]
        if steps is None:
            steps = steps_from_names(labels)
        else:
            _require_distinct(labels, steps)
        return evolution(datasets, steps, request.series, label)
    raise AssertionError(f"a FigureOptions of no known kind: {kind!r}")
