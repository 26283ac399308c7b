"""A slow, plain-Python oracle that follows the paper's appendix literally.

It shares no code with the kernels: faces are tracked as explicit triangle sets, degree-3
vertices are removed one at a time in a caller-chosen order, empty triangles and 4-belts come
from scanning all 3- and 4-subsets, sides of a belt from networkx, and truncation trees from
replaying the stackings forwards (the parent of a stacked vertex is whoever created the triangle
it was stacked into).
"""

from __future__ import annotations

import itertools
import random

import networkx as nx


def oriented_faces(lists: list[list[int]]) -> set[tuple[int, int, int]]:
    """Triangles (v, x, y) with y after x around v, rotated to start at their smallest vertex."""
    faces = set()
    for v, nbrs in enumerate(lists):
        for i, x in enumerate(nbrs):
            y = nbrs[(i + 1) % len(nbrs)]
            tri = (v, x, y)
            k = tri.index(min(tri))
            faces.add(tri[k:] + tri[:k])
    return faces


def _tree_string(node, children) -> str:
    return "(" + "".join(sorted(_tree_string(c, children) for c in children[node])) + ")"


def classify(lists: list[list[int]], seed: int = 0) -> dict:
    """Classify a triangulation given by consistently oriented rotation lists."""
    n = len(lists)
    graph = nx.Graph((v, x) for v, nbrs in enumerate(lists) for x in nbrs)
    faces = {frozenset(f) for f in oriented_faces(lists)}
    assert len(faces) == 2 * n - 4
    assert graph.number_of_edges() == 3 * n - 6
    degrees = [len(nbrs) for nbrs in lists]
    p_vector = tuple(degrees.count(d) for d in range(3, max(degrees) + 1))
    result = {"n_faces": n, "p_vector": p_vector}

    rng = random.Random(seed)
    removed: list[tuple[int, frozenset]] = []
    current = graph.copy()
    while current.number_of_nodes() > 4:
        cubic = [v for v in current if current.degree(v) == 3]
        if not cubic:
            break
        v = rng.choice(cubic)
        link = frozenset(current[v])
        faces -= {f for f in faces if v in f}
        faces.add(link)
        current.remove_node(v)
        removed.append((v, link))
    t = len(removed)
    result |= {"truncations": t, "fundamental_faces": n - t}
    if current.number_of_nodes() == 4:
        return result | {
            "family": "stacked",
            "class": "stacked",
            "trees": None,
            "depth": None,
            "round_k": n - 4,
            "split_k": None,
            "split_m": None,
            "belts4": None,
            "penalty": None,
        }
    empty = any(
        all(current.has_edge(a, b) for a, b in itertools.combinations(tri, 2))
        and frozenset(tri) not in faces
        for tri in itertools.combinations(current.nodes, 3)
    )
    family = "sc" if empty else "flag"

    # Replay the stackings forwards to grow the truncation trees.
    creator = dict.fromkeys(faces)
    parent, children = {}, {v: [] for v, _ in removed}
    for v, link in reversed(removed):
        parent[v] = creator.pop(link)
        if parent[v] is not None:
            children[parent[v]].append(v)
        for a, b in itertools.combinations(link, 2):
            creator[frozenset((v, a, b))] = v
    roots = [v for v in parent if parent[v] is None]
    trees = "+".join(sorted((_tree_string(r, children) for r in roots), key=lambda s: (len(s), s)))

    def height(v):
        return 1 + max((height(c) for c in children[v]), default=0)

    depth = max((height(r) for r in roots), default=0)
    if t == 0:
        cls = family
    elif t == 1:
        cls = family + "+1"
    elif family == "sc":
        cls = "sc>=2"
    elif t == 2:
        cls = "flag+1+1" if len(roots) == 2 else "flag+2"
    else:
        cls = "flag>=3"
    result |= {
        "family": family,
        "class": cls,
        "trees": trees,
        "depth": depth,
        "round_k": t if family == "flag" else None,
    }
    if cls != "flag":
        return result | {"split_k": None, "split_m": None, "belts4": None, "penalty": None}

    belts, weight, split_k = 0, 0, 0
    for quad in itertools.combinations(graph.nodes, 4):
        induced = graph.subgraph(quad)
        if induced.number_of_edges() != 4 or any(d != 2 for _, d in induced.degree()):
            continue  # not a chordless 4-cycle
        rest = graph.subgraph(set(graph) - set(quad))
        sizes = [len(c) for c in nx.connected_components(rest)]
        assert len(sizes) == 2
        k = min(sizes)
        belts += 1
        weight += k * (n - k - 4)
        split_k = max(split_k, k)
    return result | {
        "split_k": split_k,
        "split_m": n - 4 - split_k,
        "belts4": belts,
        "penalty": n * weight,
    }


def weinberg(lists: list[list[int]]) -> tuple[tuple[int, ...], int, int]:
    """(canonical code, symmetry, chirality) by brute force: every start edge, both turns.

    ``lists`` are rotation lists read as counter-clockwise seen from outside. Corners are the
    triangles (v, x, y); leaving one across side (a, b) leads to the other triangle on a-b.
    """
    triangles = sorted(oriented_faces(lists))
    on_side = {}
    for t, (a, b, c) in enumerate(triangles):
        for side in ((a, b), (b, c), (c, a)):
            on_side[side] = t
    # Around triangle (a, b, c): the corners across sides a-b, b-c, c-a, counter-clockwise.
    around = [[on_side[(b, a)], on_side[(c, b)], on_side[(a, c)]] for a, b, c in triangles]
    codes = []
    for start in range(len(triangles)):
        for first in range(3):
            for turn in (-1, 1):
                codes.append((_walk(around, start, first, turn), turn))
    best = min(code for code, _ in codes)
    turns = [turn for code, turn in codes if code == best]
    # -1 when only right-turning walks (turn +1: the next side counter-clockwise) reach it.
    chirality = 0 if len(set(turns)) == 2 else (1 if turns[0] == -1 else -1)
    return best, len(turns), chirality


