"""Surface Evolver datafiles (``*.fe``): one grain per body.

Two layouts are read the same way. A grain's faces are the connected sets of its body's facets,
split along *separating* edges: edges carrying the triple-line attribute (a grain-growth code
writes ``color red`` on them; ``--triple-edges`` names another), edges where the body's two
facets are shared with different other bodies (a whole foam in one file), and edges on more
than two facets of the file (a triple line between cells, whichever they are). Walking each
face's boundary, with facets oriented outwards, gives its neighbours in cyclic order; a new
neighbour starts at every corner (a vertex on three or more separating edges of the body).

Periodic files (``torus``, ``torus_filled`` with ``periods``) carry three wrap marks per edge
(``*``, ``+``, ``-``). A body's surface is made of patches, one per entry of its list of
facets, each in its facet's frame unwrapped along the wrap marks; the patches' common edges
place them in one frame, so volumes and areas come from the cell itself (unless the body gives
its ``volume``). A cell that meets its own periodic image across a facet lists that facet once
each way: the two are two patches, at two places of the cell, and where such a cell uses an
edge more than twice, the facets around the edge say which patches meet there.

The datafiles are read over their bytes by compiled kernels (``_kernels/evolver/``), many
files at a time; the kernels return codes, which this module turns into messages.
"""

from __future__ import annotations

import functools
import os
from collections.abc import Iterable, Iterator
from dataclasses import dataclass

import numpy as np

from grainclass import compilation
from grainclass._kernels.evolver import codes
from grainclass._kernels.evolver.assemble import Surfaces, _assemble
from grainclass._kernels.evolver.entries import TripleMarker
from grainclass._kernels.evolver.tokenize import Tokens, _tokenize
from grainclass.batch import GrainBatch, Shape, no_body_has
from grainclass.errors import InputError
from grainclass.geometry import polytope_measures
from grainclass.options import DEFAULT_TRIPLE_EDGES
from grainclass.parallel import map_ordered
from grainclass.readers.sniffing import SNIFF_BYTES, not_grains
from grainclass.vocabulary import plural

# What one entry of each section is called in messages, by the kernels' entry kinds.
ENTRY_NAMES = ("vertex", "edge", "facet", "body")
PART_FILES = 64  # files parsed by one call of the kernels
PART_BYTES = 4 << 20  # and at most about this many bytes

_NO_BODIES = (
    "no bodies: the file is empty, ends before its bodies section, or is not a Surface Evolver "
    "datafile"
)
_FILM = (
    "a film without bodies: facets, but no bodies section (grainclass reads the bodies of a "
    "foam, each a closed surface of facets), or a file cut off before its bodies"
)
_THREE_D = "grainclass reads 3D bodies, each a closed surface of facets"


@dataclass
class _Part:
    """The grains of consecutive files, as arrays (what a worker process sends back)."""

    paths: list[str]
    file_of: np.ndarray  # index into paths, per grain
    grain_id: list[str]
    line: np.ndarray
    n_faces: np.ndarray
    nbr_counts: np.ndarray
    neighbors: np.ndarray
    volume: np.ndarray
    area: np.ndarray
    boundary: np.ndarray
    errors: dict[int, str]
    shapes: list[Shape | None] | None = None

    def __len__(self) -> int:
        return len(self.grain_id)


def read_evolver(
    paths: Iterable[str],
    chunk_size: int,
    triple_edges: tuple[str, str] = DEFAULT_TRIPLE_EDGES,
    geometry: bool = False,
) -> Iterator[GrainBatch]:
    """Read Surface Evolver datafiles as one dataset; every body is a grain.

    Parameters
    ----------
    paths : iterable of str
        The ``.fe`` files (a folder's files, in order); each is the ``source`` of its grains.
    chunk_size : int
        Grains per batch (a batch ends with a whole file).
    triple_edges : (str, str)
        The edge attribute and value that mark triple-line segments.
    geometry : bool
        Keep each grain's shape: its facets in space, unwrapped across a periodic box.

    Yields
    ------
    GrainBatch
        One grain per body: the file's stem when the file has one body, else the body id.
    """
    read = functools.partial(_read_part, triple_edges=triple_edges, geometry=geometry)
    compilation.ahead(compilation.EVOLVER)
    pending: list[_Part] = []
    grains = 0
    # The kernels release the GIL: the groups of files are read on as many threads as there
    # are jobs, and come back in order.
    for part in map_ordered(read, _parts(list(paths), max(1, min(PART_FILES, chunk_size)))):
        pending.append(part)
        grains += len(part)
        if grains >= chunk_size:
            yield _batch(pending)
            pending, grains = [], 0
    if pending:
        yield _batch(pending)


