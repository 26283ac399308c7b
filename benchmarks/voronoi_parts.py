"""(k) A tessellation in parts on a local Dask cluster (one worker per core): ``grainclass
voronoi N --parts P -o DIR/`` against linear scaling from one process's ``grainclass voronoi
268402`` (the paper's V data set) timed in the same rounds; the largest process and all of them
together; then ``grainclass summarize DIR/``, whose mean faces per grain is Lazar et al.'s
15.535 for Poisson-Voronoi cells."""

from __future__ import annotations

import re
import subprocess
from collections.abc import Sequence
from pathlib import Path

import numpy as np
from timing import Checkout, run_each, timed, timed_processes

REFERENCE = 268_402  # cells of the paper's V data set: one process's run, scaled linearly
LAZAR_MEAN_FACES = 15.535  # Lazar, Mason, MacPherson, Srolovitz, PRE 88 (2013), 250M cells


def bench_voronoi_parts(
    work: Path, sides: Sequence[Checkout], n: int, parts: int, rounds: int = 1
) -> None:
    from grainclass.parallel import available_cpus

    cores = available_cpus()
    # Warm-up: numba's cache and the workers' start, untimed.
    run_each(
        lambda side: (
            f"{side.grainclass} voronoi 20000 --seed 1 --parts 2 "
            f"-o {work / f'warm-{side.name}'}/ -q"
        ),
        sides,
    )
    print(
        f"(k) voronoi {n:,} --parts {parts} on {cores} workers against linear scaling from one "
        f"process's voronoi {REFERENCE:,} (x{n / REFERENCE:.2f}), {rounds} round(s):"
    )
    ratios: list[list[float]] = [[] for _ in sides]
    cpu_ratios: list[list[float]] = [[] for _ in sides]
    for round_ in range(rounds):
        for k, side in enumerate(sides):
            one = timed(
                f"{side.grainclass} voronoi {REFERENCE} --seed 1 -o {work / 'v.parquet'} -q"
            )
            folder = work / f"pv-{side.name}"
            command = (
                f"rm -rf {folder} && {side.grainclass} voronoi {n} --seed 1 --parts {parts} "
                f"--workers {cores} -o {folder}/ -q"
            )
            try:
                run = timed_processes(command)
            except subprocess.CalledProcessError:
                if side.name == "ours":
                    raise
                print(f"    theirs failed: {command}")
                continue
            linear = one.seconds * n / REFERENCE
            linear_cpu = (one.user + one.system) * n / REFERENCE
            ratios[k].append(run.seconds / linear)
            cpu_ratios[k].append(run.cpu / linear_cpu)
            print(
                f"    {side.name} round {round_ + 1}: voronoi {REFERENCE:,} {one.seconds:.2f} s, "
                f"CPU {one.user + one.system:.1f} s, {one.peak_mb:.0f} MB; linear "
                f"x{n / REFERENCE:.2f}: {linear:.1f} s, CPU {linear_cpu:.1f} s\n"
                f"        in parts {run.seconds:.1f} s (x{run.seconds / linear:.2f} of linear), "
                f"CPU {run.cpu:.1f} s (x{run.cpu / linear_cpu:.2f}); largest process "
                f"{run.largest_mb:.0f} MB, all processes {run.all_mb:.0f} MB"
            )
    for k, side in enumerate(sides):
        if not ratios[k]:
            continue
        folder = work / f"pv-{side.name}"
        summary = timed(f"{side.grainclass} summarize {folder} -q > {work / 'summary.txt'}")
        text = (work / "summary.txt").read_text()
        found = re.search(r"mean faces per grain ([0-9.]+)", text)
        mean = float(found.group(1)) if found else float("nan")
        print(
            f"    {side.name}: median x{float(np.median(ratios[k])):.2f} of linear "
            f"({min(ratios[k]):.2f}-{max(ratios[k]):.2f}), CPU "
            f"x{float(np.median(cpu_ratios[k])):.2f}; summarize DIR/ {summary.seconds:.1f} s, "
            f"{summary.peak_mb:.0f} MB: mean faces per grain {mean:.3f} (Lazar et al. "
            f"{LAZAR_MEAN_FACES}, off by {mean - LAZAR_MEAN_FACES:+.3f})"
        )
