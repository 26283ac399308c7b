"""Running a batch kernel over grain ranges in threads.

The kernels release the GIL (``nogil=True``) and write disjoint rows per grain, so a batch is
cut into one contiguous range per job and the ranges run at once on a thread pool.
"""

from __future__ import annotations

import itertools
import os
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor

_jobs = os.cpu_count() or 1
_pool: ThreadPoolExecutor | None = None


def set_jobs(jobs: int) -> None:
    """Use ``jobs`` threads from now on (at least 1)."""
    global _jobs, _pool
    _jobs = max(1, int(jobs))
    if _pool is not None:
        _pool.shutdown()
        _pool = None


def get_jobs() -> int:
    """The number of threads kernels run on."""
    return _jobs


def run_ranges(kernel: Callable[..., object], n_items: int, *arrays: object) -> None:
    """Call ``kernel(first, last, *arrays)`` over ``[0, n_items)`` cut into one range per job."""
    global _pool
    cuts = [n_items * k // _jobs for k in range(_jobs + 1)]
    ranges = [(a, b) for a, b in itertools.pairwise(cuts) if b > a]
    if len(ranges) <= 1:
        kernel(0, n_items, *arrays)
        return
    if _pool is None:
        _pool = ThreadPoolExecutor(_jobs, thread_name_prefix="grainclass-kernel")
    for future in [_pool.submit(kernel, a, b, *arrays) for a, b in ranges]:
        future.result()
