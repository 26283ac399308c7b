"""Giant and garbage grains: memory and time that grow with a grain's size, never its square,
and a grain that cannot be handled is a row that says why, not a failed run."""

from __future__ import annotations

import random

import numpy as np
import pyarrow as pa
import pytest
from click.testing import CliRunner
from hypothesis import given, settings

import reference
from conftest import EXAMPLES
from grainclass import GrainBatch, classify, read_dataset
from grainclass.cli import cli
from strategies import bipyramid, triangulations


def _prism(k: int) -> list[list[int]]:
    """The k-gonal prism's face lists, counter-clockwise: k quadrilaterals, then two k-gons."""
    top, bottom = k, k + 1
    quads = [[top, (i - 1) % k, bottom, (i + 1) % k] for i in range(k)]
    return [*quads, list(range(k)), list(reversed(range(k)))]


def _prism_expected(k: int) -> dict:
    """Derived by hand on the dual, the k-gonal bipyramid (ring v_0..v_{k-1}, apexes N, S;
    n = k + 2), for k >= 5. A chordless 4-cycle through N leaves N by two ring vertices and
    may hold no third (N would be a chord), so it is N-v_i-S-v_j with v_i, v_j not adjacent;
    a cycle of ring vertices alone is the whole ring (k > 4). So there are k(k-3)/2 belts, and
    N-v_i-S-v_j, j - i = t + 1, leaves t and k - 2 - t ring vertices on its sides (t = 1..k-3).
    Split type: the most balanced, floor((k-2)/2). Penalty: n times the sum over belts of
    t (k - 2 - t); counting each belt from both its ring vertices v_i (k starts, each with
    every t) counts it twice, so the sum is (k/2) sum_{t=1}^{k-3} t (k-2-t) = (k/2) C(k-1, 3)
    and P = (k+2) k (k-1)(k-2)(k-3) / 12 (k = 5: 70, as tests/hand_derived.py has for the
    pentagonal prism)."""
    split_k = (k - 2) // 2
    return {
        "n_faces": k + 2,
        "class": "flag",
        "belts4": k * (k - 3) // 2,
        "split_k": split_k,
        "split_m": k - 2 - split_k,
        "penalty": (k + 2) * k * (k - 1) * (k - 2) * (k - 3) // 12,
    }


def _row(lists, **kwargs):
    return classify(GrainBatch.from_lists([lists]), **kwargs).to_pylist()[0]


@pytest.mark.parametrize("k", range(5, 13))
def test_small_prisms_agree_with_the_formula_and_the_oracle(k):
    expected = _prism_expected(k)
    oracle = reference.classify(_prism(k))
    assert {key: oracle[key] for key in expected} == expected
    for max_bitset_faces in (64, 0):  # the bitset path and the general path
        row = _row(_prism(k), max_bitset_faces=max_bitset_faces)
        assert {key: row[key] for key in expected} == expected


@pytest.mark.parametrize("k", [63, 64, 100, 257, 1000])
def test_large_prisms_agree_with_the_formula(k):
    row = _row(_prism(k))
    assert {key: row[key] for key in _prism_expected(k)} == _prism_expected(k)
    assert (row["symmetry"], row["chirality"]) == (4 * k, 0)  # D_kh, with mirrors


def test_a_penalty_past_int64_is_null_and_the_belts_are_counted():
    # k = 10,500: (k+2) k (k-1)(k-2)(k-3)/12 is about 1.1e19, past 2^63 - 1.
    k = 10_500
    expected = _prism_expected(k)
    assert expected["penalty"] > 2**63 - 1
    row = _row(_prism(k), types=False)
    assert row["penalty"] is None
    assert (row["belts4"], row["split_k"], row["split_m"]) == (
        expected["belts4"],
        expected["split_k"],
        expected["split_m"],
    )


def _huge_line(fields: int, seed: int = 1) -> str:
    """A line of ``fields`` faces of random neighbour indices: garbage, as a corrupted file
    may hold."""
    rng = random.Random(seed)
    faces = (
        " ".join(str(rng.randrange(fields)) for _ in range(rng.randrange(1, 7)))
        for _ in range(fields)
    )
    return "huge\t" + ";".join(faces) + "\n"


