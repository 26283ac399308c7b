"""(i) One giant grain, the k-gonal prism for k = 1,000, 4,000 and 20,000: ``classify`` end to
end with and without types, its time and peak memory."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

from inputs import prism_line
from timing import Checkout, in_turn, run_each, versus


def bench_prisms(ks: list[int], work: Path, sides: Sequence[Checkout]) -> None:
    """``classify`` of a file holding one k-gonal prism, end to end: a giant grain's time and
    peak memory (about k^2 / 2 4-belts; with types, about 4k Weinberg walks of 6k steps)."""
    out = work / "prism.parquet"
    small = work / "prism70.txt"
    small.write_text(prism_line(68))  # compile the general path and the large walks first
    run_each(lambda side: f"{side.grainclass} classify {small} -o {out} -q", sides)
    print("(i) one k-gonal prism (k + 2 faces), classify end to end: wall s, peak MB")

    def figure(run) -> str:
        return f"{run.seconds:7.2f} s {run.peak_mb:6.0f} MB"

    for k in ks:
        path = work / f"prism{k}.txt"
        path.write_text(prism_line(k))
        without, with_types = (
            in_turn(lambda side, command=command: f"{side.grainclass} {command}", sides)
            for command in (
                f"classify {path} -o {out} -q --no-types",
                f"classify {path} -o {out} -q",
            )
        )
        print(
            f"    k={k:>6,}: without types {figure(without[0])}; with types {figure(with_types[0])}"
            + versus(without, figure, "        without types, ")
            + versus(with_types, figure, "        with types, ")
        )
        path.unlink()
