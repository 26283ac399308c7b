"""Parquet output: one row group per batch, written to a temporary file and renamed at the end.

An interrupted run therefore never leaves a half-written file under the requested name.
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import ExitStack
from types import TracebackType
from typing import BinaryIO

import pyarrow as pa
import pyarrow.compute as pc
import pyarrow.parquet as pq

from grainclass import schema
from grainclass.atomic import atomic_output
from grainclass.schema import GRAIN_ID, GRAIN_SCHEMA
from grainclass.vocabulary import CLASSES, FAMILIES, STATUSES

# Columns that earlier versions of the table lacked (types, then geometry and the boundary
# flag, then belts of every length): a table without them is read with them null, as a grain
# without the data has them.
_ADDED_LATER = (
    schema.BELTS,
    schema.SPLITS,
    schema.BELT_PENALTIES,
    schema.WEINBERG,
    schema.SYMMETRY,
    schema.CHIRALITY,
    schema.BOUNDARY,
    schema.VOLUME,
    schema.AREA,
    schema.ISOPERIMETRIC,
    schema.VOXELS,
    schema.SHORTEST_TRIPLE_LINE,
)
# Columns of text that is all but unique to its grain: no statistics are written for them.
_FREE_TEXT = frozenset({GRAIN_ID, schema.ERROR, schema.TREES, schema.WEINBERG})
# Columns of words that the summaries count by: a word they do not know would be counted as
# nothing, without a sign.
_WORDS = {schema.STATUS: STATUSES, schema.FAMILY: FAMILIES, schema.CLASS: CLASSES}
# Columns that every ok grain has a value in, whatever it was classified with.
_OK_HAS = (schema.N_FACES, schema.N_TRIANGLES, schema.P_VECTOR, schema.FAMILY, schema.CLASS)


class GrainTableWriter:
    """Context manager that writes per-grain tables into one Parquet file, atomically.

    The first table fixes the columns (the grain schema plus the input's extra attributes).
    Later tables get nulls for attributes they lack; attributes first seen after the first
    table cannot be added to a Parquet file already being written and are listed in
    :attr:`dropped`.

    Parameters
    ----------
    path : str
        The file to write, or ``-`` for standard output (refused when that is a terminal).
    metadata : dict of str to str, optional
        Added to the file's key-value metadata (a part's identity, :mod:`grainclass.parts`).
    """

    def __init__(self, path: str, metadata: dict[str, str] | None = None) -> None:
        self.path = path
        self.metadata = metadata or {}
        self.rows = 0
        self.dropped: set[str] = set()
        self._writer: pq.ParquetWriter | None = None
        self._schema: pa.Schema | None = None
        self._stack = ExitStack()
        self._sink: BinaryIO | None = None

    def __enter__(self) -> GrainTableWriter:
        self._sink = self._stack.enter_context(atomic_output(self.path, binary_stdout_ok=False))
        return self

    def write(self, table: pa.Table) -> None:
        """Append one batch's table as a row group."""
        if self._writer is None:
            self._open(table.schema)
        assert self._writer is not None
        assert self._schema is not None
        for name in table.schema.names:
            if name not in self._schema.names:
                self.dropped.add(name)
        columns = [
            table.column(f.name) if f.name in table.schema.names else pa.nulls(len(table), f.type)
            for f in self._schema
        ]
        self._writer.write_table(pa.Table.from_arrays(columns, schema=self._schema))
        self.rows += len(table)

    def _open(self, schema: pa.Schema) -> None:
        if self.metadata:
            schema = schema.with_metadata({**(schema.metadata or {}), **self.metadata})
        self._schema = schema
        # Grain ids are unique: a dictionary for them only grows until Parquet gives it up, at
        # a large cost to the writing (all other columns keep theirs).
        dictionary = [name for name in schema.names if name != GRAIN_ID]
        # Nor is a row group's least and greatest id, message, forest or Weinberg vector of use
        # to a query, and computing them slows the writing.
        statistics = [name for name in schema.names if name not in _FREE_TEXT]
        self._writer = pq.ParquetWriter(
            self._sink,
            schema,
            compression="zstd",
            use_dictionary=dictionary,
            write_statistics=statistics,
        )

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        try:
            if exc_type is None and self._writer is None:
                self._open(GRAIN_SCHEMA)  # no grains at all: still a valid, empty table
            if self._writer is not None:  # also on failure: the temporary file goes anyway
                self._writer.close()
        finally:
            self._stack.__exit__(exc_type, exc, tb)


