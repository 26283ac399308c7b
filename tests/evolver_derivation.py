"""The expected values of evolver_expected.py, derived from the Surface Evolver datafiles alone.

Plain Python, numpy and networkx; nothing from grainclass. The combinatorics of a grain's dual
triangulation (reverse truncations, empty triangles, truncation trees, class) go to the oracle
``reference.classify``, which follows the paper's appendix literally and shares no code with
grainclass; everything before it (reading the file, finding faces, triple lines and corners,
building the dual) and the geometry are done here.

* Triple edges: the ``color red`` edges where a file marks any (the grain-growth fixtures);
  otherwise every edge (the hand-made foams, whose every polygon facet is one grain face).
* Grain faces = connected sets of a body's facets, joined across the edges that are not triple
  edges. Corner = vertex where >= 3 triple edges meet; triple line = maximal chain of triple
  edges between corners; the sides of a face = the triple lines on its boundary, in the order a
  walk along the boundary (in the direction of the body-signed facets) meets them.
* Dual triangulation: one vertex per face, one edge per triple line, one triangle per corner; a
  face's neighbours in the order of its boundary walk are its rotation list.
* Status: ``invalid`` if the body is not a closed surface (an edge on one of its facets only)
  or not a sphere; ``non_simple`` if a corner has more than three faces; ``degenerate`` if a
  face has two sides or two faces share two triple lines (the paper's Sec. IV); else ``ok``.
* Cross-checks, each raising DerivationError when it fails: every other edge lies on two facets
  of the body, once each way; corners - triple lines + faces = 2; a face's boundary is one
  closed walk that meets each of its triple lines once; a triple line ends at corners (none is
  closed) and lies between the same two faces all along; with red edges, no red edge inside a
  face and one fan centre (a vertex without red edges) in each face; unless non_simple, every
  corner has three triple edges and three faces. For an ok grain, the triangles of the rotation
  lists are the corners and every dual edge lies on two of them (a triangulated sphere);
  ``reference.classify`` gives the same result for 20 random removal orders, where there are
  truncations to undo; and a second reduction on the dual's graph alone (networkx, its own
  order, empty triangles counted as the graph's 3-cycles less its 2n - 4 faces) reaches the
  same fundamental size and truncation count, and finds an empty triangle exactly when the
  family is sc. The symmetry is the number of Weinberg walks that reach the smallest code, by
  brute force (``reference.weinberg``).
* A body that lists a facet twice, once each way (a periodic cell that meets its own image
  across it), is first made a file of its own (``unwrap_cell``): each entry of its list is a
  patch, its facet's corners unwrapped along the facet's edges, moved by the lattice
  translation (whole periods, -2 to 2 of each) that puts its middle nearest the cell's centre
  with the centre on its inner side: the faces of a Voronoi cell of a lattice, each halfway to
  a neighbour, as the hand-made cells are. The centre starts behind the first patch, by
  half the edge of a cube of the cell's share of the box, and is the mean of the placed
  corners after each round, until the placement stays. Corners are told apart by position,
  edges by their two corners; each patch is a facet, and the body lists them all. Everything
  below then checks the result: a wrong placement leaves edges on one patch or a surface
  that is not a sphere.
* Geometry: vertex positions unwrapped per body by breadth-first search over its edges (an
  edge's head sits at its tail plus the stored difference, shifted by wrap * period); every
  edge of the body then agrees with its wrap marks and is shorter than half the shortest period.
  Volume by the divergence theorem over the body-signed facets (det(a, b, c) / 6 summed over a
  fan of each facet), the same about the body's centroid to 1e-12 relative; area = the sum of
  the fan's triangle areas. The sign is kept: a volume is positive only if the file's body
  signs give outward normals.

``grain_file_values(path)`` gives a grain file's entry of ``FIXTURES`` (the file holds one body,
which uses each of its facets once), ``foam_file_values(path)`` a hand-made file's entry of
``FOAMS``, floats unrounded. ``python tests/evolver_derivation.py FILE...`` prints the counts
the table's comments quote.
"""

from __future__ import annotations

