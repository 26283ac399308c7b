"""From paths to results in one call: per-grain rows, the paper's tables, type counts, penalty
correlations and the numbers behind a figure.

Each function reads its inputs (any format grainclass reads, per-grain Parquet files, or folders
of either) with one :class:`~grainclass.options.ReadOptions`, given whole or as keyword settings
(the same names as the command line's options), and streams them through the classification in
bounded memory. The commands call these; so can a notebook:

>>> from grainclass import read_grains
>>> read_grains("examples/polytopes.txt")[["n_faces", "class"]].head(3).values.tolist()
[[4, 'stacked'], [5, 'stacked'], [6, 'flag']]

``watch`` sees every batch go by (the command line draws its progress so); the batch-level API
(:func:`grainclass.read_dataset`, :func:`grainclass.classify`) stays for streaming.
"""

from __future__ import annotations

import contextlib
import dataclasses
from collections.abc import Callable, Iterable, Iterator, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, TypeVar

from grainclass.errors import DataError, OptionError
from grainclass.options import FigureOptions, ReadOptions, require_choice
from grainclass.vocabulary import CLASSES

if TYPE_CHECKING:
    import pandas as pd
    import pyarrow as pa

    from grainclass.figures import Dataset
    from grainclass.summary import Summary

T = TypeVar("T")
Watch = Callable[[Iterable[Any]], Iterable[Any]]
Paths = str | Sequence[str]


def _unwatched(items: Iterable[T]) -> Iterable[T]:
    return items


def _paths(paths: Paths) -> list[str]:
    return [paths] if isinstance(paths, str) else [str(p) for p in paths]


@contextlib.contextmanager
def _jobs(options: ReadOptions) -> Iterator[None]:
    """The kernels on ``options.jobs`` threads for the call, as they were after it."""
    from grainclass.parallel import get_jobs, set_jobs

    if options.jobs is None or options.jobs == get_jobs():
        yield
        return
    before = get_jobs()
    set_jobs(options.jobs)
    try:
        yield
    finally:
        set_jobs(before)


def grain_tables(
    paths: Paths,
    options: ReadOptions | None = None,
    watch: Watch = _unwatched,
    **settings: Any,
) -> Iterator[pa.Table]:
    """The per-grain tables of the inputs, batch by batch, in input order: Parquet files as they
    are, any other input classified now (with its Weinberg vectors if ``types``, its belts up to
    ``belt_length`` if set)."""
    from grainclass.parquet import iter_grain_tables
    from grainclass.pipeline import classified_tables, input_runs
    from grainclass.schema import GRAIN_SCHEMA

    options = ReadOptions.of(options, **settings)
    with _jobs(options):
        for parquet, group in input_runs(_paths(paths)):
            tables = (
                iter_grain_tables(group[0], GRAIN_SCHEMA.names)
                if parquet
                else classified_tables(group, options)
            )
            yield from watch(tables)


def read_grains(
    paths: Paths, options: ReadOptions | None = None, watch: Watch = _unwatched, **settings: Any
) -> pd.DataFrame:
    """Every grain of the inputs as a row of a pandas DataFrame, with the columns of
    ``grainclass classify`` (docs/definitions.md), in input order.

    Parameters
    ----------
    paths : str or sequence of str
        Inputs of any format grainclass reads, per-grain Parquet files, or folders of either.
    options : ReadOptions, optional
        How to read them; ``settings`` (``input_format=``, ``types=``, ``belt_length=``, ...)
        replace its fields.

    Raises
    ------
    InputError, DataError, OptionError
    """
    import pandas as pd
    import pyarrow as pa

    from grainclass.schema import GRAIN_SCHEMA

    columns = GRAIN_SCHEMA.names
    tables = [table.select(columns) for table in grain_tables(paths, options, watch, **settings)]
    table = pa.concat_tables(tables) if tables else GRAIN_SCHEMA.empty_table()
    # Integer and boolean columns with nulls stay integers and booleans (pandas' nullable
    # types), not floats and objects.
    nullable = {
        pa.int8(): pd.Int8Dtype(),
        pa.int32(): pd.Int32Dtype(),
        pa.int64(): pd.Int64Dtype(),
        pa.bool_(): pd.BooleanDtype(),
    }
    return table.to_pandas(types_mapper=nullable.get)


@dataclass(frozen=True)
class Written:
    """What :func:`write_grains` wrote: its rows, their count by status, and the attribute
    columns that no grain of the first batch had, which are not written."""

    rows: int
    statuses: dict[str, int]
    dropped: frozenset[str]