def iter_grain_tables(path: str, columns: list[str]) -> Iterator[pa.Table]:
    """The columns of a per-grain Parquet file, one row group at a time (``-``: standard input).

    Parquet keeps its index at the end, so standard input (a FIFO) is read whole first.
    """
    from grainclass.errors import InputError
    from grainclass.readers import done_reading, read_once

    # Bytes that Python holds are released by Arrow under the GIL, and Arrow's decoding threads
    # may release the last of them just after a row group is handed over: were the process to
    # end then (an error at the first row group), such a thread would find the interpreter
    # finalizing and the process would abort. Arrow reads the file, or a copy of standard input,
    # itself; only a file name that is not UTF-8, which Arrow cannot open, is read by Python,
    # and then decoded in this thread.
    threads = True
    try:
        once = read_once(path)
        if once is not None:
            copy = pa.BufferOutputStream()
            copy.write(once.read())
            source = pa.BufferReader(copy.getvalue())
        else:
            source = _native_file(path)
            if source is None:
                source, threads = open(path, "rb"), False  # noqa: SIM115 (closed below)
        done_reading(path)
    except OSError as exc:
        raise InputError(path, exc.strerror or str(exc)) from None
    with source:
        yield from _row_groups(path, source, columns, threads)


def _native_file(path: str) -> pa.NativeFile | None:
    """The file opened by Arrow, or None where Arrow cannot open it: a name that is not UTF-8,
    or a file it fails to open, for Python to open, or to say why not in plain words."""
    try:
        path.encode("utf-8")
        return pa.OSFile(path)
    except (UnicodeEncodeError, OSError):
        return None


def _row_groups(path: str, source: object, columns: list[str], threads: bool) -> Iterator[pa.Table]:
    from grainclass.errors import InputError

    try:
        parquet = pq.ParquetFile(source)
    except (OSError, pa.ArrowInvalid) as exc:
        raise InputError(path, f"not a grainclass Parquet table ({exc})") from None
    # Asked for a column it lacks, Arrow leaves it out instead of failing.
    present = [name for name in columns if name in parquet.schema_arrow.names]
    missing = [name for name in columns if name not in present and name not in _ADDED_LATER]
    if missing:
        raise InputError(path, f"not a grainclass per-grain table: no column {', '.join(missing)}")
    for group in range(parquet.num_row_groups):
        try:
            table = parquet.read_row_group(group, columns=present, use_threads=threads)
        except (OSError, pa.ArrowInvalid) as exc:
            raise InputError(path, f"row group {group} cannot be read ({exc})") from None
        table = pa.table([_column(path, table, name) for name in columns], names=columns)
        _require_values(path, group, table)
        yield table


def _require_values(path: str, group: int, table: pa.Table) -> None:
    """Refuse a row group whose ``status`` has a null, or whose ok grains lack a value that
    every ok grain has (a table edited by hand, or saved from another tool), or have fewer
    than four faces: counted, such a grain would be counted as nothing, or fail a summary."""
    from grainclass.errors import InputError

    if schema.STATUS not in table.column_names:
        return
    status = table.column(schema.STATUS)
    if status.null_count:
        raise InputError(path, f"row group {group}: column status has a null")
    ok = pc.equal(status, "ok")
    for name in _OK_HAS:
        if name not in table.column_names:
            continue
        missing = pc.and_(ok, pc.is_null(table.column(name)))
        if pc.any(missing).as_py():
            row = pc.index(missing, True).as_py()
            raise InputError(path, f"row group {group}, row {row}: an ok grain without {name}")
    if schema.N_FACES in table.column_names:
        few = pc.and_(ok, pc.less(table.column(schema.N_FACES), 4))
        if pc.any(few).as_py():
            row = pc.index(few, True).as_py()
            faces = table.column(schema.N_FACES)[row].as_py()
            raise InputError(
                path, f"row group {group}, row {row}: an ok grain of {faces} faces (n_faces)"
            )


def _column(path: str, table: pa.Table, name: str) -> pa.ChunkedArray | pa.Array:
    """Column ``name`` of a row group as grainclass writes it. A table saved again from pandas
    may hold another type (an all-null ``boundary`` becomes Arrow's null type, 0/1 integers a
    boolean's place): it is cast, and a column that cannot be is named."""
    from grainclass.errors import InputError

    wanted = GRAIN_SCHEMA.field(name).type if name in GRAIN_SCHEMA.names else None
    if name not in table.column_names:
        return pa.nulls(len(table), wanted)
    column = table.column(name)
    if wanted is not None and column.type != wanted:
        try:
            column = column.cast(wanted)
        except (pa.ArrowInvalid, pa.ArrowNotImplementedError, pa.ArrowTypeError) as exc:
            raise InputError(
                path, f"column {name} holds {column.type}, not {wanted} ({exc})"
            ) from None
    if name in _WORDS:
        known = pa.array(_WORDS[name])
        unknown = pc.filter(
            column, pc.and_(pc.is_valid(column), pc.invert(pc.is_in(column, known)))
        )
        if len(unknown):
            raise InputError(
                path,
                f"column {name} holds {unknown[0].as_py()!r}, not one of {', '.join(_WORDS[name])}",
            )
    return column