def _parts(paths: list[str], most: int) -> Iterator[list[str]]:
    """Consecutive files, up to ``most`` of them and about PART_BYTES, for one kernel call
    (made as the reading goes: a step of a simulation has hundreds of thousands of files)."""
    part: list[str] = []
    size = 0
    for path in paths:
        try:
            length = os.stat(path).st_size
        except OSError:
            length = 0  # its reading says what is wrong
        if part and (len(part) >= most or size + length > PART_BYTES):
            yield part
            part, size = [], 0
        part.append(path)
        size += length
    if part:
        yield part


def _read_files(paths: list[str]) -> tuple[np.ndarray, np.ndarray]:
    """The bytes of the files one after another, read straight into one array, and where each
    starts (and the last ends)."""
    descriptors: list[int] = []
    try:
        for path in paths:
            try:
                descriptors.append(os.open(path, os.O_RDONLY))
            except OSError as exc:
                raise InputError(path, exc.strerror or str(exc)) from None
        sizes = [os.fstat(fd).st_size for fd in descriptors]
        starts = np.zeros(len(paths) + 1, np.int64)
        np.cumsum(sizes, out=starts[1:])
        buf = np.empty(int(starts[-1]), np.uint8)
        view = memoryview(buf)
        ends = starts[1:].copy()
        for k, (path, fd) in enumerate(zip(paths, descriptors, strict=True)):
            at, end = int(starts[k]), int(starts[k + 1])
            while at < end:
                try:
                    got = os.readv(fd, [view[at:end]])
                except OSError as exc:  # a folder given as a file, say
                    raise InputError(path, exc.strerror or str(exc)) from None
                if got == 0:  # shorter than when it was measured
                    break
                at += got
            ends[k] = at
    finally:
        for fd in descriptors:
            os.close(fd)
    if np.any(ends != starts[1:]):  # a file shrank as it was read: keep what it held
        keep = np.concatenate([np.arange(a, e) for a, e in zip(starts[:-1], ends, strict=True)])
        buf = buf[keep.astype(np.int64)]
        starts[1:] = np.cumsum(ends - starts[:-1])
    return buf, starts


