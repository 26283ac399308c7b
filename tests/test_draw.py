"""`grainclass draw`: Schlegel diagrams, checked against what a drawing of a grain must be and
against truths computed here, never by grainclass.

- Every drawing is a planar straight-line embedding of the grain's own edge graph: its corners
  are the grain's (the dual's triangles), its edges join the corners that two adjacent faces
  share, no two edges cross, the outer face's corners turn counter-clockwise, every inner
  face is a strictly convex polygon turning clockwise (seen through the outer face), and the
  inner faces' areas add up to the outer face's.
- Flips against a flip made here on the dual graph and a comparison of types by graph
  isomorphism (networkx; for simple polytopes the edge graph fixes the type up to mirror
  image, Whitney), and against the paper's own count for its two six-faced grains.
- Belts against every l-subset of faces, and truncation trees against the stackings replayed
  forwards, as the paper defines them.
- Weinberg vectors read back against the grain they came from (graph isomorphism), the named
  grains against what the paper says of them, and the gallery against types counted here.
"""

from __future__ import annotations

import collections
import itertools
import json
import math
import shutil

import networkx as nx
import numpy as np
import pyarrow.parquet as pq
import pytest
from click.testing import CliRunner

from conftest import EXAMPLES, ROOT
from grainclass import read_dataset
from grainclass.cli import cli
from grainclass.perturb import check

pytest.importorskip("matplotlib")

VORO = ROOT / "tests" / "data" / "voro" / "periodic-300.vol"
NEPER_CUBE = ROOT / "tests" / "data" / "neper" / "cube.tess"
GRAIN3D = ROOT / "tests" / "data" / "evolver" / "grain3d"
# Cells of the periodic Voronoi tessellation, of 11 to 20 faces.
CELLS = ("13", "201", "2", "7", "40")
NAMED = ("tetrahedron", "triangular-prism", "cube", "flipped-cube", "smallest-sc")
NAMED += ("dodecahedron", "A", "B", "C", "K", "L", "M")


def _run(*args):
    return CliRunner().invoke(cli, [str(a) for a in args])


def _data(tmp_path, *args, name="f.svg"):
    """Draw, and read back what was drawn (--data)."""
    figure, data = tmp_path / name, tmp_path / f"{name}.json"
    result = _run("draw", *args, "-o", figure, "--data", data, "-q")
    assert result.exit_code == 0, result.output
    assert figure.stat().st_size > 0
    return json.loads(data.read_text())["grains"]


def _grains(path, ids=None) -> dict[str, list[list[int]]]:
    """Grains of an input as their neighbour lists, read by grainclass's readers (which other
    tests check) and turned one way."""
    grains = {}
    for batch in read_dataset(str(path)):
        lists = check(batch).lists
        for g, grain_id in enumerate(batch.grain_id):
            if ids is None or str(grain_id) in ids:
                first, last = batch.face_offsets[g], batch.face_offsets[g + 1]
                grains[str(grain_id)] = [
                    lists[batch.nbr_offsets[f] : batch.nbr_offsets[f + 1]].tolist()
                    for f in range(first, last)
                ]
    return grains


def _dual(lists) -> nx.Graph:
    return nx.Graph((a, b) for a, nbrs in enumerate(lists) for b in nbrs)


def _adjacency(entry) -> list[list[int]]:
    """The grain a drawing shows, read off it alone: around each face, the face across each of
    its polygon's sides, in order (two consecutive corners share the face and one other)."""
    faces_at = collections.defaultdict(set)
    for f, corners in enumerate(entry["faces"]):
        for c in corners:
            faces_at[c].add(f)
    lists = []
    for f, corners in enumerate(entry["faces"]):
        across = []
        for c, d in zip(corners, corners[1:] + corners[:1], strict=True):
            (g,) = (faces_at[c] & faces_at[d]) - {f}
            across.append(g)
        lists.append(across)
    return lists


def _same_cycle(a, b) -> bool:
    if len(a) != len(b) or set(a) != set(b):
        return False
    k = b.index(a[0])
    turned = b[k:] + b[:k]
    return a == turned or a == [turned[0], *reversed(turned[1:])]


