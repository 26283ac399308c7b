"""Reading from pipes: a larger pipe buffer, and gathered reads instead of one per write.

A fast writer such as plantri writes 4 kB at a time, and a reader that keeps up wakes for every
write: a system call and a wake-up on each side per 4 kB, which gathered reads save (see
docs/performance.md). A piped standard input is read ahead from the start of a command
(:class:`ReadAhead`), so that the writer need not wait while the libraries load.
"""

from __future__ import annotations

import contextlib
import io
import os
import stat
import threading
import time
from collections import deque
from typing import BinaryIO

PIPE_BYTES = 1 << 20
# A read that returns less than this found the pipe nearly empty: the writer is the slower side.
SHORT_READ_BYTES = 1 << 16
# How long such a reader lets the writer's output gather. plantri writes about 200 MB/s, so it
# fills less than half of a 1 MB pipe meanwhile and never waits for the reader; a writer faster
# than 500 MB/s would, but no classification keeps up with one.
GATHER_SECONDS = 0.002


CLOSED_STANDARD_STREAMS: set[str] = set()
"""The standard streams (``stdin``, ``stdout``, ``stderr``) that the process started with
closed (``<&-``, ``>&-``, ``2>&-``): see :func:`open_closed_standard_streams`."""


def open_closed_standard_streams() -> None:
    """Put ``/dev/null`` where a standard stream's descriptor is closed, and a Python stream on
    it, so that nothing else the process opens takes descriptor 0, 1 or 2 and no write to
    standard error fails; :data:`CLOSED_STANDARD_STREAMS` remembers which were closed, so that
    reading standard input or writing standard output there is an error, not a silence."""
    import sys

    for fd, name in ((0, "stdin"), (1, "stdout"), (2, "stderr")):
        try:
            os.fstat(fd)
            continue
        except OSError:
            pass
        null = os.open(os.devnull, os.O_RDWR)
        if null != fd:
            os.dup2(null, fd)
            os.close(null)
        setattr(sys, name, open(fd, "r" if fd == 0 else "w", closefd=False))  # noqa: SIM115
        CLOSED_STANDARD_STREAMS.add(name)


def is_pipe(stream: BinaryIO) -> bool:
    """True if ``stream`` reads from a pipe or FIFO."""
    try:
        return stat.S_ISFIFO(os.fstat(stream.fileno()).st_mode)
    except (AttributeError, OSError, ValueError, io.UnsupportedOperation):
        return False


def enlarge_pipe(stream: BinaryIO) -> int:
    """Give a pipe at least 1 MB of buffer (Linux's default is 64 kB, and 1 MB the most an
    unprivileged process may ask for): a writer as fast as plantri then waits less often for the
    reader, and both make fewer system calls. Returns the pipe's buffer size, as enlarged or, if
    refused, as it was; 0 for anything that is not a pipe, or where the size cannot be known."""
    if not is_pipe(stream):
        return 0
    try:
        import fcntl  # not on Windows; F_GETPIPE_SZ and F_SETPIPE_SZ only on Linux

        size = fcntl.fcntl(stream.fileno(), fcntl.F_GETPIPE_SZ)
    except (ImportError, AttributeError, OSError):
        return 0
    # Over the system's limit for this user, the pipe stays as it is.
    with contextlib.suppress(OSError):
        if size < PIPE_BYTES:
            size = fcntl.fcntl(stream.fileno(), fcntl.F_SETPIPE_SZ, PIPE_BYTES)
    return size


def let_gather(got: int) -> None:
    """After a read of ``got`` bytes from a pipe that gathers reads (:func:`gathers_reads`): if
    it found the pipe nearly empty, wait a moment for the writer's output to gather."""
    if got < SHORT_READ_BYTES:
        time.sleep(GATHER_SECONDS)


def gathers_reads(stream: BinaryIO) -> bool:
    """Whether reads of ``stream`` should wait for a writer's output to gather: only from a pipe
    of PIPE_BYTES, enlarged here if need be. A smaller one (64 kB, Linux's default) would fill
    long before the wait ends, and keep the writer waiting instead."""
    return enlarge_pipe(stream) >= PIPE_BYTES


# How far a pipe is read ahead of its use: start-up (importing numba, pyarrow and pandas, loading
# the kernels) takes about a second, in which plantri at n = 16 writes some 200 MB.
AHEAD_BYTES = 1 << 28


