"""``make bench``: how fast and how big, measured in one run on this machine.

Reports (a) plantri alone against plantri piped through ``cat`` (what the pipe itself costs),
through ``grainclass classify`` and through ``grainclass summarize``, with ratios (medians of
rounds that each time plantri alone too: this machine's speed drifts between minutes);
(b) kernel-only grains per second; (c) 268,402 grains of adjacency text end to end; (d) peak
resident memory of every run; (e) the first run after installation (numba compiling) against a
warm run, and ``grainclass --help``; (f) the Voronoi generator; (g) ``grainclass census``
against plantri alone on the same parts; (h) ``grainclass perturb`` against ``grainclass
classify`` on the same grains, as planar_code and as adjacency text; (i) one giant grain, the
k-gonal prism for k = 1,000, 4,000 and 20,000, with and without types; (j) a folder of Surface
Evolver grain files end to end, against ``cat`` of the same files.
Benchmarks report; they assert nothing (the tests do that).
"""

from __future__ import annotations

import argparse
import itertools
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import NamedTuple

import numpy as np

from grainclass.parallel import available_cpus
from grainclass.plantri import find_plantri

ROOT = Path(__file__).resolve().parent.parent
GRAINCLASS = [sys.executable, "-m", "grainclass"]
PASSES = 3  # over the same grains in (b)


class Timing(NamedTuple):
    seconds: float  # wall
    peak_mb: float  # resident, of the largest process
    user: float  # CPU seconds of all the command's processes
    system: float


def timed(command: str, env: dict | None = None) -> Timing:
    """Wall seconds, peak resident MB (of the largest process) and CPU seconds of a shell
    command."""
    fd, record = tempfile.mkstemp(suffix=".time")
    os.close(fd)
    # bash waits for every process of the command: its children's times are all of them.
    wrapped = f"/usr/bin/time -f '%M %U %S' -o {record} -a bash -c {_quote(command)}"
    start = time.perf_counter()
    subprocess.run(wrapped, shell=True, check=True, env=env, stderr=subprocess.DEVNULL)
    seconds = time.perf_counter() - start
    peak_kb, user, system = Path(record).read_text().split()[-3:]
    os.unlink(record)
    return Timing(seconds, int(peak_kb) / 1024, float(user), float(system))


def timed_tree(command: str) -> tuple[float, float, float]:
    """Wall seconds, the peak of the summed resident MB of a command and all its descendants
    (worker processes included), and the peak of its largest single descendant, sampled every
    0.1 s."""
    start = time.perf_counter()
    process = subprocess.Popen(command, shell=True, stderr=subprocess.DEVNULL)
    peak = largest = 0
    while process.poll() is None:
        rss = _tree_rss_kb(process.pid)
        peak = max(peak, sum(rss.values()))
        largest = max([largest, *(kb for pid, kb in rss.items() if pid != process.pid)])
        time.sleep(0.1)
    seconds = time.perf_counter() - start
    if process.returncode:
        raise subprocess.CalledProcessError(process.returncode, command)
    return seconds, peak / 1024, largest / 1024


def _tree_rss_kb(root: int) -> dict[int, int]:
    """Resident kB of ``root`` and each of its descendants, by pid."""
    parents: dict[int, int] = {}
    rss: dict[int, int] = {}
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            stat = (entry / "stat").read_text()
            status = (entry / "status").read_text()
        except OSError:
            continue
        parents[int(entry.name)] = int(stat.rsplit(")", 1)[1].split()[1])
        for line in status.splitlines():
            if line.startswith("VmRSS:"):
                rss[int(entry.name)] = int(line.split()[1])
    tree, frontier = {root}, [root]
    while frontier:
        children = [pid for pid, parent in parents.items() if parent in frontier]
        frontier = [pid for pid in children if pid not in tree]
        tree.update(frontier)
    return {pid: rss.get(pid, 0) for pid in tree}


def _quote(text: str) -> str:
    return "'" + text.replace("'", "'\\''") + "'"


def _cpu(run: Timing) -> str:
    return f"  cpu {run.user + run.system:6.2f} s (system {run.system:5.2f})"