def _read_part(paths: list[str], triple_edges: tuple[str, str], geometry: bool = False) -> _Part:
    """The grains of consecutive files (a malformed file is one bad grain, not a failed run)."""
    buf, starts = _read_files(paths)
    refused: dict[int, str] = {}
    for k in range(len(paths)):
        head = buf[starts[k] : min(starts[k + 1], starts[k] + SNIFF_BYTES)].tobytes()
        why = not_grains(head, file_only=True)
        if why:  # UTF-16, compressed, Parquet: said so, not read as a file of no bodies
            refused[k] = why
    marker_words = [w.lower().encode() for w in " ".join(triple_edges).split()]
    marker = TripleMarker(
        np.frombuffer(b"".join(marker_words), np.uint8),
        np.cumsum([len(w) for w in marker_words]).astype(np.int64),
    )
    tokens = _tokenize(buf, starts, marker)
    if len(tokens.slow.entry):
        _slow_numbers(buf, tokens)
    for k in refused:
        tokens.files.status[k] = -1
    compilation.before(compilation.EVOLVER)
    with np.errstate(over="ignore"):  # the ids' hash wraps modulo 2**64 (seen without the JIT)
        grains, surfaces = _assemble(tokens.entries, tokens.files)
    g_file, g_body, g_code, g_params = grains.file, grains.body, grains.code, grains.params
    g_faces = grains.n_faces
    nbr_counts, neighbors = surfaces.nbr_counts, surfaces.neighbours
    n = len(g_file)
    loop_offsets = np.zeros(len(surfaces.loop_sizes) + 1, np.int64)
    np.cumsum(surfaces.loop_sizes, out=loop_offsets[1:])
    volume, area = polytope_measures(
        surfaces.position, surfaces.corners, loop_offsets, surfaces.loop_grain, n
    )
    volume = np.abs(volume)
    ok = g_code == codes.GRAIN_OK
    volume[~ok] = np.nan
    area[~ok] = np.nan
    given = ok & grains.given
    volume[given] = grains.volume[given]
    rows_of_file = np.bincount(g_file, minlength=len(paths))
    stems = [path.rsplit("/", 1)[-1].removesuffix(".fe") for path in paths]
    grain_id = [
        stems[f] if rows_of_file[f] == 1 else str(b)
        for f, b in zip(g_file.tolist(), g_body.tolist(), strict=True)
    ]
    line = grains.line.copy()
    errors: dict[int, str] = {}
    for g in np.flatnonzero(~ok | given).tolist():
        f, body, code = int(g_file[g]), int(g_body[g]), int(g_code[g])
        if code == codes.GRAIN_FILE:
            message, line[g] = _file_message(f, buf, tokens, refused)
        elif code == codes.GRAIN_NO_BODIES:
            message, line[g] = _no_bodies(g_params[g])
        elif code == codes.GRAIN_OK:
            message = _volume_problem(body, float(volume[g]), float(area[g]))
        else:
            message = _message(code, body, g_params[g].tolist())
        if message is not None:
            errors[g] = message
    if errors:
        bad = np.fromiter(errors, np.int64, len(errors))
        volume[bad] = np.nan
        area[bad] = np.nan
        face_ranges = np.zeros(n + 1, np.int64)
        np.cumsum(g_faces, out=face_ranges[1:])
        keep_face = np.ones(len(nbr_counts), bool)
        for g in bad.tolist():
            keep_face[face_ranges[g] : face_ranges[g + 1]] = False
        keep_nbr = np.repeat(keep_face, nbr_counts)
        g_faces = g_faces.copy()
        g_faces[bad] = 0
        nbr_counts, neighbors = nbr_counts[keep_face], neighbors[keep_nbr]
    return _Part(
        paths=paths,
        file_of=g_file,
        grain_id=grain_id,
        line=line,
        n_faces=g_faces,
        nbr_counts=nbr_counts,
        neighbors=neighbors,
        volume=volume,
        area=area,
        boundary=grains.boundary,
        errors=errors,
        shapes=_shapes(surfaces, loop_offsets, ok, set(errors)) if geometry else None,
    )


def _shapes(
    surfaces: Surfaces, loop_offsets: np.ndarray, ok: np.ndarray, bad: set[int]
) -> list[Shape | None]:
    """Each grain's facets in space, as its body lists them (None for a grain that is not
    read); which face of the grain a facet is part of is not kept."""
    first = np.searchsorted(surfaces.loop_grain, np.arange(len(ok) + 1))
    shapes: list[Shape | None] = []
    for g in range(len(ok)):
        if not ok[g] or g in bad:
            shapes.append(None)
            continue
        patches = range(first[g], first[g + 1])
        loops = [surfaces.corners[loop_offsets[p] : loop_offsets[p + 1]] for p in patches]
        used, rows = np.unique(np.concatenate(loops), return_inverse=True)
        ends = np.cumsum([len(loop) for loop in loops])[:-1]
        polygons = tuple(np.split(rows.astype(np.int64), ends))
        shapes.append(Shape(surfaces.position[used], polygons))
    return shapes