def write_grains(
    paths: Paths,
    output: str,
    options: ReadOptions | None = None,
    watch: Watch = _unwatched,
    metadata: dict[str, str] | None = None,
    **settings: Any,
) -> Written:
    """Classify every grain of the inputs into the per-grain Parquet file ``output`` (``-``:
    standard output), written whole or not at all, with ``metadata`` added to the file's."""
    from grainclass.parquet import GrainTableWriter
    from grainclass.pipeline import classified_tables

    options = ReadOptions.of(options, **settings)
    statuses: dict[str, int] = {}
    with _jobs(options), GrainTableWriter(output, metadata) as writer:
        for table in watch(classified_tables(_paths(paths), options)):
            for item in table.column("status").value_counts().to_pylist():
                statuses[item["values"]] = statuses.get(item["values"], 0) + item["counts"]
            writer.write(table)
    return Written(writer.rows, statuses, frozenset(writer.dropped))


def summary_tables(
    paths: Paths,
    options: ReadOptions | None = None,
    watch: Watch = _unwatched,
    n_values: Sequence[int] = (),
    **settings: Any,
) -> Summary:
    """The paper's tables (classes, round, split, geometry) and the headline figures of the
    inputs' grains: per-grain Parquet files are counted from their rows, other inputs
    classified for counting only. ``n_values``: numbers of faces that get a round-table row of
    their own. Grains cut by a sample boundary are left out unless ``include_boundary``."""
    from grainclass.pipeline import tallies
    from grainclass.summary import summarize

    options = ReadOptions.of(options, **settings)
    with _jobs(options):
        stream = watch(tallies(_paths(paths), options))
        return summarize(stream, tuple(n_values), options.include_boundary, options.split_length)


def type_counts(
    paths: Paths,
    options: ReadOptions | None = None,
    watch: Watch = _unwatched,
    n_faces: int | None = None,
    class_name: str | None = None,
    **settings: Any,
) -> pd.DataFrame:
    """The inputs' ok grains counted by combinatorial type (Weinberg vector), most frequent
    first (:func:`grainclass.frequencies.type_frequencies`), only those with ``n_faces`` faces
    or of class ``class_name`` if given."""
    from grainclass.frequencies import COLUMNS, type_frequencies
    from grainclass.pipeline import grain_tables as typed_tables
    from grainclass.schema import SPLITS

    options = ReadOptions.of(options, **settings)
    if class_name is not None:
        require_choice("class_name", class_name, CLASSES, "class")
    columns = [*COLUMNS, SPLITS] if options.belt_length else COLUMNS
    with _jobs(options):
        tables = watch(typed_tables(_paths(paths), columns, options))
        return type_frequencies(
            tables, n_faces, class_name, options.include_boundary, options.split_length
        )


def penalty_table(
    paths: Paths,
    options: ReadOptions | None = None,
    watch: Watch = _unwatched,
    n_values: Sequence[int] = (),
    **settings: Any,
) -> pd.DataFrame:
    """Spearman's rho per n between the flag types' counts and each candidate penalty
    (:func:`grainclass.penalties.penalty_correlations`), over belts of lengths 4..L
    (``belt_length``, default 6)."""
    from grainclass.penalties import COLUMNS, penalty_correlations
    from grainclass.pipeline import grain_tables as typed_tables

    options = ReadOptions.of(options, **settings)
    if options.belt_length is None:
        options = dataclasses.replace(options, belt_length=6)
    with _jobs(options):
        tables = watch(typed_tables(_paths(paths), COLUMNS, options))
        return penalty_correlations(tables, n_values, options.include_boundary, options.belt_length)


TYPED_KINDS = ("penalty", "ranks")  # kinds drawn from type tables (Weinberg vectors)


