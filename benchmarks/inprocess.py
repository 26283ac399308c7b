"""In-process rates, ours against theirs: a worker process per checkout, run by that
checkout's python, holds the grains, and the passes of each measure alternate between the
workers, so that both are timed in the same minutes and neither pays for the other's memory.

A worker is ``PYTHON benchmarks/inprocess.py SUITE PATH``: it imports the benchmark module
SUITE (``kernels`` or ``perturb``), whose ``measures(path)`` reads the grains, compiles what the
runs use and gives ``(grains, {name: run})``. It then writes ``ready GRAINS`` and, for each line
``THREADS NAME`` it reads, runs ``NAME`` once on that many threads and writes the wall
seconds, or ``failed`` (and, once a measure, why on standard error): the other checkout's code may
lack a function or take other arguments.
"""

from __future__ import annotations

import importlib
import os
import subprocess
import sys
import time
from collections.abc import Sequence
from pathlib import Path

from timing import PASSES, Checkout


class Worker:
    """One checkout's worker process, ready when ``grains`` is not None."""

    def __init__(self, side: Checkout, suite: str, path: Path) -> None:
        self.process = subprocess.Popen(
            [side.python, __file__, suite, str(path)],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            text=True,
        )
        reply = self._reply().split()
        self.grains = int(reply[1]) if reply[:1] == ["ready"] else None

    def _reply(self) -> str:
        assert self.process.stdout is not None
        return self.process.stdout.readline().strip()

    def seconds(self, threads: int, name: str) -> float | None:
        """One pass of measure ``name`` on ``threads`` threads, or None if it failed."""
        if self.grains is None:
            return None
        assert self.process.stdin is not None
        self.process.stdin.write(f"{threads} {name}\n")
        self.process.stdin.flush()
        reply = self._reply()
        return None if reply in ("", "failed") else float(reply)

    def close(self) -> None:
        assert self.process.stdin is not None
        self.process.stdin.close()
        self.process.wait()


def best_rates(
    sides: Sequence[Checkout],
    suite: str,
    path: Path,
    names: Sequence[str],
    threads: Sequence[int],
) -> tuple[int, dict[int, list[list[float | None]]]]:
    """Our worker's grains and, for each number of threads, each checkout's M grains/s in each
    measure: the best of ``PASSES`` passes (other loads on the machine only ever slow a pass),
    the checkouts' passes in turn, the first alternating; None where a checkout's measure
    failed."""
    workers = [Worker(side, suite, path) for side in sides]
    try:
        grains = workers[0].grains
        if grains is None:
            raise SystemExit(f"the {suite} benchmarks could not read {path}")
        rates: dict[int, list[list[float | None]]] = {}
        for count in threads:
            rates[count] = [[] for _ in sides]
            for name in names:
                best: list[float | None] = [float("inf")] * len(sides)
                for done in range(PASSES):
                    order = list(enumerate(workers))
                    for i, worker in reversed(order) if done % 2 else order:
                        seconds = worker.seconds(count, name)
                        best[i] = (
                            None if seconds is None or best[i] is None else min(best[i], seconds)
                        )
                for i, worker in enumerate(workers):
                    rate = None if best[i] is None else worker.grains / best[i] / 1e6
                    rates[count][i].append(rate)
        return grains, rates
    finally:
        for worker in workers:
            worker.close()


def rates_text(rates: Sequence[float | None]) -> str:
    return " | ".join("  n/a" if rate is None else f"{rate:5.2f}" for rate in rates)


def rate_ratios(ours: Sequence[float | None], theirs: Sequence[float | None]) -> str:
    """Ours against theirs in time (theirs' rate over ours), measure by measure."""
    return " | ".join(
        " n/a" if a is None or b is None else f"x{b / a:4.2f}"
        for a, b in zip(ours, theirs, strict=True)
    )


def main() -> None:
    suite, path = sys.argv[1:3]
    # The replies keep a descriptor of their own: whatever the code measured writes to standard
    # output goes to standard error instead.
    replies = os.fdopen(os.dup(1), "w", buffering=1)
    os.dup2(2, 1)
    from grainclass.parallel import set_jobs

    grains, runs = importlib.import_module(suite).measures(Path(path))
    replies.write(f"ready {grains}\n")
    jobs = None
    failed: set[str] = set()
    for line in sys.stdin:
        threads, name = line.split(maxsplit=1)
        if int(threads) != jobs:  # a new pool of threads only when their number changes
            jobs = int(threads)
            set_jobs(jobs)
        start = time.perf_counter()
        try:
            runs[name.strip()]()
        except Exception as exc:  # the other checkout's code may not have what it calls
            replies.write("failed\n")
            if name not in failed:  # one line a measure, not a traceback a pass
                failed.add(name)
                print(f"{name.strip()} failed here: {type(exc).__name__}: {exc}", file=sys.stderr)
        else:
            replies.write(f"{time.perf_counter() - start}\n")


if __name__ == "__main__":
    main()
