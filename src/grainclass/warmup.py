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

Where both would otherwise compile the same kernel at once, the helper says on its standard
output when it has put a stage in the cache, and the run waits for that rather than compile it
too: the fast path, which the run needs right after the general validation (``fast``), and a
reader's second stage, which the reader said was ahead before its first kernel compiled (the
Surface Evolver assembly, ``evolver``, compiled by the helper while the run compiles the
tokenizer; the run compiles the fast path, the Weinberg walk and the general validation while
it waits).
"""

from __future__ import annotations

import contextlib
import os
import subprocess
import sys
import threading
import time
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
# What the helper says on its standard output, a line each, once it is in the cache: a reader's
# stage said ahead (compilation.EVOLVER), and with the plan VALIDATION the fast path.
FAST = "fast"
_STOP_WAIT = 2.0  # seconds the helper may take to finish once the main process is done
_PARENT_POLL = 0.2  # seconds between the helper's looks at whether the run is still there
# Seconds the run waits for a stage the helper compiles, many times what one takes, before it
# compiles the stage itself: a helper that hangs costs time, never the run.
_STAGE_WAIT = 300.0


class _Helper:
    """The helper process, started at the first kernel compiled while it is wanted, the plan
    it is told (written as soon as both the process and the plan are there), and what it says
    it has put in the cache."""

    def __init__(self, types: bool, counting: bool) -> None:
        self.types = types
        self.command = [
            sys.executable,
            "-m",
            "grainclass.warmup",
            f"--run={os.getpid()}",
            *([] if types else ["--no-types"]),
            *(["--counting"] if counting else []),
        ]
        self.process: subprocess.Popen | None = None
        self.plan: bytes | None = None
        self.done = False  # the run is over: no process is started any more
        self.lock = threading.Lock()
        self.stages: list[str] = []  # readers' stages said ahead before the process started
        self.started_with: frozenset[str] = frozenset()  # those the process compiles first
        self.said: set[str] = set()
        self.ended = False  # its standard output closed: it says nothing more
        self.heard = threading.Condition()
        self.shared = False  # the run's share while the helper compiles a stage is done

    def start(self) -> None:
        with self.lock:
            if self.process is not None or self.done:
                return
            # No process to spare, or an interpreter this user may not run: the helper only
            # saves time, and the run compiles everything itself.
            with contextlib.suppress(OSError):
                self.process = subprocess.Popen(
                    self.command + [f"--ahead={stage}" for stage in self.stages],
                    stdin=subprocess.PIPE,
                    stdout=subprocess.PIPE,
                    stderr=subprocess.DEVNULL,
                )
            if self.process is None:
                return
            self.started_with = frozenset(self.stages)
            threading.Thread(target=self._listen, daemon=True).start()
            if self.plan is not None:
                self._write()

    def _listen(self) -> None:
        """Keep what the helper says until it ends (or is killed)."""
        stdout = self.process.stdout  # type: ignore[union-attr]
        try:
            for line in stdout:
                with self.heard:
                    self.said.add(line.decode(errors="replace").strip())
                    self.heard.notify_all()
        except (OSError, ValueError):
            pass
        finally:
            stdout.close()
            with self.heard:
                self.ended = True
                self.heard.notify_all()

    def wait_for(self, stage: str) -> None:
        """Return once the helper says ``stage`` is in the cache, or has ended, or after
        :data:`_STAGE_WAIT` seconds."""
        if self.process is None:
            return
        with self.heard:
            self.heard.wait_for(lambda: stage in self.said or self.ended, _STAGE_WAIT)

    def ahead(self, stage: str) -> None:
        with self.lock:
            if stage not in self.stages:
                self.stages.append(stage)

    def before(self, stage: str) -> None:
        """A reader's next stage: if the helper compiles it, the run compiles its own share
        meanwhile (once), then waits for it."""
        if stage not in self.started_with:
            return
        with self.lock:
            share, self.shared = not self.shared, True
        if share and stage not in self.said:
            _runs_share(self.types)
        self.wait_for(stage)

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
        compilation.listen_to_stages(helper)

    def watch(batches: Iterable[GrainBatch]) -> Iterator[GrainBatch]:
        told = False
        for batch in batches:
            if not told and helper is not None:
                plan = _plan(batch)
                helper.tell(plan)
                told = True
                if plan == VALIDATION and helper.running:
                    _validation_first()
                    helper.wait_for(FAST)
            yield batch

    failed = True
    try:
        yield watch
        failed = False
    finally:
        if helper is not None:
            compilation.stop_listening(helper.start)
            compilation.stop_listening_to_stages(helper)
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


def fill_cache(
    types: bool,
    plan: Callable[[], bytes],
    counting: bool = False,
    ahead: Iterable[str] = (),
    say: Callable[[str], None] = lambda stage: None,
) -> None:
    """The helper's work: the readers' stages ``ahead`` (each ``say``-d once in the cache),
    then the kernels ``classify`` calls last, with what ``plan()`` asks for once the Weinberg
    walk is compiled (see :func:`_last_kernels_first`), then ``classify`` itself on a cube
    (which by then finds its kernels in the cache). When ``counting``, what the plan asks for,
    then the counting of a cube (the fast path first, as the run needs it after the general
    validation), or nothing if the plan asks for nothing: the run starts with the fast path
    itself."""
    from grainclass.batch import GrainBatch
    from grainclass.classification import classify
    from grainclass.summary import tally_batch

    for stage in ahead:
        if stage == compilation.EVOLVER:
            _assembly_of_no_files()
            say(stage)
    batch = GrainBatch.from_lists([CUBE])
    if counting:
        told = plan()
        if told == GENERAL:
            _general_first(GrainBatch.from_lists([PRISM]))
        if told:
            _fast_path_and_walk(types=False)
            say(FAST)
            tally_batch(batch)
        return
    _last_kernels_first(batch, types, plan, say)
    classify(batch, types=types)


def _assembly_of_no_files() -> None:
    """The Surface Evolver assembly, on what the tokenizer makes of no files: the argument
    types the reader calls it with."""
    import numpy as np

    from grainclass._kernels.evolver.assemble import _assemble
    from grainclass._kernels.evolver.entries import _first_entries, _new_entries
    from grainclass._kernels.evolver.tokenize import Files

    entries = _first_entries.py_func(_new_entries.py_func(0, 0), 0, 0)
    files = Files(
        np.zeros(0, np.int8),
        np.zeros(0, np.int64),
        np.zeros((0, 3), np.int64),
        np.zeros(0, np.bool_),
        np.zeros((0, 3, 3), np.float64),
        np.zeros(0, np.int64),
        np.zeros(0, np.int64),
        np.zeros(0, np.int64),
    )
    _assemble(entries, files)


def _runs_share(types: bool) -> None:
    """What the run compiles while the helper compiles a reader's stage: what ``classify``
    calls first, the fast path and the walk (if ``types``), and the general validation, which
    real data sets mostly need (a Surface Evolver simulation's grains with a degenerate corner,
    say), and which the run would otherwise compile alone after the stage."""
    _fast_path_and_walk(types)
    _validation_first()


def _fast_path_and_walk(types: bool) -> None:
    """The fast path on a cube, and its Weinberg walk if ``types``: the calls ``classify``
    makes first."""
    from grainclass._kernels.bits import MAX_BITSET_FACES
    from grainclass.batch import GrainBatch
    from grainclass.classification import _classify_csr
    from grainclass.weinberg_columns import weinberg_types

    batch = GrainBatch.from_lists([CUBE])
    out = _classify_csr(batch, MAX_BITSET_FACES, strings=True)
    if types:
        weinberg_types(batch, out, True)


def _last_kernels_first(
    batch: GrainBatch,
    types: bool,
    plan: Callable[[], bytes] = lambda: b"",
    say: Callable[[str], None] = lambda stage: None,
) -> None:
    """The Weinberg walk, then what ``plan()`` asks for, then the table's column kernels, on
    made-up outputs of the classification (every grain ok): the calls and argument types of
    ``classify`` itself. The main process needs the general classification (GENERAL) only
    after the fast path and the general validation; when it compiles that validation first
    (VALIDATION), it needs the fast path next, which the helper then compiles (and ``say``-s)."""
    from grainclass._kernels import codes
    from grainclass.batch import GrainBatch
    from grainclass.classification import Classified, _table
    from grainclass.weinberg_columns import weinberg_types

    out = Classified.empty(batch, strings=True)
    out.status[:] = codes.OK
    out.consistent[:] = True
    walked = weinberg_types(batch, out, types)
    told = plan()
    if told == GENERAL:
        _general_first(GrainBatch.from_lists([PRISM]))
    elif told == VALIDATION:
        _fast_path_and_walk(types)  # the walk is in the cache by now
        say(FAST)
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


def _say(stage: str) -> None:
    sys.stdout.write(stage + "\n")
    sys.stdout.flush()


def _end_with(run: int) -> None:
    """End the helper once the run that started it is gone: a run stopped by a signal while
    kernels compile ends at once (``os._exit``, not waiting for its threads) and a killed one
    says nothing, and what the helper would go on compiling keeps a core busy for no one."""
    while os.getppid() == run:
        time.sleep(_PARENT_POLL)
    os._exit(0)


def _option(name: str) -> list[str]:
    return [a.removeprefix(name) for a in sys.argv[1:] if a.startswith(name)]


if __name__ == "__main__":
    # The run names itself: it may be gone before this process asks for its parent.
    run = int(next(iter(_option("--run=")), os.getppid()))
    threading.Thread(target=_end_with, args=(run,), daemon=True).start()
    fill_cache(
        types="--no-types" not in sys.argv[1:],
        plan=sys.stdin.buffer.readline,
        counting="--counting" in sys.argv[1:],
        ahead=_option("--ahead="),
        say=_say,
    )
