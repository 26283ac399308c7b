"""`grainclass perturb`: edge flips (T1 moves) in the dual triangulation, the paper's
topological edge errors (Sec. "Grain Classes and Error Analysis").

Expected values come from the paper's own example (fig. grains_with_6_faces), from a hand
derivation of the (2,2,2) polytope below, and from the plain-Python oracle
``reference.admissible_flips`` / ``reference.flip``, which works on oriented triangle sets."""

from __future__ import annotations

import itertools
import math
import subprocess
import sys

import numpy as np
import pyarrow.parquet as pq
import pytest
from click.testing import CliRunner
from hypothesis import given, settings
from hypothesis import strategies as st

import reference
from conftest import EXAMPLES, ROOT
from grainclass import GrainBatch, classify, read_dataset
from grainclass.cli import cli
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


def _line(grain_id: str, lists: list[list[int]], fields: str = "") -> str:
    return f"{grain_id}\t{';'.join(' '.join(map(str, f)) for f in lists)}{fields}\n"


def _run(*args, input: str | bytes | None = None):
    return CliRunner().invoke(cli, [str(a) for a in args], input=input)


def _ok(*args, input: str | bytes | None = None):
    result = _run(*args, input=input)
    assert result.exit_code == 0, result.output
    return result


def _classified(tmp_path, text: str) -> list[dict]:
    source, out = tmp_path / "grains.txt", tmp_path / "grains.parquet"
    source.write_text(text)
    _ok("classify", source, "-o", out, "-q")
    return pq.read_table(out).to_pylist()


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


def _ids(batch: GrainBatch) -> list[str]:
    ids = batch.grain_id
    return [str(i) for i in (ids.to_pylist() if hasattr(ids, "to_pylist") else ids)]


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


def test_every_flip_of_the_cube_gives_the_222_polytope(tmp_path):
    """The paper: "The flip of any edge of the cube gives the second polytope"."""
    flips = _ok("perturb", "-", "--all-flips", input=_line("cube", CUBE)).stdout
    rows = _classified(tmp_path, flips)
    assert len(rows) == 12
    assert {row["flipped_edge"] for row in rows} == {f"{a}-{b}" for a, b in _edges(CUBE)}
    assert all(row["status"] == "ok" and row["from_grain"] == "cube" for row in rows)
    assert {tuple(row["p_vector"]) for row in rows} == {(2, 2, 2)}
    assert {row["weinberg"] for row in rows} == {_weinberg(P222)}


def test_of_the_222_polytope_four_flips_give_it_back_one_the_cube_seven_are_not_admissible(
    tmp_path,
):
    """The paper: "the flip of any of four edges does not change the polytope, the flip of one
    edge gives the cube, and the remaining seven edges are non-admissible"."""
    flips = _ok("perturb", "-", "--all-flips", input=_line("p222", P222)).stdout
    rows = _classified(tmp_path, flips)
    flipped = {tuple(map(int, row["flipped_edge"].split("-"))): row for row in rows}
    assert set(flipped) == P222_ADMISSIBLE
    assert len(_edges(P222)) - len(flipped) == 7
    cube = [edge for edge, row in flipped.items() if row["weinberg"] == _weinberg(CUBE)]
    back = [edge for edge, row in flipped.items() if row["weinberg"] == _weinberg(P222)]
    assert cube == [(2, 4)]
    assert len(back) == 4
    assert tuple(flipped[(2, 4)]["p_vector"]) == (0, 6)
    assert flipped[(2, 4)]["new_edge"] == "0-1"


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


# The command --------------------------------------------------------------------------------------


@pytest.fixture
def jobs_restored():
    from grainclass.parallel import get_jobs, set_jobs

    jobs = get_jobs()
    yield
    set_jobs(jobs)


