"""Belts of every length: counts, split types and penalties for l = 3..L against a brute-force
oracle, today's 4-belt columns, hand-derived grains, and the commands that use them."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pyarrow as pa
import pyarrow.parquet as pq
import pytest
from click.testing import CliRunner
from hypothesis import given, settings

import reference
from conftest import EXAMPLES
from grainclass import GrainBatch, classify, read_dataset
from grainclass.cli import cli
from grainclass.penalties import spearman
from strategies import triangulations
from test_properties import _read_planar_code

LENGTHS = range(3, 7)


def _profiles(graphs, longest=6, **kwargs):
    """Per grain, ``{l: (belts, split_k, penalty)}`` from classify's three list columns."""
    rows = classify(GrainBatch.from_lists(graphs), belts=longest, **kwargs).to_pylist()
    return [
        {
            length: (r["belts"][i], r["splits"][i], r["belt_penalties"][i])
            for i, length in enumerate(range(3, longest + 1))
        }
        for r in rows
    ]


def _general(graphs, longest=6):
    """The same from the general path's kernel (rotation lists and dart weights), whatever
    the grains' sizes."""
    from grainclass._kernels.lbelts import _belt_profile
    from grainclass._kernels.validate import _rotation, grain_lists

    batch = GrainBatch.from_lists(graphs)
    out = []
    for g in range(len(graphs)):
        n, off, nb = grain_lists(g, batch.face_offsets, batch.nbr_offsets, batch.neighbors)
        rot = np.empty(off[n], np.int64)
        _rotation(n, off, nb, rot)
        profile = np.zeros((longest - 2, 3), np.int64)
        _belt_profile(n, off, rot, longest, profile)
        # -1: no split type (fewer faces than the belts' length), null in the table
        rows = [(b, None if k < 0 else k, p) for b, k, p in profile.tolist()]
        out.append({length: rows[length - 3] for length in range(3, longest + 1)})
    return out


@pytest.mark.parametrize("n", range(4, 11))
def test_every_triangulation_up_to_10_agrees_with_brute_force(plantri_output, n):
    graphs = _read_planar_code(plantri_output(n).read_bytes())
    expected = [reference.belt_profile(lists, 6) for lists in graphs]
    assert _profiles(graphs) == expected
    assert _general(graphs) == expected


@settings(max_examples=40, deadline=None)
@given(triangulations(min_vertices=11, max_vertices=15, max_flips=60))
def test_random_triangulations_agree_with_brute_force(lists):
    expected = reference.belt_profile(lists, 6)
    assert _profiles([lists]) == [expected]
    assert _general([lists]) == [expected]


@pytest.mark.parametrize("n", range(4, 13))
def test_the_4_belts_are_todays_columns_for_flag_grains(plantri_output, n):
    table = pa.concat_tables(
        classify(b, types=False, belts=4) for b in read_dataset(str(plantri_output(n)))
    )
    for row in table.to_pylist():
        if row["class"] == "flag":
            assert (row["belts"][1], row["splits"][1], row["belt_penalties"][1]) == (
                row["belts4"],
                row["split_k"],
                row["penalty"],
            )


@pytest.fixture(scope="module")
def examples():
    table = classify(next(read_dataset(str(EXAMPLES / "polytopes.txt"))), belts=6)
    return {row["grain_id"]: row for row in table.to_pylist()}


def test_the_cube(examples):
    # docs/definitions.md works it out on the octahedron: no non-trivial 3-belt, the three
    # rings of four squares (1:4:1), no 5- or 6-belt.
    cube = examples["cube"]
    assert cube["belts"] == [0, 3, 0, 0]
    assert cube["splits"] == [0, 1, 0, 0]
    assert cube["belt_penalties"] == [0, 6 * 3 * 1 * 1, 0, 0]


def test_the_dodecahedron(examples):
    # docs/definitions.md: flag with no 4-belt; 12 rings of five faces around a face (1:5:6);
    # 6-belts around an edge (30, 2:6:4) and between opposite faces (10, 3:6:3).
    for name in ("dodecahedron", "weaire_phelan_12"):
        row = examples[name]
        assert row["belts"] == [0, 0, 12, 40]
        assert row["splits"] == [0, 0, 1, 3]
        assert row["belt_penalties"] == [0, 0, 12 * 12 * 1 * 6, 12 * (30 * 2 * 4 + 10 * 3 * 3)]


def test_a_truncated_cube_has_a_3_belt_around_its_triangle(examples):
    # The triangle's three neighbours: a non-trivial 3-belt leaving the triangle (1 face) on
    # one side and the 3 far squares on the other: 1:3:3, penalty 7 x 1 x 3.
    row = examples["cube_truncated_1"]
    assert (row["belts"][0], row["splits"][0], row["belt_penalties"][0]) == (1, 1, 21)


