"""Who wants to know when numba compiles one of grainclass's kernels in this process, and
which kernels a reader calls next.

numba announces a compilation (its documented event API, ``numba:compile``), never a kernel
loaded from its cache; :mod:`grainclass._numba` passes those of grainclass's kernels on to
:func:`kernel_compiling`, which calls the listeners registered here. A reader that runs two
large kernels in turn says so (:func:`ahead` before the first, :func:`before` the second), so
that a process compiling from the other end (:mod:`grainclass.warmup`) may compile the second
while this one compiles the first. This module imports nothing heavy, so that the command line
registers its notice without loading numba.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import Protocol

_listeners: list[Callable[[], None]] = []
_listeners_lock = threading.Lock()


class StageListener(Protocol):
    """Who hears of a reader's stages: a stage is a reader's kernels that it calls after its
    first one (``"evolver"``: the Surface Evolver assembly, after the tokenizer)."""

    def ahead(self, stage: str) -> None:
        """The reader calls the kernels of ``stage`` after the ones it calls now."""

    def before(self, stage: str) -> None:
        """The reader calls the kernels of ``stage`` now (this may wait for whoever compiles
        them elsewhere)."""


_stage_listeners: list[StageListener] = []
EVOLVER = "evolver"  # the Surface Evolver assembly, which the reader calls after its tokenizer


def kernel_compiling() -> None:
    """numba starts compiling one of grainclass's kernels (called from the compiling thread):
    tell whoever listens."""
    with _listeners_lock:
        listeners = list(_listeners)
    for listener in listeners:
        listener()


def listen(listener: Callable[[], None]) -> None:
    """Call ``listener()`` whenever a kernel starts compiling, until :func:`stop_listening`."""
    with _listeners_lock:
        _listeners.append(listener)


def stop_listening(listener: Callable[[], None]) -> None:
    with _listeners_lock:
        _listeners.remove(listener)


def listen_to_stages(listener: StageListener) -> None:
    """Tell ``listener`` of the readers' stages, until :func:`stop_listening_to_stages`."""
    with _listeners_lock:
        _stage_listeners.append(listener)


def stop_listening_to_stages(listener: StageListener) -> None:
    with _listeners_lock:
        _stage_listeners.remove(listener)


def ahead(stage: str) -> None:
    """A reader says, before it calls its first kernel, that it calls the kernels of ``stage``
    after it."""
    with _listeners_lock:
        listeners = list(_stage_listeners)
    for listener in listeners:
        listener.ahead(stage)


def before(stage: str) -> None:
    """A reader is about to call the kernels of ``stage``: returns once whoever compiles them
    in another process has put them in numba's cache (at once if no one does)."""
    with _listeners_lock:
        listeners = list(_stage_listeners)
    for listener in listeners:
        listener.before(stage)


def on_first_compile(callback: Callable[[], None]) -> None:
    """Call ``callback()`` once, when this process first compiles one of grainclass's kernels
    (none of them is in numba's cache yet, or the cached one was made for other sources or
    another numba): the command line says then that it compiles. It is called from the
    compiling thread, which may not be the main one; loading kernels from the cache calls
    nothing."""
    once = threading.Lock()
    called = False

    def first() -> None:
        nonlocal called
        with once:
            if called:
                return
            called = True
        callback()

    listen(first)