@pytest.fixture(scope="module")
def voronoi_grains(tmp_path_factory):
    """A Poisson-Voronoi tessellation of 2000 seeds: adjacency text with volumes and areas."""
    path = tmp_path_factory.mktemp("perturb") / "pv.txt"
    _ok("voronoi", 2000, "--seed", 3, "-o", path, "-q")
    return path


def test_a_seed_gives_the_same_bytes_whatever_the_jobs_and_the_chunk_size(
    tmp_path, voronoi_grains, jobs_restored
):
    inputs = [voronoi_grains, EXAMPLES / "bad-grains.txt", EXAMPLES / "polytopes.txt"]
    for name, paths in (("text", inputs), ("planar_code", [EXAMPLES / "plantri-10.pc"])):
        outputs = []
        for jobs, chunk_size in ((1, 1), (1, 100_000), (2, 1), (2, 100_000), (2, 7)):
            out = tmp_path / f"{name}-{jobs}-{chunk_size}"
            args = ["--flips", 3, "--seed", 7, "--jobs", jobs, "--chunk-size", chunk_size]
            _ok("perturb", *paths, *args, "-o", out, "-q")
            outputs.append(out.read_bytes())
        assert all(output == outputs[0] for output in outputs[1:])
        other = tmp_path / f"{name}-seed8"
        _ok("perturb", *paths, "--flips", 3, "--seed", 8, "-o", other, "-q")
        assert other.read_bytes() != outputs[0]


def test_flips_0_writes_the_grains_unchanged(tmp_path, voronoi_grains):
    for source in (voronoi_grains, EXAMPLES / "plantri-10.pc"):
        out = tmp_path / source.name
        _ok("perturb", source, "--flips", 0, "-o", out, "-q")
        assert out.read_bytes() == source.read_bytes()


def test_planar_code_in_planar_code_out(tmp_path):
    source = EXAMPLES / "plantri-10.pc"
    out = tmp_path / "out.pc"
    _ok("perturb", source, "--flips", 2, "--seed", 1, "-o", out, "-q")
    assert out.read_bytes().startswith(b">>planar_code<<")
    before = next(read_dataset(str(source), chunk_size=10**6))
    after = next(read_dataset(str(out), chunk_size=10**6))
    assert len(after) == len(before) == 233
    text = _ok("perturb", source, "--flips", 2, "--seed", 1).stdout
    assert _grains(next(read_dataset(_write(tmp_path / "out.txt", text)))) == _grains(after)
    rows = classify(after).to_pylist()
    assert all(row["status"] == "ok" and row["n_faces"] == 10 for row in rows)


def _write(path, text: str) -> str:
    path.write_text(text)
    return str(path)


def test_ids_volumes_and_other_fields_are_kept(tmp_path):
    text = _line("c1", CUBE, "\tvolume=0.125\tarea=1.5\tboundary=1\tphase=beta") + _line(
        "c2", CUBE, "\tlabel=x"
    )
    out = _ok("perturb", "-", "--flips", 1, "--seed", 3, input=text).stdout
    rows = _classified(tmp_path, out)
    assert [r["grain_id"] for r in rows] == ["c1", "c2"]
    assert [r["volume"] for r in rows] == [0.125, None]
    assert [r["area"] for r in rows] == [1.5, None]
    assert [r["boundary"] for r in rows] == [True, None]
    assert [r["phase"] for r in rows] == ["beta", None]
    assert [r["label"] for r in rows] == [None, "x"]
    assert [tuple(r["p_vector"]) for r in rows] == [(2, 2, 2)] * 2


def test_grains_that_are_not_ok_pass_through_unchanged(tmp_path):
    source = EXAMPLES / "bad-grains.txt"
    out = _write(tmp_path / "out.txt", _ok("perturb", source, "--flips", 2, "--seed", 5).stdout)
    before = next(read_dataset(str(source)))
    after = next(read_dataset(out))
    assert _ids(after) == _ids(before)
    status_before = classify(before).column("status").to_pylist()
    assert classify(after).column("status").to_pylist() == status_before
    parsed = [g for g in range(len(before)) if g not in before.parse_errors]
    for g in parsed:
        if status_before[g] != "ok":
            assert _lists(after, g) == _lists(before, g)
    assert sorted(after.parse_errors) == sorted(before.parse_errors)  # read as invalid again


