"""(e) The first run after installation (numba compiling, with an empty cache) against a warm
run, on grains all ok, on grains not all ok and on a grain of 70 faces; and ``grainclass
--help``."""

from __future__ import annotations

import shutil
from collections.abc import Sequence
from pathlib import Path

from inputs import prism_line
from timing import ROOT, Checkout, in_turn, versus


def bench_startup(work: Path, sides: Sequence[Checkout]) -> None:
    out = work / "e.parquet"

    def classify(path: Path):
        # Each checkout compiles into a cache of its own.
        return lambda side: (
            f"NUMBA_CACHE_DIR={work / f'numba-cache-{side.name}'} "
            f"{side.grainclass} classify {path} -o {out} -q"
        )

    def cold(path: Path):
        for side in sides:
            shutil.rmtree(work / f"numba-cache-{side.name}", ignore_errors=True)
        return in_turn(classify(path), sides)

    example = ROOT / "examples" / "polytopes.txt"
    first = cold(example)
    warm = in_turn(classify(example), sides)
    # Grains that are not ok (degenerate, non-simple, invalid) need the general validation,
    # compiled only when some input has one: real data sets mostly do.
    bad = ROOT / "examples" / "bad-grains.txt"
    first_bad = cold(bad)
    # A grain of more than 64 faces needs the general classification, compiled only then.
    big = work / "prism70.txt"
    big.write_text(prism_line(68))  # 68 quadrilaterals and two 68-gons
    first_big = cold(big)
    helps = [in_turn(lambda side: f"{side.grainclass} --help > /dev/null", sides) for _ in range(3)]
    # The console script ``make install`` puts beside each checkout's python.
    scripts = [in_turn(lambda side: f"{side.console} --help > /dev/null", sides) for _ in range(3)]

    def seconds(run) -> str:
        return f"{run.seconds:.2f} s"

    print(
        f"(e) first run after installation (compiling): {first[0].seconds:.2f} s; "
        f"warm run: {warm[0].seconds:.2f} s"
        + versus(first, seconds, "    first run, ")
        + versus(warm, seconds, "    warm run, ")
    )
    print(
        f"    first run on grains not all ok ({bad.name}): {first_bad[0].seconds:.2f} s"
        + versus(first_bad, seconds, "        ")
    )
    print(
        f"    first run on a grain of 70 faces: {first_big[0].seconds:.2f} s"
        + versus(first_big, seconds, "        ")
    )
    for i in range(len(sides)):
        script, module = (
            min(run[i].seconds for run in runs if run[i]) for runs in (scripts, helps)
        )
        print(
            f"    grainclass --help{'' if i == 0 else ', theirs'}: {script:.3f} s (console "
            f"script), {module:.3f} s (python -m grainclass)"
        )
