"""(c) 268,402 grains of adjacency text (plantri's first triangulations with 14 vertices),
``grainclass classify`` end to end."""

from __future__ import annotations

import itertools
from collections.abc import Sequence
from pathlib import Path

from timing import Checkout, in_turn, run_each, versus


def write_adjacency(path: Path, n_vertices: int, count: int) -> None:
    """The first ``count`` triangulations with n vertices as adjacency text."""
    import subprocess

    from grainclass import read_dataset
    from grainclass.plantri import find_plantri
    from grainclass.writers import adjacency_text

    raw = path.with_suffix(".pc")
    subprocess.run([find_plantri(), str(n_vertices), str(raw)], check=True, capture_output=True)
    batches = read_dataset(str(raw), chunk_size=100_000)
    lines = (line for batch in batches for line in adjacency_text(batch).splitlines(True))
    with open(path, "wb") as out:
        out.writelines(itertools.islice(lines, count))
    raw.unlink()


def bench_adjacency(work: Path, sides: Sequence[Checkout]) -> None:
    path = work / "grains-268402.txt"
    write_adjacency(path, 14, 268_402)
    out = work / "adj.parquet"
    # Compile the text reader's kernels before timing, as (a) does for its runs.
    first = work / "grains-1000.txt"
    with open(path) as lines, open(first, "w") as head:
        head.writelines(itertools.islice(lines, 1000))
    run_each(lambda side: f"{side.grainclass} classify {first} -o {out} -q", sides)
    runs = in_turn(lambda side: f"{side.grainclass} classify {path} -o {out} -q", sides)
    size = path.stat().st_size / 1e6
    print(
        f"(c) 268,402 grains of adjacency text ({size:.0f} MB): {runs[0].seconds:.2f} s, "
        f"{runs[0].peak_mb:.0f} MB"
        + versus(runs, lambda run: f"{run.seconds:.2f} s, {run.peak_mb:.0f} MB", "    ")
    )
