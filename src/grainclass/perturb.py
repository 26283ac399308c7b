"""`perturb`: topological edge errors put into grains on purpose, as the paper's error analysis
does (Sec. "Grain Classes and Error Analysis", figs. grains_with_6_faces and
combined_cut_types).

A short edge measured wrongly is an edge flip (a T1 move): in the dual triangulation, edge A-B,
on the triangles A-B-C and B-A-D, is replaced by C-D. It is admissible when A and B have at
least four neighbours and C and D are not adjacent: the grain it makes is again simple, with as
many faces and edges. :func:`perturb` makes K flips in each ok grain, one after another, each
drawn uniformly among the edges admissible then; :func:`all_flips` makes every grain one flip
can make. The kernels are in ``_kernels/flips.py``.

Each grain's draws come from a stream of its own, started from the seed and the grain's position
in the input (0 for the first grain of the first input): the grains come out the same whatever
the chunk size and the number of threads.
"""

from __future__ import annotations

import dataclasses
import os
import secrets
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from grainclass._kernels import codes
from grainclass.batch import GrainBatch, offsets_from_counts
from grainclass.errors import OptionError
from grainclass.parallel import run_ranges

if TYPE_CHECKING:
    from grainclass.options import ReadOptions

MAX_SEED = 2**64 - 1
MAX_FLIPS = 2**63 - 1  # a count the kernels hold in an int64


def new_seed() -> int:
    """A seed for a run given none (the command reports it, so that the run can be repeated)."""
    return secrets.randbits(63)


def seed_key(seed: int) -> np.uint64:
    """The key every grain's stream starts from: the seed (0 to 2^64 - 1), scrambled."""
    from grainclass._kernels.flips import mix

    if not 0 <= seed <= MAX_SEED:
        raise OptionError("seed", f"a seed is an integer from 0 to 2^64 - 1, not {seed}")
    with np.errstate(over="ignore"):  # uint64 arithmetic wraps on purpose (seen without the JIT)
        return np.uint64(mix(np.uint64(seed)))  # a numpy scalar: numba types it as uint64


@dataclass(frozen=True)
class Checked:
    """A batch's grains validated for flipping: each grain's status (a code of
    ``_kernels.codes``) and its lists, an ok grain's turning one way (``lists`` is the batch's
    own ``neighbors`` when every ok grain's did as read)."""

    status: np.ndarray
    lists: np.ndarray


def check(batch: GrainBatch) -> Checked:
    """Validate a batch's grains: the fast path, then the general validation for the grains it
    leaves, then rotation lists for ok grains whose lists do not turn one way (lists in no
    cyclic order, or turning both ways)."""
    from grainclass._kernels.flips import _check_batch, _check_pending_batch
    from grainclass._kernels.weinberg import _rotations

    g = len(batch)
    csr = (batch.face_offsets, batch.nbr_offsets, batch.neighbors)
    parsed = np.ones(g, np.bool_)
    parsed[list(batch.parse_errors)] = False
    status = np.zeros(g, np.int8)
    one_way = np.zeros(g, np.bool_)
    run_ranges(_check_batch, g, *csr, parsed, status, one_way)
    pending = np.flatnonzero(status == codes.PENDING)
    if len(pending):
        err = np.zeros((g, 3), np.int64)
        run_ranges(_check_pending_batch, len(pending), pending, *csr, status, one_way, err)
    lists = batch.neighbors
    unoriented = np.flatnonzero((status == codes.OK) & ~one_way)
    if len(unoriented):
        lists = batch.neighbors.copy()
        run_ranges(_rotations, len(unoriented), unoriented, *csr, lists)
    return Checked(status, lists)


def _sizes(batch: GrainBatch) -> tuple[int, int]:
    """The most faces and the most neighbour entries of a grain of the batch (1 at least)."""
    if not len(batch):
        return 1, 1
    n_faces = batch.n_faces
    entries = np.diff(batch.nbr_offsets[batch.face_offsets])
    return max(int(n_faces.max()), 1), max(int(entries.max()), 1)


