"""Surface Evolver datafiles (``*.fe``): one grain per body.

Two layouts are read the same way. A grain's faces are the connected sets of its body's facets,
split along *separating* edges: edges carrying the triple-line attribute (a grain-growth code
writes ``color red`` on them; ``--triple-edges`` names another) and edges where the body's two
facets are shared with different other bodies (a whole foam in one file). Walking each face's
boundary, with facets oriented outwards, gives its neighbours in cyclic order; a new neighbour
starts at every corner (a vertex on three or more separating edges of the body).

Periodic files (``torus``, ``torus_filled`` with ``periods``) carry three wrap marks per edge
(``*``, ``+``, ``-``); volumes and areas are computed in a frame unwrapped across the body,
unless the body gives its ``volume``.
"""

from __future__ import annotations

import contextlib
import functools
import math
import re
from collections import defaultdict
from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field

import numpy as np

from grainclass.batch import GrainBatch, csr_from_lists, no_body_has, tri_state
from grainclass.errors import InputError
from grainclass.geometry import loop_arrays, polytope_measures, unit_normals
from grainclass.parallel import available_cpus, worker_pool
from grainclass.readers.sniffing import SNIFF_BYTES, not_grains

# A datafile's sections, and what one numbered line of each is called in messages.
SECTIONS = {
    "vertices": "vertex",
    "edges": "edge",
    "faces": "facet",
    "facets": "facet",
    "bodies": "body",
}
WRAPS = {"*": 0, "+": 1, "-": -1}
DEFAULT_TRIPLE_EDGES = ("color", "red")
PARALLEL_FILES = 200  # from this many files on, a process pool reads them
_NUMBER = re.compile(r"^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$")


@dataclass
class _Datafile:
    """The parts of a datafile that matter for grains."""

    periods: list[list[float]] | None = None
    coords: dict[int, tuple[float, float, float]] = field(default_factory=dict)
    # edge id -> (tail, head, head's periodic shift or None, is triple)
    edges: dict[int, tuple[int, int, tuple[float, float, float] | None, bool]] = field(
        default_factory=dict
    )
    facets: dict[int, list[int]] = field(default_factory=dict)
    # body id -> (line, signed facet ids, volume or None)
    bodies: dict[int, tuple[int, list[int], float | None]] = field(default_factory=dict)
    # (section, id) -> line, for lines that cannot be read: only the bodies that need them fail
    unreadable: dict[tuple[str, int], int] = field(default_factory=dict)


def _logical_lines(text: str) -> Iterator[tuple[int, list[str]]]:
    """(line number, tokens) with comments and ``#`` directives removed, ``\\`` lines joined."""
    if "/*" in text:
        text = re.sub(r"/\*.*?\*/", lambda m: "\n" * m.group().count("\n"), text, flags=re.S)
    if "//" not in text and "#" not in text and "\\" not in text:  # the common, quick case
        for number, line in enumerate(text.splitlines(), 1):
            tokens = line.split()
            if tokens:
                yield number, tokens
        return
    pending: list[str] = []
    start = 0
    for number, line in enumerate(text.splitlines(), 1):
        if "//" in line:
            line = line.split("//", 1)[0]
        if line.startswith("#"):
            line = ""
        line = line.rstrip()
        if not pending:
            start = number
        if line.endswith("\\"):
            pending.append(line[:-1])
            continue
        tokens = " ".join([*pending, line]).split()
        pending = []
        if tokens:
            yield start, tokens


def _parse(text: str, source: str, triple_edges: tuple[str, str]) -> _Datafile:
    data = _Datafile()
    section = None
    lines = list(_logical_lines(text))
    marker = " {} {} ".format(*(s.lower() for s in triple_edges))  # e.g. " color red "
    i = 0
    while i < len(lines):
        number, tokens = lines[i]
        i += 1
        if section is not None and tokens[0].isdecimal():  # what int() reads, unlike "²"
            if len(tokens[0]) > 18:  # past int64, and past what int() reads at 4,300 digits
                raise InputError(
                    source, f"{SECTIONS[section]} id {tokens[0][:20]}... is too long", number
                )
            _parse_entry(data, section, number, tokens, marker)
            continue
        word = tokens[0].lower()
        if word == "periods":
            rows = [t for _, row in lines[i : i + 3] for t in row]
            if len(rows) < 9 or not all(_NUMBER.match(t) for t in rows[:9]):
                raise InputError(source, "periods needs three rows of three numbers", number)
            data.periods = [[float(t) for t in rows[k : k + 3]] for k in (0, 3, 6)]
            i += 3
            continue
        if word in SECTIONS:
            section = "facets" if word == "faces" else word
            continue
        if word == "read":
            break
    return data


