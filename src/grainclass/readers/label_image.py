"""`LabelImage`: a 3D image whose voxels hold grain ids, as every image reader opens it.

Every image format (NumPy, TIFF stacks, DREAM.3D, VTK image data, SPPARKS dumps, Neper
raster tessellations) is opened into one of these; the topology pass reads it slab by slab
along z, so that an image larger than memory never has to be held whole.

Axes are named as the formats store voxels: x varies fastest, z slowest. A slab is a C-ordered
array indexed ``[z, y, x]``; for a NumPy array that is its own indexing (its last axis is x).
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class LabelImage:
    """A 3D label image, opened but not read.

    Attributes
    ----------
    source : str
        The path it was opened from, by which messages name it.
    shape : (int, int, int)
        Voxels along z, y and x.
    dtype : numpy.dtype
        The integer type its labels are stored as.
    spacing : (float, float, float) or None
        The size of a voxel along x, y and z where the file carries it, else None.
    slabs : callable
        ``slabs(depth)`` yields consecutive integer arrays of shape ``(k, ny, nx)`` with
        ``1 <= k <= depth``, together covering z = 0 .. nz - 1 in order, each read from the file
        only when asked for.
    periodic : (bool, bool, bool) or None
        Axes x, y, z that wrap where the file says so (DAMASK's grids do not say; none does
        yet), else None: the user's ``--periodic`` decides.
    """

    source: str
    shape: tuple[int, int, int]
    dtype: np.dtype
    spacing: tuple[float, float, float] | None
    slabs: Callable[[int], Iterator[np.ndarray]]
    periodic: tuple[bool, bool, bool] | None = None

    @property
    def voxels(self) -> int:
        nz, ny, nx = self.shape
        return nz * ny * nx


def in_memory(source: str, labels: np.ndarray, spacing=None, periodic=None) -> LabelImage:
    """A `LabelImage` over an array already in memory (indexed ``[z, y, x]``)."""

    def slabs(depth: int) -> Iterator[np.ndarray]:
        for z in range(0, labels.shape[0], depth):
            yield labels[z : z + depth]

    shape = (int(labels.shape[0]), int(labels.shape[1]), int(labels.shape[2]))
    return LabelImage(source, shape, labels.dtype, spacing, slabs, periodic)