def _cross(o, a, b) -> float:
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])


def _signed_area(points) -> float:
    x, y = np.asarray(points).T
    return float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1))) / 2


def _segments_cross(p, q, r, s) -> bool:
    """Whether segments pq and rs meet anywhere (they share no end)."""
    d1, d2 = _cross(r, s, p), _cross(r, s, q)
    d3, d4 = _cross(p, q, r), _cross(p, q, s)
    if ((d1 > 0) != (d2 > 0)) and ((d3 > 0) != (d4 > 0)) and d1 and d2 and d3 and d4:
        return True

    def on(a, b, c):  # c on segment ab, collinear
        return (
            abs(_cross(a, b, c)) < 1e-12
            and min(a[0], b[0]) - 1e-12 <= c[0] <= max(a[0], b[0]) + 1e-12
            and min(a[1], b[1]) - 1e-12 <= c[1] <= max(a[1], b[1]) + 1e-12
        )

    return on(r, s, p) or on(r, s, q) or on(p, q, r) or on(p, q, s)


def _check_embedding(entry, lists) -> None:
    """The drawing is a planar convex drawing of the grain ``lists``."""
    n = len(lists)
    points = np.array(entry["vertices"])
    faces = entry["faces"]
    # Its faces and edges are the grain's.
    assert len(points) == 2 * n - 4
    assert len(faces) == n
    drawn = _adjacency(entry)
    for f in range(n):
        assert _same_cycle(drawn[f], lists[f]), f
    pairs = sorted(tuple(e["faces"]) for e in entry["edges"])
    assert pairs == sorted({(min(a, b), max(a, b)) for a, nbrs in enumerate(lists) for b in nbrs})
    for edge in entry["edges"]:
        f, g = edge["faces"]
        a, b = edge["corners"]
        for c in (a, b):
            assert c in faces[f]
            assert c in faces[g]
    # No two edges cross.
    segments = [tuple(e["corners"]) for e in entry["edges"]]
    for (a, b), (c, d) in itertools.combinations(segments, 2):
        if {a, b} & {c, d}:
            # Edges at a corner meet there only: they do not run along each other.
            shared = ({a, b} & {c, d}).pop()
            u, v = ({a, b} - {shared}).pop(), ({c, d} - {shared}).pop()
            assert not (
                abs(_cross(points[shared], points[u], points[v])) < 1e-12
                and np.dot(points[u] - points[shared], points[v] - points[shared]) > 0
            )
            continue
        assert not _segments_cross(points[a], points[b], points[c], points[d]), (a, b, c, d)
    # The outer face turns counter-clockwise, the others clockwise, all strictly convex.
    outer = entry["outer_face"]
    inner_area = 0.0
    for f, corners in enumerate(faces):
        polygon = points[corners]
        sign = 1 if f == outer else -1
        turns = [
            _cross(polygon[i - 1], polygon[i], polygon[(i + 1) % len(polygon)])
            for i in range(len(polygon))
        ]
        assert min(sign * t for t in turns) > 0, (f, turns)
        if f != outer:
            inner_area += -_signed_area(polygon)
    assert math.isclose(inner_area, _signed_area(points[faces[outer]]), rel_tol=1e-9)


def test_drawings_are_planar_convex_and_the_grains_own(tmp_path):
    grains = _grains(EXAMPLES / "polytopes.txt") | _grains(VORO, set(CELLS))
    args = [EXAMPLES / "polytopes.txt", VORO, "--input-format", "auto"]
    drawn = _data(tmp_path, *args, *itertools.chain(*(("--id", i) for i in grains)))
    assert [entry["grain_id"] for entry in drawn] == list(grains)
    for entry in drawn:
        lists = grains[entry["grain_id"]]
        # By default a largest face, the one whose farthest face is nearest (the first such).
        sizes = [len(nbrs) for nbrs in lists]
        eccentricity = nx.eccentricity(_dual(lists))
        largest = [f for f, size in enumerate(sizes) if size == max(sizes)]
        assert entry["outer_face"] == min(largest, key=lambda f: (eccentricity[f], f))
        _check_embedding(entry, lists)


