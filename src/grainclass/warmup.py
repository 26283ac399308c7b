"""A cold kernel cache is filled from both ends at once, and the command line is told when
kernels compile.

numba compiles one kernel at a time in a process, so the first ``classify`` or ``summarize``
after installation (or after an upgrade of numba) spends most of its time compiling, on one
core. numba broadcasts an event when it compiles a kernel, never when it loads one from its
cache (its documented event API, ``numba:compile``), which :mod:`grainclass.compilation` passes
on to its listeners. A command's first such event is the sign
of a cold cache. When more than one job may run, a helper process then compiles the kernels
in the opposite order (the Weinberg walk first, the classification last) while the main
process goes on with the classification: each loads from numba's cache what the other has
already written there, and the two meet in the middle.

A grain that the fast path leaves needs the general validation, and one of more than 64 faces
the general classification too: each takes longer to compile than the fast path. The run
tells the helper at its first batch which of them it will need (``_plan``), and the work is
shared anew: with a large grain the helper compiles the general classification after the walk;
with grains the fast path surely leaves (their lists do not hold the 6n - 12 entries of a simple
grain's, or one has fewer than three), the run compiles the general validation before its first
batch while the helper compiles the fast path. Whatever the plan, each kernel is compiled where
it is called if it is not in the cache yet: the plan only saves time.
"""

from __future__ import annotations

import contextlib
import subprocess
import sys
import threading
from collections.abc import Callable, Iterable, Iterator
from contextlib import contextmanager
from typing import TYPE_CHECKING

from grainclass import compilation

if TYPE_CHECKING:
    from grainclass.batch import GrainBatch

CUBE = [[1, 2, 3, 4], [0, 4, 5, 2], [0, 1, 5, 3], [0, 2, 5, 4], [0, 3, 5, 1], [1, 4, 3, 2]]
_K = 65  # the 65-gonal prism, 67 faces: too large for the fast path
PRISM = [[_K, (i - 1) % _K, _K + 1, (i + 1) % _K] for i in range(_K)]
PRISM += [list(range(_K)), list(reversed(range(_K)))]
# What the run tells the helper, one line, at its first batch (nothing: only the fast path).
GENERAL = b"general\n"  # a grain of more than 64 faces: the general classification too
VALIDATION = b"validation\n"  # grains the fast path leaves: the run compiles their validation
_STOP_WAIT = 2.0  # seconds the helper may take to finish once the main process is done


class _Helper:
    """The helper process, started at the first kernel compiled while it is wanted, and the
    plan it is told (written as soon as both the process and the plan are there)."""

    def __init__(self, types: bool, counting: bool) -> None:
        self.command = [
            sys.executable,
            "-m",
            "grainclass.warmup",
            *([] if types else ["--no-types"]),
            *(["--counting"] if counting else []),
        ]
        self.process: subprocess.Popen | None = None
        self.plan: bytes | None = None
        self.done = False  # the run is over: no process is started any more
        self.lock = threading.Lock()

    def start(self) -> None:
        with self.lock:
            if self.process is not None or self.done:
                return
            # No process to spare, or an interpreter this user may not run: the helper only
            # saves time, and the run compiles everything itself.
            with contextlib.suppress(OSError):
                self.process = subprocess.Popen(
                    self.command,
                    stdin=subprocess.PIPE,
                    stdout=subprocess.DEVNULL,
                    stderr=subprocess.DEVNULL,
                )
            if self.plan is not None:
                self._write()

    @property
    def running(self) -> bool:
        return self.process is not None

    def tell(self, plan: bytes) -> None:
        with self.lock:
            if self.plan is None:
                self.plan = plan
                if self.process is not None:
                    self._write()

    def _write(self) -> None:
        # The helper may be gone already (killed, or failed): it only ever saves time.
        stdin = self.process.stdin  # type: ignore[union-attr]
        with contextlib.suppress(OSError, ValueError):
            stdin.write(self.plan)
        with contextlib.suppress(OSError, ValueError):
            stdin.close()

    def stop(self, kill: bool) -> None:
        """Once the run is done the helper has little left (what it would compile next is in
        the cache) and gets a moment to finish; if the run failed it is stopped at once."""
        with self.lock:
            self.done = True
        process = self.process
        if process is None:
            return
        if kill:
            process.kill()
        self.tell(b"")  # no batch came
        try:
            process.wait(timeout=None if kill else _STOP_WAIT)
        except subprocess.TimeoutExpired:
            process.kill()
            process.wait()


