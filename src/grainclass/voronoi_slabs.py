"""Where a tessellation in parts cuts its box, and which points each part holds: the slabs
along z (following Voro++'s search blocks of the whole tessellation), the container of a slab
and its margins, and each part's own and margin points, read or drawn
(:mod:`grainclass.voronoi_parts` runs the parts).
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from grainclass.box import Box, Points
from grainclass.errors import OptionError
from grainclass.voronoi import block_order, search_blocks

DRAW_CHUNK = 1 << 20  # random seeds drawn at a time in a task


@dataclass(frozen=True)
class Slabs:
    """``box`` cut into ``parts`` slabs along z, for ``n`` points, on Voro++'s z-blocks."""

    box: Box
    n: int
    parts: int

    def __post_init__(self) -> None:
        if self.parts < 1:
            raise OptionError("parts", f"a tessellation has at least one part, not {self.parts}")
        if self.parts > 1 and self.box.tilt is not None:
            raise OptionError("parts", "a tilted box is tessellated in one part")
        if self.parts > self.layers:
            raise OptionError(
                "parts",
                f"{self.n:,} points make {self.layers} layers of Voro++'s blocks, and a part is "
                f"at least one: at most {self.layers} parts, not {self.parts}",
            )

    @functools.cached_property
    def blocks(self) -> np.ndarray:
        """Voro++'s blocks per axis for the whole tessellation."""
        return search_blocks(self.n, self.box)

    @property
    def layers(self) -> int:
        return int(self.blocks[2])

    @functools.cached_property
    def cuts(self) -> np.ndarray:
        """The first z-block of each slab, and the number of z-blocks last."""
        return np.round(np.arange(self.parts + 1) * self.layers / self.parts).astype(np.int64)

    @property
    def spacing(self) -> float:
        """The mean spacing of the points, (volume / n)^(1/3)."""
        return (self.box.volume / self.n) ** (1 / 3)

    def z_blocks(self, xyz: np.ndarray) -> np.ndarray:
        """The z-block of each point, as :func:`grainclass.voronoi.block_cells` gives it (the
        same arithmetic, on z alone)."""
        layer = np.floor(self.box.z_fractions(xyz[:, 2]) * self.layers).astype(np.int64)
        if self.box.periodic[2]:
            return layer % self.layers
        return np.clip(layer, 0, self.layers - 1)

    def part_of(self, z_blocks: np.ndarray) -> np.ndarray:
        """The slab of points in these z-blocks."""
        return self._part_of_layer[z_blocks]

    @functools.cached_property
    def _part_of_layer(self) -> np.ndarray:
        return np.repeat(np.arange(self.parts), np.diff(self.cuts))

    def bounds(self, k: int) -> tuple[float, float]:
        """Where slab ``k`` starts and ends along z."""
        low, length = self.box.low[2], float(self.box.lengths[2])
        ends = [low + length * float(c) / self.layers for c in self.cuts[k : k + 2]]
        if k + 1 == self.parts:
            ends[1] = self.box.high[2]
        return ends[0], ends[1]

    def container(self, k: int, margin: float) -> Container:
        """What the task of slab ``k`` holds with ``margin`` on each side."""
        low, high = self.bounds(k)
        box_low, box_high = self.box.low[2], self.box.high[2]
        periodic = self.box.periodic[2]
        if periodic and (high - low) + 2 * margin >= box_high - box_low:
            return Container(self.box, whole=True)
        if not periodic:
            low, high = max(box_low, low - margin), min(box_high, high + margin)
            if low == box_low and high == box_high:
                return Container(self.box, whole=True)
        else:
            low, high = low - margin, high + margin
        box = Box(
            (self.box.low[0], self.box.low[1], low),
            (self.box.high[0], self.box.high[1], high),
            (self.box.periodic[0], self.box.periodic[1], False),
        )
        return Container(
            box,
            whole=False,
            wall_below=not periodic and low == box_low,
            wall_above=not periodic and high == box_high,
            period=float(self.box.lengths[2]) if periodic else None,
        )