def test_every_face_of_a_grain_can_be_the_outer_one(tmp_path):
    (lists,) = _grains(VORO, {"13"}).values()
    for face in range(len(lists)):
        (entry,) = _data(tmp_path, VORO, "--id", "13", "--outer-face", face, name=f"{face}.svg")
        assert entry["outer_face"] == face
        _check_embedding(entry, lists)


def test_every_triangulation_with_9_vertices_draws(tmp_path, plantri_output):
    path = plantri_output(9)
    grains = _grains(path)
    drawn = _data(tmp_path, path, *itertools.chain(*(("--id", i) for i in grains)))
    assert len(drawn) == len(grains) == 50
    for entry in drawn:
        _check_embedding(entry, grains[entry["grain_id"]])


def _flip_results(lists) -> dict[tuple[int, int], str]:
    """What flipping each edge of the dual does, made here: edge A-B lies on the triangles
    A-B-C and B-A-D (C, D the faces before and after B around A); the flip replaces it by C-D
    and is admissible unless A or B would become a 2-gon or C and D meet already. The grain
    it gives is the same type when its dual graph is isomorphic to the grain's."""
    graph = _dual(lists)
    results = {}
    for a, nbrs in enumerate(lists):
        for i, b in enumerate(nbrs):
            if a > b:
                continue
            c, d = nbrs[i - 1], nbrs[(i + 1) % len(nbrs)]
            if len(lists[a]) == 3 or len(lists[b]) == 3 or graph.has_edge(c, d):
                results[(a, b)] = "none"
                continue
            flipped = graph.copy()
            flipped.remove_edge(a, b)
            flipped.add_edge(c, d)
            results[(a, b)] = "same" if nx.is_isomorphic(flipped, graph) else "other"
    return results


def _flips_drawn(entry) -> dict[tuple[int, int], str]:
    return {tuple(e["faces"]): e["flip"] for e in entry["edges"]}


def test_flips_of_the_six_faced_grains_are_the_papers(tmp_path):
    # Fig. grains_with_6_faces: every edge of the cube gives the other polytope; of that one's
    # twelve edges, four give itself, one the cube, and seven are not admissible.
    cube, other = _data(tmp_path, "--named", "cube", "--named", "flipped-cube", "--flips")
    assert collections.Counter(_flips_drawn(cube).values()) == {"other": 12}
    assert collections.Counter(_flips_drawn(other).values()) == {"same": 4, "other": 1, "none": 7}
    assert _flips_drawn(other) == _flip_results(_adjacency(other))


def test_flips_agree_with_a_flip_and_compare_made_here(tmp_path):
    grains = _grains(EXAMPLES / "polytopes.txt", {"cube_truncated_1", "smallest_sc", "kelvin"})
    grains |= _grains(VORO, set(CELLS[:2]))
    args = [EXAMPLES / "polytopes.txt", VORO, *itertools.chain(*(("--id", i) for i in grains))]
    drawn = _data(tmp_path, *args, "--named", "A", "--named", "B", "--named", "C", "--flips")
    for entry in drawn:
        lists = grains.get(entry["grain_id"]) or _adjacency(entry)
        assert _flips_drawn(entry) == _flip_results(lists), entry["grain_id"]
    assert {"same", "other", "none"} <= {f for e in drawn for f in _flips_drawn(e).values()}


def _belts_by_brute_force(lists, length) -> dict[frozenset, tuple[int, int]]:
    """Every set of ``length`` faces whose dual graph is a cycle and whose removal leaves two
    discs (for 3 faces: not three around a corner), with the sizes of the two."""
    graph = _dual(lists)
    found = {}
    for faces in itertools.combinations(range(len(lists)), length):
        induced = graph.subgraph(faces)
        if induced.number_of_edges() != length or any(d != 2 for _, d in induced.degree()):
            continue
        if not nx.is_connected(induced):
            continue
        rest = graph.subgraph(set(graph) - set(faces))
        sizes = sorted(len(part) for part in nx.connected_components(rest))
        if len(sizes) == 2:
            found[frozenset(faces)] = tuple(sizes)
    return found