def test_grains_with_no_admissible_edge_left_are_kept_and_counted():
    text = _line("tetrahedron", TETRAHEDRON) + _line("cube", CUBE)
    for quiet in ([], ["-q"]):
        result = _ok("perturb", "-", "--flips", 1, "--seed", 0, *quiet, input=text)
        lines = result.stdout.splitlines()
        assert lines[0] == _line("tetrahedron", TETRAHEDRON).rstrip("\n")
        assert "1 had no admissible edge left" in result.stderr
    result = _ok("perturb", "-", "--all-flips", input=text)
    assert len(result.stdout.splitlines()) == 12
    assert "1 with no admissible edge gave none" in result.stderr


def test_the_seed_is_reported_when_not_given():
    result = _ok("perturb", "-", "--flips", 1, input=_line("cube", CUBE))
    seed = int(result.stderr.rsplit("seed ", 1)[1].split()[0])
    again = _ok("perturb", "-", "--flips", 1, "--seed", seed, input=_line("cube", CUBE))
    assert again.stdout == result.stdout


def test_flips_or_all_flips_and_not_both():
    for args in ([], ["--flips", "1", "--all-flips"], ["--all-flips", "--seed", "1"]):
        assert _run("perturb", "-", *args, input=_line("cube", CUBE)).exit_code == 2


def test_an_input_that_cannot_be_read_leaves_no_output(tmp_path):
    out = tmp_path / "out.txt"
    result = _run("perturb", tmp_path / "missing.txt", "--flips", 1, "-o", out)
    assert result.exit_code == 1
    assert not out.exists()


def test_perturb_pipes_into_summarize(tmp_path, voronoi_grains):
    command = [sys.executable, "-m", "grainclass"]
    perturbed = subprocess.run(
        [*command, "perturb", str(voronoi_grains), "--flips", "1", "--seed", "7"],
        check=True,
        capture_output=True,
    )
    piped = subprocess.run(
        f"{' '.join(command)} perturb {voronoi_grains} --flips 1 --seed 7 -q"
        f" | {' '.join(command)} summarize - --table round --format csv",
        shell=True,
        check=True,
        capture_output=True,
        text=True,
    )
    saved = _write(tmp_path / "perturbed.txt", perturbed.stdout.decode())
    alone = _ok("summarize", saved, "--table", "round", "--format", "csv").stdout
    assert piped.stdout == alone
    assert "2000 grains: 2000 ok, 1 flip each" in perturbed.stderr.decode()


# The edge-errors figure (fig. combined_cut_types) -------------------------------------------------


def _round_k(round_table: str) -> list[float]:
    """Percent of ok grains with round_k = 0..6, then sc, from summarize's round table (CSV):
    the differences of its round<=k columns."""
    header, row = round_table.strip().splitlines()
    values = dict(zip(header.split(","), row.split(","), strict=True))
    levels = [float(values["round0"])] + [float(values[f"round<={k}"]) for k in range(1, 7)]
    return [levels[0]] + [b - a for a, b in itertools.pairwise(levels)] + [float(values["sc"])]


