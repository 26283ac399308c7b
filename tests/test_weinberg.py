"""Weinberg vectors, symmetry and chirality against the issue's facts, a brute-force oracle and
networkx automorphism counts."""

from __future__ import annotations

import os

import numpy as np
import pyarrow as pa
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from networkx.algorithms.isomorphism import GraphMatcher

import reference
from conftest import EXAMPLES
from grainclass import GrainBatch, classify, read_dataset
from strategies import mirror, relabel, triangulations
from test_properties import _read_planar_code

CUBE_CODE = "(1,2,3,4,1,4,5,6,1,6,7,2,7,8,3,8,5,8,7,6,5,4,3,2,1)"


def _rows(grains):
    return classify(GrainBatch.from_lists(grains)).to_pylist()


@pytest.fixture(scope="module")
def examples() -> dict[str, dict]:
    table = classify(next(read_dataset(str(EXAMPLES / "polytopes.txt"))))
    return {row["grain_id"]: row for row in table.to_pylist()}


def test_cube_code_and_symmetry(examples):
    assert examples["cube"]["weinberg"] == CUBE_CODE
    assert examples["cube"]["symmetry"] == 48


@pytest.mark.parametrize(
    ("grain", "order"), [("tetrahedron", 24), ("dodecahedron", 120), ("kelvin", 48)]
)
def test_symmetry_orders_of_regular_grains(examples, grain, order):
    assert examples[grain]["symmetry"] == order
    assert examples[grain]["chirality"] == 0


def test_relabelled_dodecahedron_has_the_same_code(examples):
    # weaire_phelan_12 is the dodecahedron with its faces numbered differently.
    assert examples["weaire_phelan_12"]["weinberg"] == examples["dodecahedron"]["weinberg"]


@pytest.mark.skipif(
    os.environ.get("NUMBA_DISABLE_JIT") != "1",
    reason="a compiled kernel keeps the stamp limit it was compiled with",
)
def test_codes_stay_the_same_when_the_walk_stamps_start_over(plantri_output, monkeypatch):
    """The walks' table is cleared when their stamps reach a limit, after 2**30 walks; with a
    limit of five walks it is cleared every few grains, and no code may change."""
    from grainclass._kernels import weinberg

    batch = next(read_dataset(str(plantri_output(8))))
    expected = classify(batch).column("weinberg")
    monkeypatch.setattr(weinberg, "_MAX_STAMP", 5)
    assert classify(batch).column("weinberg").equals(expected)


@pytest.mark.parametrize("n", range(4, 12))
def test_every_plantri_triangulation_has_its_own_code(plantri_output, n):
    table = pa.concat_tables(classify(b) for b in read_dataset(str(plantri_output(n))))
    codes = table.column("weinberg").to_pylist()
    assert None not in codes
    assert len(set(codes)) == len(codes)


@pytest.mark.parametrize("n", range(4, 11))
def test_symmetry_equals_automorphisms_of_the_edge_graph(plantri_output, n):
    graphs = _read_planar_code(plantri_output(n).read_bytes())
    for lists, row in zip(graphs, _rows(graphs), strict=True):
        graph = reference.edge_graph(lists)
        automorphisms = sum(1 for _ in GraphMatcher(graph, graph).isomorphisms_iter())
        assert row["symmetry"] == automorphisms


@pytest.mark.parametrize("n", range(4, 10))
def test_codes_agree_with_brute_force_on_every_triangulation(plantri_output, n):
    graphs = _read_planar_code(plantri_output(n).read_bytes())
    for lists, row in zip(graphs, _rows(graphs), strict=True):
        code, symmetry, chirality = reference.weinberg(lists)
        assert row["weinberg"] == "(" + ",".join(map(str, code)) + ")"
        assert (row["symmetry"], row["chirality"]) == (symmetry, chirality)


def _walk_beginnings(lists: list[list[int]]):
    """For every start (corner, first edge, turn) of the reference walk: its code and the sizes
    (s, m, q) of the start corner's faces, the one walked first (on the turning side of the
    first edge), the one opposite the first edge, and the first edge's other face."""
    triangles = sorted(reference.oriented_faces(lists))
    on_side = {
        side: t for t, (a, b, c) in enumerate(triangles) for side in ((a, b), (b, c), (c, a))
    }
    around = [[on_side[(b, a)], on_side[(c, b)], on_side[(a, c)]] for a, b, c in triangles]
    for t, faces in enumerate(triangles):
        for first in range(3):
            on_edge = (faces[first], faces[(first + 1) % 3])
            opposite = len(lists[faces[(first + 2) % 3]])
            for turn in (-1, 1):
                walked, other = on_edge if turn > 0 else on_edge[::-1]
                code = reference._walk(around, t, first, turn)
                yield code, (len(lists[walked]), opposite, len(lists[other]))


def _predicted_beginning(s: int, m: int, q: int) -> list[int]:
    """What the kernel's choice of starts assumes: round the first face (1..s, back to 1), back
    one edge (s), round the opposite face (m - 2 new labels, then 1), back one edge, and round
    the first edge's other face (q - 3 new labels, then 2)."""
    return [*range(1, s + 1), 1, s, *range(s + 1, s + m - 1), 1, s + m - 2,
            *range(s + m - 1, s + m + q - 4), 2]  # fmt: skip


@pytest.mark.parametrize("n", range(4, 10))
def test_walks_begin_as_the_start_corners_faces_say(plantri_output, n):
    for lists in _read_planar_code(plantri_output(n).read_bytes()):
        for code, sizes in _walk_beginnings(lists):
            beginning = _predicted_beginning(*sizes)
            assert list(code[: len(beginning)]) == beginning


