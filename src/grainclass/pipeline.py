"""From inputs to per-grain tables, overlapping reading with classification.

Reading (planar_code parsing, text splitting) runs in a background thread while the main thread
classifies: the compiled kernels release the GIL, so the two overlap on separate cores.
"""

from __future__ import annotations

import dataclasses
import queue
import threading
from collections.abc import Iterable, Iterator, Sequence
from typing import TYPE_CHECKING, TypeVar

import pyarrow as pa

from grainclass import interrupts
from grainclass.classification import classify
from grainclass.errors import DataError, Remedy
from grainclass.options import SHORTEST_BELT, ReadOptions
from grainclass.parallel import map_ordered
from grainclass.readers import expand_paths, read_dataset, read_once

if TYPE_CHECKING:
    from grainclass.summary import Tally

T = TypeVar("T")
_DONE = object()


def prefetch(items: Iterable[T], depth: int = 2) -> Iterator[T]:
    """Yield ``items`` in order, computing up to ``depth`` ahead in a background thread.

    An exception in the producer is raised in the consumer; a consumer that stops early stops
    the producer at its next item.
    """
    slots: queue.Queue = queue.Queue(maxsize=depth)
    stop = threading.Event()

    def put(item: object) -> bool:
        """Queue ``item`` unless the consumer has stopped (then it would wait forever)."""
        while not stop.is_set():
            try:
                slots.put(item, timeout=0.1)
                return True
            except queue.Full:
                continue
        return False

    def produce() -> None:
        try:
            for item in items:
                if not put(item):
                    return
            put(_DONE)
        except BaseException as exc:  # handed to the consumer, which raises it
            put(exc)

    worker = threading.Thread(target=produce, name="grainclass-reader", daemon=True)
    worker.start()
    try:
        while True:
            interrupts.checkpoint()
            item = slots.get()
            if item is _DONE:
                return
            if isinstance(item, BaseException):
                raise item
            yield item
    finally:
        stop.set()


def classified_tables(paths: Sequence[str], options: ReadOptions) -> Iterator[pa.Table]:
    """Per-grain tables for every batch of the inputs, in input order: with the Weinberg vectors
    if ``options.types``, with belts of lengths 3..``options.belt_length`` if it is set."""
    from grainclass.parallel import get_jobs
    from grainclass.warmup import compiling_from_both_ends

    with compiling_from_both_ends(get_jobs(), options.types) as watch:
        batches = prefetch(watch(read_dataset(paths, options)))
        yield from map_ordered(
            lambda batch: classify(batch, types=options.types, belts=options.longest_belt),
            batches,
        )


def is_parquet(path: str) -> bool:
    """True for a Parquet file (or standard input, a FIFO, holding one)."""
    once = read_once(path)
    if once is not None:
        return once.peek(4)[:4] == b"PAR1"
    try:
        with open(path, "rb") as handle:
            return handle.read(4) == b"PAR1"
    except OSError:
        return False  # let the reader report it


def grain_tables(
    paths: Sequence[str], columns: list[str], options: ReadOptions
) -> Iterator[pa.Table]:
    """Per-grain tables of ``columns`` with the Weinberg vectors (``columns`` include status and
    weinberg): from classified Parquet files, which must hold them, or, for any other input,
    classified now. With ``options.belt_length``, belts of lengths 3..L too, which Parquet
    files must hold."""
    from grainclass.parquet import iter_grain_tables

    typed = dataclasses.replace(options, types=True)
    for parquet, group in input_runs(paths):
        if parquet:
            for table in iter_grain_tables(group[0], columns):
                _require_types(group[0], table)
                if options.belt_length:
                    _require_belts(group[0], table, options.belt_length)
                yield table
        else:
            for table in classified_tables(group, typed):
                yield table.select(columns)


