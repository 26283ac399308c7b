"""(a) plantri alone against plantri piped through ``cat`` (what the pipe itself costs), through
``grainclass classify`` and through ``grainclass summarize``, with ratios: medians of rounds
that each time plantri alone too (this machine's speed drifts between minutes)."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

from timing import Checkout, Timing, in_turn, ratio, rounds_line, run_each, timed


def bench_pipelines(sizes: list[int], rounds: int, work: Path, sides: Sequence[Checkout]) -> None:
    from grainclass.plantri import find_plantri

    plantri = find_plantri()
    out = work / "out.parquet"
    # What a pipe costs a reader that wakes for each of plantri's 4 kB writes.
    floor = "cat > /dev/null"
    runs = {
        "classify": "classify - -o {out} -q",
        "classify --no-types": "classify - -o {out} -q --no-types",
        "summarize": "summarize - -q > /dev/null",
        "summarize --types": "summarize - -q --types > /dev/null",
    }
    print(
        "(a) plantri N > /dev/null against plantri N | grainclass ...: wall s and ratio (medians "
        f"of {rounds} rounds, each against plantri alone in its round; the ratios' range), "
        "CPU s of all processes (system), peak MB"
    )

    def piped(n: int, arguments: str):
        return lambda side: (
            f"{plantri} {n} 2>/dev/null | {side.grainclass} {arguments.format(out=out)}"
        )

    for arguments in runs.values():  # compile whatever the runs use before timing them
        run_each(piped(9, arguments), sides)
    for n in sizes:
        alone: list[Timing] = []
        cat: list[Timing] = []
        timings: dict[str, list[list[Timing | None]]] = {name: [] for name in runs}
        for done in range(rounds):
            alone.append(timed(f"{plantri} {n} > /dev/null 2>&1"))
            cat.append(timed(f"{plantri} {n} 2>/dev/null | {floor}"))
            for name, arguments in runs.items():
                timings[name].append(in_turn(piped(n, arguments), sides, reverse=done % 2 == 1))
            out.unlink(missing_ok=True)
        print(f"    n={n}:")
        print(f"        plantri alone           {rounds_line(alone, alone)}")
        print(f"        | {'cat (the pipe alone)':21s} {rounds_line(cat, alone)}")
        for name, in_rounds in timings.items():
            ours = [pair[0] for pair in in_rounds]
            print(f"        | {name:21s} {rounds_line(ours, alone)}")
            if len(sides) > 1:
                theirs = [pair[1] for pair in in_rounds]
                figure = "failed" if None in theirs else rounds_line(theirs, alone)
                print(f"          {'theirs':21s} {figure}  {ratio(ours, theirs)}")
