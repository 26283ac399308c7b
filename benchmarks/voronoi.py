"""(f) The Voronoi generator: ``grainclass voronoi --points`` from a points file to classified
Parquet against the voro++ program alone on the same points; ``grainclass voronoi N``; classify
of its text and of voro++'s output; and two million points for the memory."""

from __future__ import annotations

import itertools
import shutil
from collections.abc import Sequence
from pathlib import Path

import numpy as np
from timing import Checkout, Timing, in_turn, run_each, timed, versus


def points_file(path: Path, n: int, seed: int) -> None:
    """``n`` uniform random points in a cube of side 1024 * (n / 268402)^(1/3), as Voro++'s
    input (``id x y z``)."""
    side = 1024 * (n / 268_402) ** (1 / 3)
    points = np.random.default_rng(seed).random((n, 3)) * side
    np.savetxt(path, np.column_stack([np.arange(n), points]), fmt="%d %.17g %.17g %.17g")


def bench_voronoi(
    work: Path, sides: Sequence[Checkout], n: int = 268_402, big: int = 2_000_000
) -> None:
    """``grainclass voronoi --points`` from a points file to classified Parquet (Weinberg
    vectors included) against the voro++ program alone on the same points, then ``big``
    points for the memory."""
    few = work / "few-points"
    points_file(few, 2000, 2)
    # Compile the classification kernels before timing.
    run_each(
        lambda side: (
            f"{side.grainclass} voronoi --points {few} --box 1024 -o {work / 'few.parquet'} -q"
        ),
        sides,
    )
    seeds = work / "seeds"
    points_file(seeds, n, 1)
    out = work / "pv.parquet"
    ours = in_turn(
        lambda side: f"{side.grainclass} voronoi --points {seeds} --box 1024 -o {out} -q", sides
    )

    def cost(run: Timing) -> str:
        return f"{run.seconds:.1f} s, {run.peak_mb:.0f} MB, CPU {run.user + run.system:.1f} s"

    line = (
        f"(f) grainclass voronoi --points ({n:,} Poisson points) -o pv.parquet: {cost(ours[0])}"
        + versus(ours, cost, "    ")
    )
    voro = shutil.which("voro++")
    if voro:
        command = f"{voro} -p -c '%i %v %F %t' 0 1024 0 1024 0 1024 {seeds}"
        alone = timed(command)
        print(
            f"{line}\n    voro++ -p -c '%i %v %F %t' alone, same points: {alone.seconds:.1f} s, "
            f"{alone.peak_mb:.0f} MB, CPU {alone.user + alone.system:.1f} s; "
            f"grainclass / voro++: x{ours[0].seconds / alone.seconds:.2f}"
        )
    else:
        print(f"{line}\n    (voro++ not installed: apt-get install voro++ to compare)")
    # Each checkout draws its own cells; both classify ours.
    text = work / "pv-ours.txt"
    drawn = in_turn(
        lambda side: f"{side.grainclass} voronoi {n} --seed 1 -o {work / f'pv-{side.name}.txt'} -q",
        sides,
    )
    print(
        f"    grainclass voronoi {n:,} --seed 1 -o pv.txt (random seeds, no types): "
        f"{drawn[0].seconds:.1f} s" + versus(drawn, lambda run: f"{run.seconds:.1f} s", "        ")
    )
    with_types = in_turn(lambda side: f"{side.grainclass} classify {text} -o {out} -q", sides)
    without = in_turn(
        lambda side: f"{side.grainclass} classify {text} -o {out} -q --no-types", sides
    )

    def rate(run) -> str:
        return f"{run.seconds:.1f} s ({n / run.seconds:,.0f} grains/s)"

    print(
        f"    classify pv.txt: {rate(with_types[0])} with Weinberg vectors, "
        f"{rate(without[0])} with --no-types"
        + versus(with_types, rate, "        with types, ")
        + versus(without, rate, "        --no-types, ")
    )
    if voro:
        # Compile the face-loop reader's kernels on a few cells first: not part of the timing.
        few_cells = work / "few.vol"
        with open(f"{seeds}.vol") as cells:
            few_cells.write_text("".join(itertools.islice(cells, 100)))
        run_each(lambda side: f"{side.grainclass} classify {few_cells} -o {out} -q", sides)
        of_voro = in_turn(lambda side: f"{side.grainclass} classify {seeds}.vol -o {out} -q", sides)
        print(
            f"    grainclass classify of voro++'s output: {of_voro[0].seconds:.1f} s, "
            f"{of_voro[0].peak_mb:.0f} MB"
            + versus(of_voro, lambda run: f"{run.seconds:.1f} s, {run.peak_mb:.0f} MB", "        ")
        )
    points_file(seeds, big, 3)
    side_length = 1024 * (big / n) ** (1 / 3)
    many = in_turn(
        lambda side: (
            f"{side.grainclass} voronoi --points {seeds} --box {side_length:.6g} -o {out} -q"
        ),
        sides,
    )

    def cells(run) -> str:
        return f"{run.seconds:.1f} s, {run.peak_mb:.0f} MB ({big / run.seconds:,.0f} cells/s)"

    print(f"    {big:,} points to Parquet: {cells(many[0])}" + versus(many, cells, "        "))
