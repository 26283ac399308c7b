"""`grainclass perturb`: edge flips (T1 moves) in the dual triangulation, the paper's
topological edge errors (Sec. "Grain Classes and Error Analysis").

Expected values come from the paper's own example (fig. grains_with_6_faces), from a hand
derivation of the (2,2,2) polytope below, and from the plain-Python oracle
``reference.admissible_flips`` / ``reference.flip``, which works on oriented triangle sets."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import reference
from grainclass import GrainBatch, classify
from grainclass.perturb import all_flips, perturb
from strategies import mirror, relabel, triangulations

# The cube, as in examples/polytopes.txt: its dual is the octahedron, faces 0|5, 1|3 and 2|4
# opposite.
CUBE = [[1, 2, 3, 4], [0, 4, 5, 2], [0, 1, 5, 3], [0, 2, 5, 4], [0, 3, 5, 1], [1, 4, 3, 2]]
# The cube with edge 0-1 flipped, by hand: faces 0 and 1 meet faces 2 and 4 at the ends of their
# edge (the common neighbours of 0 and 1), so 0 and 1 lose each other and 2 and 4 gain each
# other, 4 going in between 0 and 1 in 2's list and 2 in between 1 and 0 (which wrap around) in
# 4's. Sides 3, 3, 5, 4, 5, 4: the p-vector (2,2,2). Its 12 edges: 0-2 0-3 0-4 1-2 1-4 1-5
# touch a triangle (0 or 1) and are not admissible; of the others, 3-5 has the apexes 2 and 4,
# which meet: not admissible. Admissible: 2-3 (apexes 5, 0), 2-4 (0, 1: the cube back),
# 2-5 (1, 3), 3-4 (5, 0), 4-5 (3, 1).
P222 = [[2, 3, 4], [4, 5, 2], [0, 4, 1, 5, 3], [0, 2, 5, 4], [0, 3, 5, 1, 2], [1, 4, 3, 2]]
P222_ADMISSIBLE = {(2, 3), (2, 4), (2, 5), (3, 4), (4, 5)}
TETRAHEDRON = [[1, 2, 3], [0, 3, 2], [0, 1, 3], [0, 2, 1]]


def _weinberg(lists: list[list[int]]) -> str:
    return classify(GrainBatch.from_lists([lists])).to_pylist()[0]["weinberg"]


def _edges(lists: list[list[int]]) -> set[tuple[int, int]]:
    return {(min(v, x), max(v, x)) for v, nbrs in enumerate(lists) for x in nbrs}


def _lists(batch: GrainBatch, g: int = 0) -> list[list[int]]:
    f0, f1 = batch.face_offsets[g], batch.face_offsets[g + 1]
    return [
        batch.neighbors[batch.nbr_offsets[f] : batch.nbr_offsets[f + 1]].tolist()
        for f in range(f0, f1)
    ]


def _grains(batch: GrainBatch) -> list[list[list[int]]]:
    return [_lists(batch, g) for g in range(len(batch))]


def _triangles(lists: list[list[int]]) -> set[frozenset[int]]:
    return {frozenset(t) for t in reference.oriented_faces(lists)}


# The paper's example (fig. grains_with_6_faces) ------------------------------------------------


def test_the_hand_derived_grain_is_the_222_polytope_and_the_oracle_agrees():
    assert [len(f) for f in P222].count(3) == 2
    assert sorted(len(f) for f in P222) == [3, 3, 4, 4, 5, 5]
    assert reference.flip(CUBE, 0, 1) == reference.oriented_faces(P222)
    assert len(reference.admissible_flips(CUBE)) == 12
    assert set(reference.admissible_flips(P222)) == P222_ADMISSIBLE


# Flips against the oracle ------------------------------------------------------------------------


def _degrees(lists: list[list[int]]) -> list[int]:
    return [len(f) for f in lists]


@settings(max_examples=150, deadline=None)
@given(triangulations(max_vertices=14))
def test_all_flips_are_the_oracles_and_change_the_p_vector_by_the_flip_rule(lists):
    expected = reference.admissible_flips(lists)
    result = all_flips(GrainBatch.from_lists([lists], grain_id=["g"]))
    got = result.batch
    assert result.counts.tolist() == [len(expected)]
    assert len(got) == len(expected)
    edges = got.attributes["flipped_edge"]
    new_edges = got.attributes["new_edge"]
    assert got.attributes["from_grain"] == ["g"] * len(expected)
    for j, lists_after in enumerate(_grains(got)):
        a, b = map(int, edges[j].split("-"))
        c, d = expected[(a, b)]
        assert new_edges[j] == f"{min(c, d)}-{max(c, d)}"
        assert reference.oriented_faces(lists_after) == reference.flip(lists, a, b)
        # A and B lose a side, C and D gain one, every other face keeps its sides.
        change = np.array(_degrees(lists_after)) - np.array(_degrees(lists))
        rule = np.zeros(len(lists), int)
        rule[[a, b]] -= 1
        rule[[c, d]] += 1
        assert change.tolist() == rule.tolist()
    assert sorted(tuple(map(int, e.split("-"))) for e in edges) == sorted(expected)


@settings(max_examples=100, deadline=None)
@given(triangulations(max_vertices=14), st.integers(1, 6), st.integers(0, 2**64 - 1))
def test_random_flips_give_ok_grains_with_as_many_faces_and_edges(lists, flips, seed):
    batch = GrainBatch.from_lists([lists] * 3)
    result = perturb(batch, flips, seed)
    rows = classify(result.batch).to_pylist()
    for g, row in enumerate(rows):
        assert row["status"] == "ok"
        assert row["n_faces"] == len(lists)
        sides = sum(k * count for k, count in enumerate(row["p_vector"], start=3))
        assert sides // 2 == len(_edges(lists))  # each edge is a side of two faces
        made = int(result.flips[g])
        assert made == flips or not reference.admissible_flips(_lists(result.batch, g))


@settings(max_examples=100, deadline=None)
@given(triangulations(max_vertices=14), st.integers(0, 2**64 - 1))
def test_one_random_flip_is_one_of_the_oracles(lists, seed):
    expected = reference.admissible_flips(lists)
    result = perturb(GrainBatch.from_lists([lists]), 1, seed)
    after = _lists(result.batch)
    if not expected:
        assert after == lists
        assert result.flips.tolist() == [0]
        return
    (removed,) = _edges(lists) - _edges(after)
    assert removed in expected
    assert reference.oriented_faces(after) == reference.flip(lists, *removed)


@settings(max_examples=100, deadline=None)
@given(triangulations(max_vertices=14), st.randoms(use_true_random=False))
def test_flips_commute_with_relabelling_and_mirroring(lists, rng):
    perm = list(range(len(lists)))
    rng.shuffle(perm)

    def flips_of(grain: list[list[int]]) -> dict[tuple[int, int], set]:
        got = all_flips(GrainBatch.from_lists([grain])).batch
        edges = [tuple(map(int, e.split("-"))) for e in got.attributes["flipped_edge"]]
        return dict(zip(edges, (reference.oriented_faces(g) for g in _grains(got)), strict=True))

    plain = flips_of(lists)
    relabelled = flips_of(relabel(lists, perm))
    mirrored = flips_of(mirror(lists))
    assert len(relabelled) == len(mirrored) == len(plain)
    for (a, b), faces in plain.items():
        after = reference.lists_from_faces(faces, len(lists))
        image = (min(perm[a], perm[b]), max(perm[a], perm[b]))
        assert relabelled[image] == reference.oriented_faces(relabel(after, perm))
        assert mirrored[(a, b)] == reference.oriented_faces(mirror(after))


@settings(max_examples=50, deadline=None)
@given(triangulations(min_vertices=5, max_vertices=14), st.randoms(use_true_random=False))
def test_lists_in_no_cyclic_order_flip_as_the_triangulation_they_stand_for(lists, rng):
    shuffled = [rng.sample(f, len(f)) for f in lists]
    got = all_flips(GrainBatch.from_lists([shuffled])).batch
    expected = reference.admissible_flips(lists)
    edges = [tuple(map(int, e.split("-"))) for e in got.attributes["flipped_edge"]]
    assert sorted(edges) == sorted(expected)
    for (a, b), after in zip(edges, _grains(got), strict=True):
        flipped = {frozenset(t) for t in reference.flip(lists, a, b)}
        assert _triangles(after) == flipped
        assert classify(GrainBatch.from_lists([after])).column("status").to_pylist() == ["ok"]


# The random choice -------------------------------------------------------------------------------


def chi2_sf(statistic: float, df: int) -> float:
    """P(X >= statistic) for X chi-square with ``df`` degrees of freedom: the regularized upper
    incomplete gamma function Q(df/2, statistic/2), 1 minus its power series (plain Python;
    scipy is no dependency)."""
    s, x = df / 2, statistic / 2
    if x <= 0:
        return 1.0
    term = total = 1 / s
    k = 0
    while term > total * 1e-17:
        k += 1
        term *= x / (s + k)
        total += term
    return max(0.0, 1 - math.exp(s * math.log(x) - x - math.lgamma(s)) * total)


def chi2(counts: list[int]) -> float:
    """Pearson's statistic of counts against equal expectations."""
    expected = sum(counts) / len(counts)
    return sum((c - expected) ** 2 / expected for c in counts)