def _slow_numbers(buf: np.ndarray, tokens: Tokens) -> None:
    """Numbers the tokenizer leaves to Python's float() (many digits, underscores, digits
    outside ASCII): read in place; an entry with one that float() refuses cannot be read."""
    status, xyz = tokens.entries.status, tokens.entries.xyz
    slow = tokens.slow
    periods = tokens.files.periods
    for entry, slot, s, e in zip(
        slow.entry.tolist(), slow.slot.tolist(), slow.start.tolist(), slow.end.tolist(), strict=True
    ):
        text = bytes(buf[s:e]).decode("utf-8", "replace")
        try:
            value = float(text)
        except ValueError:
            if slot < codes.SLOW_PERIOD:
                status[entry] = codes.ENTRY_BAD
            continue
        if slot >= codes.SLOW_PERIOD:
            k = slot - codes.SLOW_PERIOD
            periods[entry, k // 3, k % 3] = value
        else:
            xyz[entry, 0 if slot == codes.SLOW_VOLUME else slot] = value
            if status[entry] == codes.ENTRY_SLOW:
                status[entry] = codes.ENTRY_OK
    status[status == codes.ENTRY_SLOW] = codes.ENTRY_OK


def _file_message(f: int, buf: np.ndarray, tokens: Tokens, refused: dict[int, str]):
    """(message, line) for a file the tokenizer did not read."""
    if f in refused:
        return refused[f], 1
    files = tokens.files
    code, line = int(files.status[f]), int(files.line[f])
    aux = files.aux[f].tolist()
    if code == codes.FILE_LONG_ID:
        token = bytes(buf[aux[1] : aux[1] + 20]).decode("utf-8", "replace")
        return f"{ENTRY_NAMES[aux[0]]} id {token}... is too long", line
    if code == codes.FILE_PERIODS:
        return "periods needs three rows of three numbers", line
    if code == codes.FILE_2D:
        model = "string model, " if aux[0] else ""
        return f"a 2D file: {_THREE_D} (this is a {model}space_dimension 2)", line
    if code == codes.FILE_STRING:
        return (
            f"a string model: {_THREE_D} (a string model's bodies are areas bounded by edges)",
            line,
        )
    if code == codes.FILE_SPACE:
        return f"a file in {aux[0]}-space: {_THREE_D} (this is space_dimension {aux[0]})", line
    if code == codes.FILE_SIMPLEX:
        return (
            "facets given by their vertices (simplex_representation): grainclass reads facets "
            "given by their edges",
            line,
        )
    return (
        "a quotient space (symmetry_group): grainclass reads periodic foams as torus or "
        "torus_filled files with periods",
        line,
    )


def _no_bodies(params: np.ndarray) -> tuple[str, int]:
    """(message, line) for a file without bodies: a film, a file with a line that could not be
    read (the first says more), or one of neither."""
    facets_line, kind, line = params[:3].tolist()
    if facets_line:
        return _FILM, facets_line
    if kind >= 0:
        return f"cannot read this {ENTRY_NAMES[kind]} line", line
    return _NO_BODIES, 1


def _message(code: int, body: int, params: list[int]) -> str:
    """Why body ``body`` is not a grain, from its GRAIN_ code and params."""
    a, b, c, d, e = params
    if code == codes.GRAIN_BODY_LINE:
        return "cannot read this body line"
    if code == codes.GRAIN_UNDEFINED:
        what = f"{ENTRY_NAMES[a]} {b}"
        if e:
            return f"body {body}: cannot read the line of its {what} (line {e})"
        user = ("its list of facets", f"facet {d}", f"edge {d}")[c]
        return f"body {body}: {user} names {what}, which the file does not define"
    if code == codes.GRAIN_TWICE:
        return (
            f"body {body} lists facet {a} twice: a body lies on both sides of a facet only "
            "where it touches its own periodic image, and this file is not periodic (is its "
            "line cut, or the facet a wall inside the body?)"
        )
    if code == codes.GRAIN_TWICE_SAME:
        times = "twice the same way" if b == 2 else f"{b} times"
        return (
            f"body {body} lists facet {a} {times}: a body lists a facet once, or once each way "
            "where it touches its own periodic image across it (is its line cut, or a sign "
            "wrong?)"
        )
    if code == codes.GRAIN_FACET_OPEN:
        return (
            f"body {body}: facet {a} is not a closed loop of edges: its edge {b} does not start "
            "where the edge before it ends"
        )
    if code == codes.GRAIN_FACET_WRAPS:
        return (
            f"body {body}: facet {a} goes around the periodic box: the wrap marks of its edges "
            "do not add up to none"
        )
    if code == codes.GRAIN_NOT_CLOSED:
        return f"not a closed surface: edge {a} lies on {plural(b, 'facet')} of body {body}"
    if code == codes.GRAIN_ORIENTATION:
        return (
            f"not an oriented surface: facets {a} and {b} of body {body} both run along edge "
            f"{c} the same way (a sign in its list of facets is wrong)"
        )
    if code == codes.GRAIN_UNPAIRED:
        return (
            f"not a closed surface: body {body} uses edge {a} {b} times (where it touches its "
            "own periodic image), and its facets around the edge do not pair off, once each way"
        )
    if code == codes.GRAIN_POINT_EDGE:
        return (
            f"not a closed surface: body {body} uses edge {a} {b} times (where it touches its "
            "own periodic image), and the edge has no length: its facets cannot be paired by "
            "the way they turn about it"
        )
    if code == codes.GRAIN_AROUND:
        return (
            f"not a sphere: unwrapped across the periodic box, the surface of body {body} does "
            f"not close up at edge {a} (a cell that goes around the box)"
        )
    if code == codes.GRAIN_EULER:
        return (
            f"not a sphere: the surface of body {body} has vertices - edges + facets = {a}, "
            "not 2 (a vertex where it touches itself, or a handle)"
        )
    if code == codes.GRAIN_PIECES:
        return "not a sphere: the surface is in more than one piece"
    if code == codes.GRAIN_NO_TRIPLE:
        return f"body {body} has no triple lines: mark them (--triple-edges)"
    return f"face {a} is not a disc: its boundary has more than one loop"


def _volume_problem(body: int, volume: float, area: float) -> str | None:
    """A body's given ``volume``, refused as adjacency text refuses one (``adjacency.py``):
    not a finite number 0 or more, or more than a ball of the surface's area holds."""
    if not (np.isfinite(volume) and volume >= 0):
        return f"body {body}: volume {volume:g}: expected a finite number, 0 or more"
    if no_body_has(volume, area):
        return (
            f"body {body}: volume {volume:g} is more than a surface of area {area:g} can hold "
            "(36 pi V^2 > S^3)"
        )
    return None


def _batch(parts: list[_Part]) -> GrainBatch:
    """One batch; each grain's ``source`` is its own file, so messages name the right one."""
    sources: list[str] = []
    errors: dict[int, str] = {}
    offset = 0
    for part in parts:
        sources += [part.paths[f] for f in part.file_of.tolist()]
        errors.update({offset + g: message for g, message in part.errors.items()})
        offset += len(part)
    n_faces = np.concatenate([p.n_faces for p in parts])
    nbr_counts = np.concatenate([p.nbr_counts for p in parts])
    face_offsets = np.zeros(len(n_faces) + 1, np.int64)
    np.cumsum(n_faces, out=face_offsets[1:])
    nbr_offsets = np.zeros(len(nbr_counts) + 1, np.int64)
    np.cumsum(nbr_counts, out=nbr_offsets[1:])
    return GrainBatch(
        source=sources,
        grain_id=[grain_id for p in parts for grain_id in p.grain_id],
        location=np.concatenate([p.line for p in parts]),
        location_kind="line",
        face_offsets=face_offsets,
        nbr_offsets=nbr_offsets,
        neighbors=np.concatenate([p.neighbors for p in parts]),
        parse_errors=errors,
        volume=np.concatenate([p.volume for p in parts]),
        area=np.concatenate([p.area for p in parts]),
        boundary=np.concatenate([p.boundary for p in parts]),
        shapes=None
        if parts[0].shapes is None
        else [shape for p in parts for shape in p.shapes or []],
    )
