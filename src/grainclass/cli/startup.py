"""What a command does as it starts: standard input read ahead while the libraries load, the
threads set, the cyclic garbage collector kept off until the first batch is through (see
:func:`grainclass.cli.main`), a line on standard error when kernels compile, and progress drawn
as batches go by."""

from __future__ import annotations

import gc
import sys
from collections.abc import Callable, Iterable, Iterator, Sequence
from typing import TYPE_CHECKING, TypeVar

if TYPE_CHECKING:
    from grainclass.options import ReadOptions

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
    """Say on standard error that kernels compile (:func:`grainclass.compilation.on_first_compile`):
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


def begin(inputs: Sequence[str], reading: ReadOptions, outputs: Sequence[str | None] = ()) -> None:
    """What every command that reads grains does first: its outputs checked not to be any of
    its inputs, its inputs read ahead (see :func:`read_ahead`) and its threads set."""
    from grainclass.atomic import refuse_inputs

    refuse_inputs(outputs, inputs)
    read_ahead(inputs, reading.input_format or "auto")
    if reading.jobs is not None:
        from grainclass.parallel import set_jobs

        set_jobs(reading.jobs)


def watcher(quiet: bool) -> Callable[[Iterable[T]], Iterator[T]]:
    """What a command passes the library to see its batches go by: progress on a terminal
    (unless ``quiet``), and the garbage collector back on after the first."""
    from grainclass.cli.progress import Progress

    progress = Progress.on_terminal(quiet)
    return lambda items: progress.wrap(after_start_up(items))