class ReadAhead(io.RawIOBase):
    """A pipe read by a background thread from the moment a command starts, up to AHEAD_BYTES
    ahead of its use, so that the writer (plantri) goes on while grainclass starts up instead of
    waiting on a full pipe: start-up then costs the pipe no time, as long as grainclass reads
    faster than the writer writes. Reads that find the pipe nearly empty let the writer's output
    gather (see GATHER_SECONDS); the stream has no fileno(), so that its readers do not gather
    again. A read error is raised to the reader once what came before it is read.

    ``source`` is an open pipe's file descriptor, or the path of a FIFO (a process
    substitution's ``/dev/fd/63`` too), which the thread opens, and so may wait for a writer
    without holding up the command; ``gather`` is then found once it is open, and an error
    opening it is the first read's. The thread also closes the FIFO, when it ends: :meth:`close`
    does not, since a descriptor closed while the thread is about to read it could go to a file
    opened meanwhile, whose bytes that read would take. (A FIFO whose writer neither writes nor
    ends stays open after :meth:`close` until the process ends.)
    """

    def __init__(self, source: int | str, gather: bool = False, limit: int = AHEAD_BYTES) -> None:
        super().__init__()
        self._source = source
        self._opened: BinaryIO | None = None  # the FIFO, opened by the thread
        self._gather = gather
        self._limit = limit
        self._chunks: deque[memoryview] = deque()
        self._held = 0  # bytes in _chunks
        self._ended = False
        self._error: OSError | None = None
        self._changed = threading.Condition()
        threading.Thread(target=self._run, name="grainclass-read-ahead", daemon=True).start()

    def _run(self) -> None:
        try:
            self._read_ahead()
        finally:
            if self._opened is not None:
                self._opened.close()

    def _read_ahead(self) -> None:
        if isinstance(self._source, str):
            try:
                self._opened = open(self._source, "rb", buffering=0)  # noqa: SIM115 (closed by _run)
            except OSError as exc:
                with self._changed:
                    self._error, self._ended = exc, True
                    self._changed.notify_all()
                return
            if self.closed:  # closed while the FIFO waited for its writer
                return
            self._gather = gathers_reads(self._opened)
            self._source = self._opened.fileno()
        while True:
            with self._changed:
                while self._held >= self._limit and not self.closed:
                    self._changed.wait()
                if self.closed:
                    return
            try:
                data = os.read(self._source, PIPE_BYTES)
            except OSError as exc:
                data, self._error = b"", exc
            with self._changed:
                if data:
                    self._chunks.append(memoryview(data))
                    self._held += len(data)
                else:
                    self._ended = True
                self._changed.notify_all()
            if not data:
                return
            if self._gather:
                let_gather(len(data))

    def readable(self) -> bool:
        return True

    def readinto(self, buffer) -> int:  # type: ignore[override]
        with self._changed:
            while not self._chunks and not self._ended:
                self._changed.wait()
            if not self._chunks:
                if self._error is not None:
                    raise self._error
                return 0
            chunk = self._chunks[0]
            n = min(len(buffer), len(chunk))
            buffer[:n] = chunk[:n]
            if n == len(chunk):
                self._chunks.popleft()
            else:
                self._chunks[0] = chunk[n:]
            self._held -= n
            self._changed.notify_all()
            return n

    def close(self) -> None:
        with self._changed:
            super().close()
            self._changed.notify_all()


# The stream read ahead (standard input's), and its ReadAhead.
_reading_ahead: tuple[BinaryIO, ReadAhead] | None = None


def read_ahead(source: BinaryIO) -> ReadAhead | None:
    """Start reading ``source`` (standard input, not read from yet) ahead, if it is a pipe: its
    :class:`ReadAhead`, also for later calls; None for anything else."""
    global _reading_ahead
    if _reading_ahead is None or _reading_ahead[0] is not source:
        if not is_pipe(source):
            return None
        _reading_ahead = (source, ReadAhead(source.fileno(), gathers_reads(source)))
    return _reading_ahead[1]


def reading_ahead(source: BinaryIO) -> ReadAhead | None:
    """The :class:`ReadAhead` of ``source`` if :func:`read_ahead` started one, else None."""
    return _reading_ahead[1] if _reading_ahead and _reading_ahead[0] is source else None


# FIFOs read ahead, by path, until their reader takes them.
_paths_ahead: dict[str, ReadAhead] = {}


def read_ahead_path(path: str) -> ReadAhead | None:
    """Start reading the FIFO at ``path`` ahead (:class:`ReadAhead`, which opens it), as
    :func:`read_ahead` does standard input: its ReadAhead, also for later calls; None for a path
    that is no FIFO (or not there: its reader says so)."""
    if path not in _paths_ahead:
        try:
            if not stat.S_ISFIFO(os.stat(path).st_mode):
                return None
        except (OSError, ValueError):
            return None
        _paths_ahead[path] = ReadAhead(path)
    return _paths_ahead[path]


def take_read_ahead(path: str) -> ReadAhead | None:
    """The :class:`ReadAhead` that :func:`read_ahead_path` started for ``path``, handed over to
    its reader (once), else None."""
    return _paths_ahead.pop(path, None)
