"""Grains from a 3D label image: each label's faces, triple lines and corners, as batches.

:func:`image_topology` reads the image once, slab by slab along z with one plane of overlap,
the planes of a slab shared among the threads (``_kernels/voxels.py``), and keeps only
per-label and per-pair tables and the blocks of voxels where three labels or more meet; it
then decides the triple lines and quadruple points of those blocks (docs/voxels.md).
:func:`image_batches` makes one row per grain (grain_id = the label, ascending): its faces are
the grains it shares a triple line with, face j of grain i is next to face k where {i, j, k}
is a triple line, in the cyclic order the quadruple points give. A grain cut by a side of the
image that does not wrap or by the background, in several pieces, with a cavity or a tunnel,
enclosed by one other grain, or touching no other grain has a row without faces and a message
saying which.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Iterator, Sequence
from dataclasses import dataclass

import numpy as np

from grainclass import parallel
from grainclass.batch import GrainBatch, offsets_from_counts
from grainclass.errors import InputError
from grainclass.options import ReadOptions
from grainclass.readers.label_image import LabelImage, checked_slab, in_memory, label_dtype
from grainclass.voxel_edits import settle

MAX_LABEL = (1 << 26) - 1
"""Labels index dense tables (17 bytes per label and thread): an image with a larger label is
read with its labels numbered 0, 1, 2, ... in ascending order (:func:`compact_labels`)."""

MAX_GRAINS = 1 << 21
"""Three grain indices make one int64 key."""

SLAB_DEPTH = 16
"""Planes read at a time: memory is a few slabs plus the per-label tables."""

BLOCKS_PER_PART = 1 << 16
"""Blocks resolved per call: a thread's scratch for them stays below 100 MB."""

AXES = "xyz"


@dataclass(frozen=True)
class ImageTopology:
    """What :func:`image_topology` finds in an image. Grains are indexed 0..G-1 in ascending
    label order; pairs, triples and quads are rows of grain indices, sorted within a row and
    unique, each with its count."""

    source: str
    labels: np.ndarray  # int64 (G,)
    voxels: np.ndarray  # int64 (G,)
    boundary: np.ndarray  # bool (G,)
    euler: np.ndarray  # int64 (G,): V - E + F - C of the grain's voxels
    pairs: np.ndarray  # int64 (P, 2): labels sharing voxel faces
    pair_faces: np.ndarray  # int64 (P,)
    triples: np.ndarray  # int64 (T, 3): the triple lines decided
    triple_weight: np.ndarray  # int64 (T,): simplices of the blocks' meshes
    quads: np.ndarray  # int64 (Q, 4): the quadruple points decided
    quad_weight: np.ndarray  # int64 (Q,)
    columns: np.ndarray  # int64 (C, 3): three labels around a lattice edge
    column_count: np.ndarray  # int64 (C,): lattice edges with them


class LabelsPastTables(InputError):
    """A label larger than :data:`MAX_LABEL`: the image is to be read with compact labels."""


def _check_labels(image: LabelImage, slab: np.ndarray, z0: int) -> None:
    """The checks every image reader makes of its slabs (z from ``z0``), made here too for an
    image opened otherwise (:func:`~grainclass.readers.label_image.in_memory`)."""
    label_dtype(image.source, slab.dtype)
    checked_slab(image.source, slab, z0)


def check_slab(image: LabelImage, slab: np.ndarray, z0: int) -> np.ndarray:
    """A slab's labels (z from ``z0``) as int32, refused where they are no labels grainclass
    takes (:class:`LabelsPastTables` for one larger than :data:`MAX_LABEL`)."""
    _check_labels(image, slab, z0)
    if slab.size and int(slab.max()) > MAX_LABEL:
        raise LabelsPastTables(image.source, f"label {int(slab.max())} is larger than {MAX_LABEL}")
    return np.ascontiguousarray(slab, dtype=np.int32)


