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

import itertools
import re
from collections import defaultdict
from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field

import numpy as np

from grainclass.batch import GrainBatch
from grainclass.errors import InputError

SECTIONS = {"vertices", "edges", "faces", "facets", "bodies"}
WRAPS = {"*": 0, "+": 1, "-": -1}
DEFAULT_TRIPLE_EDGES = ("color", "red")
_NUMBER = re.compile(r"^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$")


@dataclass
class _Datafile:
    """The parts of a datafile that matter for grains."""

    periods: np.ndarray | None = None
    coords: dict[int, np.ndarray] = field(default_factory=dict)
    # edge id -> (tail, head, wrap vector, is triple)
    edges: dict[int, tuple[int, int, np.ndarray, bool]] = field(default_factory=dict)
    facets: dict[int, list[int]] = field(default_factory=dict)
    # body id -> (line, signed facet ids, volume or None)
    bodies: dict[int, tuple[int, list[int], float | None]] = field(default_factory=dict)


def _logical_lines(text: str) -> Iterator[tuple[int, list[str]]]:
    """(line number, tokens) with comments removed and ``\\`` continuations joined."""
    text = re.sub(r"/\*.*?\*/", lambda m: "\n" * m.group().count("\n"), text, flags=re.S)
    pending: list[str] = []
    start = 0
    for number, line in enumerate(text.splitlines(), 1):
        line = line.split("//", 1)[0].split("#", 1)[0].rstrip()
        if not pending:
            start = number
        if line.endswith("\\"):
            pending.append(line[:-1])
            continue
        tokens = " ".join([*pending, line]).split()
        pending = []
        if tokens:
            yield start, tokens


def _has_attribute(tokens: list[str], key: str, value: str) -> bool:
    return any(
        t.lower() == key and i + 1 < len(tokens) and tokens[i + 1].lower() == value
        for i, t in enumerate(tokens)
    )


def _parse(text: str, source: str, triple_edges: tuple[str, str]) -> _Datafile:
    data = _Datafile()
    section = None
    lines = list(_logical_lines(text))
    key, value = (s.lower() for s in triple_edges)
    i = 0
    while i < len(lines):
        number, tokens = lines[i]
        i += 1
        word = tokens[0].lower()
        if word == "periods":
            rows = [t for _, row in lines[i : i + 3] for t in row]
            if len(rows) < 9 or not all(_NUMBER.match(t) for t in rows[:9]):
                raise InputError(source, "periods needs three rows of three numbers", number)
            data.periods = np.array(rows[:9], float).reshape(3, 3)
            i += 3
            continue
        if word in SECTIONS:
            section = "facets" if word == "faces" else word
            continue
        if word == "read":
            break
        if section is None or not tokens[0].isdigit():
            continue
        try:
            ident = int(tokens[0])
            if section == "vertices":
                data.coords[ident] = np.array(tokens[1:4], float)
            elif section == "edges":
                tail, head = int(tokens[1]), int(tokens[2])
                wrap = np.zeros(3)
                if data.periods is not None and len(tokens) >= 6 and tokens[3] in WRAPS:
                    wrap = np.array([WRAPS[t] for t in tokens[3:6]], float)
                data.edges[ident] = (tail, head, wrap, _has_attribute(tokens, key, value))
            elif section == "facets":
                data.facets[ident] = _leading_integers(tokens[1:])
            else:
                volume = None
                lowered = [t.lower() for t in tokens]
                if "volume" in lowered:
                    volume = float(tokens[lowered.index("volume") + 1])
                data.bodies[ident] = (number, _leading_integers(tokens[1:]), volume)
        except (ValueError, IndexError, KeyError):
            raise InputError(source, f"cannot read this {section[:-1]} line", number) from None
    return data


def _leading_integers(tokens: list[str]) -> list[int]:
    out = []
    for t in tokens:
        if not re.fullmatch(r"[-+]?\d+", t):
            break
        out.append(int(t))
    return out


class GrainError(ValueError):
    """A body that is not a closed surface cut into faces: its grain becomes an invalid row."""


def _oriented_facet(data: _Datafile, signed: int) -> list[tuple[int, int, int]]:
    """Directed edges (tail, head, edge id) of a facet, reversed for a negative sign."""
    darts = []
    for e in data.facets[abs(signed)]:
        tail, head, _, _ = data.edges[abs(e)]
        darts.append((tail, head, abs(e)) if e > 0 else (head, tail, abs(e)))
    if signed < 0:
        darts = [(h, t, e) for t, h, e in reversed(darts)]
    return darts