def _rounds(runs: list[Timing], alone: list[Timing]) -> str:
    """Median wall time and ratio over rounds, each run against plantri alone in its own round
    (this machine's speed drifts by tens of percent between minutes), the ratios' range, the
    median CPU time and the largest peak."""
    ratios = [run.seconds / base.seconds for run, base in zip(runs, alone, strict=True)]
    middle = Timing(
        float(np.median([run.seconds for run in runs])),
        max(run.peak_mb for run in runs),
        float(np.median([run.user for run in runs])),
        float(np.median([run.system for run in runs])),
    )
    if len(runs) == 1:
        spread = ""
    elif runs is alone:  # its ratios are all 1: the range of its times instead
        spread = (
            f" ({min(run.seconds for run in runs):.2f}-{max(run.seconds for run in runs):.2f} s)"
        )
    else:
        spread = f" ({min(ratios):4.2f}-{max(ratios):4.2f})"
    return (
        f"{middle.seconds:6.2f} s  x{float(np.median(ratios)):5.2f}{spread}{_cpu(middle)}"
        f"  {middle.peak_mb:5.0f} MB"
    )


def bench_pipelines(sizes: list[int], rounds: int, work: Path) -> None:
    plantri = find_plantri()
    gc = " ".join(GRAINCLASS)
    out = work / "out.parquet"
    runs = {
        # What a pipe costs a reader that wakes for each of plantri's 4 kB writes.
        "cat (the pipe alone)": "cat > /dev/null",
        "classify": f"{gc} classify - -o {out} -q",
        "classify --no-types": f"{gc} classify - -o {out} -q --no-types",
        "summarize": f"{gc} summarize - -q > /dev/null",
        "summarize --types": f"{gc} summarize - -q --types > /dev/null",
    }
    print(
        "(a) plantri N > /dev/null against plantri N | grainclass ...: wall s and ratio (medians "
        f"of {rounds} rounds, each against plantri alone in its round; the ratios' range), "
        "CPU s of all processes (system), peak MB"
    )
    for command in runs.values():  # compile whatever the runs use before timing them
        subprocess.run(f"{plantri} 9 2>/dev/null | {command}", shell=True, check=True)
    for n in sizes:
        alone: list[Timing] = []
        piped: dict[str, list[Timing]] = {name: [] for name in runs}
        for _ in range(rounds):
            alone.append(timed(f"{plantri} {n} > /dev/null 2>&1"))
            for name, command in runs.items():
                piped[name].append(timed(f"{plantri} {n} 2>/dev/null | {command}"))
            out.unlink(missing_ok=True)
        print(f"    n={n}:")
        print(f"        plantri alone           {_rounds(alone, alone)}")
        for name, timings in piped.items():
            print(f"        | {name:21s} {_rounds(timings, alone)}")


def _kernel_inputs(batch):
    """The arrays ``classify`` hands to the kernels (after the grain range), to time them alone."""
    g = len(batch)
    n_faces = batch.n_faces
    tree_offsets = np.zeros(g + 1, np.int64)
    np.cumsum(3 * n_faces, out=tree_offsets[1:])
    code_offsets = np.zeros(g + 1, np.int64)
    np.cumsum(6 * n_faces - 11, out=code_offsets[1:])
    return {
        "n": g,
        "classify": (
            batch.face_offsets,
            batch.nbr_offsets,
            batch.neighbors,
            np.ones(g, bool),
            64,
            True,
            np.zeros(g, np.int8),
            np.zeros(g, bool),
            np.zeros((g, 3), np.int64),
            np.zeros(g, np.int8),
            np.zeros(g, np.int32),
            np.zeros(g, np.int32),
            np.zeros(g, np.int32),
            np.zeros((g, 3), np.int64),
            tree_offsets,
            np.zeros(int(tree_offsets[-1]), np.uint8),
            np.zeros(g, np.int64),
        ),
        "weinberg": (
            np.arange(g, dtype=np.int64),
            batch.face_offsets,
            batch.nbr_offsets,
            batch.neighbors,
            code_offsets,
            np.zeros(int(code_offsets[-1]), np.int32),
            np.zeros(g, np.int32),
            np.zeros(g, np.int8),
        ),
    }


# Triangulations of the sphere with n vertices (plantri's counts, OEIS A000109).
TRIANGULATIONS = {14: 339_722, 15: 2_406_841, 16: 17_490_241, 17: 129_664_753}