def compact_labels(
    image: LabelImage, background: Sequence[int]
) -> tuple[LabelImage, np.ndarray, list[int]]:
    """The image with each label replaced by its rank among the image's labels, the labels in
    ascending order (rank -> label), and the background's ranks.

    A Potts run that starts every site with its own spin (SPPARKS's ``set site unique``)
    keeps labels up to its number of sites, past what the dense per-label tables index; its
    grains are few. This reads the image once more: once for its labels, then ranked slab by
    slab as the pass reads it.
    """
    values = None
    z = 0
    for slab in image.slabs(SLAB_DEPTH):
        _check_labels(image, slab, z)
        z += len(slab)
        found = np.unique(slab)
        values = found if values is None else np.union1d(values, found)
    if values is None:
        raise InputError(image.source, "an image without voxels")
    if len(values) > MAX_GRAINS + len(background):
        raise InputError(
            image.source, f"{len(values)} labels: grainclass takes at most {MAX_GRAINS} grains"
        )

    def slabs(depth: int) -> Iterator[np.ndarray]:
        for slab in image.slabs(depth):
            yield np.searchsorted(values, slab).astype(np.int32)

    ranked = LabelImage(
        image.source, image.shape, np.dtype(np.int32), image.spacing, slabs, image.periodic
    )
    wanted = [int(b) for b in background if int(b) >= 0]
    at = np.searchsorted(values, wanted)
    ranks = [int(r) for r, b in zip(at, wanted, strict=True) if r < len(values) and values[r] == b]
    return ranked, values, ranks


class _Tables:
    """One thread's per-label tables, grown to the largest label seen."""

    def __init__(self) -> None:
        self.counts = np.zeros(0, np.int64)
        self.euler = np.zeros(0, np.int64)
        self.boundary = np.zeros(0, np.uint8)

    def grow(self, size: int) -> None:
        if size > len(self.counts):
            old = len(self.counts)
            for name, dtype in (("counts", np.int64), ("euler", np.int64), ("boundary", np.uint8)):
                table = np.zeros(size, dtype)
                table[:old] = getattr(self, name)
                setattr(self, name, table)


def _as_flags(periodic: str | Sequence[bool] | None, image: LabelImage) -> tuple[int, int, int]:
    if periodic is None:
        flags = image.periodic or (False, False, False)
    elif isinstance(periodic, str):
        flags = tuple(axis in periodic for axis in AXES)
    else:
        flags = tuple(bool(f) for f in periodic)
    return int(flags[0]), int(flags[1]), int(flags[2])


