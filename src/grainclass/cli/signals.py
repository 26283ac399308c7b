"""Stop signals: Ctrl-C, SIGTERM and SIGHUP undo what a command began, then end it.

A stop signal asks for a stop (:mod:`grainclass.interrupts`), which the run raises at its next
checkpoint, between batches (KeyboardInterrupt, or :class:`~grainclass.interrupts.Stopped`), so
that what a command has begun (a temporary output file, worker processes) is undone on the way
out; busy threads are then let go, not waited for. A run that reaches no checkpoint within
:data:`GRACE_SECONDS` (it is importing, reading a file whole, compiling a kernel) is ended
from a thread of its own: its temporary outputs are removed and the process exits with the
signal's code.
"""

from __future__ import annotations

import contextlib
import os
import signal
import sys
import threading
import time

from grainclass import interrupts

_STOPS = ("SIGINT", "SIGTERM", "SIGHUP")  # SIGTERM and SIGHUP are not on Windows
GRACE_SECONDS = 2.0

_stopping = False  # set by the first stop signal, and once all is done
_done = threading.Event()  # set once the command is done, whether it stopped or not


def stop(signum: int, frame: object) -> None:
    """The handler of the stop signals: the first asks for a stop and starts the watch over it;
    later ones are let go.

    While a run undoes what it began and waits for its threads, a second signal (``timeout``
    sends one to the process, then one to its group; a second Ctrl-C) would cut that short.
    Later signals are let go here rather than set to be ignored, since processes started from
    here on would inherit that."""
    global _stopping
    if _stopping:
        return
    _stopping = True
    interrupts.request(signum)
    threading.Thread(target=_end_unless_stopped, args=(signum,), daemon=True).start()


def _end_unless_stopped(signum: int) -> None:
    """End the process if, :data:`GRACE_SECONDS` after the stop was asked for, no checkpoint has
    raised it: its temporary outputs and worker processes go, and it exits as a stopped run
    does."""
    deadline = time.monotonic() + GRACE_SECONDS
    while time.monotonic() < deadline:
        if _done.wait(0.05) or interrupts.raised():
            return
    from grainclass.atomic import remove_temporaries
    from grainclass.cli.exit_codes import ExitCode

    remove_temporaries()
    # Worker processes (a census's local Dask cluster) would outlive a process that ends so.
    multiprocessing = sys.modules.get("multiprocessing")
    if multiprocessing is not None:
        for child in multiprocessing.active_children():
            with contextlib.suppress(OSError, ValueError):
                child.terminate()
    name = signal.Signals(signum).name
    said = "interrupted" if signum == signal.SIGINT else f"stopped by {name}"
    with contextlib.suppress(OSError):
        os.write(2, f"grainclass: {said}\n".encode())
    os._exit(ExitCode.stopped_by(signum))


def catch_stops() -> None:
    """Stop signals ask for a stop (:func:`stop`)."""
    for name in _STOPS:
        # One ignored already stays so: nohup ignores SIGHUP for a run to outlive its terminal,
        # and a shell, SIGINT for a job it starts in the background.
        if hasattr(signal, name) and signal.getsignal(getattr(signal, name)) != signal.SIG_IGN:
            signal.signal(getattr(signal, name), stop)


def all_done() -> None:
    """From now on stop signals are ignored: the command is done, its outputs whole, and the
    interpreter, as it shuts down, gives back the signals it handles to the system, whose
    default would end the process by the signal (a run that is done would seem stopped). No
    process is started from here on, to inherit that."""
    global _stopping
    _stopping = True
    _done.set()
    for name in _STOPS:
        if hasattr(signal, name) and signal.getsignal(getattr(signal, name)) == stop:
            signal.signal(getattr(signal, name), signal.SIG_IGN)


def threads_busy() -> bool:
    """Whether a thread of ours still runs a kernel (or numba compiles one)."""
    parallel = sys.modules.get("grainclass.parallel")
    return parallel is not None and parallel.threads_busy()