def _sample(plantri: str, n: int, path: Path) -> None:
    """About a million triangulations with n vertices into ``path``: plantri's part 0 of as many
    (``0/mod``) as the enumeration has millions. Its first million would not do: at n = 16 they
    are all stacked, a grain the kernels classify without looking for empty triangles, 4-belts
    or truncation trees (the whole enumeration is 10% stacked, 72% flag and 18% sc; part 0/17,
    10%, 69% and 18%)."""
    parts = max(1, TRIANGULATIONS.get(n, 0) // 1_000_000)
    subprocess.run([plantri, str(n), f"0/{parts}", str(path)], check=True, capture_output=True)


def _batches(path: Path, raw: bool) -> list:
    from grainclass.readers import read_dataset

    return list(read_dataset(str(path), chunk_size=100_000, raw_planar_code=raw))


def bench_kernel(sizes: list[int], work: Path) -> None:
    from grainclass._kernels.batch import _classify_batch
    from grainclass._kernels.weinberg import _weinberg_batch
    from grainclass.classification import classify
    from grainclass.parallel import map_ordered, run_ranges, set_jobs
    from grainclass.summary import tally_batch

    plantri = find_plantri()
    print(
        f"(b) in process, M grains/s, the best of {PASSES} passes (other loads on the machine "
        "only ever slow a pass): census, tally_batch() of planar_code bytes (a batch a thread) | "
        "classification kernel (CSR, with truncation-tree strings) | Weinberg kernel | "
        "classify() | classify(types=False)"
    )
    for n in sizes:
        path = work / f"p{n}.pc"
        _sample(plantri, n, path)
        records = _batches(path, raw=True)
        batches = _batches(path, raw=False)
        grains = sum(len(b) for b in batches)
        inputs = [_kernel_inputs(b) for b in batches]
        classify(batches[0])
        tally_batch(records[0])
        for threads in sorted({1, available_cpus()}):
            set_jobs(threads)
            rates = []
            for run in (
                lambda records=records: list(map_ordered(tally_batch, records)),
                lambda inputs=inputs: [
                    run_ranges(_classify_batch, i["n"], *i["classify"]) for i in inputs
                ],
                lambda inputs=inputs: [
                    run_ranges(_weinberg_batch, i["n"], *i["weinberg"]) for i in inputs
                ],
                lambda batches=batches: [classify(b) for b in batches],
                lambda batches=batches: [classify(b, types=False) for b in batches],
            ):
                best = float("inf")
                for _ in range(PASSES):
                    start = time.perf_counter()
                    run()
                    best = min(best, time.perf_counter() - start)
                rates.append(grains / best / 1e6)
            print(
                f"    n={n}, {threads} thread(s), {grains:,} grains: "
                + " | ".join(f"{r:5.2f}" for r in rates)
            )
        path.unlink()


def write_adjacency(path: Path, n_vertices: int, count: int) -> None:
    """The first ``count`` triangulations with n vertices as adjacency text."""
    from itertools import islice

    from grainclass.readers import read_dataset
    from grainclass.writers import adjacency_text

    plantri = find_plantri()
    raw = path.with_suffix(".pc")
    subprocess.run([plantri, str(n_vertices), str(raw)], check=True, capture_output=True)
    batches = read_dataset(str(raw), chunk_size=100_000)
    lines = (line for batch in batches for line in adjacency_text(batch).splitlines(True))
    with open(path, "wb") as out:
        out.writelines(islice(lines, count))
    raw.unlink()


def bench_adjacency(work: Path) -> None:
    path = work / "grains-268402.txt"
    write_adjacency(path, 14, 268_402)
    gc = " ".join(GRAINCLASS)
    # Compile the text reader's kernels before timing, as (a) does for its runs.
    first = work / "grains-1000.txt"
    with open(path) as lines, open(first, "w") as out:
        out.writelines(itertools.islice(lines, 1000))
    subprocess.run(f"{gc} classify {first} -o {work / 'adj.parquet'} -q", shell=True, check=True)
    seconds, mem, *_ = timed(f"{gc} classify {path} -o {work / 'adj.parquet'} -q")
    size = path.stat().st_size / 1e6
    print(f"(c) 268,402 grains of adjacency text ({size:.0f} MB): {seconds:.2f} s, {mem:.0f} MB")


def bench_startup(work: Path) -> None:
    gc = " ".join(GRAINCLASS)
    example = ROOT / "examples" / "polytopes.txt"
    cache = work / "numba-cache"
    shutil.rmtree(cache, ignore_errors=True)
    env = dict(os.environ, NUMBA_CACHE_DIR=str(cache))
    first = timed(f"{gc} classify {example} -o {work / 'e.parquet'} -q", env)
    warm = timed(f"{gc} classify {example} -o {work / 'e.parquet'} -q", env)
    # Grains that are not ok (degenerate, non-simple, invalid) need the general validation,
    # compiled only when some input has one: real data sets mostly do.
    shutil.rmtree(cache, ignore_errors=True)
    bad = ROOT / "examples" / "bad-grains.txt"
    first_bad = timed(f"{gc} classify {bad} -o {work / 'e.parquet'} -q", env)
    # A grain of more than 64 faces needs the general classification, compiled only then.
    shutil.rmtree(cache, ignore_errors=True)
    big = work / "prism70.txt"
    k = 68  # the 68-gonal prism: 68 quadrilaterals and two 68-gons
    faces = [[k, (i - 1) % k, k + 1, (i + 1) % k] for i in range(k)]
    faces += [list(range(k)), list(reversed(range(k)))]
    big.write_text("prism70\t" + ";".join(" ".join(map(str, f)) for f in faces) + "\n")
    first_big = timed(f"{gc} classify {big} -o {work / 'e.parquet'} -q", env)
    helps = [timed(f"{gc} --help > /dev/null").seconds for _ in range(3)]
    console = shutil.which("grainclass")
    script = [timed(f"{console} --help > /dev/null").seconds for _ in range(3)] if console else []
    print(
        f"(e) first run after installation (compiling): {first.seconds:.2f} s; "
        f"warm run: {warm.seconds:.2f} s"
    )
    print(f"    first run on grains not all ok ({bad.name}): {first_bad.seconds:.2f} s")
    print(f"    first run on a grain of 70 faces: {first_big.seconds:.2f} s")
    print(
        "    grainclass --help: " + (f"{min(script):.3f} s (console script), " if script else ""),
        f"{min(helps):.3f} s (python -m grainclass)",
        sep="",
    )


def bench_voronoi(work: Path, n: int = 268_402, big: int = 2_000_000) -> None:
    """``grainclass voronoi --points`` from a points file to classified Parquet (Weinberg
    vectors included) against the voro++ program alone on the same points, then ``big``
    points for the memory."""
    gc = " ".join(GRAINCLASS)
    few = work / "few-points"
    _points_file(few, 2000, 2)
    # Compile the classification kernels before timing.
    subprocess.run(
        f"{gc} voronoi --points {few} --box 1024 -o {work / 'few.parquet'} -q",
        shell=True,
        check=True,
    )
    seeds = work / "seeds"
    _points_file(seeds, n, 1)
    out = work / "pv.parquet"
    ours = timed(f"{gc} voronoi --points {seeds} --box 1024 -o {out} -q")
    line = (
        f"(f) grainclass voronoi --points ({n:,} Poisson points) -o pv.parquet: "
        f"{ours.seconds:.1f} s, {ours.peak_mb:.0f} MB, CPU {ours.user + ours.system:.1f} s"
    )
    voro = shutil.which("voro++")
    if voro:
        command = f"{voro} -p -c '%i %v %F %t' 0 1024 0 1024 0 1024 {seeds}"
        alone = timed(command)
        print(
            f"{line}\n    voro++ -p -c '%i %v %F %t' alone, same points: {alone.seconds:.1f} s, "
            f"{alone.peak_mb:.0f} MB, CPU {alone.user + alone.system:.1f} s; "
            f"grainclass / voro++: x{ours.seconds / alone.seconds:.2f}"
        )
    else:
        print(f"{line}\n    (voro++ not installed: apt-get install voro++ to compare)")
    text = work / "pv.txt"
    seconds = timed(f"{gc} voronoi {n} --seed 1 -o {text} -q").seconds
    print(
        f"    grainclass voronoi {n:,} --seed 1 -o pv.txt (random seeds, no types): {seconds:.1f} s"
    )
    with_types = timed(f"{gc} classify {text} -o {out} -q").seconds
    without = timed(f"{gc} classify {text} -o {out} -q --no-types").seconds
    print(
        f"    classify pv.txt: {with_types:.1f} s ({n / with_types:,.0f} grains/s) with Weinberg "
        f"vectors, {without:.1f} s ({n / without:,.0f} grains/s) with --no-types"
    )
    if voro:
        # Compile the face-loop reader's kernels on a few cells first: not part of the timing.
        few_cells = work / "few.vol"
        with open(f"{seeds}.vol") as cells:
            few_cells.write_text("".join(itertools.islice(cells, 100)))
        subprocess.run(f"{gc} classify {few_cells} -o {out} -q", shell=True, check=True)
        of_voro = timed(f"{gc} classify {seeds}.vol -o {out} -q")
        print(
            f"    grainclass classify of voro++'s output: {of_voro.seconds:.1f} s, "
            f"{of_voro.peak_mb:.0f} MB"
        )
    _points_file(seeds, big, 3)
    side = 1024 * (big / n) ** (1 / 3)
    many = timed(f"{gc} voronoi --points {seeds} --box {side:.6g} -o {out} -q")
    print(
        f"    {big:,} points to Parquet: {many.seconds:.1f} s, {many.peak_mb:.0f} MB "
        f"({big / many.seconds:,.0f} cells/s)"
    )


def _points_file(path: Path, n: int, seed: int) -> None:
    """``n`` uniform random points in a cube of side 1024 * (n / 268402)^(1/3), as Voro++'s
    input (``id x y z``)."""
    side = 1024 * (n / 268_402) ** (1 / 3)
    points = np.random.default_rng(seed).random((n, 3)) * side
    np.savetxt(path, np.column_stack([np.arange(n), points]), fmt="%d %.17g %.17g %.17g")


def bench_census(sizes: list[int], parts: int, work: Path) -> None:
    """``grainclass census`` on a local cluster (one worker per core) against plantri alone on
    the same parts, as many at a time as there are cores."""
    plantri = find_plantri()
    cores = available_cpus()
    gc = " ".join(GRAINCLASS)
    # A warm-up (its report on stderr too is not a figure of the benchmark).
    subprocess.run(
        f"{gc} census 9 --parts 2 -o {work / 'census-warm'} -q > /dev/null 2>&1",
        shell=True,
        check=True,
    )
    print(f"(g) census, {parts} parts per n, {cores} workers, against plantri on the same parts:")
    for n in sizes:
        indices = " ".join(str(i) for i in range(parts))
        alone = timed(
            f"printf '%s\\n' {indices} | xargs -P {cores} -I@ {plantri} -h {n} @/{parts} "
            "> /dev/null 2>&1"
        ).seconds
        whole = timed(f"{plantri} -h {n} > /dev/null 2>&1").seconds
        command = f"{gc} census {n} --parts {parts} -o {work / f'census-{n}'} -q > /dev/null"
        seconds, total, worker = timed_tree(command)
        print(
            f"    n={n}: plantri alone, the same parts {alone:7.1f} s (one plantri {n}: "
            f"{whole:.1f} s); census {seconds:7.1f} s  x{seconds / alone:4.2f}  "
            f"largest process {worker:.0f} MB, all processes {total:.0f} MB"
        )


def bench_perturb(work: Path, rounds: int, n: int = 16) -> None:
    """``perturb --flips 1`` and ``--flips 3`` against ``classify`` (with and without the
    Weinberg vectors) on the same million grains (plantri's part 0/17 at n = 16), read from
    a planar_code file and from adjacency text, in rounds that each time every command (this
    machine's speed drifts between minutes): wall seconds and ratios to classify, medians over
    the rounds; then the kernels' rates in process."""
    from grainclass.classification import classify
    from grainclass.perturb import perturb
    from grainclass.writers import adjacency_text

    plantri = find_plantri()
    gc = " ".join(GRAINCLASS)
    planar = work / f"perturb{n}.pc"
    _sample(plantri, n, planar)
    batches = _batches(planar, raw=False)
    grains = sum(len(b) for b in batches)
    text = work / f"perturb{n}.txt"
    with open(text, "wb") as out:
        for batch in batches:
            out.write(adjacency_text(batch))
    small_pc, small_txt = work / "small.pc", work / "small.txt"
    subprocess.run([plantri, "9", str(small_pc)], check=True, capture_output=True)
    with open(text) as lines, open(small_txt, "w") as out:
        out.writelines(itertools.islice(lines, 1000))
    runs = {
        "classify": "classify {src} -o {out}.parquet -q",
        "classify --no-types": "classify {src} -o {out}.parquet -q --no-types",
        "perturb --flips 1": "perturb {src} --flips 1 --seed 1 -o {out}.grains -q",
        "perturb --flips 3": "perturb {src} --flips 3 --seed 1 -o {out}.grains -q",
    }
    print(
        f"(h) perturb against classify on the same {grains:,} grains (plantri {n}, part 0/"
        f"{max(1, TRIANGULATIONS.get(n, 0) // 1_000_000)}): wall s, and ratio to classify "
        f"(medians of {rounds} rounds; the ratios' range), CPU s, peak MB"
    )
    for name, src, small in (
        ("planar_code", planar, small_pc),
        ("adjacency text", text, small_txt),
    ):
        for command in runs.values():  # compile what the runs use before timing them
            subprocess.run(
                f"{gc} {command.format(src=small, out=work / 'warm')}", shell=True, check=True
            )
        timings: dict[str, list[Timing]] = {label: [] for label in runs}
        for _ in range(rounds):
            for label, command in runs.items():
                timings[label].append(timed(f"{gc} {command.format(src=src, out=work / 'o')}"))
        size = src.stat().st_size / 1e6
        print(f"    {name} ({size:.0f} MB):")
        for label, runs_of in timings.items():
            print(f"        {label:21s} {_rounds(runs_of, timings['classify'])}")
    rates = []
    classify(batches[0])
    perturb(batches[0], 1, 1)
    for run in (
        lambda: [classify(b) for b in batches],
        lambda: [classify(b, types=False) for b in batches],
        lambda: [perturb(b, 1, 1) for b in batches],
        lambda: [perturb(b, 3, 1) for b in batches],
    ):
        best = float("inf")
        for _ in range(PASSES):
            start = time.perf_counter()
            run()
            best = min(best, time.perf_counter() - start)
        rates.append(grains / best / 1e6)
    print(
        "    in process, M grains/s, the best of "
        f"{PASSES} passes: classify() | classify(types=False) | perturb(1 flip) | "
        "perturb(3 flips): " + " | ".join(f"{r:5.2f}" for r in rates)
    )
    for path in (planar, text):
        path.unlink()


def prism_line(k: int) -> str:
    """The k-gonal prism as a line of adjacency text: k quadrilaterals and two k-gons."""
    faces = [[k, (i - 1) % k, k + 1, (i + 1) % k] for i in range(k)]
    faces += [list(range(k)), list(reversed(range(k)))]
    return f"prism{k}\t" + ";".join(" ".join(map(str, f)) for f in faces) + "\n"


def bench_prisms(ks: list[int], work: Path) -> None:
    """``classify`` of a file holding one k-gonal prism, end to end: a giant grain's time and
    peak memory (about k^2 / 2 4-belts; with types, about 4k Weinberg walks of 6k steps)."""
    gc = " ".join(GRAINCLASS)
    out = work / "prism.parquet"
    small = work / "prism70.txt"
    small.write_text(prism_line(68))  # compile the general path and the large walks first
    subprocess.run(f"{gc} classify {small} -o {out} -q", shell=True, check=True)
    print("(i) one k-gonal prism (k + 2 faces), classify end to end: wall s, peak MB")
    for k in ks:
        path = work / f"prism{k}.txt"
        path.write_text(prism_line(k))
        runs = []
        for flags in ("--no-types", ""):
            run = timed(f"{gc} classify {path} -o {out} -q {flags}")
            runs.append(f"{run.seconds:7.2f} s {run.peak_mb:6.0f} MB")
        print(f"    k={k:>6,}: without types {runs[0]}; with types {runs[1]}")
        path.unlink()


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


def bench_evolver(sizes: list[int], rounds: int, work: Path, compare: list[str]) -> None:
    """``grainclass classify FOLDER`` against ``cat FOLDER/*.fe > /dev/null``, the same files
    read from the page cache; ``compare``: other grainclass source trees (a checkout of main,
    say) timed in the same rounds."""
    gc = " ".join(GRAINCLASS)
    out = work / "grains.parquet"
    trees = [("this tree", None), *((src, src) for src in compare)]
    print(
        f"(j) Surface Evolver grain files, end to end on {available_cpus()} cores: wall s and MB/s "
        f"(median of {rounds} rounds), against cat of the same files; CPU s of all processes"
    )
    warm = work / "grains-warm"
    grain_folder(warm, 20)
    for _, src in trees:  # compile whatever the runs use before timing them
        env = None if src is None else dict(os.environ, PYTHONPATH=src)
        # Its two degenerate grains make even -q name the counts: not a line of the report.
        subprocess.run(
            f"{gc} classify {warm} -o {out} -q",
            shell=True,
            check=True,
            env=env,
            stderr=subprocess.DEVNULL,
        )
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
        cats, runs = [], {name: [] for name, _ in trees}
        for _ in range(rounds):
            cats.append(timed(floor))
            for name, src in trees:
                env = None if src is None else dict(os.environ, PYTHONPATH=src)
                runs[name].append(timed(f"{gc} classify {folder} -o {out} -q", env))
            out.unlink(missing_ok=True)
        cat_s = float(np.median([t.seconds for t in cats]))
        print(f"    {n:,} files, {size:.0f} MB: cat {cat_s:.2f} s ({size / cat_s:,.0f} MB/s)")
        for name, timings in runs.items():
            wall = float(np.median([t.seconds for t in timings]))
            cpu = float(np.median([t.user + t.system for t in timings]))
            spread = f"{min(t.seconds for t in timings):.2f}-{max(t.seconds for t in timings):.2f}"
            peak = max(t.peak_mb for t in timings)
            print(
                f"        classify ({name}): {wall:6.2f} s ({spread}), {size / wall:6.1f} MB/s, "
                f"x{wall / cat_s:.1f} cat; cpu {cpu:.2f} s, {peak:.0f} MB"
            )
        shutil.rmtree(folder)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[14, 15, 16])
    parser.add_argument(
        "--rounds", type=int, default=3, help="rounds of (a), each with plantri alone (default 3)"
    )
    parser.add_argument("--kernel-sizes", type=int, nargs="+", default=[14, 16])
    parser.add_argument("--census-sizes", type=int, nargs="+", default=[16])
    parser.add_argument("--census-parts", type=int, default=4)
    parser.add_argument("--census-only", action="store_true", help="only (g), the census")
    parser.add_argument(
        "--perturb-only", action="store_true", help="only (h), perturb against classify"
    )
    parser.add_argument("--prisms", type=int, nargs="+", default=[1000, 4000, 20000])
    parser.add_argument("--prisms-only", action="store_true", help="only (i), the prisms")
    parser.add_argument("--voronoi-only", action="store_true", help="only (f), Voronoi cells")
    parser.add_argument(
        "--evolver-files",
        type=int,
        nargs="+",
        default=[1_000, 50_000],
        help="folder sizes of (j), in grain files of about 22 kB (default 1000 50000: start-up "
        "and steady state)",
    )
    parser.add_argument("--evolver-only", action="store_true", help="only (j), Evolver files")
    parser.add_argument(
        "--compare-src",
        nargs="+",
        default=[],
        metavar="DIR",
        help="other grainclass source trees (src/ of a checkout) timed beside this one in (j)",
    )
    args = parser.parse_args()
    if args.rounds < 1:
        parser.error("--rounds must be at least 1")
    print(f"grainclass benchmarks on {available_cpus()} cores, {time.strftime('%Y-%m-%d %H:%M')}")
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        if args.perturb_only or args.prisms_only or args.voronoi_only or args.evolver_only:
            if args.voronoi_only:
                bench_voronoi(work)
            if args.perturb_only:
                bench_perturb(work, args.rounds)
            if args.prisms_only:
                bench_prisms(args.prisms, work)
            if args.evolver_only:
                bench_evolver(args.evolver_files, args.rounds, work, args.compare_src)
            return
        if not args.census_only:
            bench_startup(work)
            bench_pipelines(args.sizes, args.rounds, work)
            bench_kernel(args.kernel_sizes, work)
            bench_adjacency(work)
            bench_voronoi(work)
        bench_census(args.census_sizes, args.census_parts, work)
        if not args.census_only:
            bench_perturb(work, args.rounds)
            bench_prisms(args.prisms, work)
            bench_evolver(args.evolver_files, args.rounds, work, args.compare_src)


if __name__ == "__main__":
    main()
