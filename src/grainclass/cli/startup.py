"""What a command does while the libraries load: standard input read ahead, the cyclic garbage
collector kept off until the first batch is through (see :func:`grainclass.cli.main`), and a
line on standard error when kernels compile."""

from __future__ import annotations

import gc
import sys
from collections.abc import Iterable, Iterator, Sequence
from typing import TypeVar

T = TypeVar("T")

COMPILING = "grainclass: compiling kernels, once per installation (this can take a minute)"
_quiet = False  # -q was given: set while click parses, read from a compiling thread


def note_quiet(ctx: object, param: object, quiet: bool) -> bool:
    """The callback of -q/--quiet: remembers it for :func:`announce_compilation`, which runs in
    whichever thread compiles, outside click's context."""
    global _quiet
    _quiet = quiet
    return quiet


def announce_compilation() -> None:
    """Say on standard error that kernels compile (:func:`grainclass.warmup.on_first_compile`):
    the first run after installation waits 10-30 s for numba, which a person at a terminal is
    told even with -q (a line, once, as progress would be drawn); a log or a pipe is told
    unless -q is given."""
    terminal = sys.stderr.isatty()
    if terminal or not _quiet:
        # On a terminal a progress line may be drawn: the notice replaces it.
        sys.stderr.write(("\r\033[K" if terminal else "") + COMPILING + "\n")
        sys.stderr.flush()


def after_start_up(items: Iterable[T]) -> Iterator[T]:
    """``items``, with the cyclic garbage collector (off since :func:`grainclass.cli.main`)
    back on once the first has come through, or once there are none."""
    try:
        for item in items:
            resume_collection()
            yield item
    finally:
        resume_collection()


def resume_collection() -> None:
    """Collect cyclic garbage from now on, except among the objects made so far (the imported
    libraries, the kernels loaded from numba's cache), which live as long as the process."""
    if not gc.isenabled():
        gc.freeze()
        gc.enable()


def read_ahead(inputs: Sequence[str], input_format: str) -> None:
    """Standard input, if it is an input and a pipe, and the first input, if it is a FIFO (a
    process substitution, ``<(plantri 16)``), are read from now on, while the libraries load
    (:class:`grainclass.pipes.ReadAhead`), so that the program writing them need not wait.
    Later FIFOs are opened in their turn; Surface Evolver files are read whole by their own
    reader."""
    from grainclass.pipes import read_ahead as read_pipe_ahead
    from grainclass.pipes import read_ahead_path

    if "-" in inputs:
        read_pipe_ahead(sys.stdin.buffer)
    first = inputs[0]
    if first != "-" and input_format != "evolver" and not first.lower().endswith(".fe"):
        read_ahead_path(first)
