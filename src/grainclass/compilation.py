"""Who wants to know when numba compiles one of grainclass's kernels in this process.

numba announces a compilation (its documented event API, ``numba:compile``), never a kernel
loaded from its cache; :mod:`grainclass._numba` passes those of grainclass's kernels on to
:func:`kernel_compiling`, which calls the listeners registered here. This module imports
nothing heavy, so that the command line registers its notice without loading numba.
"""

from __future__ import annotations

import threading
from collections.abc import Callable

_listeners: list[Callable[[], None]] = []
_listeners_lock = threading.Lock()


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
