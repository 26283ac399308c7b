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