def _parse_entry(
    data: _Datafile, section: str, number: int, tokens: list[str], marker: str
) -> None:
    """One numbered line of a section; one that cannot be read is noted in ``unreadable`` (a
    body's with no facets), for the bodies that need it to report."""
    ident = int(tokens[0])  # the caller saw digits
    try:
        if section == "vertices":
            data.coords[ident] = (float(tokens[1]), float(tokens[2]), float(tokens[3]))
        elif section == "edges":
            tail, head = int(tokens[1]), int(tokens[2])
            shift = None
            if data.periods is not None and len(tokens) >= 6 and tokens[3] in WRAPS:
                shift = _shift(data.periods, tokens[3:6])
            triple = len(tokens) > 4 and marker in f" {' '.join(tokens[3:]).lower()} "
            data.edges[ident] = (tail, head, shift, triple)
        elif section == "facets":
            edges = _leading_integers(tokens[1:])
            if len(edges) < 3:
                raise ValueError("a facet needs three edges or more")
            data.facets[ident] = edges
        else:
            volume = None
            lowered = [t.lower() for t in tokens]
            if "volume" in lowered:
                volume = float(tokens[lowered.index("volume") + 1])
            facets = _leading_integers(tokens[1:])
            if not facets:
                raise ValueError("a body needs facets")
            data.bodies[ident] = (number, facets, volume)
    except (ValueError, IndexError, KeyError):
        data.unreadable[(section, ident)] = number
        if section == "bodies":
            data.bodies[ident] = (number, [], None)


def _leading_integers(tokens: list[str]) -> list[int]:
    """The ids at the start of an entry; what follows them must be an attribute's name (a
    ``13.0`` or a ``+`` there is a damaged id, and the line cannot be read)."""
    try:
        return [int(t) for t in tokens]
    except ValueError:  # attributes follow the ids
        out = []
        for t in tokens:
            if not t.lstrip("+-").isdecimal():
                if not (t[0].isalpha() or t[0] == "_"):
                    raise ValueError(f"{t!r} is neither an id nor an attribute") from None
                break
            out.append(int(t))
        return out


def _shift(periods: list[list[float]], marks: list[str]) -> tuple[float, float, float] | None:
    """Offset of an edge's head from its stored position: wrap marks times period vectors."""
    wraps = [WRAPS[m] for m in marks]
    if not any(wraps):
        return None
    return (
        sum(w * p[0] for w, p in zip(wraps, periods, strict=True)),
        sum(w * p[1] for w, p in zip(wraps, periods, strict=True)),
        sum(w * p[2] for w, p in zip(wraps, periods, strict=True)),
    )


class GrainError(ValueError):
    """A body that is not a closed surface cut into faces: its grain becomes an invalid row."""


class _Undefined(LookupError):
    """A body needs an entry (``section``, ``ident``) that ``user`` refers to and the file
    lacks (or could not read): see :func:`_missing`."""

    def __init__(self, section: str, ident: int, user: str) -> None:
        super().__init__(section, ident, user)
        self.section, self.ident, self.user = section, ident, user


def _oriented_facet(data: _Datafile, signed: int) -> list[tuple[int, int, int]]:
    """Directed edges (tail, head, edge id) of a facet, reversed for a negative sign."""
    darts = []
    try:
        edge_ids = data.facets[abs(signed)]
    except KeyError:
        raise _Undefined("facets", abs(signed), "its list of facets") from None
    for e in edge_ids:
        try:
            tail, head, _, _ = data.edges[abs(e)]
        except KeyError:
            raise _Undefined("edges", abs(e), f"facet {abs(signed)}") from None
        darts.append((tail, head, abs(e)) if e > 0 else (head, tail, abs(e)))
    if signed < 0:
        darts = [(h, t, e) for t, h, e in reversed(darts)]
    return darts