import itertools
import sys
from collections import Counter, deque
from dataclasses import dataclass, field
from pathlib import Path

import networkx as nx
import numpy as np

import reference

WRAPS = {"*": 0, "+": 1, "-": -1}
REMOVAL_ORDERS = 20  # random removal orders (seeds) given to reference.classify


class DerivationError(Exception):
    """A cross-check failed: the file is not what the derivation takes it for."""


def _check(condition: bool, message: str) -> None:
    if not condition:
        raise DerivationError(message)


@dataclass
class Datafile:
    """What the derivation reads of a Surface Evolver datafile."""

    periods: np.ndarray | None = None  # rows: the three period vectors of a torus file
    vertices: dict[int, np.ndarray] = field(default_factory=dict)
    edges: dict[int, tuple[int, int]] = field(default_factory=dict)  # tail, head
    wraps: dict[int, np.ndarray] = field(default_factory=dict)  # -1, 0 or +1 per period
    red: set[int] = field(default_factory=set)
    facets: dict[int, list[int]] = field(default_factory=dict)  # signed edge ids
    bodies: dict[int, list[int]] = field(default_factory=dict)  # signed facet ids


def _leading_ids(tokens: list[str]) -> list[int]:
    """The signed integers ``tokens`` start with; attributes follow them."""
    ids = []
    for token in tokens:
        if not token.lstrip("+-").isdecimal():
            break
        ids.append(int(token))
    return ids


def read_datafile(path: Path) -> Datafile:
    data = Datafile()
    torus = False
    section = None
    lines = iter(Path(path).read_text().splitlines())
    for raw in lines:
        line = raw.split("//")[0].strip()
        keyword = line.lower()
        if not line:
            continue
        if keyword in ("torus", "torus_filled"):
            torus = True
        elif keyword == "periods":
            data.periods = np.array([[float(x) for x in next(lines).split()] for _ in range(3)])
            _check(data.periods.shape == (3, 3), f"{path}: periods are not three 3-vectors")
        elif keyword in ("vertices", "edges", "faces", "bodies"):
            section = keyword
        elif section == "vertices":
            tokens = line.split()
            data.vertices[int(tokens[0])] = np.array([float(x) for x in tokens[1:4]])
        elif section == "edges":
            tokens = line.split()
            edge = int(tokens[0])
            data.edges[edge] = (int(tokens[1]), int(tokens[2]))
            marks = tokens[3:6] if torus else ["*"] * 3
            data.wraps[edge] = np.array([WRAPS[mark] for mark in marks])
            attributes = [word.lower() for word in tokens[6 if torus else 3 :]]
            if attributes[:2] == ["color", "red"]:
                data.red.add(edge)
        elif section in ("faces", "bodies"):
            tokens = line.split()
            ids = _leading_ids(tokens[1:])
            (data.facets if section == "faces" else data.bodies)[int(tokens[0])] = ids
        else:
            raise DerivationError(f"{path}: a line outside the sections: {raw!r}")
    _check(not torus or data.periods is not None, f"{path}: a torus file without periods")
    return data


def _loops(data: Datafile, body: int) -> dict[int, list[tuple[int, int, int]]]:
    """Each facet of ``body`` as its directed edges (tail, head, edge id), in the direction the
    body's sign for it gives."""
    loops = {}
    for signed_facet in data.bodies[body]:
        loop = []
        for signed_edge in data.facets[abs(signed_facet)]:
            edge = abs(signed_edge)
            tail, head = data.edges[edge]
            loop.append((tail, head, edge) if signed_edge > 0 else (head, tail, edge))
        if signed_facet < 0:
            loop = [(head, tail, edge) for tail, head, edge in reversed(loop)]
        for (_, head, _), (tail, _, _) in itertools.pairwise([*loop, loop[0]]):
            _check(head == tail, f"facet {abs(signed_facet)} is not a closed loop of edges")
        loops[abs(signed_facet)] = loop
    return loops