@pytest.mark.parametrize("length", [3, 4, 5, 6])
def test_belts_are_every_set_of_faces_whose_dual_is_a_cycle(tmp_path, length):
    grains = _grains(EXAMPLES / "polytopes.txt", {"smallest_sc", "cube_truncated_1", "kelvin"})
    grains |= _grains(VORO, {"13"})
    args = [EXAMPLES / "polytopes.txt", VORO, *itertools.chain(*(("--id", i) for i in grains))]
    drawn = _data(tmp_path, *args, "--named", "A", "--belt-length", length, "--columns", 8)
    for entry in drawn:
        lists = grains.get(entry["grain_id"]) or _adjacency(entry)
        truth = _belts_by_brute_force(lists, length)
        got = {
            frozenset(b): tuple(s) for b, s in zip(entry["belts"], entry["belt_sides"], strict=True)
        }
        assert got == truth, entry["grain_id"]
        assert len(entry["belts"]) == len(got) == entry["belt_count"]
        graph = _dual(lists)
        for belt in entry["belts"]:  # in cyclic order
            assert all(graph.has_edge(a, b) for a, b in zip(belt, belt[1:] + belt[:1], strict=True))


def test_one_belt_and_the_papers_belts_of_a_b_and_c(tmp_path):
    # Sec. III.D: A has two belts of type 3:4:3, B one, C none.
    drawn = _data(tmp_path, *[x for g in "ABC" for x in ("--named", g)], "--belt-length", 4)
    assert [sum(s == [3, 3] for s in e["belt_sides"]) for e in drawn] == [2, 1, 0]
    (entry,) = _data(tmp_path, "--named", "A", "--belt-length", 4, "--belt", 3, name="one.svg")
    assert entry["belts"] == [drawn[0]["belts"][2]]
    assert entry["belt_numbers"] == [3]


def _replayed_trees(lists) -> tuple[list[int], list[int]]:
    """Depth and parent of each face in its truncation tree (0 and -1 for a face of the
    fundamental polytope, -1 for a root): triangles removed one at a time until none is left
    (or the tetrahedron), then the truncations replayed forwards, each triangle's parent the
    face whose truncation made the corner it truncates (Lutz et al. Sec. II.B)."""
    graph = _dual(lists)
    corners = {
        frozenset((f, a, b))
        for f, nbrs in enumerate(lists)
        for a, b in zip(nbrs, nbrs[1:] + nbrs[:1], strict=True)
    }
    removed = []
    while graph.number_of_nodes() > 4:
        triangles = sorted(v for v in graph if graph.degree(v) == 3)
        if not triangles:
            break
        v = triangles[0]
        link = frozenset(graph[v])
        corners = {c for c in corners if v not in c} | {link}
        graph.remove_node(v)
        removed.append((v, link))
    maker = dict.fromkeys(corners)
    depth, parent = [0] * len(lists), [-1] * len(lists)
    for v, link in reversed(removed):
        made_by = maker.pop(link)
        parent[v] = -1 if made_by is None else made_by
        depth[v] = 1 if made_by is None else depth[made_by] + 1
        for a, b in itertools.combinations(link, 2):
            maker[frozenset((v, a, b))] = v
    return depth, parent


def test_truncation_trees_are_the_stackings_replayed(tmp_path):
    ids = {"cube_truncated_1", "cube_truncated_2_opposite", "cube_truncated_twice_one_corner"}
    grains = _grains(EXAMPLES / "polytopes.txt", ids) | _grains(VORO, set(CELLS))
    args = [EXAMPLES / "polytopes.txt", VORO, *itertools.chain(*(("--id", i) for i in grains))]
    drawn = _data(tmp_path, *args, "--trees")
    assert any(max(e["truncation_depth"]) >= 2 for e in drawn)
    for entry in drawn:
        depth, parent = _replayed_trees(grains[entry["grain_id"]])
        assert entry["truncation_depth"] == depth, entry["grain_id"]
        assert entry["truncation_parent"] == parent, entry["grain_id"]
        assert entry["labels"] == entry["face_ids"]  # faces named, to find them in the trees


