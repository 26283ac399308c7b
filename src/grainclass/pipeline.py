"""From inputs to per-grain tables, overlapping reading with classification.

Reading (planar_code parsing, text splitting) runs in a background thread while the main thread
classifies: the compiled kernels release the GIL, so the two overlap on separate cores.
"""

from __future__ import annotations

import queue
import threading
from collections.abc import Iterable, Iterator, Sequence
from typing import TYPE_CHECKING, TypeVar

import pyarrow as pa

from grainclass import DEFAULT_CHUNK_SIZE
from grainclass.classification import classify
from grainclass.parallel import map_ordered
from grainclass.readers import read_dataset, read_once
from grainclass.readers.evolver import DEFAULT_TRIPLE_EDGES

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
            item = slots.get()
            if item is _DONE:
                return
            if isinstance(item, BaseException):
                raise item
            yield item
    finally:
        stop.set()


def classified_tables(
    paths: Sequence[str],
    format: str | None = None,
    chunk_size: int = DEFAULT_CHUNK_SIZE,
    triple_edges: tuple[str, str] = DEFAULT_TRIPLE_EDGES,
    types: bool = True,
    belts: int = 0,
) -> Iterator[pa.Table]:
    """Per-grain tables for every batch of the inputs, in input order, with belts of lengths
    3..``belts`` if it is not 0."""
    from grainclass.parallel import get_jobs
    from grainclass.warmup import compiling_from_both_ends

    with compiling_from_both_ends(get_jobs(), types) as watch:
        batches = prefetch(watch(read_dataset(paths, format, chunk_size, triple_edges)))
        yield from map_ordered(lambda batch: classify(batch, types=types, belts=belts), batches)


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
    paths: Sequence[str],
    columns: list[str],
    format: str | None = None,
    chunk_size: int = DEFAULT_CHUNK_SIZE,
    triple_edges: tuple[str, str] = DEFAULT_TRIPLE_EDGES,
    belts: int = 0,
) -> Iterator[pa.Table]:
    """Per-grain tables with the Weinberg vectors (``columns`` include status and weinberg):
    from classified Parquet files, which must hold them, or, for any other input, classified
    now. With ``belts``, belts of lengths 3..``belts`` too, which Parquet files must hold."""
    from grainclass.parquet import iter_grain_tables

    for path in paths:
        if is_parquet(path):
            for table in iter_grain_tables(path, columns):
                _require_types(path, table)
                if belts:
                    _require_belts(path, table, belts)
                yield table
        else:
            tables = classified_tables([path], format, chunk_size, triple_edges, belts=belts)
            for table in tables:
                yield table.select(columns)


def _require_belts(path: str, table: pa.Table, longest: int) -> None:
    """Refuse a per-grain table whose ok grains lack belts up to length ``longest``."""
    import pyarrow.compute as pc

    from grainclass import schema
    from grainclass.errors import InputError

    ok = table.filter(pc.equal(table.column(schema.STATUS), "ok"))
    if not len(ok):
        return
    present = [c for c in (schema.SPLITS, schema.BELT_PENALTIES) if c in ok.column_names]
    lengths = pc.list_value_length(ok.column(present[0]))
    shortest = pc.min(pc.fill_null(lengths, 0)).as_py()
    if shortest < longest - 2:
        raise InputError(
            path,
            f"ok grains without belts of length up to {longest}: classify the input again "
            f"with --belts --belt-lengths {max(longest, 6)}",
        )


def _require_types(path: str, table: pa.Table) -> None:
    """Refuse a table whose ok grains lack their Weinberg vectors (classified with
    ``--no-types``): counted, they would all vanish from the types."""
    from grainclass.errors import InputError
    from grainclass.summary import untyped_grains

    if untyped_grains(table):  # this row group's: the rest of the file is not read yet
        raise InputError(
            path,
            "ok grains without a Weinberg vector (classified with --no-types): "
            "classify the input again without --no-types",
        )


def tallies(
    paths: Sequence[str],
    format: str | None = None,
    chunk_size: int = DEFAULT_CHUNK_SIZE,
    triple_edges: tuple[str, str] = DEFAULT_TRIPLE_EDGES,
    types: bool = False,
    include_boundary: bool = False,
    belt_length: int = 4,
) -> Iterator[Tally]:
    """What ``summarize`` counts, batch by batch: classified Parquet files are tallied from their
    rows; other inputs are classified on the fly for counting only (planar_code straight from
    its bytes), with the Weinberg vectors if ``types`` asks for them, never into per-grain
    tables. With a ``belt_length`` other than 4, flag grains are counted by the split type of
    their l-belts (Parquet files must hold them)."""
    from grainclass.parallel import get_jobs
    from grainclass.parquet import iter_grain_tables
    from grainclass.schema import SPLITS
    from grainclass.summary import COLUMNS, tally_batch, tally_table
    from grainclass.warmup import compiling_from_both_ends

    by_length = belt_length != 4
    for path in paths:
        if is_parquet(path):
            for table in iter_grain_tables(path, [*COLUMNS, SPLITS] if by_length else COLUMNS):
                if by_length:
                    _require_belts(path, table, belt_length)
                yield tally_table(table, include_boundary, belt_length)
            continue
        # The Weinberg walks and the belts need the CSR lists; counting alone reads planar_code
        # as bytes.
        raw = not types and not by_length
        batches = read_dataset([path], format, chunk_size, triple_edges, raw_planar_code=raw)
        with compiling_from_both_ends(get_jobs(), types, counting=not types) as watch:
            yield from map_ordered(
                lambda batch: tally_batch(batch, include_boundary, types, belt_length),
                prefetch(watch(batches)),
            )
