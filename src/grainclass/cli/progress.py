"""Progress on standard error: grains and grains per second while a command reads, parts and
time left while a census or a data set in parts runs."""

from __future__ import annotations

import math
import sys
import time
from collections.abc import Callable, Iterable, Iterator
from typing import TYPE_CHECKING, TypeVar

from grainclass import interrupts

if TYPE_CHECKING:
    from grainclass.census import CensusProgress
    from grainclass.parts import PartsProgress

T = TypeVar("T")


class Progress:
    """Grains done and grains per second, redrawn in place; off unless ``enabled``."""

    def __init__(self, enabled: bool) -> None:
        self.enabled = enabled
        self.grains = 0
        self.start = time.perf_counter()
        self._drawn = 0.0

    @classmethod
    def on_terminal(cls, quiet: bool) -> Progress:
        """Progress drawn when standard error is a terminal, unless ``quiet``."""
        return cls(enabled=not quiet and sys.stderr.isatty())

    def wrap(self, tables: Iterable[T]) -> Iterator[T]:
        """Pass ``tables`` (tables or batches: anything with a length) through, counting."""
        for table in tables:
            interrupts.checkpoint()
            self.grains += len(table)  # type: ignore[arg-type]
            now = time.perf_counter()
            if self.enabled and now - self._drawn > 0.2:
                rate = self.grains / max(now - self.start, 1e-9)
                sys.stderr.write(f"\r{self.grains:,} grains, {rate:,.0f} grains/s ")
                sys.stderr.flush()
                self._drawn = now
            yield table
        if self.enabled and self._drawn:
            sys.stderr.write("\r\033[K")
            sys.stderr.flush()


def format_seconds(seconds: float | None) -> str:
    """``1:02:03``-style time for progress lines; ``?`` when unknown."""
    if seconds is None or not math.isfinite(seconds):
        return "?"
    seconds = round(seconds)
    return f"{seconds // 3600}:{seconds // 60 % 60:02d}:{seconds % 60:02d}"


def census_line(progress: CensusProgress) -> str:
    return (
        f"census: {progress.done}/{progress.total} parts, {progress.grains:,} triangulations "
        f"({progress.rate:,.0f}/s), about {format_seconds(progress.seconds_left)} left"
    )


def parts_line(command: str, unit: str) -> Callable[[PartsProgress], str]:
    """The progress line of ``command`` writing a data set in parts of ``unit``s (``cells``)."""

    def line(progress: PartsProgress) -> str:
        return (
            f"{command}: {progress.done}/{progress.total} parts, {progress.grains:,} {unit} "
            f"({progress.rate:,.0f}/s), about {format_seconds(progress.seconds_left)} left"
        )

    return line


class PartsPrinter:
    """The progress of a run in parts (a census, a data set): redrawn in place on a terminal;
    elsewhere (a log file) a line at most every ``every`` seconds, and one when the last part
    is in. ``line`` words it (default: a census's)."""

    def __init__(self, every: float = 10.0, line: Callable = census_line) -> None:
        self.every = every
        self.line = line
        self._printed = -math.inf
        self._ended = False

    def __call__(self, progress: CensusProgress | PartsProgress) -> None:
        last = progress.done == progress.total
        if self._ended:
            return
        self._ended = last
        if sys.stderr.isatty():
            sys.stderr.write("\r" + self.line(progress) + "\033[K" + ("\n" if last else ""))
        elif last or time.monotonic() - self._printed >= self.every:
            sys.stderr.write(self.line(progress) + "\n")
            self._printed = time.monotonic()
        sys.stderr.flush()
