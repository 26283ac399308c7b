"""Hypothesis strategies: random triangulations of the sphere and ways to rewrite them."""

from __future__ import annotations

from hypothesis import strategies as st


def rotation_lists(faces: set[tuple[int, int, int]], n: int) -> list[list[int]]:
    """Rotation lists from oriented triangles: (v, x, y) means y follows x around v."""
    following: list[dict[int, int]] = [{} for _ in range(n)]
    for a, b, c in faces:
        following[a][b] = c
        following[b][c] = a
        following[c][a] = b
    lists = []
    for v in range(n):
        start = min(following[v])
        order = [start]
        while following[v][order[-1]] != start:
            order.append(following[v][order[-1]])
        lists.append(order)
    return lists


@st.composite
def triangulations(
    draw, max_vertices: int = 16, max_flips: int = 40, min_vertices: int = 4
) -> list[list[int]]:
    """A random triangulation: the tetrahedron, random stackings, then random edge flips.

    Stacking alone gives stacked triangulations; flips reach every triangulation with the same
    number of vertices (Wagner), so all classes turn up.
    """
    faces = {(0, 1, 2), (0, 2, 3), (0, 3, 1), (1, 3, 2)}
    n = draw(st.integers(min_vertices, max_vertices))
    for v in range(4, n):
        a, b, c = draw(st.sampled_from(sorted(faces)))
        faces.remove((a, b, c))
        faces |= {(a, b, v), (b, c, v), (c, a, v)}
    for _ in range(draw(st.integers(0, max_flips))):
        a, b, c = draw(st.sampled_from(sorted(faces)))
        other = next(f for f in faces if _has_directed_edge(f, b, a))
        d = _third(other, b, a)
        edges = {frozenset(e) for f in faces for e in ((f[0], f[1]), (f[1], f[2]), (f[2], f[0]))}
        degree = {v: sum(v in e for e in edges) for v in (a, b)}
        if frozenset((c, d)) in edges or min(degree.values()) <= 3:
            continue  # the flip would make a double edge or a vertex of degree 2
        faces -= {(a, b, c), other}
        faces |= {_rotate((c, a, d)), _rotate((d, b, c))}
        faces = {_rotate(f) for f in faces}
    return rotation_lists(faces, n)


def _rotate(f: tuple[int, int, int]) -> tuple[int, int, int]:
    k = f.index(min(f))
    return f[k:] + f[:k]


def _has_directed_edge(f: tuple[int, int, int], x: int, y: int) -> bool:
    return any(f[i] == x and f[(i + 1) % 3] == y for i in range(3))


def _third(f: tuple[int, int, int], x: int, y: int) -> int:
    return next(v for v in f if v not in (x, y))


def relabel(lists: list[list[int]], perm: list[int]) -> list[list[int]]:
    """Face ``v`` becomes face ``perm[v]``."""
    out: list[list[int]] = [[] for _ in lists]
    for v, nbrs in enumerate(lists):
        out[perm[v]] = [perm[x] for x in nbrs]
    return out


def mirror(lists: list[list[int]]) -> list[list[int]]:
    """The mirror image: every cyclic order reversed."""
    return [list(reversed(nbrs)) for nbrs in lists]


def bipyramid(k: int) -> list[list[int]]:
    """The k-gonal bipyramid (the dual of the k-gonal prism): k + 2 vertices, cyclic lists."""
    north, south = k, k + 1
    ring = [[(i - 1) % k, north, (i + 1) % k, south] for i in range(k)]
    return [*ring, list(range(k)), list(reversed(range(k)))]


def planar_code_record(lists: list[list[int]]) -> bytes:
    """A 1-byte planar_code record from 0-based neighbour lists."""
    return bytes([len(lists)] + [x for nbrs in lists for x in [*(y + 1 for y in nbrs), 0]])
