"""(g) ``grainclass census`` on a local cluster (one worker per core) against plantri alone on
the same parts, as many at a time as there are cores."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

from timing import Checkout, TreeTiming, in_turn, run_each, timed, timed_tree, versus


def bench_census(sizes: list[int], parts: int, work: Path, sides: Sequence[Checkout]) -> None:
    from grainclass.parallel import available_cpus
    from grainclass.plantri import find_plantri

    plantri = find_plantri()
    cores = available_cpus()
    # A warm-up (its report on stderr too is not a figure of the benchmark).
    run_each(
        lambda side: (
            f"{side.grainclass} census 9 --parts 2 -o {work / f'census-warm-{side.name}'} -q"
        ),
        sides,
    )
    print(f"(g) census, {parts} parts per n, {cores} workers, against plantri on the same parts:")
    for n in sizes:
        indices = " ".join(str(i) for i in range(parts))
        alone = timed(
            f"printf '%s\\n' {indices} | xargs -P {cores} -I@ {plantri} -h {n} @/{parts} "
            "> /dev/null 2>&1"
        ).seconds
        whole = timed(f"{plantri} -h {n} > /dev/null 2>&1").seconds
        # Each checkout in a census directory of its own: a census resumes from the one it finds.
        runs = in_turn(
            lambda side, n=n: (
                f"{side.grainclass} census {n} --parts {parts} "
                f"-o {work / f'census-{n}-{side.name}'} -q > /dev/null"
            ),
            sides,
            timer=timed_tree,
        )

        def figure(run: TreeTiming, alone: float = alone) -> str:
            return (
                f"census {run.seconds:7.1f} s  x{run.seconds / alone:4.2f}  "
                f"largest process {run.largest_mb:.0f} MB, all processes {run.all_mb:.0f} MB"
            )

        print(
            f"    n={n}: plantri alone, the same parts {alone:7.1f} s (one plantri {n}: "
            f"{whole:.1f} s); {figure(runs[0])}" + versus(runs, figure, "        ")
        )