@pytest.mark.parametrize(
    ("df", "critical"),
    [(4, 18.467), (11, 31.264), (29, 58.301), (50, 86.661)],  # tabulated, p = 0.001
)
def test_chi2_sf_gives_the_tabulated_critical_values(df, critical):
    assert chi2_sf(critical, df) == pytest.approx(0.001, rel=2e-3)


def _flipped_edge(before: list[list[int]], after: list[list[int]]) -> tuple[int, int]:
    (edge,) = _edges(before) - _edges(after)
    return edge


def test_over_many_seeds_the_flipped_edge_is_uniform_among_the_admissible():
    batch = GrainBatch.from_lists([P222])
    counts = dict.fromkeys(sorted(P222_ADMISSIBLE), 0)
    for seed in range(2500):
        counts[_flipped_edge(P222, _lists(perturb(batch, 1, seed).batch))] += 1
    assert chi2_sf(chi2(list(counts.values())), len(counts) - 1) > 0.001


def test_the_second_flip_is_uniform_among_the_edges_admissible_after_the_first():
    """Cube, two flips: the first edge uniform among the cube's 12, the second among the 5
    of the (2,2,2) polytope the first made (a chi-square per first edge, summed)."""
    batch = GrainBatch.from_lists([CUBE])
    seconds: dict[tuple[int, int], dict[tuple[int, int], int]] = {}
    for seed in range(3000):
        once = _lists(perturb(batch, 1, seed).batch)  # the same stream: the first of two flips
        twice = _lists(perturb(batch, 2, seed).batch)
        first = _flipped_edge(CUBE, once)
        admissible = reference.admissible_flips(once)
        assert len(admissible) == 5
        second = seconds.setdefault(first, dict.fromkeys(admissible, 0))
        (edge,) = _edges(once) - _edges(twice)
        second[edge] += 1
    firsts = [sum(c.values()) for c in seconds.values()]
    assert len(firsts) == 12
    assert chi2_sf(chi2(firsts), 11) > 0.001
    pooled = sum(chi2(list(c.values())) for c in seconds.values())
    assert chi2_sf(pooled, 12 * 4) > 0.001


def test_grains_at_different_positions_draw_apart():
    """One seed, the same grain 2500 times: each position its own stream, uniform together."""
    batch = GrainBatch.from_lists([P222] * 2500)
    out = perturb(batch, 1, seed=11).batch
    counts = dict.fromkeys(sorted(P222_ADMISSIBLE), 0)
    for after in _grains(out):
        counts[_flipped_edge(P222, after)] += 1
    assert chi2_sf(chi2(list(counts.values())), 4) > 0.001
