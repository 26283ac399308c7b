"""(h) ``grainclass perturb`` against ``grainclass classify`` on the same grains, as planar_code
and as adjacency text, end to end; then their rates in process. Also the worker suite
``perturb`` of ``inprocess.py``."""

from __future__ import annotations

import itertools
import subprocess
from collections.abc import Callable, Sequence
from pathlib import Path

from inprocess import best_rates, rate_ratios, rates_text
from inputs import sample, sample_parts
from timing import PASSES, Checkout, Timing, in_turn, ratio, rounds_line, run_each

MEASURES = ["classify", "classify-no-types", "perturb-1", "perturb-3"]
RUNS = {
    "classify": "classify {src} -o {out}.parquet -q",
    "classify --no-types": "classify {src} -o {out}.parquet -q --no-types",
    "perturb --flips 1": "perturb {src} --flips 1 --seed 1 -o {out}.grains -q",
    "perturb --flips 3": "perturb {src} --flips 3 --seed 1 -o {out}.grains -q",
}


def measures(path: Path) -> tuple[int, dict[str, Callable[[], object]]]:
    """The grains of the planar_code file ``path``, and a run of each measure over them, the
    kernels they use compiled (or loaded from numba's cache)."""
    from grainclass import classify, read_dataset
    from grainclass.perturb import perturb

    batches = list(read_dataset(str(path), chunk_size=100_000))
    classify(batches[0])
    perturb(batches[0], 1, 1)
    runs = {
        "classify": lambda: [classify(b) for b in batches],
        "classify-no-types": lambda: [classify(b, types=False) for b in batches],
        "perturb-1": lambda: [perturb(b, 1, 1) for b in batches],
        "perturb-3": lambda: [perturb(b, 3, 1) for b in batches],
    }
    return sum(len(b) for b in batches), runs


def bench_perturb(work: Path, rounds: int, sides: Sequence[Checkout], n: int = 16) -> None:
    """``perturb --flips 1`` and ``--flips 3`` against ``classify`` (with and without the
    Weinberg vectors) on the same million grains (plantri's part 0/17 at n = 16), read from
    a planar_code file and from adjacency text, in rounds that each time every command (this
    machine's speed drifts between minutes): wall seconds and ratios to classify, medians over
    the rounds; then the kernels' rates in process."""
    from grainclass import read_dataset
    from grainclass.parallel import available_cpus
    from grainclass.plantri import find_plantri
    from grainclass.writers import adjacency_text

    plantri = find_plantri()
    planar = work / f"perturb{n}.pc"
    sample(plantri, n, planar)
    text = work / f"perturb{n}.txt"
    grains = 0
    with open(text, "wb") as out:
        for batch in read_dataset(str(planar), chunk_size=100_000):
            out.write(adjacency_text(batch))
            grains += len(batch)
    small_pc, small_txt = work / "small.pc", work / "small.txt"
    subprocess.run([plantri, "9", str(small_pc)], check=True, capture_output=True)
    with open(text) as lines, open(small_txt, "w") as out:
        out.writelines(itertools.islice(lines, 1000))
    print(
        f"(h) perturb against classify on the same {grains:,} grains (plantri {n}, part 0/"
        f"{sample_parts(n)}): wall s, and ratio to classify "
        f"(medians of {rounds} rounds; the ratios' range), CPU s, peak MB"
    )
    for name, src, small in (
        ("planar_code", planar, small_pc),
        ("adjacency text", text, small_txt),
    ):
        for arguments in RUNS.values():  # compile what the runs use before timing them
            command = arguments.format(src=small, out=work / "warm")
            run_each(lambda side, command=command: f"{side.grainclass} {command}", sides)
        timings: dict[str, list[list[Timing | None]]] = {label: [] for label in RUNS}
        for done in range(rounds):
            for label, arguments in RUNS.items():
                command = arguments.format(src=src, out=work / "o")
                timings[label].append(
                    in_turn(
                        lambda side, command=command: f"{side.grainclass} {command}",
                        sides,
                        reverse=done % 2 == 1,
                    )
                )
        size = src.stat().st_size / 1e6
        print(f"    {name} ({size:.0f} MB):")
        base = [[pair[i] for pair in timings["classify"]] for i in range(len(sides))]
        for label, in_rounds in timings.items():
            ours = [pair[0] for pair in in_rounds]
            print(f"        {label:21s} {rounds_line(ours, base[0])}")
            if len(sides) > 1:
                theirs = [pair[1] for pair in in_rounds]
                failed = None in theirs or None in base[1]
                figure = "failed" if failed else rounds_line(theirs, base[1])
                print(f"          {'theirs':19s} {figure}  {ratio(ours, theirs)}")
    threads = available_cpus()
    grains, rates = best_rates(sides, "perturb", planar, MEASURES, [threads])
    print(
        f"    in process, {threads} thread(s), M grains/s, the best of "
        f"{PASSES} passes: classify() | classify(types=False) | perturb(1 flip) | "
        f"perturb(3 flips): {rates_text(rates[threads][0])}"
    )
    if len(sides) > 1:
        print(
            f"        theirs: {rates_text(rates[threads][1])}; "
            f"ours/theirs in time: {rate_ratios(rates[threads][0], rates[threads][1])}"
        )
    for path in (planar, text):
        path.unlink()