@dataclass(frozen=True)
class Perturbed:
    """A batch after :func:`perturb`: its grains (ids, volumes and other fields as they were
    read), each grain's status as read (a code of ``_kernels.codes``), and the flips made in
    each (fewer than asked for where no edge was admissible any more; 0 where not ok)."""

    batch: GrainBatch
    status: np.ndarray
    flips: np.ndarray
    asked: int

    def __len__(self) -> int:
        return len(self.batch)

    @property
    def ok(self) -> int:
        return int(np.count_nonzero(self.status == codes.OK))

    @property
    def stuck(self) -> int:
        """Ok grains left with no admissible edge before ``asked`` flips."""
        return int(np.count_nonzero((self.status == codes.OK) & (self.flips < self.asked)))


def _wrapping(kernel: Callable[..., None]) -> Callable[..., None]:
    """``kernel``, called with numpy's overflow warnings off in the thread that runs it (the
    random streams wrap modulo 2^64 on purpose; numpy warns of it where the kernels run as
    plain Python, under NUMBA_DISABLE_JIT, and its error state is each thread's own)."""

    def call(*args: object) -> None:
        with np.errstate(over="ignore"):
            kernel(*args)

    return call


def perturb(batch: GrainBatch, flips: int, seed: int, first_position: int = 0) -> Perturbed:
    """Make ``flips`` random admissible edge flips in each ok grain of ``batch``.

    Parameters
    ----------
    batch : GrainBatch
        Grains as the readers give them.
    flips : int
        Flips per grain, one after another, each edge drawn uniformly among those admissible in
        the grain as it is then. A grain left with no admissible edge keeps the flips made.
    seed : int
        0 to 2^64 - 1: the same seed gives the same grains.
    first_position : int
        The position of the batch's first grain in the whole input: grain g's draws come from
        the seed and ``first_position + g``.

    Returns
    -------
    Perturbed
        The grains after the flips, in order, with their ids, volumes, areas, boundary flags
        and attributes. A grain that is not ok, or that no flip changed, keeps its lists as
        read; a flipped grain's lists turn one way (face 0's, as read).

    Examples
    --------
    >>> cube = [[1, 2, 3, 4], [0, 4, 5, 2], [0, 1, 5, 3], [0, 2, 5, 4], [0, 3, 5, 1], [1, 4, 3, 2]]
    >>> out = perturb(GrainBatch.from_lists([cube]), flips=1, seed=7).batch
    >>> sorted(np.diff(out.nbr_offsets).tolist())  # A and B lose a side, C and D gain one
    [3, 3, 4, 4, 5, 5]
    """
    from grainclass._kernels.flips import _flip_batch

    if not 0 <= flips <= MAX_FLIPS:
        raise OptionError("flips", f"flips per grain go from 0 to 2^63 - 1, not {flips}")
    checked = check(batch)
    g = len(batch)
    done = np.zeros(g, np.int64)
    if flips == 0 or not g:
        return Perturbed(batch, checked.status, done, flips)
    key = seed_key(seed)
    max_faces, max_entries = _sizes(batch)
    out_offsets = np.zeros_like(batch.nbr_offsets)
    out_lists = np.empty_like(batch.neighbors)
    run_ranges(
        _wrapping(_flip_batch),
        g,
        batch.face_offsets,
        batch.nbr_offsets,
        batch.neighbors,
        checked.lists,
        checked.status,
        flips,
        key,
        first_position,
        max_faces,
        max_entries,
        out_offsets,
        out_lists,
        done,
    )
    flipped = dataclasses.replace(batch, nbr_offsets=out_offsets, neighbors=out_lists)
    return Perturbed(flipped, checked.status, done, flips)


FROM_GRAIN, FLIPPED_EDGE, NEW_EDGE = "from_grain", "flipped_edge", "new_edge"


@dataclass(frozen=True)
class AllFlips:
    """The grains of :func:`all_flips`, and for the input batch each grain's status and number
    of admissible edges (the grains it gave)."""

    batch: GrainBatch
    status: np.ndarray
    counts: np.ndarray

    def __len__(self) -> int:
        return len(self.batch)

    @property
    def stuck(self) -> int:
        """Ok grains with no admissible edge, which gave no grain."""
        return int(np.count_nonzero((self.status == codes.OK) & (self.counts == 0)))