@settings(max_examples=40, deadline=None)
@given(triangulations(max_vertices=16))
def test_random_walks_begin_as_the_start_corners_faces_say(lists):
    for code, sizes in _walk_beginnings(lists):
        beginning = _predicted_beginning(*sizes)
        assert list(code[: len(beginning)]) == beginning


@settings(max_examples=60, deadline=None)
@given(triangulations(max_vertices=18), st.randoms(use_true_random=False))
def test_relabelling_keeps_and_mirroring_flips_chirality(lists, rng):
    perm = list(range(len(lists)))
    rng.shuffle(perm)
    mixed = [
        list(reversed(nbrs)) if f and rng.random() < 0.5 else nbrs for f, nbrs in enumerate(lists)
    ]
    original, relabelled, mirrored, mixed_row = _rows(
        [lists, relabel(lists, perm), mirror(lists), mixed]
    )
    code, symmetry, chirality = reference.weinberg(lists)
    assert original["weinberg"] == "(" + ",".join(map(str, code)) + ")"
    assert (original["symmetry"], original["chirality"]) == (symmetry, chirality)
    keys = ("weinberg", "symmetry", "chirality")
    assert [relabelled[k] for k in keys] == [original[k] for k in keys]
    assert [mixed_row[k] for k in keys] == [original[k] for k in keys]  # face 0 sets the sense
    assert mirrored["weinberg"] == original["weinberg"]
    assert mirrored["symmetry"] == original["symmetry"]
    assert mirrored["chirality"] == -original["chirality"]


@settings(max_examples=6, deadline=None)
@given(
    triangulations(min_vertices=55, max_vertices=90, max_flips=150),
    st.randoms(use_true_random=False),
)
def test_large_grains_agree_with_brute_force(lists, rng):
    # 55 faces or more: labels of three digits (written by the loop), and beyond 64 faces the
    # general path; lists turned at random make the rotations be recovered first.
    mixed = [list(reversed(nbrs)) if rng.random() < 0.5 else nbrs for nbrs in lists]
    (row,) = _rows([mixed])
    code, symmetry, chirality = reference.weinberg(lists)
    assert max(code) >= 100
    assert row["weinberg"] == "(" + ",".join(map(str, code)) + ")"
    assert row["chirality"] == (chirality if mixed[0] == lists[0] else -chirality)  # face 0's sense
    assert row["symmetry"] == symmetry


def _prism(k: int) -> list[list[int]]:
    """The k-gonal prism's face lists, turning one way: k quadrilaterals, then the two k-gons."""
    top, bottom = k, k + 1
    quads = [[top, (i - 1) % k, bottom, (i + 1) % k] for i in range(k)]
    return [*quads, list(range(k)), list(reversed(range(k)))]


@given(st.integers(min_value=63, max_value=80), st.randoms(use_true_random=False))
@settings(max_examples=8, deadline=None)
def test_prisms_beyond_the_bitsets_keep_their_lists_when_they_turn_one_way(k, rng):
    """Beyond 64 faces the general path validates; lists that already turn one way are the
    rotation lists as they are (no recovery), and lists turned at random give the same row. A
    k-prism's symmetry is its group D_kh, of order 4k, with mirrors: achiral."""
    from grainclass.classification import _classify_csr

    one_way = _prism(k)
    turned = [list(reversed(f)) if rng.random() < 0.5 else f for f in one_way]
    turned[0] = one_way[0]  # face 0 keeps its sense: the code's orientation is face 0's
    batch = GrainBatch.from_lists([one_way, turned])
    kept = _classify_csr(batch, 64, strings=True).consistent
    assert list(kept) == [True, turned == one_way]
    first, second = classify(batch).to_pylist()
    assert (first["n_faces"], first["symmetry"], first["chirality"]) == (k + 2, 4 * k, 0)
    assert {**first, "grain_id": None} == {**second, "grain_id": None}


def test_papers_grains_a_b_c(plantri_output):
    # The paper's Fig. 15: three 10-face flag grains with p-vector (0,4,4,2). A has two belts of
    # type 3:4:3 and symmetry order 8, B one and order 2, C none and order 2. By the definition
    # (every 4-belt counts) their penalties are 540, 450 and 280.
    table = pa.concat_tables(classify(b) for b in read_dataset(str(plantri_output(10))))
    rows = [r for r in table.to_pylist() if r["class"] == "flag" and r["p_vector"] == [0, 4, 4, 2]]
    got = sorted((r["penalty"], r["symmetry"], r["split_k"]) for r in rows)
    assert got == [(280, 2, 2), (450, 2, 3), (540, 8, 3)]


@given(
    st.lists(
        st.one_of(
            st.none(),  # a grain that is not ok
            st.lists(st.integers(1, 99), min_size=1, max_size=40),
            st.lists(st.integers(1, 12_345), min_size=1, max_size=12),
        ),
        max_size=8,
    )
)
@settings(max_examples=200, deadline=None)
def test_code_strings_are_written_as_python_writes_them(grains):
    # Entries of 1 to 5 digits: codes whose entries all have one or two digits are written by
    # selects, others by a loop per digit.
    from grainclass._kernels.columns import _code_strings

    ok = np.array([g is not None for g in grains], bool)
    lengths = [len(g) if g is not None else 0 for g in grains]
    code_offsets = np.concatenate([[0], np.cumsum(lengths)]).astype(np.int64)
    codes = np.array([v for g in grains if g is not None for v in g], np.int32)
    offsets, data = _code_strings(codes, code_offsets, ok)
    written = [bytes(data[offsets[i] : offsets[i + 1]]).decode() for i in range(len(grains))]
    expected = ["(" + ",".join(map(str, g)) + ")" if g is not None else "" for g in grains]
    assert written == expected
    assert len(data) == offsets[-1]