def _geometry(data: Datafile, loops: dict, edges: set[int]) -> dict:
    """Volume and area of a closed body, its vertices unwrapped by breadth-first search."""
    torus = data.periods is not None
    periods = data.periods if torus else np.zeros((3, 3))
    step = {}  # edge -> the vector from its tail to its head
    neighbours: dict[int, list[tuple[int, int]]] = {}
    for e in edges:
        tail, head = data.edges[e]
        step[e] = data.vertices[head] - data.vertices[tail] + data.wraps[e] @ periods
        neighbours.setdefault(tail, []).append((head, e))
        neighbours.setdefault(head, []).append((tail, e))
    start = min(neighbours)
    position = {start: data.vertices[start]}
    queue = deque([start])
    while queue:
        v = queue.popleft()
        for w, e in neighbours[v]:
            if w not in position:
                position[w] = position[v] + (step[e] if data.edges[e][0] == v else -step[e])
                queue.append(w)
    _check(len(position) == len(neighbours), "the body's edges do not connect its vertices")
    scale = max(1.0, *np.linalg.norm(periods, axis=1))
    for e in edges:
        tail, head = data.edges[e]
        _check(
            np.allclose(position[head] - position[tail], step[e], rtol=0, atol=1e-9 * scale),
            f"edge {e} disagrees with its wrap marks once the body is unwrapped",
        )
    longest = max(np.linalg.norm(s) for s in step.values())
    if torus:
        shortest_period = min(np.linalg.norm(periods, axis=1))
        _check(longest < shortest_period / 2, f"an edge of length {longest} wraps ambiguously")
    centroid = np.mean(list(position.values()), axis=0)
    volume = volume_about_centroid = area = 0.0
    for loop in loops.values():
        points = [position[tail] for tail, _, _ in loop]
        for b, c in itertools.pairwise(points[1:]):
            a = points[0]
            volume += np.linalg.det(np.array([a, b, c])) / 6
            volume_about_centroid += np.linalg.det(np.array([a, b, c]) - centroid) / 6
            area += np.linalg.norm(np.cross(b - a, c - a)) / 2
    _check(
        abs(volume - volume_about_centroid) <= 1e-12 * abs(volume),
        f"the volume depends on the origin ({volume} against {volume_about_centroid})",
    )
    return {"volume": float(volume), "area": float(area), "longest_edge": float(longest)}