def _grain(data: _Datafile, body: int, facet_bodies: dict[int, list[int]]) -> tuple:
    """(neighbour lists, volume, area) of one body."""
    _, signed_facets, given_volume = data.bodies[body]
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
    other = [tuple(b for b in facet_bodies[abs(f)] if b != body) for f in signed_facets]
    parent = list(range(len(facets)))

    def find(k: int) -> int:
        while parent[k] != k:
            parent[k] = parent[parent[k]]
            k = parent[k]
        return k

    for e, (a, b) in on_edge.items():
        if not data.edges[e][3] and other[a] == other[b]:
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
    volume, area = _measure(data, facets)
    return neighbours, (given_volume if given_volume is not None else abs(volume)), area


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


def _measure(data: _Datafile, facets: list[list[tuple[int, int, int]]]) -> tuple[float, float]:
    """Signed volume and area of a closed body, in a frame unwrapped from one of its vertices."""
    step: dict[int, list[tuple[int, np.ndarray]]] = defaultdict(list)
    for darts in facets:
        for _, _, e in darts:
            t, h, wrap, _ = data.edges[e]
            shift = wrap @ data.periods if data.periods is not None else 0.0
            delta = data.coords[h] + shift - data.coords[t]
            step[t].append((h, delta))
            step[h].append((t, -delta))
    first = facets[0][0][0]
    position = {first: data.coords[first]}
    queue = [first]
    while queue:
        v = queue.pop()
        for w, delta in step[v]:
            if w not in position:
                position[w] = position[v] + delta
                queue.append(w)
    volume = area = 0.0
    for darts in facets:
        corners = [position[tail] for tail, _, _ in darts]
        for b, c in itertools.pairwise(corners[1:]):
            cross = np.cross(b - corners[0], c - corners[0])
            area += 0.5 * float(np.linalg.norm(cross))
            volume += float(np.dot(corners[0], np.cross(b, c))) / 6.0
    return volume, area


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
    grains: list[_Grain] = []
    for path in paths:
        stem = path.rsplit("/", 1)[-1].removesuffix(".fe")
        try:
            with open(path, encoding="utf-8", errors="replace") as handle:
                data = _parse(handle.read(), path, triple_edges)
        except OSError as exc:
            raise InputError(path, exc.strerror or str(exc)) from None
        except InputError as exc:  # a malformed file is one bad grain, not a failed run
            grains.append(_Grain(stem, path, exc.line or 1, error=exc.message))
            data = _Datafile()
        facet_bodies: dict[int, list[int]] = defaultdict(list)
        for body, (_, signed, _) in data.bodies.items():
            for f in signed:
                facet_bodies[abs(f)].append(body)
        for body, (line, _, _) in data.bodies.items():
            grain_id = stem if len(data.bodies) == 1 else str(body)
            try:
                lists, volume, area = _grain(data, body, facet_bodies)
                grains.append(_Grain(grain_id, path, line, lists, volume, area))
            except GrainError as exc:
                grains.append(_Grain(grain_id, path, line, error=str(exc)))
            except KeyError as exc:
                grains.append(_Grain(grain_id, path, line, error=f"body {body}: unknown id {exc}"))
        if len(grains) >= chunk_size:
            yield _batch(grains)
            grains = []
    if grains:
        yield _batch(grains)


@dataclass
class _Grain:
    grain_id: str
    path: str
    line: int
    lists: list[list[int]] = field(default_factory=list)
    volume: float = np.nan
    area: float = np.nan
    error: str | None = None


def _batch(grains: list[_Grain]) -> GrainBatch:
    """One batch; each grain's ``source`` is its own file, so messages name the right one."""
    return GrainBatch(
        source=[g.path for g in grains],
        grain_id=[g.grain_id for g in grains],
        location=np.array([g.line for g in grains], np.int64),
        location_kind="line",
        face_offsets=np.concatenate([[0], np.cumsum([len(g.lists) for g in grains])]),
        nbr_offsets=np.concatenate(
            [[0], np.cumsum([len(nbrs) for g in grains for nbrs in g.lists], dtype=np.int64)]
        ),
        neighbors=np.array([x for g in grains for nbrs in g.lists for x in nbrs], np.int32),
        parse_errors={k: g.error for k, g in enumerate(grains) if g.error is not None},
        volume=np.array([g.volume for g in grains]),
        area=np.array([g.area for g in grains]),
    )
