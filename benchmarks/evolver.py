"""(j) A folder of Surface Evolver grain files, ``grainclass classify FOLDER`` end to end,
against ``cat`` of the same files read from the page cache."""

from __future__ import annotations

import shutil
from collections.abc import Sequence
from pathlib import Path

import numpy as np
from timing import ROOT, Checkout, Timing, in_turn, ratio, run_each, timed

GRAIN_FILES = ROOT / "tests" / "data" / "evolver" / "grain3d"


def grain_folder(folder: Path, n_files: int, variants: int = 100) -> int:
    """``n_files`` grain files of a grain-growth time step in ``folder`` (``21000-ID.fe``): the
    ten real ones of tests/data/evolver/grain3d, ``variants`` times over with their vertices
    moved by up to 2e-6 (the simulator's 6 significant digits kept), then copied round-robin.
    Returns their bytes."""
    rng = np.random.default_rng(0)
    sources = [path.read_text() for path in sorted(GRAIN_FILES.glob("*.fe"))]
    texts = []
    for k in range(min(variants, n_files)):
        head, rest = sources[k % len(sources)].split("\nedges\n", 1)
        lines = head.split("\n")
        start = lines.index("vertices") + 1
        for i in range(start, len(lines)):
            fields = lines[i].split("\t")
            if len(fields) < 4:
                continue
            moved = np.array(fields[1:4], float) + rng.uniform(-2e-6, 2e-6, 3)
            fields[1:4] = [f"{x:.6g}" for x in moved]
            lines[i] = "\t".join(fields)
        texts.append(("\n".join(lines) + "\nedges\n" + rest).encode())
    folder.mkdir(parents=True, exist_ok=True)
    total = 0
    for i in range(n_files):
        data = texts[i % len(texts)]
        (folder / f"21000-{i:08d}.fe").write_bytes(data)
        total += len(data)
    return total


def bench_evolver(sizes: list[int], rounds: int, work: Path, sides: Sequence[Checkout]) -> None:
    """``grainclass classify FOLDER`` against ``cat FOLDER/*.fe > /dev/null``, the same files
    read from the page cache."""
    from grainclass.parallel import available_cpus

    out = work / "grains.parquet"
    print(
        f"(j) Surface Evolver grain files, end to end on {available_cpus()} cores: wall s and MB/s "
        f"(median of {rounds} rounds), against cat of the same files; CPU s of all processes"
    )
    warm = work / "grains-warm"
    grain_folder(warm, 20)
    # Compile whatever the runs use before timing them (its two degenerate grains make even -q
    # name the counts).
    run_each(lambda side: f"{side.grainclass} classify {warm} -o {out} -q", sides)
    for n in sizes:
        folder = work / f"grains-{n}"
        size = grain_folder(folder, n) / 1e6
        # Past ARG_MAX, *.fe cannot be expanded: xargs hands cat the names in parts.
        files = f"{folder}/*.fe" if n <= 20_000 else None
        floor = (
            f"cat {files} > /dev/null"
            if files
            else f"find {folder} -name '*.fe' -print0 | xargs -0 cat > /dev/null"
        )
        cats: list[Timing] = []
        runs: list[list[Timing | None]] = []
        for done in range(rounds):
            cats.append(timed(floor))
            runs.append(
                in_turn(
                    lambda side, folder=folder: f"{side.grainclass} classify {folder} -o {out} -q",
                    sides,
                    reverse=done % 2 == 1,
                )
            )
            out.unlink(missing_ok=True)
        cat_s = float(np.median([t.seconds for t in cats]))
        print(f"    {n:,} files, {size:.0f} MB: cat {cat_s:.2f} s ({size / cat_s:,.0f} MB/s)")
        for i, side in enumerate(sides):
            timings = [pair[i] for pair in runs]
            label = f"classify ({side.name})" if len(sides) > 1 else "classify"
            if None in timings:
                print(f"        {label}: failed")
                continue
            wall = float(np.median([t.seconds for t in timings]))
            cpu = float(np.median([t.user + t.system for t in timings]))
            spread = f"{min(t.seconds for t in timings):.2f}-{max(t.seconds for t in timings):.2f}"
            peak = max(t.peak_mb for t in timings)
            print(
                f"        {label}: {wall:6.2f} s ({spread}), {size / wall:6.1f} MB/s, "
                f"x{wall / cat_s:.1f} cat; cpu {cpu:.2f} s, {peak:.0f} MB"
                + ("" if i == 0 else f"; {ratio([p[0] for p in runs], timings)}")
            )
        shutil.rmtree(folder)