def input_runs(paths: Sequence[str]) -> Iterator[tuple[bool, list[str]]]:
    """The inputs (a folder stands for its Parquet or ``*.fe`` files) as runs: each
    per-grain Parquet table alone ``(True, [path])``, consecutive inputs of grains together
    ``(False, paths)``, to be read as one stream."""
    for parquet, group in parquet_runs(paths):
        if parquet:
            for path in group:
                yield True, [path]
        else:
            yield False, group


def parquet_runs(paths: Sequence[str]) -> Iterator[tuple[bool, list[str]]]:
    """The inputs as runs of consecutive per-grain Parquet tables ``(True, paths)`` (the parts
    of a data set, say) and of consecutive inputs of grains ``(False, paths)``."""
    run: list[str] = []
    kind = None
    for path in expand_paths(paths):
        parquet = is_parquet(path)
        if run and parquet != kind:
            yield bool(kind), run
            run = []
        kind = parquet
        run.append(path)
    if run:
        yield bool(kind), run


def _require_belts(path: str, table: pa.Table, longest: int) -> None:
    """Refuse a per-grain table whose ok grains lack belts up to length ``longest``."""
    import pyarrow.compute as pc

    from grainclass import schema

    ok = table.filter(pc.equal(table.column(schema.STATUS), "ok"))
    if not len(ok):
        return
    present = [c for c in (schema.SPLITS, schema.BELT_PENALTIES) if c in ok.column_names]
    lengths = pc.list_value_length(ok.column(present[0]))
    shortest = pc.min(pc.fill_null(lengths, 0)).as_py()
    if shortest < longest - 2:
        raise DataError(
            f"{path}: ok grains without their belts of length up to {longest}",
            Remedy("belt_length", longest, reclassify=True),
        )


def _require_types(path: str, table: pa.Table) -> None:
    """Refuse a table whose ok grains lack their Weinberg vectors (classified without types):
    counted, they would all vanish from the types."""
    from grainclass.summary import untyped_grains

    if untyped_grains(table):  # this row group's: the rest of the file is not read yet
        raise DataError(
            f"{path}: ok grains without a Weinberg vector (classified without types)",
            Remedy("types", True, reclassify=True),
        )


def tallies(paths: Sequence[str], options: ReadOptions) -> Iterator[Tally]:
    """What ``summarize`` counts, batch by batch: classified Parquet files are tallied from their
    rows; other inputs are classified on the fly for counting only (planar_code straight from
    its bytes), with the Weinberg vectors if ``options.types`` asks for them, never into
    per-grain tables. With a ``belt_length``, flag grains are counted by the split type of
    their l-belts (Parquet files must hold them)."""
    from grainclass.parallel import get_jobs
    from grainclass.parquet import iter_grain_tables
    from grainclass.schema import SPLITS
    from grainclass.summary import COLUMNS, tally_batch, tally_table
    from grainclass.warmup import compiling_from_both_ends

    length = options.split_length
    by_length = length != SHORTEST_BELT
    columns = [*COLUMNS, SPLITS] if by_length else COLUMNS

    def row_groups(group: list[str]) -> Iterator[tuple[str, pa.Table]]:
        for path in group:
            for table in iter_grain_tables(path, columns):
                yield path, table

    def tally(item: tuple[str, pa.Table]) -> Tally:
        path, table = item
        if by_length:
            _require_belts(path, table, length)
        return tally_table(table, options.include_boundary, length)

    for parquet, group in parquet_runs(paths):
        if parquet:
            # The row groups of a run of tables (a data set's parts) are read in one thread
            # and tallied on every thread, in order; memory holds a row group per thread.
            yield from map_ordered(tally, prefetch(row_groups(group)))
            continue
        # The Weinberg walks and the belts need the CSR lists; counting alone reads planar_code
        # as bytes.
        raw = not options.types and not by_length
        batches = read_dataset(group, options, raw_planar_code=raw)
        with compiling_from_both_ends(get_jobs(), options.types, counting=not options.types) as w:
            yield from map_ordered(
                lambda batch: tally_batch(batch, options.include_boundary, options.types, length),
                prefetch(w(batches)),
            )