def _grain(data: _Datafile, body: int, facet_bodies: dict[int, list[int]], marked: bool) -> tuple:
    """(neighbour lists, volume, area, boundary) of a body; ``marked``: triple edges marked."""
    _, signed_facets, given_volume = data.bodies[body]
    if len({abs(f) for f in signed_facets}) < len(signed_facets):
        twice = next(
            abs(f) for f in signed_facets if signed_facets.count(f) + signed_facets.count(-f) > 1
        )
        raise GrainError(
            f"body {body} lists facet {twice} twice: it touches its own periodic image (enlarge "
            "the periodic box so that every facet lies between two bodies), or its line is cut"
        )
    facets = [_oriented_facet(data, f) for f in signed_facets]
    on_edge: dict[int, list[int]] = defaultdict(list)
    for k, darts in enumerate(facets):
        for _, _, e in darts:
            on_edge[e].append(k)
    for e, ks in on_edge.items():
        if len(ks) != 2:
            raise GrainError(
                f"not a closed surface: edge {e} lies on {len(ks)} facet(s) of body {body}"
            )
    # Every edge on two facets: the surface closes. A sphere's has V - E + F = 2; one vertex
    # where the surface touches itself would leave a face adjacency that passes for a grain's.
    vertices = {tail for darts in facets for tail, _, _ in darts}
    euler = len(vertices) - len(on_edge) + len(facets)
    if euler != 2:
        raise GrainError(
            f"not a sphere: the surface of body {body} has vertices - edges + facets = {euler}, "
            "not 2 (a vertex where it touches itself, or a handle)"
        )
    other = [tuple(b for b in facet_bodies[abs(f)] if b != body) for f in signed_facets]
    parent = list(range(len(facets)))

    def find(k: int) -> int:
        while parent[k] != k:
            parent[k] = parent[parent[k]]
            k = parent[k]
        return k

    row = _vertex_rows(facets)
    corners, loop_offsets = loop_arrays([[row[t] for t, _, _ in darts] for darts in facets])
    position = _positions(data, facets, row)
    normal = None if marked else unit_normals(position, corners, loop_offsets)
    for e, (a, b) in on_edge.items():
        if data.edges[e][3] or other[a] != other[b]:
            continue
        # Without marked triple edges, facets on the outside of a foam (shared with no other
        # body) make one face only where they are coplanar: the sample boundary cuts grains.
        if normal is not None and not other[a] and float(normal[a] @ normal[b]) < 1 - 1e-9:
            continue
        parent[find(a)] = find(b)
    roots = sorted({find(k) for k in range(len(facets))})
    face_of_root = {r: f for f, r in enumerate(roots)}
    face = [face_of_root[find(k)] for k in range(len(facets))]
    separating = {e for e, (a, b) in on_edge.items() if face[a] != face[b]}
    if not separating:
        raise GrainError(f"body {body} has no triple lines: mark them (--triple-edges)")
    degree: dict[int, int] = defaultdict(int)
    for e in separating:
        tail, head, _, _ = data.edges[e]
        degree[tail] += 1
        degree[head] += 1
    # Boundary darts of each face, and the face across each separating edge.
    leaving: list[dict[int, list[tuple[int, int]]]] = [defaultdict(list) for _ in roots]
    across: dict[tuple[int, int], int] = {}
    for k, darts in enumerate(facets):
        for tail, head, e in darts:
            if e in separating:
                leaving[face[k]][tail].append((head, e))
                a, b = on_edge[e]
                across[(face[k], e)] = face[b] if a == k else face[a]
    neighbours = [_walk_boundary(f, leaving[f], across, degree) for f in range(len(roots))]
    volumes, areas = polytope_measures(
        position, corners, loop_offsets, np.zeros(len(facets), np.int64), 1
    )
    volume, area = float(volumes[0]), float(areas[0])
    # Cut by the sample boundary: facets shared with no other body, in a non-periodic foam. A
    # lone body (one grain per file) cannot tell.
    boundary = None
    if data.periods is not None:
        boundary = False
    elif len(data.bodies) > 1:
        boundary = any(not o for o in other)
    if given_volume is not None:
        volume = _checked_volume(body, given_volume, area)
    return neighbours, abs(volume), area, boundary


def _checked_volume(body: int, volume: float, area: float) -> float:
    """A body's given ``volume``, refused as adjacency text refuses one (``adjacency.py``):
    not a finite number 0 or more, or more than a ball of the surface's area holds."""
    if not (math.isfinite(volume) and volume >= 0):
        raise GrainError(f"body {body}: volume {volume:g}: expected a finite number, 0 or more")
    if no_body_has(volume, area):
        raise GrainError(
            f"body {body}: volume {volume:g} is more than a surface of area {area:g} can hold "
            "(36 pi V^2 > S^3)"
        )
    return volume