def test_the_papers_grains_a_b_c(plantri_output):
    # Sec. III.D: A has two 3:4:3 belts, B one, C none, and penalties 540, 450, 280 by the
    # definition (tests/test_weinberg.py). With n = 10, a 4-belt of type 1:5 adds 50, 2:4 80
    # and 3:3 90; each of the four 4-gons has one of type 1:5 around it, so A has 540 = 200 +
    # 2 x 80 + 2 x 90 (eight 4-belts), B 450 = 200 + 2 x 80 + 90 (seven), C 280 = 200 + 80
    # (five). Each of the four pentagons has a 5-belt around it (its neighbours, 1:5:4).
    table = pa.concat_tables(
        classify(b, belts=6) for b in read_dataset(str(plantri_output(10)))
    ).to_pylist()
    rows = [r for r in table if r["class"] == "flag" and r["p_vector"] == [0, 4, 4, 2]]
    got = sorted((r["penalty"], r["belts"][1], r["splits"][1], r["belts"][0]) for r in rows)
    assert got == [(280, 5, 2, 0), (450, 7, 3, 0), (540, 8, 3, 0)]
    for row in rows:
        assert row["belts"][2] >= 4


def test_a_large_prism_has_its_belts_on_the_general_path():
    # The 70-gonal prism's dual, the bipyramid: a chordless cycle through an apex N leaves it
    # by two ring vertices and can only come back through the other apex: N-v_i-S-v_j, a 4-belt
    # for each pair of ring vertices not adjacent; else it is the ring itself (70 > 6).
    k = 70
    quads = [[k, (i - 1) % k, k + 1, (i + 1) % k] for i in range(k)]
    prism = [*quads, list(range(k)), list(reversed(range(k)))]
    (row,) = classify(GrainBatch.from_lists([prism]), types=False, belts=6).to_pylist()
    assert row["belts"] == [0, k * (k - 3) // 2, 0, 0]
    assert row["splits"] == [0, (k - 2) // 2, 0, 0]
    assert row["belt_penalties"][1] == row["penalty"]


def test_without_belts_the_columns_are_null(examples):
    row = classify(GrainBatch.from_lists([reference_cube()])).to_pylist()[0]
    assert (row["belts"], row["splits"], row["belt_penalties"]) == (None, None, None)


def reference_cube():
    return [[1, 2, 3, 4], [0, 4, 5, 2], [0, 1, 5, 3], [0, 2, 5, 4], [0, 3, 5, 1], [1, 4, 3, 2]]


def test_spearman_is_pearson_of_average_ranks():
    # By hand: ranks of x (1, 2, 3, 4) and of y (4, 2.5, 2.5, 1): rho = -0.9486832980505138.
    x = pd.Series([10, 20, 30, 40])
    y = pd.Series([9, 5, 5, 1])
    rx, ry = np.array([1, 2, 3, 4.0]), np.array([4, 2.5, 2.5, 1])
    by_hand = ((rx - 2.5) * (ry - 2.5)).sum() / math.sqrt(((rx - 2.5) ** 2).sum() * 4.5)
    assert spearman(x, y) == pytest.approx(by_hand)
    assert spearman(x, x) == pytest.approx(1.0)
    assert math.isnan(spearman(x, pd.Series([3, 3, 3, 3])))


@pytest.fixture(scope="module")
def pv_belts(tmp_path_factory):
    """A small Poisson-Voronoi data set classified with belts up to 6."""
    from grainclass.voronoi import poisson_voronoi

    tmp = tmp_path_factory.mktemp("pv")
    out = tmp / "pv.parquet"
    tables = [classify(b, belts=6) for b in poisson_voronoi(3000, seed=3)]
    pq.write_table(pa.concat_tables(tables), out)
    return out


def test_penalties_command_prints_a_row_per_n(pv_belts):
    result = CliRunner().invoke(cli, ["penalties", str(pv_belts), "--format", "csv", "-q"])
    assert result.exit_code == 0, result.output
    lines = result.output.strip().splitlines()
    assert lines[0] == "n,types,grains,P4,P4..L,P4/sym,P4..L/sym,sym,(1+P4)*sym,(1+P4..L)*sym"
    assert len(lines) > 3


def test_split_by_belt_length_in_types_and_summarize(pv_belts):
    runner = CliRunner()
    summary = runner.invoke(
        cli, ["summarize", str(pv_belts), "--table", "split", "--belt-length", "5", "-q"]
    )
    assert summary.exit_code == 0, summary.output
    assert "k:5:m" in summary.output
    types = runner.invoke(cli, ["types", str(pv_belts), "--belt-length", "6", "--top", "5"])
    assert types.exit_code == 0, types.output
    assert ":6:" in types.output


def test_a_table_without_belts_is_refused_with_what_to_do(tmp_path):
    out = tmp_path / "cube.parquet"
    pq.write_table(classify(GrainBatch.from_lists([reference_cube()])), out)
    result = CliRunner().invoke(cli, ["penalties", str(out), "-q"])
    assert result.exit_code == 1
    assert "classify the input again with --belt-length 6" in result.output