@pytest.fixture(scope="module")
def garbage_among_good(tmp_path_factory):
    """The bundled polytopes, a 200,000-field garbage line, and the polytopes again."""
    good = (EXAMPLES / "polytopes.txt").read_text()
    path = tmp_path_factory.mktemp("huge") / "grains.txt"
    path.write_text(good + _huge_line(200_000) + good)
    return path


def _rows(path, **kwargs):
    return pa.concat_tables(classify(b, **kwargs) for b in read_dataset(str(path))).to_pylist()


def test_a_200000_field_line_among_good_grains_is_one_invalid_row(garbage_among_good):
    good = _rows(EXAMPLES / "polytopes.txt")
    rows = _rows(garbage_among_good)
    assert len(rows) == 2 * len(good) + 1
    huge = rows[len(good)]
    assert huge["grain_id"] == "huge"
    assert huge["status"] == "invalid"
    assert huge["n_faces"] == 200_000
    for got, want in zip(rows[: len(good)] + rows[len(good) + 1 :], good + good, strict=True):
        assert {**got, "source": None} == {**want, "source": None}


def test_a_grain_over_the_memory_limit_is_refused_with_the_limit_named(garbage_among_good):
    rows = _rows(garbage_among_good, grain_memory=10 * 2**20)
    (huge,) = [r for r in rows if r["grain_id"] == "huge"]
    assert huge["status"] == "invalid"
    assert "too large" in huge["error"]
    assert "10.0 MB a grain may take (GRAINCLASS_GRAIN_MEMORY" in huge["error"]
    assert sum(r["status"] == "ok" for r in rows) == len(rows) - 1


def test_the_memory_limit_comes_from_the_environment(monkeypatch):
    from grainclass.memory import grain_memory_limit

    monkeypatch.setenv("GRAINCLASS_GRAIN_MEMORY", "1.5")
    assert grain_memory_limit() == int(1.5 * 2**20)
    monkeypatch.setenv("GRAINCLASS_GRAIN_MEMORY", "")
    assert grain_memory_limit() == 2048 * 2**20


def _stacked_chain(t: int) -> list[list[int]]:
    """The octahedron with t vertices stacked each into a face of the one before: reduced
    one a round, they form one truncation tree that is a path of t vertices."""
    faces = {(0, 1, 2), (0, 2, 3), (0, 3, 4), (0, 4, 1), (5, 2, 1), (5, 3, 2), (5, 4, 3), (5, 1, 4)}
    face = (0, 1, 2)
    for v in range(6, 6 + t):
        a, b, c = face
        faces.remove(face)
        faces |= {(a, b, v), (b, c, v), (c, a, v)}
        face = (b, c, v)
    from strategies import rotation_lists

    return rotation_lists({f[f.index(min(f)) :] + f[: f.index(min(f))] for f in faces}, 6 + t)


def test_a_deep_truncation_tree_is_written_or_refused_by_its_strings_size():
    t = 2000
    lists = _stacked_chain(t)
    row = _row(lists, types=False)
    assert (row["status"], row["class"], row["truncations"], row["depth"]) == (
        "ok",
        "flag>=3",
        t,
        t,
    )
    assert row["trees"] == "(" * t + ")" * t
    # Its subtrees' strings take t (t + 1) bytes: 4 MB, more than 3 MB; the grain's arrays less.
    refused = _row(lists, types=False, grain_memory=3 * 2**20)
    assert refused["status"] == "invalid"
    assert "truncation forest" in refused["error"]


def test_the_bipyramid_keeps_its_tetrahedron_on_both_paths():
    for k in (3, 70):
        rows = [_row(bipyramid(k), max_bitset_faces=m) for m in (64, 0)]
        assert rows[0]["class"] == rows[1]["class"] == ("stacked" if k == 3 else "flag")


@settings(max_examples=25, deadline=None)
@given(triangulations(min_vertices=8, max_vertices=40, max_flips=80))
def test_the_large_grains_weinberg_kernel_agrees_with_brute_force(lists):
    """The walks on tables of darts (grains of more than DENSE_FACES faces), run here on
    small grains, against the reference walk."""
    from grainclass._kernels.weinberg import _weinberg_large_batch

    batch = GrainBatch.from_lists([lists])
    n = len(lists)
    code_offsets = np.array([0, 6 * n - 11], np.int64)
    codes = np.zeros(6 * n - 11, np.int32)
    symmetry, chirality = np.zeros(1, np.int32), np.zeros(1, np.int8)
    _weinberg_large_batch(
        0, 1, np.zeros(1, np.int64), batch.face_offsets, batch.nbr_offsets, batch.neighbors,
        code_offsets, codes, symmetry, chirality,
    )  # fmt: skip
    code, sym, chir = reference.weinberg(lists)
    assert tuple(codes) == code
    assert (symmetry[0], chirality[0]) == (sym, chir)


