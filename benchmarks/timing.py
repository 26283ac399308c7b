"""What every benchmark shares: a command's wall time, peak memory and CPU time; the checkouts
whose grainclass is timed (this tree's, and another's to compare with); a pair of commands
timed in turn; the figures as text."""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import NamedTuple, TypeVar

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
PASSES = 3  # of each in-process measure over the same grains: the best counts

T = TypeVar("T")


class Timing(NamedTuple):
    seconds: float  # wall
    peak_mb: float  # resident, of the largest process
    user: float  # CPU seconds of all the command's processes
    system: float


@dataclass(frozen=True)
class Checkout:
    """A grainclass installation to time: ``name`` is ``ours`` (this tree) or ``theirs``."""

    name: str
    root: Path
    python: str

    @property
    def grainclass(self) -> str:
        """The shell command that runs this checkout's grainclass."""
        return f"{self.python} -m grainclass"

    @property
    def console(self) -> Path:
        """The console script beside its python (``make install`` puts it there)."""
        return Path(self.python).with_name("grainclass")

    def commit(self) -> str:
        """Its commit, ``+`` if its files differ from it."""
        git = ["git", "-C", str(self.root)]
        head = subprocess.run(
            [*git, "rev-parse", "--short", "HEAD"], capture_output=True, text=True
        )
        dirty = subprocess.run(
            [*git, "status", "--porcelain", "--untracked-files=no"], capture_output=True, text=True
        )
        return head.stdout.strip() + ("+" if dirty.stdout.strip() else "") or "no git"


def checkouts(other: Path | None) -> list[Checkout]:
    """This tree's grainclass (the python running the benchmarks), and ``other``'s: a checkout
    with its own ``.venv`` (its ``make install``), whose python is not resolved, so that it is
    that venv's."""
    ours = Checkout("ours", ROOT, sys.executable)
    if other is None:
        return [ours]
    python = other / ".venv" / "bin" / "python"
    if not python.is_file():
        raise SystemExit(f"{python} not found: run make install in {other}")
    return [ours, Checkout("theirs", other.resolve(), str(python))]


def timed(command: str) -> Timing:
    """Wall seconds, peak resident MB (of the largest process) and CPU seconds of a shell
    command."""
    fd, record = tempfile.mkstemp(suffix=".time")
    os.close(fd)
    # bash waits for every process of the command: its children's times are all of them.
    wrapped = f"/usr/bin/time -f '%M %U %S' -o {record} -a bash -c {_quote(command)}"
    start = time.perf_counter()
    try:
        subprocess.run(wrapped, shell=True, check=True, stderr=subprocess.DEVNULL)
        seconds = time.perf_counter() - start
        peak_kb, user, system = Path(record).read_text().split()[-3:]
    finally:
        os.unlink(record)
    return Timing(seconds, int(peak_kb) / 1024, float(user), float(system))


class TreeTiming(NamedTuple):
    seconds: float  # wall
    all_mb: float  # peak of the summed resident memory of the command and its descendants
    largest_mb: float  # peak of its largest single descendant


Measured = Timing | TreeTiming
M = TypeVar("M", Timing, TreeTiming)


def _quote(text: str) -> str:
    return "'" + text.replace("'", "'\\''") + "'"


def timed_tree(command: str) -> TreeTiming:
    """Wall seconds, the peak of the summed resident MB of a command and all its descendants
    (worker processes included), and the peak of its largest single descendant, sampled every
    0.1 s."""
    start = time.perf_counter()
    process = subprocess.Popen(command, shell=True, stderr=subprocess.DEVNULL)
    peak = largest = 0
    while process.poll() is None:
        rss = _tree_rss_kb(process.pid)
        peak = max(peak, sum(rss.values()))
        largest = max([largest, *(kb for pid, kb in rss.items() if pid != process.pid)])
        time.sleep(0.1)
    seconds = time.perf_counter() - start
    if process.returncode:
        raise subprocess.CalledProcessError(process.returncode, command)
    return TreeTiming(seconds, peak / 1024, largest / 1024)


def _tree_rss_kb(root: int) -> dict[int, int]:
    """Resident kB of ``root`` and each of its descendants, by pid."""
    parents: dict[int, int] = {}
    rss: dict[int, int] = {}
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            stat = (entry / "stat").read_text()
            status = (entry / "status").read_text()
        except OSError:
            continue
        parents[int(entry.name)] = int(stat.rsplit(")", 1)[1].split()[1])
        for line in status.splitlines():
            if line.startswith("VmRSS:"):
                rss[int(entry.name)] = int(line.split()[1])
    tree, frontier = {root}, [root]
    while frontier:
        children = [pid for pid, parent in parents.items() if parent in frontier]
        frontier = [pid for pid in children if pid not in tree]
        tree.update(frontier)
    return {pid: rss.get(pid, 0) for pid in tree}


