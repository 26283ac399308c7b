"""Every triangulation of the sphere from plantri reproduces the paper's enumeration tables.

Expected numbers are transcribed from the paper (Tables I, II, tbl:flag_few_vertices and the
all* rows of tbl:distribution) in scripts/paper_tables.py, not produced by grainclass.
"""

from __future__ import annotations

import json
import subprocess
import sys

import pyarrow as pa
import pytest

from grainclass import classify, read_dataset
from paper_tables import CLASS_COLUMNS, ROUND_ALL, ROUND_COLUMNS, SPLIT, TABLE_I, TABLE_II


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
