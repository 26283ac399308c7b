"""Where a command's output goes: all of it written, pipes closed early, no Parquet on a
terminal. (Files are written whole or not at all by :func:`grainclass.atomic.atomic_output`.)"""

from __future__ import annotations

import os
import sys
from typing import BinaryIO

import click

from grainclass.cli.exit_codes import ExitCode


def write_all(sink: BinaryIO, data: str | bytes) -> None:
    """Write all of ``data``: a pipe whose reader goes away mid-write takes part of it and says
    so only in the count, and the next write raises BrokenPipeError."""
    view = memoryview(data.encode() if isinstance(data, str) else data)
    while view:
        view = view[sink.write(view) :]


def quiet_broken_pipe() -> ExitCode:
    """The reader of our output went away (``| head``): stop quietly with 141, as a Unix tool
    killed by SIGPIPE does (Python ignores the signal, so the write fails instead); what is
    still buffered for standard output goes nowhere."""
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, sys.stdout.fileno())
    return ExitCode.BROKEN_PIPE


def refuse_parquet_on_terminal(path: str) -> None:
    """Parquet is not for a terminal's eyes: ``-o -`` there is a usage error."""
    if path == "-" and sys.stdout.isatty():
        raise click.UsageError("refusing to write Parquet to a terminal; use -o FILE")
