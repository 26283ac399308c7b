"""Stops that wait for a safe moment.

A stop signal's exception is never raised where the signal lands: in numba's dispatcher, in a
C library calling back into Python or in an import, an exception raised by a signal handler
can be lost, turned into a SystemError or leave state half-made (a kernel half-loaded from
numba's cache). The command line's handler asks for a stop (:func:`request`), and the run raises
it at its next checkpoint (:func:`checkpoint`): between batches, where what the run has begun
unwinds as it does on any error. A library caller that asks for no stops finds every
checkpoint a no-op.
"""

from __future__ import annotations

import signal

_requested: int | None = None  # the first stop signal asked for
_raised = False  # whether a checkpoint has raised it


class Stopped(BaseException):
    """SIGTERM or SIGHUP, raised at a checkpoint as Ctrl-C's KeyboardInterrupt is."""

    def __init__(self, signum: int) -> None:
        super().__init__(signum)
        self.signum = signum


def request(signum: int) -> None:
    """Ask for a stop by signal ``signum``; only the first request counts."""
    global _requested
    if _requested is None:
        _requested = signum


def raised() -> bool:
    """Whether a checkpoint has raised the stop asked for."""
    return _raised


def checkpoint() -> None:
    """Raise the stop asked for, once: KeyboardInterrupt for SIGINT, :class:`Stopped` for
    another signal."""
    global _raised
    if _requested is None or _raised:
        return
    _raised = True
    raise KeyboardInterrupt if _requested == signal.SIGINT else Stopped(_requested)
