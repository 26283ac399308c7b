"""Reading ahead and mapping in threads (`pipeline.prefetch`, `parallel.map_ordered`) without
losing order, results, errors or threads."""

from __future__ import annotations

import os
import threading

import pytest

from grainclass.pipeline import prefetch


def test_prefetch_keeps_order():
    assert list(prefetch(iter(range(100)), depth=3)) == list(range(100))


def test_prefetch_raises_the_producers_error_in_the_consumer():
    def items():
        yield 1
        raise ValueError("bad record")

    stream = prefetch(items())
    assert next(stream) == 1
    with pytest.raises(ValueError, match="bad record"):
        next(stream)


def test_prefetch_thread_ends_when_the_consumer_stops_with_the_queue_full():
    """The producer has queued its last item and waits to say it is done; the consumer stops
    reading (an error downstream). The reader thread must not wait forever: a long-lived
    process (a census worker) would keep one per failed stream."""
    exhausted = threading.Event()

    def items():
        yield 1
        yield 2
        exhausted.set()

    before = set(threading.enumerate())
    stream = prefetch(items(), depth=1)
    assert next(stream) == 1
    assert exhausted.wait(10)  # 2 is queued, the queue is full, the end is waiting to be queued
    (reader,) = set(threading.enumerate()) - before
    stream.close()
    reader.join(10)
    assert not reader.is_alive()


@pytest.mark.parametrize("jobs", [1, 2, 4])
def test_map_ordered_gives_what_a_failing_input_gave_before_its_error(jobs):
    from grainclass.parallel import get_jobs, map_ordered, set_jobs

    def items():
        yield 1
        yield 2
        raise ValueError("the input broke")

    before = get_jobs()
    set_jobs(jobs)
    try:
        stream = map_ordered(lambda x: 10 * x, items())
        assert [next(stream), next(stream)] == [10, 20]
        with pytest.raises(ValueError, match="the input broke"):
            next(stream)
    finally:
        set_jobs(before)


def test_map_ordered_keeps_order_and_raises_a_workers_error_in_its_place():
    from grainclass.parallel import get_jobs, map_ordered, set_jobs

    def slow_first(x: int) -> int:
        if x == 3:
            raise ValueError("item 3")
        if x == 0:
            threading.Event().wait(0.05)  # finishes after the others
        return x

    before = get_jobs()
    set_jobs(2)
    try:
        stream = map_ordered(slow_first, range(6))
        assert [next(stream), next(stream), next(stream)] == [0, 1, 2]
        with pytest.raises(ValueError, match="item 3"):
            next(stream)
    finally:
        set_jobs(before)


def test_available_cpus_follow_the_affinity_mask(monkeypatch):
    """A container or ``taskset`` may allow this process fewer CPUs than the machine has."""
    from grainclass.parallel import available_cpus

    monkeypatch.setattr(os, "sched_getaffinity", lambda pid: {0, 3, 5}, raising=False)
    monkeypatch.setattr(os, "cpu_count", lambda: 64)
    assert available_cpus() == 3


def test_available_cpus_without_an_affinity_mask_are_the_machines(monkeypatch):
    from grainclass.parallel import available_cpus

    monkeypatch.delattr(os, "sched_getaffinity", raising=False)
    monkeypatch.setattr(os, "cpu_count", lambda: 6)
    assert available_cpus() == 6
    monkeypatch.setattr(os, "cpu_count", lambda: None)  # unknown
    assert available_cpus() == 1


def test_evolver_files_are_read_in_this_thread_when_one_job_is_allowed(monkeypatch):
    """Groups of two files, one job: no pool of threads (nor of processes) is made."""
    from pathlib import Path

    from grainclass import parallel
    from grainclass.readers import evolver

    def no_pool(name: str) -> None:
        pytest.fail(f"a pool of threads ({name}) where one job is allowed")

    monkeypatch.setattr(parallel, "_jobs", 1)
    monkeypatch.setattr(parallel, "_pool", no_pool)
    monkeypatch.setattr(evolver, "PART_FILES", 2)
    paths = sorted(str(p) for p in (Path(__file__).parent / "data" / "evolver").glob("*.fe"))
    assert len(paths) >= 2
    assert sum(len(batch) for batch in evolver.read_evolver(paths, 100)) >= len(paths)


def _end_worker():

    os._exit(130)  # as a worker pool's worker ends on Ctrl-C


def test_stopping_the_worker_pools_waits_for_a_broken_pool_to_be_torn_down():
    """Workers that Ctrl-C ended leave their pool broken, its thread closing the pipe that wakes
    it; the interpreter's exit must not find that still under way (Python 3.11 then wrote into
    the closing pipe and printed a traceback). An interrupted command stops its pools first."""
    from concurrent.futures.process import BrokenProcessPool, _ExecutorManagerThread

    from grainclass.parallel import stop_worker_pools, worker_pool

    pool = worker_pool(1)
    with pytest.raises(BrokenProcessPool):
        pool.submit(_end_worker).result(timeout=60)
    stop_worker_pools()
    assert not any(isinstance(t, _ExecutorManagerThread) for t in threading.enumerate())


def test_a_broken_worker_pool_may_be_shut_down_from_two_threads_at_once():
    """An interrupted command's stop_worker_pools and the pool's own user (a reader in another
    thread) may shut a pool down at once: two shutdowns closed its result queue twice (Bad file
    descriptor), 8 times in 40 such pools here before they took turns."""
    from concurrent.futures.process import BrokenProcessPool

    from grainclass.parallel import worker_pool

    errors: list[OSError] = []

    def shut_down(pool) -> None:
        try:
            pool.shutdown(wait=True, cancel_futures=True)
        except OSError as exc:
            errors.append(exc)

    for _ in range(20):
        pool = worker_pool(1)
        with pytest.raises(BrokenProcessPool):
            pool.submit(_end_worker).result(timeout=60)
        both = [threading.Thread(target=shut_down, args=(pool,)) for _ in range(2)]
        for thread in both:
            thread.start()
        for thread in both:
            thread.join()
    assert errors == []


def test_a_pool_whose_workers_cannot_start_works_in_this_process(no_interpreter):
    """It was a traceback (a broken pool) at the first task."""
    from grainclass.errors import NoWorkersWarning
    from grainclass.parallel import worker_pool

    with pytest.warns(NoWorkersWarning, match=r"could not start \(one ended as it started\)"):
        pool = worker_pool(2)
    assert list(pool.map(abs, [-1, -2, 3], chunksize=2)) == [1, 2, 3]
    with pytest.raises(ValueError, match="invalid literal"):
        pool.submit(int, "x").result()  # a task's error, raised where its result would be
    pool.shutdown()


def test_a_pool_without_semaphores_works_in_this_process(monkeypatch):
    """Where /dev/shm is missing, the pool's queues cannot be made: that was reported as an
    error of the output file."""
    import errno

    import grainclass.parallel as parallel
    from grainclass.errors import NoWorkersWarning

    def no_semaphores(*args, **kwargs):
        raise OSError(errno.ENOSYS, "Function not implemented")

    monkeypatch.setattr(parallel, "_WorkerPool", no_semaphores)
    with pytest.warns(NoWorkersWarning, match=r"could not start \(Function not implemented\)"):
        pool = parallel.worker_pool(2)
    assert pool.submit(divmod, 7, 2).result() == (3, 1)