def all_flips(batch: GrainBatch) -> AllFlips:
    """Every grain that one admissible flip makes of each ok grain of ``batch``, in input order
    and, per grain, by the flipped edge A-B (A < B) in the order of A, then of B in A's list.

    Each output grain has the id ``ID:A-B`` and its source grain's volume, area, boundary flag
    and attributes, with three fields more: ``from_grain`` (the source grain's id),
    ``flipped_edge`` (``A-B``, the faces that no longer meet) and ``new_edge`` (``C-D``, the
    faces that meet now), faces numbered from 0 as in the source grain. Grains that are not ok
    and grains with no admissible edge give none.

    Examples
    --------
    >>> cube = [[1, 2, 3, 4], [0, 4, 5, 2], [0, 1, 5, 3], [0, 2, 5, 4], [0, 3, 5, 1], [1, 4, 3, 2]]
    >>> flips = all_flips(GrainBatch.from_lists([cube], grain_id=["cube"]))
    >>> len(flips), flips.batch.grain_id[0], flips.batch.attributes["new_edge"][0]
    (12, 'cube:0-1', '2-4')
    """
    from grainclass._kernels.flips import _all_flips_batch, _count_admissible

    checked = check(batch)
    g = len(batch)
    max_faces, max_entries = _sizes(batch)
    csr = (batch.face_offsets, batch.nbr_offsets, checked.lists, checked.status)
    counts = np.zeros(g, np.int64)
    run_ranges(_count_admissible, g, *csr, max_faces, max_entries, counts)
    out_first = offsets_from_counts(counts)
    sources = np.repeat(np.arange(g), counts)
    n_faces = batch.n_faces[sources]
    entries = np.diff(batch.nbr_offsets[batch.face_offsets])[sources]
    out_face_offsets = offsets_from_counts(n_faces)
    out_bases = offsets_from_counts(entries)
    out_offsets = np.zeros(int(out_face_offsets[-1]) + 1, np.int64)
    out_lists = np.empty(int(out_bases[-1]), np.int32)
    edges = np.zeros((len(sources), 4), np.int64)
    run_ranges(
        _all_flips_batch,
        g,
        *csr,
        max_faces,
        max_entries,
        out_first,
        out_face_offsets,
        out_bases[:-1],
        out_offsets,
        out_lists,
        edges,
    )
    return AllFlips(
        _flipped_batch(batch, sources, edges, out_offsets, out_lists), checked.status, counts
    )


def _flipped_batch(
    batch: GrainBatch,
    sources: np.ndarray,
    edges: np.ndarray,
    nbr_offsets: np.ndarray,
    neighbors: np.ndarray,
) -> GrainBatch:
    """The grains of :func:`all_flips` as a batch, each with its source grain's fields."""
    ids = _ids(batch)
    source_ids = [ids[s] for s in sources.tolist()]
    flipped = [f"{a}-{b}" for a, b in edges[:, :2].tolist()]
    new = [f"{min(c, d)}-{max(c, d)}" for c, d in edges[:, 2:].tolist()]
    attributes = {
        key: [values[s] for s in sources.tolist()] for key, values in batch.attributes.items()
    }
    attributes |= {FROM_GRAIN: source_ids, FLIPPED_EDGE: flipped, NEW_EDGE: new}

    def picked(values: np.ndarray | None) -> np.ndarray | None:
        return None if values is None else values[sources]

    return GrainBatch(
        source=batch.source
        if isinstance(batch.source, str)
        else [batch.source[s] for s in sources],
        grain_id=[f"{i}:{e}" for i, e in zip(source_ids, flipped, strict=True)],
        location=batch.location[sources],
        location_kind=batch.location_kind,
        face_offsets=offsets_from_counts(batch.n_faces[sources]),
        nbr_offsets=nbr_offsets,
        neighbors=neighbors,
        volume=picked(batch.volume),
        area=picked(batch.area),
        boundary=picked(batch.boundary),
        attributes=attributes,
    )


def _ids(batch: GrainBatch) -> list[str]:
    ids = batch.grain_id
    return [str(i) for i in (ids.to_pylist() if hasattr(ids, "to_pylist") else ids)]