def test_weinberg_vectors_come_back_as_their_grains(tmp_path, plantri_output):
    path = plantri_output(8)
    table = tmp_path / "g.parquet"
    assert _run("classify", path, "-o", table, "-q").exit_code == 0
    rows = pq.read_table(table).to_pylist()
    codes = [x for row in rows for x in ("--weinberg", row["weinberg"])]
    drawn = _data(tmp_path, *codes)
    grains = _grains(path)
    for row, entry in zip(rows, drawn, strict=True):
        assert entry["weinberg"] == row["weinberg"]
        assert nx.is_isomorphic(_dual(_adjacency(entry)), _dual(grains[row["grain_id"]]))
    # A per-grain table's grain is drawn from its Weinberg vector.
    by_id = _data(tmp_path, table, "--id", rows[3]["grain_id"], name="table.svg")
    assert nx.is_isomorphic(_dual(_adjacency(by_id[0])), _dual(grains[rows[3]["grain_id"]]))


def _p_vector(lists) -> list[int]:
    sizes = [len(nbrs) for nbrs in lists]
    return [sizes.count(k) for k in range(3, max(sizes) + 1)]


def _automorphisms(lists) -> int:
    graph = _dual(lists)
    return sum(1 for _ in nx.algorithms.isomorphism.GraphMatcher(graph, graph).isomorphisms_iter())


def test_named_grains_are_what_the_paper_says(tmp_path):
    drawn = _data(tmp_path, *[x for name in NAMED for x in ("--named", name)])
    grains = {entry["grain_id"]: _adjacency(entry) for entry in drawn}
    assert list(grains) == list(NAMED)
    examples = _grains(EXAMPLES / "polytopes.txt")
    for name, example in [
        ("tetrahedron", "tetrahedron"),
        ("triangular-prism", "triangular_prism"),
        ("cube", "cube"),
        ("dodecahedron", "dodecahedron"),
        ("K", "kelvin"),  # Kelvin's cell
        ("smallest-sc", "smallest_sc"),
    ]:
        assert nx.is_isomorphic(_dual(grains[name]), _dual(examples[example])), name
    # The other six-faced grain: p-vector (2,2,2).
    assert _p_vector(grains["flipped-cube"]) == [2, 2, 2]
    # Fig. smallest_nonflag: no triangle, and a 3-belt that is not three faces at a corner.
    assert _p_vector(grains["smallest-sc"])[0] == 0
    assert _belts_by_brute_force(grains["smallest-sc"], 3)
    # Sec. III.D: A, B and C have 10 faces and p-vector (0,4,4,2), symmetry groups of order
    # 8, 2 and 2; K, L and M 14 faces and p-vector (0,6,0,8), three different grains.
    for name in "ABC":
        assert _p_vector(grains[name]) == [0, 4, 4, 2]
    assert [_automorphisms(grains[name]) for name in "ABC"] == [8, 2, 2]
    for name in "KLM":
        assert _p_vector(grains[name]) == [0, 6, 0, 8]
    for a, b in itertools.combinations("KLMABC", 2):
        assert not nx.is_isomorphic(_dual(grains[a]), _dual(grains[b]))


def test_gallery_is_the_most_frequent_types_counted_here(tmp_path):
    table = tmp_path / "pv.parquet"
    assert _run("classify", VORO, "-o", table, "-q").exit_code == 0
    rows = [r for r in pq.read_table(table).to_pylist() if r["status"] == "ok"]
    counts = collections.Counter(r["weinberg"] for r in rows)
    drawn = _data(tmp_path, table, "--top", 4)
    assert [e["count"] for e in drawn] == sorted(counts.values(), reverse=True)[:4]
    for entry in drawn:
        assert counts[entry["weinberg"]] == entry["count"]
        assert entry["fraction"] == pytest.approx(entry["count"] / len(rows))
    five = [r for r in rows if r["n_faces"] == 14]
    counts = collections.Counter(r["weinberg"] for r in five)
    drawn = _data(tmp_path, VORO, "--n", 14, name="n.svg")
    assert {e["weinberg"]: e["count"] for e in drawn} == dict(counts)