def _walk_boundary(f, leaving, across, degree) -> list[int]:
    darts = [(tail, head, e) for tail, outs in leaving.items() for head, e in outs]
    start = next((d for d in darts if degree[d[0]] >= 3), darts[0])
    loop, used = [], set()
    tail, head, e = start
    while (tail, e) not in used:
        used.add((tail, e))
        loop.append((tail, e))
        nxt = [(h, x) for h, x in leaving[head] if (head, x) not in used]
        if not nxt:
            break
        tail, (head, e) = head, nxt[0]
    if len(used) != len(darts):
        raise GrainError(f"face {f} is not a disc: its boundary has more than one loop")
    neighbours: list[int] = []
    for i, (tail, e) in enumerate(loop):
        g = across[(f, e)]
        if i == 0 or degree[tail] >= 3 or g != neighbours[-1]:
            neighbours.append(g)
    if len(neighbours) > 1 and neighbours[0] == neighbours[-1] and degree[loop[0][0]] < 3:
        neighbours.pop()  # the walk started inside a triple line: its two ends are one
    return neighbours


def _vertex_rows(facets: list[list[tuple[int, int, int]]]) -> dict[int, int]:
    """Row of each vertex of a body in the unwrapped position array (see :func:`_positions`)."""
    return {tail: k for k, tail in enumerate(dict.fromkeys(t for ds in facets for t, _, _ in ds))}


def _positions(
    data: _Datafile, facets: list[list[tuple[int, int, int]]], row: dict[int, int]
) -> np.ndarray:
    """Vertex positions of a body in one frame, unwrapped across periodic boundaries.

    Breadth-first over the body's edges, each step adding the edge's vector (head plus its
    periodic shift, minus tail). Plain floats: a numpy call per vertex would cost more.
    """
    try:
        if not any(data.edges[e][2] for darts in facets for _, _, e in darts):
            return np.array([data.coords[v] for v in row])  # nothing wraps: stored positions
    except KeyError as exc:
        raise _undefined_vertex(facets, exc.args[0]) from None
    step: dict[int, list[tuple[int, float, float, float]]] = defaultdict(list)
    for darts in facets:
        for _, _, e in darts:
            t, h, shift, _ = data.edges[e]
            try:
                (tx, ty, tz), (hx, hy, hz) = data.coords[t], data.coords[h]
            except KeyError as exc:
                raise _undefined_vertex(facets, exc.args[0]) from None
            if shift is not None:
                hx, hy, hz = hx + shift[0], hy + shift[1], hz + shift[2]
            dx, dy, dz = hx - tx, hy - ty, hz - tz
            step[t].append((h, dx, dy, dz))
            step[h].append((t, -dx, -dy, -dz))
    first = facets[0][0][0]
    placed = {first: data.coords[first]}
    queue = [first]
    while queue:
        v = queue.pop()
        x, y, z = placed[v]
        for w, dx, dy, dz in step[v]:
            if w not in placed:
                placed[w] = (x + dx, y + dy, z + dz)
                queue.append(w)
    if len(placed) != len(row):  # V - E + F = 2 of two pieces (a sphere and a torus, say)
        raise GrainError("not a sphere: the surface is in more than one piece")
    position = np.empty((len(row), 3))
    for v, k in row.items():
        position[k] = placed[v]
    return position


def _undefined_vertex(facets: list[list[tuple[int, int, int]]], vertex: int) -> _Undefined:
    """The error for a vertex without coordinates, named with an edge that ends at it."""
    edge = next(e for darts in facets for t, h, e in darts if vertex in (t, h))
    return _Undefined("vertices", vertex, f"edge {edge}")


def read_evolver(
    paths: Iterable[str],
    chunk_size: int,
    triple_edges: tuple[str, str] = DEFAULT_TRIPLE_EDGES,
) -> Iterator[GrainBatch]:
    """Read Surface Evolver datafiles as one dataset; every body is a grain.

    Parameters
    ----------
    paths : iterable of str
        The ``.fe`` files (a folder's files, in order); each is the ``source`` of its grains.
    chunk_size : int
        Grains per batch.
    triple_edges : (str, str)
        The edge attribute and value that mark triple-line segments.

    Yields
    ------
    GrainBatch
        One grain per body: the file's stem when the file has one body, else the body id.
    """
    paths = list(paths)
    read = functools.partial(_read_file, triple_edges=triple_edges)
    grains: list[_Grain] = []
    with contextlib.ExitStack() as stack:
        per_file: Iterable[list[_Grain]] = map(read, paths)
        cpus = available_cpus()
        if len(paths) >= PARALLEL_FILES and cpus > 1:
            # Parsing is pure Python: a folder of dumps is read by one process per core.
            pool = worker_pool(cpus)
            stack.callback(pool.shutdown, wait=True, cancel_futures=True)
            per_file = pool.map(read, paths, chunksize=16)
        for file_grains in per_file:
            grains += file_grains
            if len(grains) >= chunk_size:
                yield _batch(grains)
                grains = []
    if grains:
        yield _batch(grains)


