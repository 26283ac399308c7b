"""Label images made here for the tests: voxelized periodic Voronoi tessellations of given seeds
(each voxel labelled with the id of the seed nearest its centre, by the periodic distance), the
BCC lattice, and centroidal Voronoi seeds by Lloyd's iterations."""

from __future__ import annotations

import numba
import numpy as np


@numba.njit(cache=True)
def _nearest(seeds, resolution):
    """Brute force, every voxel against every seed: the tests' images are small."""
    labels = np.empty((resolution, resolution, resolution), np.int64)
    for z in range(resolution):
        for y in range(resolution):
            for x in range(resolution):
                px, py, pz = (x + 0.5) / resolution, (y + 0.5) / resolution, (z + 0.5) / resolution
                best, best_d = 0, 1e300
                for s in range(len(seeds)):
                    dx = px - seeds[s, 0]
                    dy = py - seeds[s, 1]
                    dz = pz - seeds[s, 2]
                    dx -= np.floor(dx + 0.5)  # the nearest periodic image
                    dy -= np.floor(dy + 0.5)
                    dz -= np.floor(dz + 0.5)
                    d = dx * dx + dy * dy + dz * dz
                    if d < best_d:
                        best, best_d = s, d
                labels[z, y, x] = best
    return labels


def nearest_seed(seeds: np.ndarray, resolution: int, first_id: int = 1) -> np.ndarray:
    """The periodic Voronoi tessellation of ``seeds`` (n x 3, in the unit cube, columns x, y,
    z) voxelized at ``resolution``^3, indexed [z, y, x], labels ``first_id`` + seed index (ties
    to the lower index)."""
    return _nearest(np.ascontiguousarray(seeds, np.float64), resolution) + first_id


def bcc_seeds(cells: int) -> np.ndarray:
    """The BCC lattice of ``cells``^3 cubic cells in the unit cube (2 cells^3 seeds), shifted off
    the voxel grid's planes of symmetry so that no voxel centre is equidistant from two."""
    corner = (
        np.stack(np.meshgrid(*[np.arange(cells)] * 3, indexing="ij"), axis=-1).reshape(-1, 3)
        / cells
    )
    seeds = np.concatenate([corner, corner + 0.5 / cells])
    return (seeds + np.array([0.013, 0.007, 0.003])) % 1.0


def lloyd(seeds: np.ndarray, iterations: int, sample: int) -> np.ndarray:
    """``iterations`` of Lloyd's algorithm on the periodic unit cube, each seed moved to the
    centroid of the points of a ``sample``^3 grid nearest to it (the periodic mean)."""
    centres = (np.arange(sample) + 0.5) / sample
    z, y, x = np.meshgrid(centres, centres, centres, indexing="ij")
    points = np.stack([x.ravel(), y.ravel(), z.ravel()], axis=1)
    seeds = np.array(seeds, np.float64)
    for _ in range(iterations):
        owner = nearest_seed(seeds, sample, first_id=0).ravel()
        offsets = points - seeds[owner]
        offsets -= np.round(offsets)
        counts = np.bincount(owner, minlength=len(seeds))
        for axis in range(3):
            shift = np.bincount(owner, weights=offsets[:, axis], minlength=len(seeds))
            seeds[:, axis] += np.where(counts > 0, shift / np.maximum(counts, 1), 0.0)
        seeds %= 1.0
    return seeds
