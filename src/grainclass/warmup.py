"""A cold kernel cache is filled from both ends at once.

numba compiles one kernel at a time in a process, so the first ``classify`` after installation
(or after an upgrade of numba) spends most of its time compiling, on one core. When the cache
is cold and more than one job may run, a helper process classifies a cube with the kernels
called in the opposite order (the Weinberg walk first, the classification last) while the main
process starts with the classification: each loads from numba's cache what the other has
already written there, and the two meet in the middle. A first batch with a grain of more than
64 faces needs the general classification too, which the main process reaches after the general
validation: the helper is told so, and compiles it right after the Weinberg walk.
"""

from __future__ import annotations

import contextlib
import subprocess
import sys
from collections.abc import Callable, Iterable, Iterator
from contextlib import contextmanager
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from grainclass.batch import GrainBatch

CUBE = [[1, 2, 3, 4], [0, 4, 5, 2], [0, 1, 5, 3], [0, 2, 5, 4], [0, 3, 5, 1], [1, 4, 3, 2]]
_K = 65  # the 65-gonal prism, 67 faces: too large for the fast path
PRISM = [[_K, (i - 1) % _K, _K + 1, (i + 1) % _K] for i in range(_K)]
PRISM += [list(range(_K)), list(reversed(range(_K)))]
_GENERAL = b"general\n"  # what the helper reads when the general classification comes first
_STOP_WAIT = 2.0  # seconds the helper may take to finish once the main process is done


def cold(kernel: object) -> bool:
    """True if numba's cache holds nothing usable for ``kernel`` (no index, or one written
    for another version of its source)."""
    try:
        return not kernel._cache._cache_file._load_index()  # type: ignore[attr-defined]
    except Exception:  # no JIT (NUMBA_DISABLE_JIT), or numba's cache internals moved
        return False


@contextmanager
def compiling_from_both_ends(
    jobs: int, types: bool
) -> Iterator[Callable[[Iterable[GrainBatch]], Iterator[GrainBatch]]]:
    """Run the body with a helper compiling from the other end when the cache is cold and
    ``jobs`` > 1. Once the body is done the helper has little left (what it would compile next
    is in the cache) and gets a moment to finish; if the body fails it is stopped at once.

    Yields ``watch``, which passes the run's batches through and, at the first, tells the helper
    whether the run needs the general classification (the helper asks once it has compiled the
    Weinberg walk, and waits for the answer).
    """
    from grainclass._kernels.batch import _classify_batch
    from grainclass._kernels.bits import MAX_BITSET_FACES
    from grainclass._kernels.weinberg import _weinberg_batch

    helper = None
    if jobs > 1 and cold(_weinberg_batch if types else _classify_batch):
        # No process to spare, or an interpreter this user may not run: the helper only saves
        # time, and the run compiles everything itself.
        with contextlib.suppress(OSError):
            helper = subprocess.Popen(
                [sys.executable, "-m", "grainclass.warmup", *([] if types else ["--no-types"])],
                stdin=subprocess.PIPE,
                stdout=subprocess.DEVNULL,
                stderr=subprocess.DEVNULL,
            )

    def tell(general: bool) -> None:
        # The helper may be gone already (killed, or failed): it only ever saves time.
        with contextlib.suppress(OSError, ValueError):
            if general:
                helper.stdin.write(_GENERAL)  # type: ignore[union-attr]
            helper.stdin.close()  # type: ignore[union-attr]

    def watch(batches: Iterable[GrainBatch]) -> Iterator[GrainBatch]:
        told = False
        for batch in batches:
            if not told and helper is not None:
                tell(len(batch) > 0 and int(batch.n_faces.max()) > MAX_BITSET_FACES)
                told = True
            yield batch

    try:
        yield watch
    except BaseException:
        if helper is not None:
            helper.kill()
            tell(False)
            helper.wait()
        raise
    if helper is not None:
        tell(False)  # no batch came: the usual order
        try:
            helper.wait(timeout=_STOP_WAIT)
        except subprocess.TimeoutExpired:
            helper.kill()
            helper.wait()


def fill_cache(types: bool, general: Callable[[], bool]) -> None:
    """The helper's work: the kernels ``classify`` calls last (the general classification
    among them if ``general()`` says so once the Weinberg walk is compiled), then ``classify``
    itself on a cube (which by then finds its kernels in the cache)."""
    from grainclass.batch import GrainBatch
    from grainclass.classification import classify

    batch = GrainBatch.from_lists([CUBE])
    _last_kernels_first(batch, types, general)
    classify(batch, types=types)


def _last_kernels_first(
    batch: GrainBatch, types: bool, general: Callable[[], bool] = lambda: False
) -> None:
    """The Weinberg walk, the general classification if ``general()``, and the table's column
    kernels, on made-up outputs of the classification (every grain ok): the calls and argument
    types of ``classify`` itself. The main process, which starts with the fast path and the
    general validation, needs the general classification before the table's columns."""
    from grainclass._kernels import codes
    from grainclass.batch import GrainBatch
    from grainclass.classification import _Classified, _table, _types

    out = _Classified.empty(batch, strings=True)
    out.status[:] = codes.OK
    out.consistent[:] = True
    walked = _types(batch, out, types)
    if general():
        _general_first(GrainBatch.from_lists([PRISM]))
    _table(batch, out, walked)


def _general_first(batch: GrainBatch) -> None:
    """The general classification, on grains taken as validated and too large for the fast
    path (as the general validation leaves them): the call ``classify`` makes."""
    import numpy as np

    from grainclass._kernels import codes
    from grainclass.classification import _Classified, _classify_general

    out = _Classified.empty(batch, strings=True)
    out.status[:] = codes.PENDING
    _classify_general(batch, out, np.flatnonzero(out.status == codes.PENDING), strings=True)


if __name__ == "__main__":
    # The run says, at its first batch, whether it needs the general classification; a run that
    # ends without a batch closes the pipe.
    fill_cache(
        types="--no-types" not in sys.argv[1:],
        general=lambda: sys.stdin.buffer.readline() == _GENERAL,
    )