def _directed_sides(polygons) -> collections.Counter:
    return collections.Counter(
        (a, b)
        for polygon in polygons
        for a, b in zip(polygon, polygon[1:] + polygon[:1], strict=True)
    )


def _enclosed_volume(points, polygons) -> float:
    """The volume a closed surface of polygons encloses, positive when they turn
    counter-clockwise seen from outside (the divergence theorem, over fans of triangles)."""
    return sum(
        float(np.dot(points[p[0]], np.cross(points[p[i]], points[p[i + 1]]))) / 6
        for p in polygons
        for i in range(1, len(p) - 1)
    )


def _tess_faces(path) -> dict[str, set[tuple[float, ...]]]:
    """Each face of a Neper file by its id, as the set of its vertices' coordinates, read
    here: a **vertex line is an id and x y z; a **face entry's first line is its id, its
    number of vertices and their ids."""
    lines = [line.split() for line in path.read_text().splitlines()]
    at = {line[0]: i for i, line in enumerate(lines) if line and line[0].startswith("**")}
    start = at["**vertex"]
    coords = {
        words[0]: tuple(float(x) for x in words[1:4])
        for words in lines[start + 2 : start + 2 + int(lines[start + 1][0])]
    }
    start = at["**face"]
    faces = {}
    for k in range(int(lines[start + 1][0])):
        words = lines[start + 2 + 4 * k]
        faces[words[0]] = {coords[v] for v in words[2 : 2 + int(words[1])]}
    return faces


def test_a_neper_cell_in_space_is_its_file_face_for_face(tmp_path):
    (entry,) = _data(tmp_path, NEPER_CUBE, "--id", "1", "--3d")
    shape = entry["shape"]
    points = np.array(shape["positions"])
    polygons = shape["polygons"]
    # Each face's polygon has the corners the file gives the face of that id.
    faces = _tess_faces(NEPER_CUBE)
    for polygon, face in zip(polygons, shape["polygon_faces"], strict=True):
        corners = {tuple(points[c].tolist()) for c in polygon}
        assert corners == faces[entry["face_ids"][face]]
    # A closed surface turning one way, outwards: the unit cube.
    sides = _directed_sides(polygons)
    assert set(sides.values()) == {1}
    assert all((b, a) in sides for a, b in sides)
    assert _enclosed_volume(points, polygons) == pytest.approx(1.0)


def _fe_vertices(path) -> np.ndarray:
    """The vertices section of a Surface Evolver file, read here."""
    rows, inside = [], False
    for line in path.read_text().splitlines():
        words = line.split()
        if words[:1] == ["vertices"]:
            inside = True
        elif inside and words and words[0].isdigit():
            rows.append([float(x) for x in words[1:4]])
        elif inside and words:
            break
    return np.array(rows)


def test_evolver_grains_in_space_are_their_files_closed_surfaces(tmp_path):
    ids = ["21000-00000006", "21000-00000014", "21000-00000030"]
    drawn = _data(tmp_path, GRAIN3D, *itertools.chain(*(("--id", i) for i in ids)), "--3d")
    volumes = pq.read_table(_classified(tmp_path, GRAIN3D)).to_pandas().set_index("grain_id")
    for entry in drawn:
        points = np.array(entry["shape"]["positions"])
        polygons = entry["shape"]["polygons"]
        # Every corner is one of the file's, moved by whole periods of the unit box.
        vertices = _fe_vertices(GRAIN3D / f"{entry['grain_id']}.fe")
        for point in points:
            shifts = point - vertices
            assert np.any(np.all(np.abs(shifts - np.round(shifts)) < 1e-9, axis=1))
        # A closed surface turning one way, outwards, enclosing the grain's volume.
        sides = _directed_sides(polygons)
        assert set(sides.values()) == {1}
        assert all((b, a) in sides for a, b in sides)
        volume = _enclosed_volume(points, polygons)
        assert volume == pytest.approx(volumes.loc[entry["grain_id"], "volume"], rel=1e-9)


