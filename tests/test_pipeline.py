"""`pipeline.prefetch`: reading ahead in a thread without losing order, errors or threads."""

from __future__ import annotations

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
