"""A Dask client: of a running cluster (a scheduler's address), or of a local cluster of
worker processes started for the run and closed with it; what runs on more than one process
(the census, tessellations and classifications in parts) runs on it, as :class:`Tasks`."""

from __future__ import annotations

import contextlib
import logging
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import TYPE_CHECKING

from grainclass.errors import ClusterError, MissingDependencyError, OptionError

if TYPE_CHECKING:
    from distributed import Client

SCHEDULER_TIMEOUT = "30s"  # to reach a running scheduler (--scheduler)
LOCAL_WORKERS_PER_CPU = 4  # more worker processes than this on a machine only crowd its memory


def require_dask() -> None:
    """Raise :class:`MissingDependencyError` unless Dask's distributed scheduler can be
    imported (the census extra)."""
    try:
        import distributed  # noqa: F401
    except ImportError as exc:
        raise MissingDependencyError(
            f"this needs Dask ({exc.name} is missing): pip install 'grainclass[census]'"
        ) from None


def _check_address(scheduler: str) -> None:
    """Refuse an address that names no scheduler before a client tries to reach it: a client
    that fails to start leaves threads that wait a minute to close."""
    from distributed.comm import get_address_host_port

    try:
        _, port = get_address_host_port(scheduler)
    except (ValueError, TypeError) as exc:
        raise OptionError("scheduler", f"{scheduler!r} is no scheduler address: {exc}") from None
    if not 0 < port < 2**16:
        raise OptionError("scheduler", f"{scheduler!r}: port {port} is out of range 1-65535")


@contextmanager
def dask_client(scheduler: str | None = None, workers: int | None = None) -> Iterator[Client]:
    """A Dask client: of the cluster whose scheduler is at ``scheduler``, else of a new local
    cluster of ``workers`` processes (default: one per core), one thread each, closed on the way
    out."""
    from distributed import Client, LocalCluster

    from grainclass.parallel import available_cpus, interrupts_blocked

    if scheduler:
        _check_address(scheduler)
        try:
            client = Client(scheduler, timeout=SCHEDULER_TIMEOUT)
        except (OSError, ValueError, TimeoutError) as exc:
            raise ClusterError(f"no Dask scheduler at {scheduler!r}: {exc}") from None
        with client:
            yield client
        return
    most = LOCAL_WORKERS_PER_CPU * available_cpus()
    if workers is not None and workers > most:
        raise OptionError(
            "workers",
            f"a local cluster of {workers} worker processes on {available_cpus()} CPUs: at most "
            f"{most} (each worker holds the libraries, some 200 MB)",
        )

    # A worker restarted after a loss is not news here. silence_logs holds Dask's logs to errors
    # while the cluster runs, not while it closes, when a census stopped by Ctrl-C would log its
    # links to the workers closing, with tracebacks: they are held so until the cluster is gone.
    logs = logging.getLogger("distributed")
    level = logs.level
    logs.setLevel(logging.CRITICAL)
    try:
        with contextlib.ExitStack() as stack:
            # The workers start (from Dask's threads, which take this thread's signal mask)
            # with Ctrl-C held back until they take it up (dask_setup, below); here it is held
            # until the cluster is up and will be closed on the way out.
            with interrupts_blocked():
                cluster = stack.enter_context(
                    LocalCluster(
                        n_workers=workers or available_cpus(),
                        threads_per_worker=1,
                        processes=True,
                        # No dashboard (bokeh is not a dependency); the scheduler's small HTTP
                        # server listens on a free local port, so that several clusters can run
                        # at once.
                        dashboard_address="127.0.0.1:0",
                        # A failed part is reported by the census itself, once: the workers'
                        # own reports of it (a traceback each) stay out of the way.
                        silence_logs=logging.CRITICAL,
                        preload=[__name__],
                    )
                )
            yield stack.enter_context(Client(cluster))
    finally:
        logs.setLevel(level)


def dask_setup(worker: object) -> None:
    """Run by each worker process of :func:`dask_client`'s local cluster once it has started:
    Ctrl-C ends it at once and quietly (``parallel.end_quietly_on_interrupt``), not with a page
    of traceback from each worker."""
    from grainclass.parallel import end_quietly_on_interrupt

    end_quietly_on_interrupt()


class Tasks:
    """Tasks of one run on a Dask cluster, each under a name, and their outcomes as each
    finishes: its value, or the exception that ended it (a task whose workers died on every
    try ends in Dask's ``KilledWorker``; one that died fewer times was run again elsewhere).

    Keys carry a token of the run: on a shared scheduler, another run must not be handed this
    one's results. Tasks left when the run ends (stopped, or failed) are cancelled.
    """

    def __init__(self, client: Client, prefix: str) -> None:
        import uuid

        self.client = client
        self.prefix = f"{prefix}-{uuid.uuid4().hex[:12]}"
        self._futures: dict = {}
        self._tries: dict[str, int] = {}

    def submit(self, name: str, function: Callable, *args: object, priority: int = 0) -> None:
        """Run ``function(*args)`` as the task ``name`` (again, if it ran before: a new key)."""
        tries = self._tries[name] = self._tries.get(name, 0) + 1
        future = self.client.submit(
            function, *args, key=f"{self.prefix}-{name}-{tries}", pure=False, priority=priority
        )
        self._futures[future] = name

    def scatter(self, data: object) -> object:
        """``data`` sent to a worker ahead of the task that takes it: a future to pass it by
        (arguments of many megabytes would go through the scheduler in the task itself)."""
        return self.client.scatter(data, hash=False)

    def __len__(self) -> int:
        return len(self._futures)

    def finished(self, tick: Callable[[], None] | None = None) -> Iterator[tuple[str, object]]:
        """``(name, value or exception)`` of each task as it finishes, tasks submitted meanwhile
        included; a stop asked for is raised between them, and ``tick`` is called at least
        every half second."""
        from distributed import wait

        from grainclass import interrupts

        try:
            while self._futures:
                interrupts.checkpoint()
                try:
                    done, _ = wait(list(self._futures), timeout=0.5, return_when="FIRST_COMPLETED")
                except TimeoutError:
                    done = set()
                for future in done:
                    name = self._futures.pop(future)
                    try:
                        value: object = future.result()
                    except Exception as exc:  # the run reports it, naming the task
                        value = exc
                    finally:
                        future.release()
                    yield name, value
                if tick is not None:
                    tick()
        finally:
            if self._futures:
                self.client.cancel(list(self._futures))
                self._futures.clear()


def task_failure(name: str, error: BaseException) -> str:
    """What ended task ``name``, in words: a worker that died on every try is said so."""
    from distributed import KilledWorker

    if isinstance(error, KilledWorker):
        return f"{name}: every worker that ran it died (out of memory, or killed): {error}"
    return f"{name}: {error}"