def derive_body(data: Datafile, body: int) -> dict:
    """Everything the derivation finds for one body (see the module's docstring)."""
    loops = _loops(data, body)
    uses: dict[int, list[tuple[int, int]]] = {}  # edge -> (facet, +1 along it / -1 against)
    for facet, loop in loops.items():
        for tail, _, e in loop:
            uses.setdefault(e, []).append((facet, 1 if tail == data.edges[e][0] else -1))
    open_edges = tuple(sorted(e for e, on in uses.items() if len(on) == 1))
    if open_edges:
        return {"status": "invalid", "reason": "not closed", "open_edges": open_edges}
    for e, on in uses.items():
        _check(
            sorted(way for _, way in on) == [-1, 1], f"edge {e} is not on two facets, one each way"
        )
    vertices = {v for e in uses for v in data.edges[e]}
    found = {
        "n_facets": len(loops),
        "n_edges": len(uses),
        "n_vertices": len(vertices),
        "wrapped_edges": sum(bool(data.wraps[e].any()) for e in uses),
        "wrapped_axes": "".join(
            a for k, a in enumerate("xyz") if any(data.wraps[e][k] for e in uses)
        ),
    }
    if len(vertices) - len(uses) + len(loops) != 2:
        return found | {"status": "invalid", "reason": "not a sphere"}
    found |= _geometry(data, loops, set(uses))

    triple = {e for e in uses if e in data.red} if data.red else set(uses)
    facet_graph = nx.Graph()
    facet_graph.add_nodes_from(loops)
    facet_graph.add_edges_from(tuple(f for f, _ in uses[e]) for e in uses if e not in triple)
    faces = sorted((sorted(c) for c in nx.connected_components(facet_graph)), key=min)
    face_of = {facet: k for k, component in enumerate(faces) for facet in component}
    across = {e: {face_of[f] for f, _ in uses[e]} for e in triple}
    for e, pair in across.items():
        _check(len(pair) == 2, f"triple edge {e} lies inside a face")
    faces_at: dict[int, set[int]] = {}  # vertex -> the faces of its facets
    for facet, loop in loops.items():
        for tail, _, _ in loop:
            faces_at.setdefault(tail, set()).add(face_of[facet])

    triple_at: dict[int, list[int]] = {}  # vertex -> its triple edges
    for e in triple:
        for v in data.edges[e]:
            triple_at.setdefault(v, []).append(e)
    corners = {v for v, at in triple_at.items() if len(at) >= 3}
    _check(all(len(at) >= 2 for at in triple_at.values()), "a triple line ends at no corner")
    line_graph = nx.Graph()
    line_graph.add_nodes_from(triple)
    line_graph.add_edges_from(at for at in triple_at.values() if len(at) == 2)
    lines = sorted((sorted(c) for c in nx.connected_components(line_graph)), key=min)
    line_of = {e: k for k, line in enumerate(lines) for e in line}
    line_faces = []
    for line in lines:
        _check(
            any(v in corners for e in line for v in data.edges[e]),
            f"triple line of edge {line[0]} is closed, without a corner",
        )
        pairs = {frozenset(across[e]) for e in line}
        _check(len(pairs) == 1, f"triple line of edge {line[0]} changes faces along its way")
        line_faces.append(pairs.pop())
    if data.red:
        centres = [faces_at[v] for v in vertices if v not in triple_at]
        _check(all(len(fs) == 1 for fs in centres), "a vertex without red edges on two faces")
        _check(
            sorted(min(fs) for fs in centres) == list(range(len(faces))),
            "not one fan centre in each face",
        )

    # A face's boundary walk: its triple edges, in the direction of its facets, one closed loop.
    sides = []
    for component in faces:
        after = {}
        for facet in component:
            for tail, head, e in loops[facet]:
                if e in triple:
                    _check(
                        tail not in after, f"the boundary of the face of facet {facet} is pinched"
                    )
                    after[tail] = (head, e)
        walk, v = [], min(after)
        for _ in range(len(after)):
            _check(v in after, f"the boundary of the face of facet {component[0]} breaks off")
            v, e = after[v]
            walk.append(line_of[e])
        _check(v == min(after), f"the boundary of the face of facet {component[0]} is not one loop")
        runs = [line for line, _ in itertools.groupby(walk)]
        if len(runs) > 1 and runs[0] == runs[-1]:
            runs.pop()
        _check(len(set(runs)) == len(runs), f"a triple line meets the face of {component[0]} twice")
        sides.append(runs)
    n_corners, n_lines, n_faces = len(corners), len(lines), len(faces)
    _check(n_corners - n_lines + n_faces == 2, f"{n_corners} - {n_lines} + {n_faces} != 2")
    found |= {"n_faces": n_faces, "n_corners": n_corners, "n_triple_lines": n_lines}
    found["sides"] = sorted(len(runs) for runs in sides)

    most = max(len(faces_at[v]) for v in corners)
    if most > 3:
        return found | {
            "status": "non_simple",
            "reason": f"corner of {most} faces",
            "max_faces_at_corner": most,
        }
    for v in corners:
        _check(len(triple_at[v]) == 3 == len(faces_at[v]), f"corner {v}: not 3 edges, 3 faces")
    _check(min(found["sides"]) >= 2, "a face with fewer than two sides")
    two_gons = found["sides"].count(2)
    shared = max(Counter(line_faces).values())
    if two_gons or shared > 1:
        return found | {"status": "degenerate", "n_two_gons": two_gons}

    # The dual: a face's rotation list = the faces across its sides, in boundary-walk order.
    lists = [[next(iter(line_faces[line] - {f})) for line in runs] for f, runs in enumerate(sides)]
    triangles = {frozenset(t) for t in reference.oriented_faces(lists)}
    _check(triangles == {frozenset(faces_at[v]) for v in corners}, "dual triangles != corners")
    _check(len(triangles) == n_corners, "two corners with the same three faces")
    on_triangles = Counter(pair for t in triangles for pair in itertools.combinations(sorted(t), 2))
    _check(set(on_triangles.values()) == {2}, "a dual edge not on exactly two triangles")
    result = reference.classify(lists, seed=0)
    if result["truncations"]:  # without a degree-3 vertex there is no order to vary
        for seed in range(1, REMOVAL_ORDERS):
            _check(reference.classify(lists, seed) == result, f"removal order {seed} differs")

    graph = nx.Graph(tuple(pair) for pair in line_faces)
    while len(graph) > 4 and (cubic := [v for v in graph if graph.degree(v) == 3]):
        graph.remove_node(max(cubic))
    empty = sum(nx.triangles(graph).values()) // 3 - (2 * len(graph) - 4)
    _check(
        (len(graph), n_faces - len(graph), empty > 0)
        == (result["fundamental_faces"], result["truncations"], result["family"] == "sc"),
        "the graph-only reduction disagrees",
    )
    p_vector = tuple(found["sides"].count(k) for k in range(3, max(found["sides"]) + 1))
    return (
        found
        | {"status": "ok", "p_vector": p_vector}
        | {key: result[key] for key in ("class", "truncations", "fundamental_faces", "trees")}
        | {"symmetry": reference.weinberg(lists)[1]}
    )