def _walk(around, start, first, turn) -> tuple[int, ...]:
    labels = {start: 1}
    used = set()
    code = [1]
    cur, k = start, first
    for _ in range(3 * len(around)):
        used.add((cur, k))
        nxt = around[cur][k]
        back = around[nxt].index(cur)
        if nxt not in labels:
            labels[nxt] = len(labels) + 1
            k = (back + turn) % 3
        elif (nxt, back) not in used:
            k = back
        else:  # the next unused edge in the turning direction (none after the last step)
            others = ((back + turn) % 3, (back + 2 * turn) % 3)
            k = next((j for j in others if (nxt, j) not in used), back)
        code.append(labels[nxt])
        cur = nxt
    return tuple(code)


def edge_graph(lists: list[list[int]]) -> nx.Graph:
    """The grain's edge graph: corners (dual triangles) adjacent across a dual edge."""
    triangles = [frozenset(t) for t in oriented_faces(lists)]
    graph = nx.Graph()
    graph.add_nodes_from(range(len(triangles)))
    for i, j in itertools.combinations(range(len(triangles)), 2):
        if len(triangles[i] & triangles[j]) == 2:
            graph.add_edge(i, j)
    return graph


def lists_from_faces(faces: set[tuple[int, int, int]], n: int) -> list[list[int]]:
    """Rotation lists from oriented triangles (v, x, y): y follows x around v; each list starts
    at its smallest neighbour."""
    following: list[dict[int, int]] = [{} for _ in range(n)]
    for a, b, c in faces:
        following[a][b] = c
        following[b][c] = a
        following[c][a] = b
    lists = []
    for v in range(n):
        order = [min(following[v])]
        while following[v][order[-1]] != order[0]:
            order.append(following[v][order[-1]])
        lists.append(order)
    return lists


def admissible_flips(lists: list[list[int]]) -> dict[tuple[int, int], tuple[int, int]]:
    """Every admissible edge flip of a triangulation given by rotation lists turning one way,
    by the paper's rule, from its oriented triangles alone: edge A-B (A < B) lies on the
    triangles (A, B, C) and (B, A, D); it is admissible when A and B have degree 4 or more and
    C and D are not adjacent. Returns {(A, B): (C, D)}."""
    faces = oriented_faces(lists)
    third = {}
    for tri in faces:
        for i in range(3):
            third[(tri[i], tri[(i + 1) % 3])] = tri[(i + 2) % 3]
    adjacent = {(v, x) for v, nbrs in enumerate(lists) for x in nbrs}
    flips = {}
    for (a, b), c in third.items():
        if a > b:
            continue
        d = third[(b, a)]
        if len(lists[a]) >= 4 and len(lists[b]) >= 4 and (c, d) not in adjacent:
            flips[(a, b)] = (c, d)
    return flips


def flip(lists: list[list[int]], a: int, b: int) -> set[tuple[int, int, int]]:
    """The oriented triangles after flipping edge A-B: (A, B, C) and (B, A, D) give way to
    (A, D, C) and (D, B, C), which turn the same way around the quadrilateral A-D-B-C."""
    faces = oriented_faces(lists)
    (abc,) = [t for t in faces if _directed(t, a, b)]
    (bad,) = [t for t in faces if _directed(t, b, a)]
    c = next(v for v in abc if v not in (a, b))
    d = next(v for v in bad if v not in (a, b))
    return (faces - {abc, bad}) | {_smallest_first((a, d, c)), _smallest_first((d, b, c))}


def _directed(tri: tuple[int, int, int], x: int, y: int) -> bool:
    return any(tri[i] == x and tri[(i + 1) % 3] == y for i in range(3))


def _smallest_first(tri: tuple[int, int, int]) -> tuple[int, int, int]:
    k = tri.index(min(tri))
    return tri[k:] + tri[:k]


def belt_profile(
    lists: list[list[int]], longest: int = 6
) -> dict[int, tuple[int, int | None, int]]:
    """``{l: (belts, split_k, penalty)}`` for l = 3..longest by brute force: every l-subset of
    vertices whose induced subgraph is one cycle (for l = 3 only those whose removal leaves
    two sides: a face leaves one), its sides from networkx; split_k is the largest smaller
    side, penalty n times the sum of k (n - l - k). Without an l-belt, split_k is 0 (the
    paper's Def. of split type: 0:l:(n - l)) where n >= l, and None where n < l: a disc of
    n - l < 0 faces is none, and the definition asks k <= m."""
    n = len(lists)
    graph = nx.Graph((v, x) for v, nbrs in enumerate(lists) for x in nbrs)
    profile = {}
    for length in range(3, longest + 1):
        belts = penalty = 0
        split_k = 0 if n >= length else None
        for subset in itertools.combinations(range(n), length):
            induced = graph.subgraph(subset)
            if induced.number_of_edges() != length or any(d != 2 for _, d in induced.degree()):
                continue
            if not nx.is_connected(induced):
                continue
            rest = graph.subgraph(set(graph) - set(subset))
            sizes = [len(c) for c in nx.connected_components(rest)]
            if len(sizes) < 2:
                continue
            assert len(sizes) == 2
            k = min(sizes)
            belts += 1
            split_k = max(split_k, k)
            penalty += n * k * (n - length - k)
        profile[length] = (belts, split_k, penalty)
    return profile
