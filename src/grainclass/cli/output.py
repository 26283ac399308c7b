"""Where a command's output goes: files written whole or not at all, and pipes closed early."""

from __future__ import annotations

import os
import sys
from collections.abc import Iterator
from contextlib import contextmanager
from typing import BinaryIO

import click


def write_all(sink: BinaryIO, data: str | bytes) -> None:
    """Write all of ``data``: a pipe whose reader goes away mid-write takes part of it and says
    so only in the count, and the next write raises BrokenPipeError."""
    view = memoryview(data.encode() if isinstance(data, str) else data)
    while view:
        view = view[sink.write(view) :]


@contextmanager
def opened(path: str) -> Iterator[BinaryIO]:
    """The output ``path`` (``-``: standard output), opened now, so that a path that cannot be
    written fails before the work, not after it; written whole or not at all (see
    :func:`grainclass.atomic.atomic_output`). A closed pipe ends quietly."""
    from grainclass.atomic import atomic_output
    from grainclass.errors import OutputError

    try:
        with atomic_output(path) as sink:
            yield sink
    except BrokenPipeError:
        quiet_broken_pipe()
    except OutputError as exc:
        raise click.ClickException(str(exc)) from None


def quiet_broken_pipe() -> None:
    """The reader of our output went away (``| head``): stop quietly, as Unix tools do."""
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, sys.stdout.fileno())
    sys.exit(1)


def refuse_parquet_on_terminal(path: str) -> None:
    """Parquet is not for a terminal's eyes: ``-o -`` there is a usage error."""
    if path == "-" and sys.stdout.isatty():
        raise click.UsageError("refusing to write Parquet to a terminal; use -o FILE")


def table_format(output_format: str | None, path: str) -> str:
    """The format of a summary or type table: as named, else from the output's extension, else
    text."""
    from grainclass.render import EXTENSIONS

    return output_format or EXTENSIONS.get(os.path.splitext(path)[1].lower(), "text")