def _patch(data: Datafile, signed_facet: int) -> list[tuple[np.ndarray, int]]:
    """A patch: the corners of a facet in its own frame (each edge's head where its tail and
    wrap marks put it), with the edge that leaves each, in the direction of the body's sign."""
    periods = data.periods if data.periods is not None else np.zeros((3, 3))
    corners, point = [], None
    for signed_edge in data.facets[abs(signed_facet)]:
        edge = abs(signed_edge)
        tail, head = data.edges[edge]
        step = data.vertices[head] + data.wraps[edge] @ periods - data.vertices[tail]
        if signed_edge < 0:
            tail, step = head, -step
        if point is None:
            point = data.vertices[tail]
        corners.append((point, edge))
        point = point + step
    _check(np.allclose(point, corners[0][0]), f"facet {abs(signed_facet)} does not close up")
    if signed_facet < 0:  # the same corners the other way round, each with the edge before it
        corners = [(p, corners[k - 1][1]) for k, (p, _) in enumerate(corners)][::-1]
    return corners


def unwrap_cell(data: Datafile, body: int) -> Datafile:
    """Body ``body`` of a periodic file, placed patch by patch around its centre (the module's
    docstring), as a file of one body (1) whose facets are its patches."""
    patches = [_patch(data, f) for f in data.bodies[body]]
    periods = data.periods
    scale = float(max(np.linalg.norm(periods, axis=1)))
    shifts = np.array(list(itertools.product(range(-2, 3), repeat=3))) @ periods
    middles = [np.mean([p for p, _ in patch], axis=0) for patch in patches]
    normals = []
    for patch in patches:
        points = [p for p, _ in patch]
        newell = sum(np.cross(a, b) for a, b in zip(points, points[1:] + points[:1], strict=True))
        normals.append(newell / np.linalg.norm(newell))
    share = abs(np.linalg.det(periods)) / len(data.bodies)
    centre = middles[0] - normals[0] * share ** (1 / 3) / 2
    placed = None
    for _ in range(20):
        chosen = []
        for middle, normal in zip(middles, normals, strict=True):
            heights = (middle + shifts - centre) @ normal
            distances = np.linalg.norm(middle + shifts - centre, axis=1)
            outward = np.flatnonzero(heights > 1e-9 * scale)
            _check(len(outward) > 0, "a patch with no place on the outward side of the centre")
            chosen.append(int(outward[np.argmin(distances[outward])]))
        if chosen == placed:
            break
        placed = chosen
        centre = np.mean(
            [p + shifts[k] for patch, k in zip(patches, placed, strict=True) for p, _ in patch],
            axis=0,
        )
    else:
        raise DerivationError(f"body {body}: the placement of its patches does not settle")
    cell = Datafile()
    corner_ids: dict[tuple, int] = {}
    edge_ids: dict[tuple[int, int], int] = {}
    for number, (patch, k) in enumerate(zip(patches, placed, strict=True), 1):
        ids = []
        for point, _ in patch:
            key = tuple(np.round((point + shifts[k]) / scale, 9))
            if key not in corner_ids:
                corner_ids[key] = len(corner_ids) + 1
                cell.vertices[corner_ids[key]] = point + shifts[k]
            ids.append(corner_ids[key])
        loop = []
        for j, (_, edge) in enumerate(patch):
            a, b = ids[j], ids[(j + 1) % len(ids)]
            if (b, a) in edge_ids:
                loop.append(-edge_ids[(b, a)])
                continue
            _check((a, b) not in edge_ids, f"body {body}: two patches run along an edge one way")
            edge_ids[(a, b)] = len(edge_ids) + 1
            cell.edges[edge_ids[(a, b)]] = (a, b)
            cell.wraps[edge_ids[(a, b)]] = np.zeros(3, int)
            if edge in data.red:
                cell.red.add(edge_ids[(a, b)])
            loop.append(edge_ids[(a, b)])
        cell.facets[number] = loop
    cell.bodies[1] = list(cell.facets)
    return cell