def image_topology(
    image: LabelImage,
    periodic: str | Sequence[bool] | None = None,
    background: Sequence[int] = (),
) -> ImageTopology:
    """Read a label image once and find its grains' faces, triple lines and corners.

    Parameters
    ----------
    image : LabelImage
        The image, read slab by slab.
    periodic : str or (bool, bool, bool), optional
        The axes that wrap (``"xyz"``, ``"xy"``, ``""``); None: as the image says, else none.
    background : sequence of int
        Labels that are no grain: a grain touching one is a boundary grain.

    Raises
    ------
    InputError
        An empty image, labels that are not integers, negative or larger than
        :data:`MAX_LABEL`, more than :data:`MAX_GRAINS` grains, or a file cut short.
    """
    from grainclass._kernels.voxels import _resolve_blocks, _scan_planes

    nz, ny, nx = image.shape
    if min(image.shape) < 1:
        raise InputError(image.source, f"an empty image ({nz} x {ny} x {nx} voxels)")
    px, py, pz = _as_flags(periodic, image)
    jobs = max(1, min(parallel.get_jobs(), 8))
    tables = [_Tables() for _ in range(jobs)]
    bg_labels = sorted({int(b) for b in background if 0 <= int(b) <= MAX_LABEL})
    background_flags = np.zeros(0, np.uint8)
    pair_keys: list[np.ndarray] = []
    blocks: list[np.ndarray] = []
    state = {"size": 0}

    def grow(size: int) -> np.ndarray:
        nonlocal background_flags
        if size > state["size"]:
            state["size"] = size
            for table in tables:
                table.grow(size)
            background_flags = np.zeros(size, np.uint8)
            background_flags[[b for b in bg_labels if b < size]] = 1
        return background_flags

    def scan(planes: np.ndarray, stop: int, z0: int) -> None:
        flags = grow(int(planes.max()) + 1)
        cuts = [stop * k // jobs for k in range(jobs + 1)]

        def run(job: int) -> tuple[np.ndarray, np.ndarray]:
            t = tables[job]
            return _scan_planes(
                planes, cuts[job], cuts[job + 1], z0, nz, px, py, pz, flags,
                t.counts, t.euler, t.boundary,
            )  # fmt: skip

        for contacts, found in parallel.map_ordered(run, range(jobs)):
            if len(contacts):
                keys, counts = np.unique(contacts, return_counts=True)
                pair_keys.append(np.stack([keys, counts]))
            if len(found):
                blocks.append(found.astype(np.int32))
        if len(pair_keys) > 8:
            pair_keys[:] = [_merge_counts(pair_keys)]

    first_plane = None
    carry = None
    z = 0
    try:
        for slab in image.slabs(SLAB_DEPTH):
            slab = check_slab(image, slab, z)
            if slab.shape[1:] != (ny, nx):
                raise InputError(image.source, f"a slab of shape {slab.shape}, not (k, {ny}, {nx})")
            if first_plane is None:
                first_plane = slab[:1].copy()
            planes = slab if carry is None else np.concatenate([carry, slab])
            z0 = z - (0 if carry is None else 1)
            scan(planes, len(planes) - 1, z0)
            carry = slab[-1:].copy()
            z += len(slab)
    except OSError as exc:
        raise InputError(image.source, exc.strerror or str(exc)) from None
    if carry is None or first_plane is None or z != nz:
        raise InputError(image.source, f"cut short: {z} of {nz} planes along z")
    last = np.concatenate([carry, first_plane]) if pz else carry
    scan(last, 1, nz - 1)

    counts = sum(t.counts for t in tables)
    euler = sum(t.euler for t in tables)
    boundary = np.logical_or.reduce([t.boundary for t in tables]) if tables else None
    present = counts > 0
    present[[b for b in bg_labels if b < len(present)]] = False
    labels = np.flatnonzero(present)
    if len(labels) > MAX_GRAINS:
        raise InputError(
            image.source, f"{len(labels)} grains: grainclass takes at most {MAX_GRAINS}"
        )
    index = np.full(len(counts), -1, np.int64)
    index[labels] = np.arange(len(labels))
    merged = _merge_counts(pair_keys) if pair_keys else np.zeros((2, 0), np.int64)
    keys, faces = merged[0], merged[1]
    all_blocks = np.concatenate(blocks) if blocks else np.zeros((0, 8), np.int32)
    # Parts of at most BLOCKS_PER_PART blocks: each part's scratch is 56 rows a block.
    n_parts = max(2 * jobs, -(-len(all_blocks) // BLOCKS_PER_PART))
    cuts = [len(all_blocks) * k // n_parts for k in range(n_parts + 1)]
    parts = list(
        parallel.map_ordered(
            lambda k: _resolve_blocks(all_blocks, cuts[k], cuts[k + 1], keys, faces, index),
            range(n_parts),
        )
    )
    n = len(labels)
    triples, triple_weight = _sum_rows([p[0] for p in parts], [p[1] for p in parts], n)
    quads, quad_weight = _sum_rows([p[2] for p in parts], [p[3] for p in parts], n)
    columns, column_count = _sum_rows([p[4] for p in parts], [p[5] for p in parts], n)
    pairs = np.stack([index[keys >> 32], index[keys & 0xFFFFFFFF]], axis=1)
    triples, triple_weight, quads, quad_weight = settle(
        pairs, faces, triples, triple_weight, quads, quad_weight
    )
    return ImageTopology(
        image.source, labels, counts[labels], boundary[labels].astype(bool), euler[labels],
        pairs, faces, triples, triple_weight, quads, quad_weight, columns, column_count,
    )  # fmt: skip


def _merge_counts(parts: list[np.ndarray]) -> np.ndarray:
    """Rows (keys, counts) of several parts summed by key."""
    both = np.concatenate(parts, axis=1)
    keys, inverse = np.unique(both[0], return_inverse=True)
    return np.stack([keys, np.bincount(inverse, weights=both[1]).astype(np.int64)])


def _sum_rows(
    rows: list[np.ndarray], weights: list[np.ndarray], n: int
) -> tuple[np.ndarray, np.ndarray]:
    """The distinct rows of grain indices (< n, sorted within a row) of several parts, in
    lexicographic order, with their weights summed."""
    width = rows[0].shape[1] if rows else 3
    every = np.concatenate(rows) if rows else np.zeros((0, width), np.int64)
    weight = np.concatenate(weights) if weights else np.zeros(0, np.int64)
    if len(every) == 0:
        return every.reshape(0, width), weight
    if float(n) ** width < 2**62:
        key = np.zeros(len(every), np.int64)
        for column in range(width):
            key = key * n + every[:, column]
        _, first, inverse = np.unique(key, return_index=True, return_inverse=True)
    else:
        order = np.lexsort(every.T[::-1])
        ordered = every[order]
        new = np.r_[True, np.any(ordered[1:] != ordered[:-1], axis=1)]
        group = np.cumsum(new) - 1
        inverse = np.empty(len(every), np.int64)
        inverse[order] = group
        first = order[new]
    return every[first], np.bincount(inverse.ravel(), weights=weight).astype(np.int64)


def _directed(triples: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Each triple (a, b, c) as the six rows (i, j, k) of its permutations, sorted."""
    a, b, c = triples[:, 0], triples[:, 1], triples[:, 2]
    i = np.concatenate([a, a, b, b, c, c])
    j = np.concatenate([b, c, a, c, a, b])
    k = np.concatenate([c, b, c, a, b, a])
    order = np.argsort((i * n + j) * n + k, kind="stable")
    return i[order], j[order], k[order]


def _quad_pairs(quads: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
    """Each quad as 12 rows: the key i * n + j of an ordered pair of it and the other two."""
    rows, rest = [], []
    for x in range(4):
        for y in range(4):
            if x != y:
                u, v = (w for w in range(4) if w not in (x, y))
                rows.append(quads[:, x] * n + quads[:, y])
                rest.append(quads[:, [u, v]])
    keys = np.concatenate(rows) if rows else np.zeros(0, np.int64)
    kl = np.concatenate(rest) if rest else np.zeros((0, 2), np.int64)
    order = np.argsort(keys, kind="stable")
    return keys[order], np.ascontiguousarray(kl[order])


def _problems(topology: ImageTopology) -> dict[int, str]:
    """Why grains get no faces, by grain index: cut, not one solid piece, enclosed, alone."""
    labels = topology.labels
    n = len(labels)
    neighbours = np.bincount(topology.pairs.ravel(), minlength=n)
    only = np.full(n, -1, np.int64)
    for a, b in topology.pairs:
        if neighbours[a] == 1:
            only[a] = b
        if neighbours[b] == 1:
            only[b] = a
    problems: dict[int, str] = {}
    for g in np.flatnonzero(topology.boundary):
        problems[int(g)] = (
            "a boundary grain: it touches a side of the image that does not wrap (--periodic) "
            "or the background (--background), where its faces are cuts"
        )
    # A solid grain with one neighbour is enclosed by it.
    only[topology.boundary | (topology.euler != 1)] = -1
    enclosed: dict[int, list[int]] = {}
    for g in np.flatnonzero(only >= 0):
        enclosed.setdefault(int(only[g]), []).append(int(labels[g]))
    for g in np.flatnonzero(topology.euler != 1):
        g = int(g)
        what = (
            f"its {topology.voxels[g]} voxels are not one solid piece (Euler characteristic "
            f"{topology.euler[g]}, 1 for a ball): in several pieces (--components makes each "
            "its own grain), with a tunnel through it, or around a cavity"
        )
        if g in enclosed:
            inside = ", ".join(str(x) for x in enclosed[g][:5])
            what += f"; it encloses grain {inside}" + (", ..." if len(enclosed[g]) > 5 else "")
        problems.setdefault(g, what)
    for g in np.flatnonzero(neighbours == 0):
        problems.setdefault(int(g), "it touches no other grain")
    for g in np.flatnonzero(only >= 0):
        problems.setdefault(
            int(g), f"enclosed by grain {labels[only[g]]}, its only neighbour: it has no corners"
        )
    for g, inside in enclosed.items():
        if g not in problems:
            problems[g] = f"it encloses grain {', '.join(str(x) for x in inside[:5])}"
    return problems


def image_batches(
    topology: ImageTopology,
    chunk_size: int,
    spacing: tuple[float, float, float] | None = None,
    triples: np.ndarray | None = None,
) -> Iterator[GrainBatch]:
    """The grains of an image, one row per label in ascending order, in batches of at most
    ``chunk_size``. ``triples`` in place of the topology's own (another rule, to compare)."""
    from grainclass._kernels.voxels import _face_cycles

    labels = topology.labels
    n = len(labels)
    tri = topology.triples if triples is None else triples
    problems = _problems(topology)
    i, j, k = _directed(tri, n)
    bad = np.zeros(n, bool)
    bad[list(problems)] = True
    keep = ~bad[i]
    i, j, k = i[keep], j[keep], k[keep]
    group_key = i * n + j
    starts = (
        np.flatnonzero(np.r_[True, group_key[1:] != group_key[:-1]])
        if len(i)
        else np.zeros(0, np.int64)
    )
    group_start = np.append(starts, len(i)).astype(np.int64)
    keys = group_key[starts]
    quad_keys, quad_kl = _quad_pairs(topology.quads, n)
    quad_lo = np.searchsorted(quad_keys, keys).astype(np.int64)
    quad_hi = np.searchsorted(quad_keys, keys, side="right").astype(np.int64)
    order = np.empty(len(k), np.int64)
    ordered = np.empty(len(keys), np.int64)
    _face_cycles(group_start, k, quad_lo, quad_hi, quad_kl, order, ordered)
    grain_of_face = keys // n
    face_counts = np.bincount(grain_of_face, minlength=n)
    face_offsets = offsets_from_counts(face_counts)
    # A neighbour k of face j of grain g is the face (g, k) of g: its place among g's faces.
    local = np.searchsorted(keys, np.repeat(grain_of_face, np.diff(group_start)) * n + order)
    local -= face_offsets[np.repeat(grain_of_face, np.diff(group_start))]
    # The shortest triple line of each grain, as lattice edges around which it shows alone.
    col_keys = (topology.columns[:, 0] * n + topology.columns[:, 1]) * n + topology.columns[:, 2]
    tri_keys = (tri[:, 0] * n + tri[:, 1]) * n + tri[:, 2]
    at = np.searchsorted(col_keys, tri_keys)
    found = at < len(col_keys)
    found[found] = col_keys[at[found]] == tri_keys[found]
    length = np.where(found, topology.column_count[np.minimum(at, len(col_keys) - 1)], 0)
    shortest = np.full(n, np.iinfo(np.int64).max, np.int64)
    for column in range(3):
        np.minimum.at(shortest, tri[:, column], length)
    has_line = (shortest < np.iinfo(np.int64).max) & ~bad
    voxel_volume = float(np.prod(spacing)) if spacing is not None else 1.0
    for start in range(0, n, chunk_size):
        stop = min(start + chunk_size, n)
        f0, f1 = face_offsets[start], face_offsets[stop]
        nbr_offsets = group_start[f0 : f1 + 1] - group_start[f0]
        yield GrainBatch(
            source=topology.source,
            grain_id=[str(x) for x in labels[start:stop]],
            location=labels[start:stop],
            location_kind="label",
            face_offsets=face_offsets[start : stop + 1] - f0,
            nbr_offsets=nbr_offsets,
            neighbors=local[group_start[f0] : group_start[f1]],
            volume=topology.voxels[start:stop] * voxel_volume,
            boundary=topology.boundary[start:stop].astype(np.int8),
            parse_errors={g - start: problems[g] for g in range(start, stop) if g in problems},
            face_labels=labels[keys[f0:f1] % n],
            voxels=topology.voxels[start:stop],
            shortest_triple_line=np.where(has_line, shortest, -1)[start:stop],
        )


def read_image(image: LabelImage, options: ReadOptions) -> Iterator[GrainBatch]:
    """The grains of a label image as batches, read as ``options`` say (periodic axes, voxel
    size, background labels, connected pieces as grains of their own: then grain_id numbers
    the pieces and a ``label`` column gives each piece's label).

    Raises
    ------
    InputError
        An image that cannot be read (see :func:`image_topology`).
    MissingDependencyError
        ``components`` without connected-components-3d (``grainclass[images]``).
    """
    periodic = _as_flags(options.periodic, image)
    background: Sequence[int] = options.background
    try:
        yield from _read_image(image, options, periodic, background, None)
    except LabelsPastTables:  # raised before any batch: the whole image is read first
        image, values, background = compact_labels(image, background)
        yield from _read_image(image, options, periodic, background, values)


def _read_image(
    image: LabelImage,
    options: ReadOptions,
    periodic: tuple[int, int, int],
    background: Sequence[int],
    values: np.ndarray | None,
) -> Iterator[GrainBatch]:
    """:func:`read_image` of an image whose label ``r`` is ``values[r]`` (None: itself)."""
    original = None
    if options.components:
        from grainclass.components import connected_pieces

        slabs, z = [], 0
        for slab in image.slabs(SLAB_DEPTH):
            slabs.append(check_slab(image, slab, z))
            z += len(slab)
        whole = np.concatenate(slabs)
        pieces, original = connected_pieces(whole, periodic, background)
        image = in_memory(image.source, pieces, image.spacing, image.periodic)
        background = (0,)
    if values is not None and original is not None:
        original = values[original]
    topology = image_topology(image, periodic, background)
    if values is not None and original is None:
        topology = dataclasses.replace(topology, labels=values[topology.labels])
    spacing = options.spacing or image.spacing
    for batch in image_batches(topology, options.chunk_size, spacing):
        if original is not None:
            labels = [str(original[int(g)]) for g in batch.grain_id]
            batch = dataclasses.replace(batch, attributes={"label": labels})
        yield batch