_NO_BODIES = (
    "no bodies: the file is empty, ends before its bodies section, or is not a Surface Evolver "
    "datafile"
)


def _read_file(path: str, triple_edges: tuple[str, str]) -> list[_Grain]:
    """The grains of one datafile (a malformed file is one bad grain, not a failed run)."""
    stem = path.rsplit("/", 1)[-1].removesuffix(".fe")
    try:
        with open(path, "rb") as handle:
            raw = handle.read()
        why = not_grains(raw[:SNIFF_BYTES], file_only=True)
        if why:  # UTF-16, compressed, Parquet: said so, not read as a file of no bodies
            return [_Grain(stem, path, 1, error=why)]
        text = raw.decode("utf-8-sig", errors="replace")
        # Line ends as text mode reads them: \r\n and \r alone are \n.
        data = _parse(text.replace("\r\n", "\n").replace("\r", "\n"), path, triple_edges)
    except OSError as exc:
        raise InputError(path, exc.strerror or str(exc)) from None
    except InputError as exc:
        return [_Grain(stem, path, exc.line or 1, error=exc.message)]
    if not data.bodies:  # an empty or cut-off dump still has its row, not silence
        if data.unreadable:  # the first line that could not be read says more
            (section, _), line = min(data.unreadable.items(), key=lambda item: item[1])
            return [_Grain(stem, path, line, error=f"cannot read this {SECTIONS[section]} line")]
        return [_Grain(stem, path, 1, error=_NO_BODIES)]
    facet_bodies: dict[int, list[int]] = defaultdict(list)
    for body, (_, signed, _) in data.bodies.items():
        for f in signed:
            facet_bodies[abs(f)].append(body)
    marked = any(edge[3] for edge in data.edges.values())
    grains = []
    for body, (line, _, _) in data.bodies.items():
        grain_id = stem if len(data.bodies) == 1 else str(body)
        if ("bodies", body) in data.unreadable:
            grains.append(_Grain(grain_id, path, line, error="cannot read this body line"))
            continue
        try:
            lists, volume, area, boundary = _grain(data, body, facet_bodies, marked)
            grains.append(_Grain(grain_id, path, line, lists, volume, area, boundary))
        except GrainError as exc:
            grains.append(_Grain(grain_id, path, line, error=str(exc)))
        except _Undefined as exc:
            grains.append(_Grain(grain_id, path, line, error=_missing(data, body, exc)))
    return grains


def _missing(data: _Datafile, body: int, undefined: _Undefined) -> str:
    """Why body ``body`` met an id it could not find: a line that could not be read, or none."""
    what = f"{SECTIONS[undefined.section]} {undefined.ident}"
    line = data.unreadable.get((undefined.section, undefined.ident))
    if line is not None:
        return f"body {body}: cannot read the line of its {what} (line {line})"
    return f"body {body}: {undefined.user} names {what}, which the file does not define"


@dataclass
class _Grain:
    grain_id: str
    path: str
    line: int
    lists: list[list[int]] = field(default_factory=list)
    volume: float = np.nan
    area: float = np.nan
    boundary: bool | None = None
    error: str | None = None


def _batch(grains: list[_Grain]) -> GrainBatch:
    """One batch; each grain's ``source`` is its own file, so messages name the right one."""
    face_offsets, nbr_offsets, neighbors = csr_from_lists([g.lists for g in grains])
    return GrainBatch(
        source=[g.path for g in grains],
        grain_id=[g.grain_id for g in grains],
        location=np.array([g.line for g in grains], np.int64),
        location_kind="line",
        face_offsets=face_offsets,
        nbr_offsets=nbr_offsets,
        neighbors=neighbors,
        parse_errors={k: g.error for k, g in enumerate(grains) if g.error is not None},
        volume=np.array([g.volume for g in grains]),
        area=np.array([g.area for g in grains]),
        boundary=tri_state([g.boundary for g in grains]),
    )