def figure_table(
    paths: Paths,
    request: FigureOptions,
    labels: Sequence[str] = (),
    options: ReadOptions | None = None,
    watch: Watch = _unwatched,
    **settings: Any,
) -> pd.DataFrame:
    """The numbers a figure draws, one row per point (``dataset, series, x, y`` and ``yerr``
    where error bars are drawn): each input a data set named by ``labels`` (default: its file
    name), or, for ``evolution``, each input a time step of one data set (``labels``: at most
    one name for it).

    Raises
    ------
    DataError
        When a data set cannot give the figure (no ok grains, no volumes, no time step).
    """
    import os

    from grainclass.figures import figure_data

    paths = _paths(paths)
    options = ReadOptions.of(options, **settings)
    if request.kind == "evolution":
        if len(labels) > 1:
            raise OptionError("labels", "evolution draws one data set: give it one name at most")
        if request.steps is not None and len(request.steps) != len(paths):
            raise OptionError(
                "steps", f"{len(request.steps)} time steps for {len(paths)} inputs: give one each"
            )
        names = paths
    elif labels and len(labels) != len(paths):
        raise OptionError("labels", f"{len(labels)} names for {len(paths)} inputs: give one each")
    else:
        names = list(labels) or [
            "stdin" if p == "-" else os.path.basename(os.path.normpath(p)) for p in paths
        ]
    with _jobs(options):
        datasets = _datasets(paths, names, request, options, watch)
    label = labels[0] if labels and request.kind == "evolution" else "steps"
    return figure_data(request, datasets, label)


def _datasets(
    paths: list[str], names: list[str], request: FigureOptions, options: ReadOptions, watch: Watch
) -> list[Dataset]:
    """Each input as a data set of the figure: its summary, or, for the kinds drawn from types,
    its type table; for ``edge-errors``, the first input's counts after 0..3 random edge flips
    per grain, then the others' counts."""
    from grainclass.figures import Dataset

    if request.kind == "edge-errors":
        return _edge_error_datasets(paths, names, request.seed or 0, options, watch)
    datasets = []
    for path, name in zip(paths, names, strict=True):
        if request.kind == "penalty" and request.penalty != "P4":
            datasets.append(Dataset(name, types=_candidate_types(path, request, options, watch)))
        elif request.kind in TYPED_KINDS:
            datasets.append(Dataset(name, types=type_counts(path, options, watch)))
        else:
            unbelted = dataclasses.replace(options, types=False, belt_length=None)
            summary = summary_tables(path, unbelted, watch, request.n_values)
            datasets.append(Dataset(name, summary=summary))
    return datasets


def _edge_error_datasets(
    paths: list[str], names: list[str], seed: int, options: ReadOptions, watch: Watch
) -> list[Dataset]:
    """The first input's grains after 0, 1, 2 and 3 random edge flips per grain (the streams of
    ``grainclass perturb --flips K --seed SEED``), perturbed as they are read, then the other
    inputs as they are."""
    from grainclass.figures import EEPG, Dataset
    from grainclass.perturb import perturbed_tallies
    from grainclass.pipeline import is_parquet, tallies
    from grainclass.summary import merge_tallies

    first = paths[0]
    if is_parquet(first):
        raise DataError(
            f"{first}: edge-errors flips the edges of the first input's grains, which a "
            "classified Parquet table no longer holds: give the grains themselves (adjacency "
            "text, planar_code, Evolver, ...)"
        )
    by_level: dict[int, list[pd.DataFrame]] = {k: [] for k in EEPG}

    def unflipped() -> Iterator:  # each batch's tally as read, for watch to count
        for level_tallies in perturbed_tallies(first, EEPG, seed, options):
            for k, part in zip(EEPG, level_tallies, strict=True):
                by_level[k].append(part.counts)
            yield level_tallies[0]

    for _ in watch(unflipped()):
        pass
    datasets = [Dataset(names[0], counts=merge_tallies(by_level[k]), eepg=k) for k in EEPG]
    counting = dataclasses.replace(options, types=False, belt_length=None)
    for path, name in zip(paths[1:], names[1:], strict=True):
        counted = watch(tallies([path], counting))
        datasets.append(Dataset(name, counts=merge_tallies([t.counts for t in counted])))
    return datasets


def _candidate_types(
    path: str, request: FigureOptions, options: ReadOptions, watch: Watch
) -> pd.DataFrame:
    """The flag types of one input with the candidate penalty in the penalty column and their
    frequency among its ok grains."""
    import pandas as pd

    from grainclass import schema
    from grainclass.penalties import COLUMNS, candidates, flag_types
    from grainclass.pipeline import grain_tables as typed_tables

    longest = options.belt_length or 6
    belted = dataclasses.replace(options, belt_length=longest)
    types = flag_types(watch(typed_tables([path], COLUMNS, belted)), options.include_boundary)
    return pd.DataFrame(
        {
            schema.N_FACES: types[schema.N_FACES],
            schema.CLASS: "flag",
            schema.PENALTY: candidates(types, longest)[request.penalty] if len(types) else [],
            "count": types["count"],
            "fraction": types["count"] / max(types.attrs["ok_grains"], 1),
        }
    )