class ProcessesTiming(NamedTuple):
    seconds: float  # wall
    cpu: float  # user + system seconds of the command and every process it waited for
    largest_mb: float  # peak resident memory of its largest process
    all_mb: float  # peak of the summed resident memory of all its processes, sampled


def timed_processes(command: str) -> ProcessesTiming:
    """Wall and CPU seconds of a shell command whose processes (Dask's workers) it waits for,
    its largest process's peak memory (``/usr/bin/time``), and the peak of all its processes
    together, sampled every 0.1 s. On a shared machine the CPU time tells the work done apart
    from the wait for a core."""
    fd, record = tempfile.mkstemp(suffix=".time")
    os.close(fd)
    wrapped = f"/usr/bin/time -f '%M %U %S' -o {record} bash -c {_quote(command)}"
    start = time.perf_counter()
    process = subprocess.Popen(wrapped, shell=True, stderr=subprocess.DEVNULL)
    peak = 0
    while process.poll() is None:
        peak = max(peak, sum(_tree_rss_kb(process.pid).values()))
        time.sleep(0.1)
    seconds = time.perf_counter() - start
    try:
        if process.returncode:
            raise subprocess.CalledProcessError(process.returncode, command)
        largest_kb, user, system = Path(record).read_text().split()[-3:]
    finally:
        os.unlink(record)
    return ProcessesTiming(
        seconds, float(user) + float(system), int(largest_kb) / 1024, peak / 1024
    )


def in_turn(
    command: Callable[[Checkout], str],
    sides: Sequence[Checkout],
    timer: Callable[[str], T] = timed,
    reverse: bool = False,
) -> list[T | None]:
    """The command of each checkout, timed by ``timer`` one after the other (ours first, or
    last with ``reverse``: rounds alternate the order, so that neither side always runs in
    the other's wake). The other checkout's entry is None where its command fails (an option
    it does not have, say); ours failing ends the benchmarks."""
    timings: list[T | None] = [None] * len(sides)
    order = list(enumerate(sides))
    for i, side in reversed(order) if reverse else order:
        try:
            timings[i] = timer(command(side))
        except subprocess.CalledProcessError as error:
            if side.name == "ours":
                raise
            print(f"theirs failed (exit {error.returncode}): {command(side)}", file=sys.stderr)
    return timings


def run_each(command: Callable[[Checkout], str], sides: Sequence[Checkout]) -> None:
    """The command of each checkout, untimed: a warm-up that compiles what the timed runs use
    (their report on standard error is not a figure of the benchmarks)."""
    for side in sides:
        subprocess.run(
            command(side),
            shell=True,
            check=side.name == "ours",
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        )


def ratio(ours: Sequence[Measured | None], theirs: Sequence[Measured | None]) -> str:
    """Ours against theirs: the median of the rounds' ratios of wall time, and their range."""
    pairs = list(zip(ours, theirs, strict=True))
    if any(a is None or b is None for a, b in pairs):
        return "theirs failed"
    ratios = [a.seconds / b.seconds for a, b in pairs]
    spread = f" ({min(ratios):4.2f}-{max(ratios):4.2f})" if len(ratios) > 1 else ""
    return f"ours/theirs x{float(np.median(ratios)):4.2f}{spread}"


def versus(runs: Sequence[M | None], figure: Callable[[M], str], indent: str) -> str:
    """A line for the other checkout's run of a figure (after ours, in ``runs[0]``): its
    figure and the ratio; nothing without another checkout."""
    if len(runs) == 1:
        return ""
    theirs = runs[1]
    text = "failed" if theirs is None else f"{figure(theirs)}; {ratio(runs[:1], runs[1:])}"
    return f"\n{indent}theirs: {text}"


def cpu(run: Timing) -> str:
    return f"  cpu {run.user + run.system:6.2f} s (system {run.system:5.2f})"


def rounds_line(runs: list[Timing], alone: list[Timing]) -> str:
    """Median wall time and ratio over rounds, each run against a baseline in its own round
    (this machine's speed drifts by tens of percent between minutes), the ratios' range, the
    median CPU time and the largest peak."""
    ratios = [run.seconds / base.seconds for run, base in zip(runs, alone, strict=True)]
    middle = Timing(
        float(np.median([run.seconds for run in runs])),
        max(run.peak_mb for run in runs),
        float(np.median([run.user for run in runs])),
        float(np.median([run.system for run in runs])),
    )
    if len(runs) == 1:
        spread = ""
    elif runs is alone:  # its ratios are all 1: the range of its times instead
        spread = (
            f" ({min(run.seconds for run in runs):.2f}-{max(run.seconds for run in runs):.2f} s)"
        )
    else:
        spread = f" ({min(ratios):4.2f}-{max(ratios):4.2f})"
    return (
        f"{middle.seconds:6.2f} s  x{float(np.median(ratios)):5.2f}{spread}{cpu(middle)}"
        f"  {middle.peak_mb:5.0f} MB"
    )
