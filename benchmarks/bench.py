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
Evolver grain files end to end, against ``cat`` of the same files; (k) ``grainclass voronoi N
--parts P -o DIR/`` on a local Dask cluster against linear scaling from one process's
``voronoi 268402``, and the mean faces per grain of ``summarize DIR/``; (l) label images:
``classify`` of a 320^3 ``.npy`` against ``np.load`` + ``np.unique`` of it, and a 1024^3
image's peak memory. Each topic is a module of its own beside this one.

With ``--compare-src DIR``, every figure of grainclass is measured for another checkout too
(its own ``.venv``, from its ``make install``), ours and theirs in turn in the same rounds, and
printed with the ratio of wall times, ours/theirs (below 1: ours is faster).
Benchmarks report; they assert nothing (the tests do that).
"""

from __future__ import annotations

import argparse
import os
import tempfile
import time
from pathlib import Path

from adjacency import bench_adjacency
from census import bench_census
from evolver import bench_evolver
from kernels import bench_kernel
from perturb import bench_perturb
from pipelines import bench_pipelines
from prisms import bench_prisms
from startup import bench_startup
from timing import Checkout, checkouts
from voronoi import bench_voronoi
from voronoi_parts import bench_voronoi_parts
from voxels import bench_voxels


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
        "--parts-seeds",
        type=int,
        default=10_000_000,
        help="seeds of (k), a tessellation in parts (default 10,000,000: some minutes)",
    )
    parser.add_argument("--parts", type=int, default=16, help="parts of (k) (default 16)")
    parser.add_argument("--parts-rounds", type=int, default=1, help="rounds of (k) (default 1)")
    parser.add_argument("--parts-only", action="store_true", help="only (k), voronoi in parts")
    parser.add_argument("--voxels-only", action="store_true", help="only (l), label images")
    parser.add_argument(
        "--voxels-big",
        type=int,
        default=1024,
        help="side of (l)'s large image, for its peak memory (default 1024; 0: none)",
    )
    parser.add_argument(
        "--compare-src",
        type=Path,
        metavar="DIR",
        help="another grainclass checkout, installed with its own make install: each figure "
        "is measured for it too, in turn with ours, and given with the ratio",
    )
    args = parser.parse_args()
    if args.rounds < 1:
        parser.error("--rounds must be at least 1")
    from grainclass.parallel import available_cpus

    sides = checkouts(args.compare_src)
    # The machine may be shared: its load, at the start and at the end, says how much to trust.
    print(
        f"grainclass benchmarks on {available_cpus()} cores, {time.strftime('%Y-%m-%d %H:%M')}, "
        f"load average {os.getloadavg()[0]:.1f}"
    )
    if len(sides) > 1:
        ours, theirs = sides
        print(f"ours: {ours.root} ({ours.commit()}); theirs: {theirs.root} ({theirs.commit()})")
    with tempfile.TemporaryDirectory() as tmp:
        run(args, Path(tmp), sides)
    print(f"done {time.strftime('%H:%M')}, load average {os.getloadavg()[0]:.1f}")


def run(args: argparse.Namespace, work: Path, sides: list[Checkout]) -> None:
    """The sections the options ask for, in the report's order."""
    only = (
        args.perturb_only,
        args.prisms_only,
        args.voronoi_only,
        args.evolver_only,
        args.voxels_only,
    )
    if any(only) or args.parts_only:
        if args.parts_only:
            bench_voronoi_parts(work, sides, args.parts_seeds, args.parts, args.parts_rounds)
        if args.voronoi_only:
            bench_voronoi(work, sides)
        if args.perturb_only:
            bench_perturb(work, args.rounds, sides)
        if args.prisms_only:
            bench_prisms(args.prisms, work, sides)
        if args.evolver_only:
            bench_evolver(args.evolver_files, args.rounds, work, sides)
        if args.voxels_only:
            bench_voxels(work, args.rounds, sides, args.voxels_big)
        return
    if not args.census_only:
        bench_startup(work, sides)
        bench_pipelines(args.sizes, args.rounds, work, sides)
        bench_kernel(args.kernel_sizes, work, sides)
        bench_adjacency(work, sides)
        bench_voronoi(work, sides)
    bench_census(args.census_sizes, args.census_parts, work, sides)
    if not args.census_only:
        bench_perturb(work, args.rounds, sides)
        bench_prisms(args.prisms, work, sides)
        bench_evolver(args.evolver_files, args.rounds, work, sides)
        bench_voronoi_parts(work, sides, args.parts_seeds, args.parts, args.parts_rounds)
        bench_voxels(work, args.rounds, sides, args.voxels_big)


if __name__ == "__main__":
    main()