@contextmanager
def compiling_from_both_ends(
    jobs: int, types: bool, counting: bool = False
) -> Iterator[Callable[[Iterable[GrainBatch]], Iterator[GrainBatch]]]:
    """Run the body with a helper compiling from the other end once a kernel compiles in the
    body (a cold cache) and ``jobs`` > 1. ``counting`` (``summarize`` without types): the run
    counts grains and writes no table, and the helper has work only when the plan needs more
    than the fast path.

    Yields ``watch``, which passes the run's batches through and, at the first, tells the helper
    the plan (which it reads once it has compiled the Weinberg walk, waiting for it if need be)
    and, if the helper runs, compiles the general validation first if the plan says so.
    """
    helper = _Helper(types, counting) if jobs > 1 else None
    if helper is not None:
        compilation.listen(helper.start)

    def watch(batches: Iterable[GrainBatch]) -> Iterator[GrainBatch]:
        told = False
        for batch in batches:
            if not told and helper is not None:
                plan = _plan(batch)
                helper.tell(plan)
                told = True
                if plan == VALIDATION and helper.running:
                    _validation_first()
            yield batch

    failed = True
    try:
        yield watch
        failed = False
    finally:
        if helper is not None:
            compilation.stop_listening(helper.start)
            helper.stop(kill=failed)


def _plan(batch: GrainBatch) -> bytes:
    """What a run whose first batch is ``batch`` will compile beyond the fast path."""
    import numpy as np

    from grainclass._kernels.bits import MAX_BITSET_FACES
    from grainclass.batch import GrainBatch

    if not isinstance(batch, GrainBatch) or not len(batch):
        return b""  # planar_code records that summarize counts as bytes: their own kernel
    n_faces = batch.n_faces
    if int(n_faces.max()) > MAX_BITSET_FACES:
        return GENERAL
    parsed = np.ones(len(batch), np.bool_)
    parsed[list(batch.parse_errors)] = False  # the fast path marks these itself
    entries = np.diff(batch.nbr_offsets[batch.face_offsets])
    short_list = np.diff(batch.nbr_offsets) < 3  # a 2-gon, say
    left = np.any(parsed & (entries != 6 * n_faces - 12)) or np.any(
        np.repeat(parsed, n_faces) & short_list
    )
    return VALIDATION if left else b""


def _validation_first() -> None:
    """The general validation, on a cube the fast path left: the call ``classify`` makes."""
    import numpy as np

    from grainclass._kernels.bits import MAX_BITSET_FACES
    from grainclass.batch import GrainBatch
    from grainclass.classification import Classified, _validate_pending

    batch = GrainBatch.from_lists([CUBE])
    out = Classified.empty(batch, strings=True)
    _validate_pending(batch, out, np.zeros(1, np.int64), MAX_BITSET_FACES, strings=True)


def fill_cache(types: bool, plan: Callable[[], bytes], counting: bool = False) -> None:
    """The helper's work: the kernels ``classify`` calls last, with what ``plan()`` asks for
    once the Weinberg walk is compiled (see :func:`_last_kernels_first`), then ``classify``
    itself on a cube (which by then finds its kernels in the cache). When ``counting``, what
    the plan asks for, then the counting of a cube (the fast path first, as the run needs it
    after the general validation), or nothing if the plan asks for nothing: the run starts with
    the fast path itself."""
    from grainclass.batch import GrainBatch
    from grainclass.classification import classify
    from grainclass.summary import tally_batch

    batch = GrainBatch.from_lists([CUBE])
    if counting:
        told = plan()
        if told == GENERAL:
            _general_first(GrainBatch.from_lists([PRISM]))
        if told:
            tally_batch(batch)
        return
    _last_kernels_first(batch, types, plan)
    classify(batch, types=types)


def _last_kernels_first(
    batch: GrainBatch, types: bool, plan: Callable[[], bytes] = lambda: b""
) -> None:
    """The Weinberg walk, then what ``plan()`` asks for, then the table's column kernels, on
    made-up outputs of the classification (every grain ok): the calls and argument types of
    ``classify`` itself. The main process needs the general classification (GENERAL) only
    after the fast path and the general validation; when it compiles that validation first
    (VALIDATION), it needs the fast path next, which the helper then compiles."""
    from grainclass._kernels import codes
    from grainclass.batch import GrainBatch
    from grainclass.classification import Classified, _table, classify
    from grainclass.weinberg_columns import weinberg_types

    out = Classified.empty(batch, strings=True)
    out.status[:] = codes.OK
    out.consistent[:] = True
    walked = weinberg_types(batch, out, types)
    told = plan()
    if told == GENERAL:
        _general_first(GrainBatch.from_lists([PRISM]))
    elif told == VALIDATION:
        classify(GrainBatch.from_lists([CUBE]), types=types)
    _table(batch, out, walked)


def _general_first(batch: GrainBatch) -> None:
    """The general classification, on grains taken as validated and too large for the fast
    path (as the general validation leaves them): the call ``classify`` makes."""
    import numpy as np

    from grainclass._kernels import codes
    from grainclass.classification import Classified, _classify_general

    out = Classified.empty(batch, strings=True)
    out.status[:] = codes.PENDING
    _classify_general(batch, out, np.flatnonzero(out.status == codes.PENDING), strings=True)


if __name__ == "__main__":
    fill_cache(
        types="--no-types" not in sys.argv[1:],
        plan=sys.stdin.buffer.readline,
        counting="--counting" in sys.argv[1:],
    )
