"""Both cores: kernels over grain ranges in threads, or whole batches in threads.

The kernels release the GIL (``nogil=True``) and write disjoint rows per grain. A single call
(``classify(batch)`` from the library) cuts its batch into one contiguous range per job and runs
the ranges at once. A stream of batches (the command line) runs whole batches at once instead,
each on one thread, with results handed out in input order: no thread waits for another at
every batch, which matters when a producer (plantri in a pipe) shares the cores.

Worker processes started elsewhere (the census's Dask workers) start with Ctrl-C held back
(:func:`interrupts_blocked`) and then end at once and quietly on it
(:func:`end_quietly_on_interrupt`).
"""

from __future__ import annotations

import collections
import contextlib
import itertools
import os
import signal
import sys
import threading
from collections.abc import Callable, Iterable, Iterator
from concurrent.futures import Future, ThreadPoolExecutor
from typing import TypeVar

from grainclass import interrupts

T = TypeVar("T")
R = TypeVar("R")


def available_cpus() -> int:
    """The CPUs this process may run on: its affinity mask where the system keeps one (a
    container, ``taskset`` or a batch scheduler may allow fewer than the machine has), else
    every CPU of the machine. Every default count of threads and workers comes from here."""
    if hasattr(os, "sched_getaffinity"):
        return len(os.sched_getaffinity(0)) or 1
    return os.cpu_count() or 1


_jobs = available_cpus()
_pools: dict[str, ThreadPoolExecutor] = {}
_in_batch_worker = threading.local()
_running = 0  # tasks of the thread pools under way
_running_lock = threading.Lock()


def set_jobs(jobs: int) -> None:
    """Use ``jobs`` threads from now on (at least 1)."""
    global _jobs
    _jobs = max(1, int(jobs))
    for pool in _pools.values():
        pool.shutdown()
    _pools.clear()


def get_jobs() -> int:
    """The number of threads kernels run on."""
    return _jobs


def _pool(name: str) -> ThreadPoolExecutor:
    if name not in _pools:
        _pools[name] = ThreadPoolExecutor(_jobs, thread_name_prefix=f"grainclass-{name}")
    return _pools[name]


def run_ranges(kernel: Callable[..., object], n_items: int, *arrays: object) -> None:
    """Call ``kernel(first, last, *arrays)`` over ``[0, n_items)`` cut into one range per job
    (one range only inside :func:`map_ordered`, whose batches already fill the cores)."""
    jobs = 1 if getattr(_in_batch_worker, "active", False) else _jobs
    cuts = [n_items * k // jobs for k in range(jobs + 1)]
    ranges = [(a, b) for a, b in itertools.pairwise(cuts) if b > a]
    if len(ranges) <= 1:
        kernel(0, n_items, *arrays)
        return
    pool = _pool("kernel")
    for future in [pool.submit(_counted, kernel, a, b, *arrays) for a, b in ranges]:
        future.result()


def _counted(function: Callable[..., R], *args: object) -> R:
    global _running
    with _running_lock:
        _running += 1
    try:
        return function(*args)
    finally:
        with _running_lock:
            _running -= 1


def threads_busy() -> bool:
    """Whether a task of the thread pools is still running: a kernel, or numba compiling one
    (at a first run, seconds that nothing can cut short)."""
    return _running > 0


def _in_worker(function: Callable[[T], R], item: T) -> R:
    _in_batch_worker.active = True
    return _counted(function, item)


def map_ordered(function: Callable[[T], R], items: Iterable[T]) -> Iterator[R]:
    """``function(item)`` for every item, in input order, up to one item per job at once.

    At most one more item than there are jobs is in flight, so memory stays bounded. An
    exception is raised where its item's result would have come.
    """
    if _jobs == 1:
        for item in items:
            interrupts.checkpoint()
            yield function(item)
        return
    pool = _pool("batch")
    pending: collections.deque[Future[R]] = collections.deque()
    iterator = iter(items)
    try:
        while True:
            interrupts.checkpoint()
            try:
                item = next(iterator)
            except StopIteration:
                break
            except Exception:
                # The input failed: the results of the items it gave first still come out, as
                # they do with one job, and then its error.
                while pending:
                    yield pending.popleft().result()
                raise
            pending.append(pool.submit(_in_worker, function, item))
            if len(pending) > _jobs:
                yield pending.popleft().result()
        while pending:
            yield pending.popleft().result()
    finally:
        for future in pending:
            future.cancel()


@contextlib.contextmanager
def interrupts_blocked() -> Iterator[None]:
    """SIGINT blocked in this thread while the body starts worker processes, which keep it
    blocked (the mask outlives exec) until they take it up (:func:`end_quietly_on_interrupt`).
    Ctrl-C reaches every process of the terminal's group, and a worker interrupted mid-import
    prints pages of tracebacks and can leave its pool hung. Held back, not lost: a Ctrl-C in
    the body reaches this process as the body ends."""
    if not hasattr(signal, "pthread_sigmask"):  # Windows
        yield
        return
    from multiprocessing import resource_tracker

    # multiprocessing's resource tracker, started with the first worker of a process, unblocks
    # SIGINT in the thread that starts it, for every worker started after it there: started
    # before the mask, it leaves it alone.
    resource_tracker.ensure_running()
    before = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, before)


def end_quietly_on_interrupt(*_: object) -> None:
    """In a worker process, once it has started (in its main thread): SIGINT ends it at once,
    without a traceback (one held back while it started, too); its parent, interrupted as well,
    stops and says so."""
    signal.signal(signal.SIGINT, _end_quietly)
    if hasattr(signal, "pthread_sigmask"):
        signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT})


def _end_quietly(signum: int, frame: object) -> None:
    # A part it was writing (a data set in parts) is not left half-made. Nothing is imported
    # here: the signal may come while the process imports, holding the locks an import takes.
    atomic = sys.modules.get("grainclass.atomic")
    if atomic is not None:
        atomic.remove_temporaries()
    os._exit(128 + signum)
