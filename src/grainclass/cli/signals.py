"""Stop signals: Ctrl-C, SIGTERM and SIGHUP undo what a command began, then end it.

A stop raises an exception in the main thread (KeyboardInterrupt, or :class:`Stopped`), so that
what a command has begun (a temporary output file) is undone on the way out; worker processes and
busy threads are then let go, not waited for.
"""

from __future__ import annotations

import _thread
import signal
import sys

_STOPS = ("SIGINT", "SIGTERM", "SIGHUP")  # SIGTERM and SIGHUP are not on Windows

_stopping = False  # set by the first stop signal, and once all is done


class Stopped(BaseException):
    """SIGTERM or SIGHUP, raised like Ctrl-C's KeyboardInterrupt."""

    def __init__(self, signum: int) -> None:
        super().__init__(signum)
        self.signum = signum


def stop(signum: int, frame: object) -> None:
    """The handler of the stop signals: the first raises, later ones are let go.

    While a run undoes what it began and waits for its threads, a second signal (``timeout``
    sends one to the process, then one to its group; a second Ctrl-C) would cut that short, or,
    once all is done, end the interpreter's shutdown in a traceback. Later signals are let go
    here rather than set to be ignored, since processes started from here on would inherit
    that."""
    global _stopping
    if _stopping:
        return
    _stopping = True
    raise KeyboardInterrupt if signum == signal.SIGINT else Stopped(signum)


def _lost_stop(unraisable: sys.UnraisableHookArgs) -> None:
    """``sys.unraisablehook``: a stop that :func:`stop` raised where Python ignores exceptions
    (a weakref's callback, a ``__del__`` run by the garbage collector) is lost, and with it every
    later stop signal, which :func:`stop` lets go. The signal is sent again, from a thread of its
    own, to be raised in the code that runs next (sent from here, it would be raised here again;
    a ``threading.Thread`` waits for its start, and it would be raised in that wait)."""
    global _stopping
    exc = unraisable.exc_value
    if not isinstance(exc, KeyboardInterrupt | Stopped):
        sys.__unraisablehook__(unraisable)
        return
    _stopping = False
    signum = exc.signum if isinstance(exc, Stopped) else signal.SIGINT
    _thread.start_new_thread(signal.raise_signal, (signum,))


def catch_stops() -> None:
    """Stop signals raise (:func:`stop`), and are sent again if raised where Python ignores
    exceptions (:func:`_lost_stop`)."""
    for name in _STOPS:
        # One ignored already stays so: nohup ignores SIGHUP for a run to outlive its terminal,
        # and a shell, SIGINT for a job it starts in the background.
        if hasattr(signal, name) and signal.getsignal(getattr(signal, name)) != signal.SIG_IGN:
            signal.signal(getattr(signal, name), stop)
    sys.unraisablehook = _lost_stop


def all_done() -> None:
    """From now on stop signals are let go: one would only end the shutdown in a traceback."""
    global _stopping
    _stopping = True


def threads_busy() -> bool:
    """Whether a thread of ours still runs a kernel (or numba compiles one)."""
    parallel = sys.modules.get("grainclass.parallel")
    return parallel is not None and parallel.threads_busy()