def _classified(tmp_path, path):
    table = tmp_path / f"{path.name}.parquet"
    assert _run("classify", path, "-o", table, "-q").exit_code == 0
    return table


def test_the_same_input_gives_the_same_svg_bytes(tmp_path):
    args = ["--named", "A", "--named", "smallest-sc", "--dual", "--flips", "--trees"]
    args += ["--belt-length", "4"]
    first, second = tmp_path / "a.svg", tmp_path / "b.svg"
    assert _run("draw", *args, "-o", first, "-q").exit_code == 0
    assert _run("draw", *args, "-o", second, "-q").exit_code == 0
    assert first.read_bytes() == second.read_bytes()
    assert b"<svg" in first.read_bytes()


@pytest.mark.parametrize("fmt", ["png", "pdf"])
def test_other_formats(tmp_path, fmt):
    figure = tmp_path / f"f.{fmt}"
    assert _run("draw", "--named", "cube", "--dual", "-o", figure, "-q").exit_code == 0
    assert figure.read_bytes()[:4] == {"png": b"\x89PNG", "pdf": b"%PDF"}[fmt]


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["polytopes.txt", "--id", "nope"], "no grain with id nope in"),
        (["bad-grains.txt", "--id", "trihedron"], "grain trihedron is degenerate"),
        (["bad-grains.txt", "--id", "asymmetric"], "grain asymmetric is invalid"),
        (["polytopes.txt", "--id", "cube", "--outer-face", "6"], "has 6 faces, 0 to 5"),
        (["--named", "cube", "--belt-length", "4", "--belt", "4"], "has 3 belts of 4 faces"),
        (["g.parquet", "--id", "cube"], "has no Weinberg vector"),
        (["polytopes.txt", "--id", "cube", "--3d"], "has no corner positions"),
    ],
)
def test_bad_input_exits_1_and_writes_nothing(tmp_path, args, message):
    (tmp_path / "in").mkdir()
    for name in ("polytopes.txt", "bad-grains.txt"):
        shutil.copy(EXAMPLES / name, tmp_path / "in")
    table = tmp_path / "in" / "g.parquet"
    assert _run("classify", EXAMPLES / "polytopes.txt", "--no-types", "-o", table).exit_code == 0
    args = [str(tmp_path / "in" / a) if a.endswith((".txt", ".parquet")) else a for a in args]
    out = tmp_path / "out"
    out.mkdir()
    result = _run("draw", *args, "-o", out / "f.svg", "--data", out / "f.json")
    assert result.exit_code == 1
    assert message in result.stderr
    assert len(result.stderr.strip().splitlines()) == 1
    assert list(out.iterdir()) == []


@pytest.mark.parametrize(
    "args",
    [
        ["-o", "f.svg"],  # nothing to draw
        ["--named", "cube", "-o", "f.jpg"],
        ["--weinberg", "(1,2,3,1)", "-o", "f.svg"],
        ["--weinberg", "(1,2,3,4,1,4,5,6,1,6,7,2,7,8,3,8,5,8,7,6,5,3,4,2,1)", "-o", "f.svg"],
        ["--named", "cube", "--belt", "1", "-o", "f.svg"],  # a belt of no length
        ["--named", "cube", "--belt-length", "2", "-o", "f.svg"],
        ["x.txt", "--named", "cube", "-o", "f.svg"],  # an input, but no grain of it chosen
        ["--id", "1", "-o", "f.svg"],  # an id, but no input
        ["--named", "octahedron", "-o", "f.svg"],
        ["--named", "cube", "--3d", "-o", "f.svg"],  # no corner positions to draw it from
    ],
)
def test_usage_errors_exit_2(tmp_path, args):
    result = _run("draw", *[str(tmp_path / a) if a.startswith("f.") else a for a in args])
    assert result.exit_code == 2, result.output
    assert not list(tmp_path.iterdir())