@dataclass(frozen=True)
class Container:
    """The box a part's points are tessellated in: the whole box (``whole``), or its slab and
    margins, walled along z; ``wall_below`` and ``wall_above`` where that wall is the box's
    own, ``period`` the box's length along a periodic z."""

    box: Box
    whole: bool
    wall_below: bool = True
    wall_above: bool = True
    period: float | None = None

    def images(self, z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Of points at heights ``z``: which have an image in the container (a mask) and the
        shift along z that takes them there (0, or a period either way)."""
        if self.whole:
            return np.ones(len(z), dtype=bool), np.zeros(len(z))
        low, high = self.box.low[2], self.box.high[2]
        shifts = [0.0] if self.period is None else [0.0, -self.period, self.period]
        inside = np.zeros(len(z), dtype=bool)
        shift = np.zeros(len(z))
        for s in shifts:
            moved = z + s
            fits = (moved >= low) & ((moved < high) | (self.wall_above & (moved <= high)))
            fits &= ~inside
            shift[fits] = s
            inside |= fits
        return inside, shift


@dataclass
class PartPoints:
    """What a part tessellates: its own points (their ids the grains' ids, in the order their
    cells are computed) and a margin of other parts' points, moved to their image in the
    container. ``keys`` number every point among all points (for the checks across parts),
    ``margin_parts`` says whose each margin point is."""

    own: Points
    own_keys: np.ndarray
    margin_xyz: np.ndarray
    margin_radii: np.ndarray | None
    margin_keys: np.ndarray
    margin_parts: np.ndarray


def split_points(points: Points, slabs: Slabs) -> Callable[[int, float], PartPoints]:
    """For points read by this process: a function that gives each part its points and, with
    a margin, its neighbours'."""
    z_blocks = slabs.z_blocks(points.xyz)
    owner = slabs.part_of(z_blocks)
    order = block_order(points.xyz, slabs.box, slabs.blocks)
    keys = np.arange(len(points.xyz))

    def of_part(k: int, margin: float) -> PartPoints:
        own = order[owner[order] == k]
        container = slabs.container(k, margin)
        others = np.flatnonzero(owner != k)
        inside, shift = container.images(points.xyz[others, 2])
        others, shift = others[inside], shift[inside]
        xyz = points.xyz[others].copy()
        xyz[:, 2] += shift
        radii = points.radii
        return PartPoints(
            own=Points(
                points.xyz[own],
                points.ids[own],
                points.locations[own],
                points.source,
                points.location_kind,
                None if radii is None else radii[own],
            ),
            own_keys=keys[own],
            margin_xyz=xyz,
            margin_radii=None if radii is None else radii[others],
            margin_keys=keys[others],
            margin_parts=owner[others],
        )

    return of_part


def seed_points(
    slabs: Slabs, index: int, seed: int | None, source: str, container: Container
) -> PartPoints:
    """The random seeds of part ``index`` of ``slabs`` and its margin, drawn from ``seed`` as one
    process draws them all (``voronoi.poisson_voronoi``): ``DRAW_CHUNK`` at a time from one
    generator, which gives the same numbers as one draw of them all."""
    side = float(slabs.box.lengths[0])
    rng = np.random.default_rng(seed)
    per_layer = np.zeros(slabs.layers, dtype=np.int64)
    own, own_keys, margin, margin_keys, margin_parts = [], [], [], [], []
    near = _near_layers(slabs, index, container)
    for first in range(0, slabs.n, DRAW_CHUNK):
        xyz = rng.random((min(DRAW_CHUNK, slabs.n - first), 3)) * side
        z_blocks = slabs.z_blocks(xyz)
        per_layer += np.bincount(z_blocks, minlength=slabs.layers)
        # Only points of the layers near the part are looked at further: with many parts,
        # the others are most points, and each part draws them all.
        candidates = np.flatnonzero(near[z_blocks])
        xyz = xyz[candidates]
        owner = slabs.part_of(z_blocks[candidates])
        mine = owner == index
        own.append(xyz[mine])
        own_keys.append(first + candidates[mine])
        inside, shift = container.images(xyz[:, 2])
        others = np.flatnonzero(inside & ~mine)
        moved = xyz[others]
        moved[:, 2] += shift[others]
        margin.append(moved)
        margin_keys.append(first + candidates[others])
        margin_parts.append(owner[others])
    xyz, keys = np.concatenate(own), np.concatenate(own_keys)
    order = block_order(xyz, slabs.box, slabs.blocks)
    # Grains are numbered by their rank in the order the whole tessellation computes them: the
    # points of the slabs below come first.
    ids = int(per_layer[: slabs.cuts[index]].sum()) + np.arange(len(xyz), dtype=np.int64)
    return PartPoints(
        own=Points(xyz[order], ids, ids.copy(), source, "record"),
        own_keys=keys[order],
        margin_xyz=np.concatenate(margin),
        margin_radii=None,
        margin_keys=np.concatenate(margin_keys),
        margin_parts=np.concatenate(margin_parts),
    )


def _near_layers(slabs: Slabs, k: int, container: Container) -> np.ndarray:
    """Per layer of blocks, whether its points may be part ``k``'s or in its container: the
    layers that meet the container (or one of its periodic images), and their neighbours,
    which a point rounded across a layer's side may be in."""
    if container.whole:
        return np.ones(slabs.layers, dtype=bool)
    low, length = slabs.box.low[2], float(slabs.box.lengths[2])
    sides = low + length * np.arange(slabs.layers + 1) / slabs.layers
    near = np.zeros(slabs.layers, dtype=bool)
    near[slabs.cuts[k] : slabs.cuts[k + 1]] = True
    for shift in [0.0] if container.period is None else [0.0, -length, length]:
        near |= (sides[1:] + shift >= container.box.low[2]) & (
            sides[:-1] + shift <= container.box.high[2]
        )
    return near | np.roll(near, 1) | np.roll(near, -1)