def _cell(data: Datafile, body: int) -> tuple[Datafile, int]:
    """What derive_body takes for body ``body``: the file itself, or, for a body that lists a
    facet twice, its cell unwrapped (:func:`unwrap_cell`)."""
    facets = [abs(f) for f in data.bodies[body]]
    if data.periods is not None and len(set(facets)) < len(facets):
        return unwrap_cell(data, body), 1
    return data, body


def grain_file_values(path: Path) -> dict:
    """A grain-growth file's entry of ``FIXTURES``."""
    data = read_datafile(path)
    _check(len(data.bodies) == 1, f"{path}: not one body")
    (body,) = data.bodies
    _check(
        sorted(abs(f) for f in data.bodies[body]) == sorted(data.facets),
        f"{path}: the body does not use every facet of the file once",
    )
    grain = derive_body(data, body)
    _check(grain["status"] in ("ok", "degenerate"), f"{path}: {grain['status']}")
    ok = grain["status"] == "ok"
    values = {
        "n_faces": grain["n_faces"],
        "p_vector": grain["p_vector"] if ok else None,
        "status": grain["status"],
        "class": grain["class"] if ok else None,
        "truncations": grain["truncations"] if ok else None,
        "volume": grain["volume"],
        "area": grain["area"],
        "n_corners": grain["n_corners"],
        "n_triple_lines": grain["n_triple_lines"],
    }
    if not ok:
        values["n_two_gons"] = grain["n_two_gons"]
    return values


def foam_file_values(path: Path) -> dict:
    """A hand-made file's entry of ``FOAMS``: every body if all are ok, else its one body's."""
    data = read_datafile(path)
    grains = {body: derive_body(*_cell(data, body)) for body in data.bodies}
    if all(g["status"] == "ok" for g in grains.values()):
        keys = ("n_faces", "p_vector", "class", "truncations", "symmetry", "volume", "area")
        bodies = {body: {key: g[key] for key in keys} for body, g in grains.items()}
        return {"status": "ok", "bodies": bodies}
    _check(len(grains) == 1, f"{path}: bodies not all ok; FOAMS has no entry of that kind")
    (grain,) = grains.values()
    keys = {
        "invalid": ("status", "reason", "open_edges"),
        "non_simple": ("status", "reason", "n_faces", "max_faces_at_corner", "volume", "area"),
    }[grain["status"]]
    return {key: grain[key] for key in keys}


def main(paths: list[str]) -> None:
    for path in paths:
        data = read_datafile(Path(path))
        for body in data.bodies:
            grain = derive_body(*_cell(data, body))
            print(f"{Path(path).name} body {body}:")
            for key, value in grain.items():
                print(f"    {key}: {value}")


if __name__ == "__main__":
    main(sys.argv[1:])
