"""Both cores: kernels over grain ranges in threads, or whole batches in threads.

The kernels release the GIL (``nogil=True``) and write disjoint rows per grain. A single call
(``classify(batch)`` from the library) cuts its batch into one contiguous range per job and runs
the ranges at once. A stream of batches (the command line) runs whole batches at once instead,
each on one thread, with results handed out in input order: no thread waits for another at
every batch, which matters when a producer (plantri in a pipe) shares the cores.

Work that holds the GIL can run in worker processes instead (:func:`worker_pool`), which a
terminal's Ctrl-C ends at once and quietly.
"""

from __future__ import annotations

import collections
import contextlib
import itertools
import os
import signal
import threading
import warnings
import weakref
from collections.abc import Callable, Iterable, Iterator
from concurrent.futures import Executor, Future, ProcessPoolExecutor, ThreadPoolExecutor
from typing import TypeVar

from grainclass.errors import NoWorkersWarning

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
        yield from map(function, items)
        return
    pool = _pool("batch")
    pending: collections.deque[Future[R]] = collections.deque()
    iterator = iter(items)
    try:
        while True:
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


class _WorkerPool(ProcessPoolExecutor):
    """Each submission (map's too) within :func:`interrupts_blocked`: a submission may start a
    worker, so every worker starts with Ctrl-C held back, whichever call starts it. Shut down
    one caller at a time: an interrupted command's :func:`stop_worker_pools` and the pool's own
    user may both shut it down, and two at once close its result queue twice (Python 3.11: Bad
    file descriptor)."""

    def __init__(self, *args, **kwargs) -> None:
        super().__init__(*args, **kwargs)
        self._shutting_down = threading.Lock()
        self._in_process: Executor | None = None

    def submit(self, fn, /, *args, **kwargs):  # type: ignore[override]
        if self._in_process is None:
            try:
                with interrupts_blocked():
                    return super().submit(fn, *args, **kwargs)
            except OSError as exc:  # no worker could start: this one and the rest run here
                self._in_process = _in_process(exc)
        return self._in_process.submit(fn, *args, **kwargs)

    def shutdown(self, wait: bool = True, *, cancel_futures: bool = False) -> None:
        with self._shutting_down:
            super().shutdown(wait=wait, cancel_futures=cancel_futures)


_worker_pools: weakref.WeakSet[ProcessPoolExecutor] = weakref.WeakSet()


def worker_pool(workers: int) -> Executor:
    """Spawned worker processes (not forked: the parent may be running compiled kernels in
    threads) that end at once and quietly on Ctrl-C (ignoring it would keep their parent
    waiting for their tasks); an interrupted command stops the pools with
    :func:`stop_worker_pools`. Where no worker can start, an executor that runs each task in
    this process as it is submitted, with a :class:`NoWorkersWarning`."""
    from concurrent.futures.process import BrokenProcessPool
    from multiprocessing import get_context

    try:
        pool = _WorkerPool(
            workers, mp_context=get_context("spawn"), initializer=end_quietly_on_interrupt
        )
    except OSError as exc:  # its queues' semaphores, say, where /dev/shm is missing
        return _in_process(exc)
    _worker_pools.add(pool)
    try:
        # A worker that cannot start (an interpreter that may not be run, or is gone) dies
        # unseen, and the pool breaks at whatever task comes first: find out before there are
        # tasks to lose.
        pool.submit(os.getpid).result()
    except (OSError, BrokenProcessPool) as exc:
        pool.shutdown(wait=True, cancel_futures=True)
        return _in_process(exc)
    return pool


class _InProcess(Executor):
    """A pool of worker processes that runs each task in this process as it is submitted."""

    def submit(self, fn, /, *args, **kwargs):  # type: ignore[override]
        future: Future = Future()
        try:
            future.set_result(fn(*args, **kwargs))
        except Exception as exc:  # raised by result(), as from a worker
            future.set_exception(exc)
        return future


def _in_process(failure: Exception) -> Executor:
    """Where worker processes cannot start, the work is done here, more slowly, and the run
    says so, rather than failing with a traceback (a broken pool), as an error of the output
    file, or silently, as if its output pipe had closed (the resource tracker's Broken pipe)."""
    why = failure.strerror if isinstance(failure, OSError) else None
    warnings.warn(
        f"worker processes could not start ({why or 'one ended as it started'}): "
        "working in this process instead",
        NoWorkersWarning,
        stacklevel=3,
    )
    return _InProcess()


def stop_worker_pools() -> None:
    """Shut down every pool of :func:`worker_pool` still open, and wait for it. A pool whose
    workers Ctrl-C ended is broken, and its thread closes its wake-up pipe as it ends: were
    that still under way as the interpreter exits, Python 3.11's exit hook could write into the
    pipe as it closes, and print a traceback (Bad file descriptor)."""
    for pool in list(_worker_pools):
        pool.shutdown(wait=True, cancel_futures=True)


def end_quietly_on_interrupt(*_: object) -> None:
    """In a worker process, once it has started (in its main thread): SIGINT ends it at once,
    without a traceback (one held back while it started, too); its parent, interrupted as well,
    stops and says so."""
    signal.signal(signal.SIGINT, _end_quietly)
    if hasattr(signal, "pthread_sigmask"):
        signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT})


def _end_quietly(signum: int, frame: object) -> None:
    os._exit(128 + signum)
