"""Every triangulation of the sphere from plantri reproduces the paper's enumeration tables.

Expected numbers are transcribed from the paper (Tables I, II, tbl:flag_few_vertices and the
all* rows of tbl:distribution), not produced by grainclass.
"""

from __future__ import annotations

import json
import subprocess
import sys

import pyarrow as pa
import pytest

from grainclass import classify, read_dataset

# tbl:few_vertices_I: n -> all, min. deg. >= 4, flag
TABLE_I = {
    6: (2, 1, 1),
    7: (5, 1, 1),
    8: (14, 2, 2),
    9: (50, 5, 4),
    10: (233, 12, 10),
    11: (1249, 34, 25),
    12: (7595, 130, 87),
}
# tbl:few_vertices_II: n -> all, stacked, flag, flag+1, flag+1+1, flag+2, flag>=3, sc, sc+1, sc>=2
TABLE_II = {
    4: (1, 1, 0, 0, 0, 0, 0, 0, 0, 0),
    5: (1, 1, 0, 0, 0, 0, 0, 0, 0, 0),
    6: (2, 1, 1, 0, 0, 0, 0, 0, 0, 0),
    7: (5, 3, 1, 1, 0, 0, 0, 0, 0, 0),
    8: (14, 7, 2, 1, 3, 1, 0, 0, 0, 0),
    9: (50, 24, 4, 3, 5, 2, 11, 1, 0, 0),
    10: (233, 93, 10, 13, 19, 7, 86, 2, 3, 0),
    11: (1249, 434, 25, 47, 78, 30, 590, 9, 16, 20),
    12: (7595, 2110, 87, 217, 354, 127, 4301, 43, 99, 257),
    13: (49566, 11002, 313, 1041, 1799, 608, 30938, 212, 650, 3003),
    14: (339722, 58713, 1357, 5288, 9780, 3016, 224839, 1115, 3997, 31617),
}
# tbl:flag_few_vertices: n -> {k: number of flag triangulations of split type k:(n-4-k)}
SPLIT = {
    6: {1: 1},
    7: {1: 1},
    8: {2: 2},
    9: {1: 1, 2: 3},
    10: {1: 2, 2: 1, 3: 7},
    11: {1: 3, 2: 6, 3: 16},
    12: {0: 1, 1: 9, 2: 15, 3: 16, 4: 46},
    13: {1: 28, 2: 52, 3: 62, 4: 171},
    14: {0: 1, 1: 97, 2: 209, 3: 235, 4: 261, 5: 554},
}
# tbl:distribution, rows all*_{n=13} and all*_{n=14}: round0, round<=1..6, sc
ROUND_ALL = {
    13: (0.63, 2.73, 7.59, 15.19, 25.63, 37.82, 51.59, 7.80),
    14: (0.40, 1.96, 5.72, 12.04, 20.81, 31.36, 43.11, 10.81),
}
CLASS_COLUMNS = ["all", "stacked", "flag", "flag+1", "flag+1+1", "flag+2", "flag>=3"]
CLASS_COLUMNS += ["sc", "sc+1", "sc>=2"]
ROUND_COLUMNS = ["round0"] + [f"round<={k}" for k in range(1, 7)] + ["sc"]


def _grainclass(*args: str, stdin=None) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "grainclass", *args],
        stdin=stdin,
        capture_output=True,
        check=True,
    )


def _summary(paths, *extra: str) -> dict:
    return json.loads(_grainclass("summarize", *map(str, paths), "--format", "json", *extra).stdout)


@pytest.fixture(scope="module")
def summary_4_to_12(plantri_output, tmp_path_factory):
    out = tmp_path_factory.mktemp("enum") / "all.parquet"
    _grainclass("classify", *(str(plantri_output(n)) for n in range(4, 13)), "-o", str(out))
    return _summary([out])


@pytest.mark.parametrize("n", range(4, 13))
def test_enumeration_reproduces_table_ii(summary_4_to_12, n):
    row = next(r for r in summary_4_to_12["classes"] if r["n"] == n)
    assert tuple(row[c] for c in CLASS_COLUMNS) == TABLE_II[n]


@pytest.mark.parametrize("n", range(6, 13))
def test_enumeration_reproduces_split_table(summary_4_to_12, n):
    row = next(r for r in summary_4_to_12["split"] if r["n"] == n)
    assert {int(k): v for k, v in row.items() if k != "n" and v} == SPLIT[n]


def test_enumeration_total_row_and_headline(summary_4_to_12):
    total = next(r for r in summary_4_to_12["classes"] if r["n"] == "total")
    assert total["all"] == sum(TABLE_II[n][0] for n in range(4, 13))
    assert summary_4_to_12["headline"]["ok"] == total["all"]
    assert summary_4_to_12["headline"]["invalid"] == 0


def _classes(path) -> list[str]:
    table = pa.concat_tables(classify(b) for b in read_dataset(str(path)))
    return table.column("class").to_pylist()


@pytest.mark.parametrize("n", range(6, 13))
def test_plantri_4_connected_triangulations_are_exactly_the_flag_grains(plantri_output, n):
    # Table I: flag triangulations are the 4-connected ones (plantri -c4).
    classes = _classes(plantri_output(n, "-c4"))
    assert classes == ["flag"] * TABLE_I[n][2]


@pytest.mark.parametrize("n", range(6, 13))
def test_plantri_min_degree_4_triangulations_are_the_fundamental_ones(plantri_output, n):
    # Table I: minimum degree >= 4 means no triangular face: fundamental, flag or sc.
    classes = _classes(plantri_output(n, "-m4"))
    assert len(classes) == TABLE_I[n][1]
    assert set(classes) <= {"flag", "sc"}
    assert classes.count("flag") == TABLE_I[n][2]


@pytest.mark.slow
@pytest.mark.parametrize("n", [13, 14])
def test_enumeration_reproduces_paper_for_13_and_14(plantri, tmp_path, n):
    out = tmp_path / f"all{n}.parquet"
    with subprocess.Popen(
        [plantri, str(n)], stdout=subprocess.PIPE, stderr=subprocess.DEVNULL
    ) as producer:
        _grainclass("classify", "-", "-o", str(out), stdin=producer.stdout)
    assert producer.returncode == 0
    summary = _summary([out], "--n", str(n))
    row = next(r for r in summary["classes"] if r["n"] == n)
    assert tuple(row[c] for c in CLASS_COLUMNS) == TABLE_II[n]
    split = next(r for r in summary["split"] if r["n"] == n)
    assert {int(k): v for k, v in split.items() if k != "n" and v} == SPLIT[n]
    rnd = next(r for r in summary["round"] if r["grains"] == f"n={n}")
    assert tuple(round(rnd[c], 2) for c in ROUND_COLUMNS) == ROUND_ALL[n]