def test_edge_errors_are_summarize_of_perturb_for_each_eepg(tmp_path, voronoi_grains):
    pytest.importorskip("matplotlib")
    import pandas as pd

    other = EXAMPLES / "polytopes.txt"
    figure, data = tmp_path / "e.svg", tmp_path / "e.csv"
    args = ["--label", "E", "--label", "P", "--seed", 9, "-o", figure, "--data", data, "-q"]
    _ok("plot", "edge-errors", voronoi_grains, other, *args)
    table = pd.read_csv(data, dtype={"x": str})
    assert list(dict.fromkeys(table.series)) == [f"{k} EEPG" for k in range(4)]
    for label, source, flips in [("E", voronoi_grains, k) for k in range(4)] + [("P", other, 0)]:
        perturbed = tmp_path / f"{label}{flips}.txt"
        _ok("perturb", source, "--flips", flips, "--seed", 9, "-o", perturbed, "-q")
        csv = ["--table", "round", "--format", "csv"]
        expected = _round_k(_ok("summarize", perturbed, *csv).stdout)
        drawn = table[(table.dataset == label) & (table.series == f"{flips} EEPG")]
        assert drawn.x.tolist()[:7] == [str(k) for k in range(7)]
        assert drawn.x.tolist()[-1] == "sc"
        got = [*drawn.y.tolist()[:7], drawn.y.tolist()[-1]]
        assert got == pytest.approx(expected, abs=1e-9)
        assert sum(drawn.y) == pytest.approx(100.0)
    assert figure.read_bytes().startswith(b"<?xml")


def test_edge_errors_needs_the_first_data_set_as_grains(tmp_path):
    pytest.importorskip("matplotlib")
    parquet = tmp_path / "grains.parquet"
    _ok("classify", EXAMPLES / "polytopes.txt", "-o", parquet, "-q")
    figure = tmp_path / "e.png"
    result = _run("plot", "edge-errors", parquet, "-o", figure)
    assert result.exit_code == 1
    assert "give the grains themselves" in result.stderr
    assert not figure.exists()
    _ok("plot", "edge-errors", EXAMPLES / "polytopes.txt", parquet, "-o", figure, "-q")
    seeded = _run("plot", "round", parquet, "-o", figure, "--seed", 1)
    assert seeded.exit_code == 2


@settings(max_examples=10, deadline=None)
@given(triangulations(min_vertices=65, max_vertices=80, max_flips=200))
def test_grains_of_more_than_64_faces_flip_as_the_oracle_says(lists):
    expected = reference.admissible_flips(lists)
    got = all_flips(GrainBatch.from_lists([lists])).batch
    edges = [tuple(map(int, e.split("-"))) for e in got.attributes["flipped_edge"]]
    assert sorted(edges) == sorted(expected)
    for (a, b), after in zip(edges, _grains(got), strict=True):
        assert reference.oriented_faces(after) == reference.flip(lists, a, b)
    once = _lists(perturb(GrainBatch.from_lists([lists]), 1, seed=3).batch)
    assert reference.oriented_faces(once) == reference.flip(lists, *_flipped_edge(lists, once))


def test_planar_code_on_standard_input_comes_out_as_planar_code():
    data = (EXAMPLES / "plantri-10.pc").read_bytes()
    out = _ok("perturb", "-", "--flips", 1, "--seed", 2, input=data).stdout_bytes
    assert out.startswith(b">>planar_code<<")
    named = _ok(
        "perturb", "-", "--flips", 1, "--seed", 2, "--input-format", "planar_code", input=data
    ).stdout_bytes
    assert named == out
    mixed = _ok("perturb", "-", EXAMPLES / "polytopes.txt", "--flips", 0, input=data).stdout
    assert mixed.startswith("1\t")  # adjacency text: not every input is planar_code


def test_surface_evolver_grains_come_out_as_adjacency_text_with_their_geometry(tmp_path):
    source = ROOT / "tests" / "data" / "evolver" / "kelvin_foam.fe"
    before = classify(next(read_dataset(str(source)))).to_pylist()
    out = _ok("perturb", source, "--flips", 1, "--seed", 4).stdout
    after = _classified(tmp_path, out)
    assert [r["grain_id"] for r in after] == [r["grain_id"] for r in before]
    assert [r["volume"] for r in after] == [r["volume"] for r in before]
    assert [r["area"] for r in after] == [r["area"] for r in before]
    assert [r["n_faces"] for r in after] == [r["n_faces"] for r in before]
    assert [r["status"] for r in after] == [r["status"] for r in before]
