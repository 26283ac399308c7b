"""(b) Kernel-only grains per second, in process: the census kernel, the classification kernel,
the Weinberg kernel, and ``classify()`` with and without types, over about a million of
plantri's triangulations. Also the worker suite ``kernels`` of ``inprocess.py``."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from pathlib import Path

import numpy as np
from inprocess import best_rates, rate_ratios, rates_text
from inputs import sample
from timing import PASSES, Checkout

MEASURES = ["tally", "classification", "weinberg", "classify", "classify-no-types"]


def _kernel_inputs(batch) -> dict:
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


def measures(path: Path) -> tuple[int, dict[str, Callable[[], object]]]:
    """The grains of the planar_code file ``path``, and a run of each measure over them, the
    kernels they use compiled (or loaded from numba's cache)."""
    from grainclass import classify, read_dataset
    from grainclass._kernels.batch import _classify_batch
    from grainclass._kernels.weinberg import _weinberg_batch
    from grainclass.parallel import map_ordered, run_ranges
    from grainclass.summary import tally_batch

    records = list(read_dataset(str(path), chunk_size=100_000, raw_planar_code=True))
    batches = list(read_dataset(str(path), chunk_size=100_000))
    inputs = [_kernel_inputs(b) for b in batches]
    classify(batches[0])
    tally_batch(records[0])
    runs = {
        "tally": lambda: list(map_ordered(tally_batch, records)),
        "classification": lambda: [
            run_ranges(_classify_batch, i["n"], *i["classify"]) for i in inputs
        ],
        "weinberg": lambda: [run_ranges(_weinberg_batch, i["n"], *i["weinberg"]) for i in inputs],
        "classify": lambda: [classify(b) for b in batches],
        "classify-no-types": lambda: [classify(b, types=False) for b in batches],
    }
    return sum(len(b) for b in batches), runs


def bench_kernel(sizes: list[int], work: Path, sides: Sequence[Checkout]) -> None:
    from grainclass.parallel import available_cpus
    from grainclass.plantri import find_plantri

    plantri = find_plantri()
    print(
        f"(b) in process, M grains/s, the best of {PASSES} passes (other loads on the machine "
        "only ever slow a pass): census, tally_batch() of planar_code bytes (a batch a thread) | "
        "classification kernel (CSR, with truncation-tree strings) | Weinberg kernel | "
        "classify() | classify(types=False)"
    )
    for n in sizes:
        path = work / f"p{n}.pc"
        sample(plantri, n, path)
        threads = sorted({1, available_cpus()})
        grains, rates = best_rates(sides, "kernels", path, MEASURES, threads)
        for count in threads:
            print(f"    n={n}, {count} thread(s), {grains:,} grains: {rates_text(rates[count][0])}")
            if len(sides) > 1:
                theirs = rates[count][1]
                print(
                    f"        theirs: {rates_text(theirs)}; "
                    f"ours/theirs in time: {rate_ratios(rates[count][0], theirs)}"
                )
        path.unlink()