@settings(max_examples=30, deadline=None)
@given(triangulations(min_vertices=65, max_vertices=110, max_flips=300))
def test_large_random_grains_agree_with_the_oracle(lists):
    row = _row(lists, types=False)
    oracle = reference.classify(lists)
    for key in ("class", "truncations", "trees", "split_k", "belts4", "penalty"):
        assert row[key] == oracle[key], key


def _prism_line(k: int) -> str:
    return "prism\t" + ";".join(" ".join(map(str, face)) for face in _prism(k)) + "\n"


@pytest.fixture
def giant_among_polytopes(tmp_path):
    """The bundled polytopes (all of at most 14 faces) with a 100-gonal prism among them."""
    good = (EXAMPLES / "polytopes.txt").read_text()
    path = tmp_path / "grains.txt"
    path.write_text(good + _prism_line(100) + good)
    return path


def _refusing_belts(monkeypatch):
    """The belts kernel as a system that refuses memory for any range holding a grain of more
    than 64 faces (as it may for one giant grain among small ones)."""
    from grainclass._kernels import lbelts

    kernel = lbelts._belts_batch

    def refusing(first, last, grains, face_offsets, *arrays):
        chosen = grains[first:last]
        if (face_offsets[chosen + 1] - face_offsets[chosen] > 64).any():
            raise MemoryError
        return kernel(first, last, grains, face_offsets, *arrays)

    monkeypatch.setattr(lbelts, "_belts_batch", refusing)


BY_BELT_LENGTH = [
    ["summarize", "--table", "split", "--belt-length", "5"],
    ["types", "--belt-length", "5", "--format", "csv"],
]


def _without_the_giant(runner, args, polytopes):
    """What the command prints for the bundled polytopes twice over, without the giant."""
    doubled = polytopes.parent / "doubled.txt"
    doubled.write_text((EXAMPLES / "polytopes.txt").read_text() * 2)
    result = runner.invoke(cli, [args[0], str(doubled), *args[1:], "-q"])
    assert result.exit_code == 0, result.output
    return result.stdout


@pytest.mark.parametrize("args", BY_BELT_LENGTH, ids=["summarize", "types"])
@pytest.mark.parametrize("cause", ["refused", "over the limit"])
def test_a_giant_grain_refused_memory_for_its_belts_is_one_invalid_grain(
    args, cause, giant_among_polytopes, monkeypatch
):
    runner = CliRunner()
    expected = _without_the_giant(runner, args, giant_among_polytopes)
    if cause == "refused":
        _refusing_belts(monkeypatch)
    else:  # the prism could need about 0.1 MB on the general path
        monkeypatch.setenv("GRAINCLASS_GRAIN_MEMORY", "0.05")
    result = runner.invoke(cli, [args[0], str(giant_among_polytopes), *args[1:], "-q"])
    assert result.exit_code == 0, result.output
    if args[0] == "types":  # the types of ok grains: the giant is not one
        assert result.stdout == expected
    else:
        before = "grains: 26 (ok 26, degenerate 0, non_simple 0, invalid 0)"
        after = "grains: 27 (ok 26, degenerate 0, non_simple 0, invalid 1)"
        assert before in expected
        assert result.stdout == expected.replace(before, after)


def test_classify_with_belts_marks_the_grain_refused_memory_invalid(
    giant_among_polytopes, monkeypatch
):
    _refusing_belts(monkeypatch)
    rows = _rows(giant_among_polytopes, belts=5)
    (giant,) = [r for r in rows if r["grain_id"] == "prism"]
    assert giant["status"] == "invalid"
    assert "out of memory" in giant["error"]
    assert (giant["belts"], giant["splits"], giant["weinberg"]) == (None, None, None)
    assert [r["status"] for r in rows].count("ok") == len(rows) - 1
