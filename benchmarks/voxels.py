"""(l) Label images: ``grainclass classify`` of a 320^3 uint32 ``.npy`` (about 2,000 grains of
25 voxels across) end to end, against ``np.load`` + ``np.unique`` of the same file in the same
rounds; then the peak memory of a 1024^3 image (4.3 GB on disk, read slab by slab)."""

from __future__ import annotations

import sys
from collections.abc import Sequence
from pathlib import Path

import numba
import numpy as np
from timing import Checkout, Timing, in_turn, run_each, timed, versus


@numba.njit(cache=True)
def _jittered_voronoi(z0, planes, resolution, cells, seeds, out):
    """Planes z0 .. z0 + planes - 1 of a periodic tessellation of one jittered seed per cubic
    cell (``seeds[cz, cy, cx]``, in cell units, within 0.1 .. 0.9 of the cell): each voxel gets
    the id of the nearest of the 8 seeds of the cells around its position shifted by half a
    cell, nearly always its Voronoi cell's; cheap, and grains enough for a benchmark."""
    scale = cells / resolution
    for k in range(planes):
        pz = (z0 + k + 0.5) * scale
        for y in range(resolution):
            py = (y + 0.5) * scale
            for x in range(resolution):
                px = (x + 0.5) * scale
                cx, cy, cz = int(px - 0.5), int(py - 0.5), int(pz - 0.5)
                if px < 0.5:
                    cx = -1
                if py < 0.5:
                    cy = -1
                if pz < 0.5:
                    cz = -1
                best, best_d = 0, 1e300
                for dz in range(2):
                    for dy in range(2):
                        for dx in range(2):
                            ix, iy, iz = cx + dx, cy + dy, cz + dz
                            jx, jy, jz = ix % cells, iy % cells, iz % cells
                            s = seeds[jz, jy, jx]
                            ex = px - (ix + s[0])
                            ey = py - (iy + s[1])
                            ez = pz - (iz + s[2])
                            d = ex * ex + ey * ey + ez * ez
                            if d < best_d:
                                best_d = d
                                best = 1 + jz * cells * cells + jy * cells + jx
                out[k, y, x] = best


def label_image(path: Path, resolution: int, voxels_across: float = 25.0, seed: int = 1) -> int:
    """A periodic Voronoi label image of about ``voxels_across`` voxels a grain, written as a
    uint32 ``.npy`` plane block by plane block (never held whole); returns its grains."""
    cells = max(3, round(resolution / voxels_across))
    rng = np.random.default_rng(seed)
    seeds = 0.5 + (rng.random((cells, cells, cells, 3)) - 0.5) * 0.8
    image = np.lib.format.open_memmap(
        path, mode="w+", dtype=np.uint32, shape=(resolution, resolution, resolution)
    )
    for z in range(0, resolution, 32):
        planes = min(32, resolution - z)
        block = np.empty((planes, resolution, resolution), np.uint32)
        _jittered_voronoi(z, planes, resolution, cells, seeds, block)
        image[z : z + planes] = block
    image.flush()
    del image
    return cells**3


def bench_voxels(work: Path, rounds: int, sides: Sequence[Checkout], big: int = 1024) -> None:
    """The 320^3 image against loading it and finding its labels; then ``big``^3's memory."""
    small = work / "image40.npy"
    label_image(small, 40)
    out = work / "image.parquet"
    run_each(
        lambda side: f"{side.grainclass} classify {small} --periodic xyz -o {out} -q", sides
    )  # compile the pass before timing
    image = work / "image320.npy"
    grains = label_image(image, 320)
    unique = f"{sys.executable} -c 'import numpy as np; np.unique(np.load(\"{image}\"))'"
    print(f"(l) label images: a 320^3 uint32 .npy of {grains} grains (131 MB), wall s, peak MB")

    def figure(run: Timing) -> str:
        return f"{run.seconds:6.2f} s {run.peak_mb:6.0f} MB"

    baseline: list[Timing] = []
    ours: list[list[Timing | None]] = []
    for _ in range(rounds):
        baseline.append(timed(unique))
        ours.append(
            in_turn(
                lambda side: f"{side.grainclass} classify {image} --periodic xyz -o {out} -q",
                sides,
            )
        )
    base = sorted(baseline, key=lambda run: run.seconds)[len(baseline) // 2]
    mine = sorted((runs[0] for runs in ours if runs[0]), key=lambda run: run.seconds)
    middle = mine[len(mine) // 2]
    ratios = sorted(
        runs[0].seconds / b.seconds for runs, b in zip(ours, baseline, strict=True) if runs[0]
    )
    print(f"    np.load + np.unique: {figure(base)}")
    print(
        f"    classify --periodic xyz: {figure(middle)}, x{ratios[len(ratios) // 2]:.2f} "
        f"({ratios[0]:.2f}-{ratios[-1]:.2f}) of np.load + np.unique"
        + versus(ours[0], figure, "        ")
    )
    image.unlink()
    if big:
        path = work / f"image{big}.npy"
        grains = label_image(path, big)
        run = timed(f"{sides[0].grainclass} classify {path} --periodic xyz -o {out} -q")
        print(f"    {big}^3 ({grains} grains, {path.stat().st_size / 1e9:.1f} GB): {figure(run)}")
        path.unlink()
