"""Output files that appear whole or not at all."""

from __future__ import annotations

import contextlib
import os
import re
import signal
import stat
import sys
import tempfile
from collections.abc import Iterable, Iterator
from contextlib import contextmanager
from typing import BinaryIO

from grainclass.errors import OutputError

_STOPS = {
    getattr(signal, name) for name in ("SIGINT", "SIGTERM", "SIGHUP") if hasattr(signal, name)
}

# The temporary files of the outputs being written, for a run ended at once to remove
# (grainclass.cli.signals).
_temporaries: set[str] = set()

# Paths that name an open file descriptor of this process, whatever it is open on.
_FD_ALIAS = re.compile(r"^/(dev/(stdout|stderr|fd/\d+)|proc/(self|\d+)/fd/\d+)$")


def refuse_inputs(outputs: Iterable[str | None], inputs: Iterable[str]) -> None:
    """Refuse an output that is one of the inputs (the same file, through links too): written,
    it would replace what is being read.

    Raises
    ------
    OutputError
        Naming the output and the input it is.
    """
    existing = [p for p in inputs if p != "-" and os.path.isfile(p)]
    for output in outputs:
        if output is None or output == "-" or not os.path.isfile(output):
            continue
        for path in existing:
            with contextlib.suppress(OSError):
                if os.path.samefile(output, path):
                    raise OutputError(f"{output}: is also an input ({path}); write elsewhere")


@contextmanager
def atomic_output(path: str, binary_stdout_ok: bool = True) -> Iterator[BinaryIO]:
    """A binary stream for ``path``: written to a temporary file beside it and renamed when the
    block ends without an error, removed otherwise. ``-`` is standard output (written as it
    goes; ``binary_stdout_ok=False`` refuses it when that is a terminal).

    A symbolic link is followed: the file it names is replaced, the link stays. A path that
    names something other than a file (``/dev/null``, a FIFO), or one of the process's own
    open files (``/dev/stdout``, ``/dev/fd/3``), is written through as it goes, as a shell's
    redirection would: renaming over it would replace the device, the pipe or the file.
    Replacing a file keeps its permissions, and a file that may not be written is not
    replaced. An OSError in the block becomes an OutputError,
    except a BrokenPipeError (the reader went away), which callers end quietly on.
    """
    if path == "-":
        from grainclass.pipes import CLOSED_STANDARD_STREAMS

        if "stdout" in CLOSED_STANDARD_STREAMS:
            raise OutputError("standard output is closed: write to a file instead")
        if not binary_stdout_ok and sys.stdout.isatty():
            raise OutputError("refusing to write binary output to a terminal; use -o FILE")
        with _as_output_error("standard output"):
            yield sys.stdout.buffer
            sys.stdout.buffer.flush()
        return
    try:
        mode = os.stat(path).st_mode
    except OSError:
        mode = None
    if _FD_ALIAS.match(path) or (mode is not None and not stat.S_ISREG(mode)):
        # Appended to, as by the shell's >>: /dev/stdout after > or >> a file is that file,
        # opened already (truncated or not, as the user asked), and replacing it would cut
        # the link to what the process writes there.
        with _as_output_error(path), open(path, "ab") as sink:
            yield sink
        return
    if mode is not None and not os.access(path, os.W_OK):
        # A file made read-only to keep it is refused, as the shell's > refuses it: renaming
        # over it would need only the folder's permission.
        raise OutputError(f"{path}: cannot write here (Permission denied)")
    target = os.path.realpath(path)
    # A stop signal between the temporary file's creation and the block that removes it would
    # leave it behind: they are held back until that block has begun.
    held = _hold_stops()
    try:
        fd, tmp = tempfile.mkstemp(
            prefix=f".{os.path.basename(target)}.", suffix=".tmp", dir=os.path.dirname(target)
        )
    except OSError as exc:
        _release_stops(held)
        raise OutputError(f"{path}: cannot write here ({exc.strerror})") from None
    _temporaries.add(tmp)
    try:
        _release_stops(held)
        with _as_output_error(path):
            with os.fdopen(fd, "wb") as sink:
                yield sink
            # mkstemp makes the file private: give it the permissions of the file it replaces,
            # or those open() would.
            if mode is None:
                umask = os.umask(0)
                os.umask(umask)
                mode = 0o666 & ~umask
            os.chmod(tmp, stat.S_IMODE(mode))
            os.replace(tmp, target)
    except BaseException:
        # Gone already when an interrupt came just after the rename: the file is whole.
        with contextlib.suppress(FileNotFoundError):
            os.unlink(tmp)
        raise
    finally:
        _temporaries.discard(tmp)


def remove_temporaries() -> None:
    """Remove the temporary files of every output being written: the process is about to end
    without unwinding (a stop that reached no checkpoint)."""
    for tmp in list(_temporaries):
        with contextlib.suppress(OSError):
            os.unlink(tmp)


@contextmanager
def _as_output_error(name: str) -> Iterator[None]:
    """OSError in the block as an OutputError naming ``name``. The readers report their own
    system errors as InputError: one here is the output's (a full disk, a path that names a
    folder)."""
    try:
        yield
    except BrokenPipeError:
        raise
    except OSError as exc:
        raise OutputError(f"{name}: cannot write here ({exc.strerror or exc})") from None


def _hold_stops() -> set[signal.Signals] | None:
    """Hold back the stop signals in this thread: the mask before, to restore; None where
    signals cannot be masked."""
    if not hasattr(signal, "pthread_sigmask"):
        return None
    return signal.pthread_sigmask(signal.SIG_BLOCK, _STOPS)


def _release_stops(held: set[signal.Signals] | None) -> None:
    """Restore the mask :func:`_hold_stops` changed; a stop held back meanwhile arrives now."""
    if held is not None:
        signal.pthread_sigmask(signal.SIG_SETMASK, held)