def output_format(paths: Sequence[str], format: str | None) -> str:
    """What ``perturb`` writes for these inputs: planar_code when every input is planar_code
    (named so, or sniffed), else adjacency text, which every reader's grains can be written
    as. Standard input and FIFOs are peeked at, not consumed."""
    from grainclass.readers import SNIFF_BYTES, read_once, sniff

    if format is not None:
        return "planar_code" if format == "planar_code" else "adjacency"
    for path in paths:
        if path != "-" and (os.path.isdir(path) or path.lower().endswith(".fe")):
            return "adjacency"
        once = read_once(path)
        try:
            if once is not None:
                head = once.peek(SNIFF_BYTES)[:SNIFF_BYTES]
            else:
                with open(path, "rb") as handle:
                    head = handle.read(SNIFF_BYTES)
        except OSError:
            return "adjacency"  # the reader says what is wrong with it
        if sniff(head) != "planar_code":
            return "adjacency"
    return "planar_code"


@dataclass(frozen=True)
class Written:
    """A batch's result and its grains written out (``left_out`` of them could not be: see
    :func:`grainclass.writers.unwritable`); its length is the batch's grains, what a progress
    line counts."""

    result: Perturbed | AllFlips
    data: bytes
    left_out: int = 0

    def __len__(self) -> int:
        return len(self.result.status)


@dataclass
class Counts:
    """What a run of :func:`perturbed_batches` did, added up batch by batch: grains read, ok
    ones, those not ok by status, ok grains left with no admissible edge (before the last flip;
    for all flips, with none at all), grains written, and grains that could not be."""

    grains: int = 0
    ok: int = 0
    not_ok: dict[str, int] = field(default_factory=dict)
    stuck: int = 0
    written: int = 0
    left_out: int = 0

    def add(self, item: Written) -> None:
        from grainclass.vocabulary import STATUSES

        status = item.result.status
        self.grains += len(status)
        self.ok += int(np.count_nonzero(status == codes.OK))
        for code, count in zip(*np.unique(status, return_counts=True), strict=True):
            if code != codes.OK:
                name = STATUSES[code]
                self.not_ok[name] = self.not_ok.get(name, 0) + int(count)
        self.stuck += item.result.stuck
        self.written += len(item.result.batch) - item.left_out
        self.left_out += item.left_out


def _positioned(batches: Iterator[GrainBatch]) -> Iterator[tuple[int, GrainBatch]]:
    """Each batch with the position of its first grain in the whole input."""
    position = 0
    for batch in batches:
        yield position, batch
        position += len(batch)


def perturbed_batches(
    paths: Sequence[str],
    flips: int | None,
    seed: int,
    options: ReadOptions,
    write: str | None = None,
) -> Iterator[Written]:
    """:func:`perturb` (``flips`` per grain) or, when ``flips`` is None, :func:`all_flips` of
    every batch of the inputs, in input order, each with its grains written in the format
    ``write`` (``adjacency`` or ``planar_code``; None: no bytes). The inputs are read in a
    background thread, and batches are perturbed and written in threads at once (see
    :func:`grainclass.pipeline.classified_tables`)."""
    from grainclass.parallel import map_ordered
    from grainclass.pipeline import prefetch
    from grainclass.readers import read_dataset
    from grainclass.writers import unwritable, write_batch

    batches = _positioned(read_dataset(paths, options))

    def work(item: tuple[int, GrainBatch]) -> Written:
        position, batch = item
        result = all_flips(batch) if flips is None else perturb(batch, flips, seed, position)
        if write is None:
            return Written(result, b"")
        data = write_batch(result.batch, write)
        return Written(result, data, unwritable(result.batch, write))

    yield from map_ordered(work, prefetch(batches))


def perturbed_tallies(
    path: str, levels: Sequence[int], seed: int, options: ReadOptions
) -> Iterator[list]:
    """For every batch of ``path``, a :class:`grainclass.summary.Tally` of its grains after
    each number of flips of ``levels`` (0: as read), with the streams of
    ``grainclass perturb --flips K --seed SEED`` for each K: what ``summarize`` counts of that
    command's output."""
    from grainclass.parallel import map_ordered
    from grainclass.pipeline import prefetch
    from grainclass.readers import read_dataset
    from grainclass.summary import tally_batch

    batches = _positioned(read_dataset([path], options))

    def work(item: tuple[int, GrainBatch]) -> list:
        position, batch = item
        return [
            tally_batch(perturb(batch, k, seed, position).batch, options.include_boundary)
            for k in levels
        ]

    yield from map_ordered(work, prefetch(batches))
