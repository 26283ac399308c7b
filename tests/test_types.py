"""`grainclass types`: frequencies of combinatorial types."""

from __future__ import annotations

import itertools
import json

import pytest
from click.testing import CliRunner

from conftest import EXAMPLES
from grainclass.cli import cli
from grainclass.errors import EmptyInputWarning
from test_weinberg import CUBE_CODE

INPUTS = [str(EXAMPLES / "polytopes.txt"), str(EXAMPLES / "plantri-10.pc")]


def _types(*args: str) -> list[dict]:
    result = CliRunner().invoke(cli, ["types", *INPUTS, "--format", "json", *args])
    assert result.exit_code == 0, result.output
    return json.loads(result.stdout)


def test_types_merges_equal_grains_and_sorts_by_count():
    rows = _types()
    # 233 triangulations with n = 10 plus 13 examples, of which the dodecahedron and the
    # Weaire-Phelan dodecahedron are one type: 245 types, that one twice.
    assert len(rows) == 245
    top = rows[0]
    assert (top["n_faces"], top["p_vector"], top["count"], top["symmetry"]) == (
        12,
        "(0,0,12)",
        2,
        120,
    )
    assert top["split"] == "0:8"
    assert abs(top["fraction"] - 2 / 246) < 1e-12  # of 233 + 13 grains
    assert all(a["count"] >= b["count"] for a, b in itertools.pairwise(rows))


def test_types_filters_and_top():
    cube = _types("--n", "6")
    assert [(r["weinberg"], r["class"], r["split"], r["penalty"]) for r in cube] == [
        (CUBE_CODE, "flag", "1:1", 18)
    ]
    # The tetrahedron is stacked: no split type and no penalty, both null alike.
    assert [(r["split"], r["penalty"]) for r in _types("--n", "4")] == [(None, None)]
    flags10 = _types("--n", "10", "--class", "flag")
    assert len(flags10) == 10  # Table II: 10 flag triangulations with n = 10
    assert len(_types("--top", "3")) == 3


def test_types_leaves_boundary_grains_out_as_summarize_does(tmp_path):
    """Two cubes and two tetrahedra, one of each cut by the sample boundary."""
    cube = "1 2 3 4;0 4 5 2;0 1 5 3;0 2 5 4;0 3 5 1;1 4 3 2"
    tetrahedron = "1 2 3;0 3 2;0 1 3;0 2 1"
    path = tmp_path / "cut.txt"
    path.write_text(
        f"a\t{cube}\tboundary=1\nb\t{cube}\nc\t{tetrahedron}\tboundary=0\n"
        f"d\t{tetrahedron}\tboundary=yes\n"
    )
    runner = CliRunner()
    for args, counts in (([], {4: 1, 6: 1}), (["--include-boundary"], {4: 2, 6: 2})):
        result = runner.invoke(cli, ["types", str(path), "--format", "json", *args])
        assert result.exit_code == 0, result.output
        assert {r["n_faces"]: r["count"] for r in json.loads(result.stdout)} == counts
        summary = runner.invoke(cli, ["summarize", str(path), "--format", "json", *args])
        assert json.loads(summary.stdout)["headline"]["grains"] == sum(counts.values())
    # What was left out is said, as summarize's headline says it: of the grains asked for.
    for args, left_out in (([], 2), (["--n", "6"], 1)):
        result = runner.invoke(cli, ["types", str(path), *args])
        assert result.exit_code == 0, result.output
        note = f"{left_out} grains cut by the sample boundary left out"
        assert f"types, most frequent first; {note}" in result.stdout
        assert f"grainclass: {note} (--include-boundary counts them)" in result.stderr
    for args in (["--include-boundary"], ["--n", "5"], ["-q"]):
        result = runner.invoke(cli, ["types", str(path), *args])
        assert "left out" not in result.stderr


def test_types_writes_vorotop_distribution(tmp_path):
    out = tmp_path / "grains.distribution"
    result = CliRunner().invoke(
        cli, ["types", *INPUTS, "--vorotop", str(out), "-o", str(tmp_path / "t.csv")]
    )
    assert result.exit_code == 0
    header, lines = out.read_text().splitlines()[:4], out.read_text().splitlines()[4:]
    assert header[:3] == [
        f"#\tDISTRIBUTION CREATED FROM {' '.join(INPUTS)}",
        "#\tTotal particles sampled: 246",  # 233 triangulations and 13 examples
        "#\tTotal Voronoi topologies observed: 245",
    ]
    assert len(lines) == 245
    code, total, left, achiral, right = lines[0].split("\t")
    assert code.startswith("(1,2,3,4,5,1,")
    assert (total, left, achiral, right) == (
        "2",
        "0",
        "2",
        "0",
    )
    assert all(
        int(t) == int(a) + int(b) + int(c)
        for t, a, b, c in (line.split("\t")[1:] for line in lines)
    )
    assert (tmp_path / "t.csv").read_text().startswith("weinberg,n_faces,p_vector,class,split")


def test_summarize_counts_a_type_once_from_rows_and_from_raw_input(tmp_path):
    # Raw inputs hash the Weinberg codes without writing them, Parquet rows hash the strings:
    # the hashes must agree for a type seen both ways to count once.
    grains = tmp_path / "grains.parquet"
    runner = CliRunner()
    assert runner.invoke(cli, ["classify", *INPUTS, "-o", str(grains)]).exit_code == 0
    both = [str(grains), *INPUTS, "--types", "--format", "json"]
    result = runner.invoke(cli, ["summarize", *both])
    assert result.exit_code == 0, result.output
    assert json.loads(result.stdout)["headline"]["types"] == 245


def test_distinct_types_are_counted_only_when_every_input_knows_its_grains_types(tmp_path):
    """12 types among the 13 examples, 233 among the triangulations with n = 10 (none shared
    but the dodecahedron's, which is not a triangulation of 10 vertices): 245 together."""
    examples = tmp_path / "examples.parquet"
    plain = tmp_path / "plain.parquet"
    runner = CliRunner()
    assert runner.invoke(cli, ["classify", INPUTS[0], "-o", str(examples), "-q"]).exit_code == 0
    no_types = ["classify", INPUTS[1], "-o", str(plain), "-q", "--no-types"]
    assert runner.invoke(cli, no_types).exit_code == 0

    def types(*args: str) -> int | None:
        result = runner.invoke(cli, ["summarize", *args, "--format", "json", "-q"])
        assert result.exit_code == 0, result.output
        return json.loads(result.stdout)["headline"]["types"]

    assert types(str(examples)) == 12
    assert types(str(examples), INPUTS[1], "--types") == 245
    assert types(str(examples), INPUTS[1]) is None  # the raw input's types were not computed
    assert types(str(examples), str(plain)) is None  # nor were those of the table's grains
    bad = tmp_path / "bad.txt"
    bad.write_text("g\t1 2;0 2;0 1\n")  # degenerate: no ok grain, no type, but known so
    assert types(str(bad), "--types") == 0


def test_code_hashes_are_the_hashes_of_the_code_strings():
    import numpy as np

    from grainclass import GrainBatch
    from grainclass._kernels.columns import _code_hashes, _code_strings, _fnv1a
    from grainclass.classification import MAX_BITSET_FACES, _classify_csr
    from grainclass.weinberg_columns import weinberg_types
    from strategies import bipyramid

    # Bipyramids up to 120 faces: labels of one, two and three digits.
    batch = GrainBatch.from_lists([bipyramid(k) for k in (3, 4, 9, 30, 70, 118)])
    types = weinberg_types(batch, _classify_csr(batch, MAX_BITSET_FACES, strings=False), True)
    assert types.computed.all()
    assert max(types.weinberg) >= 100
    strings = _code_strings(types.weinberg, types.code_offsets, types.computed)
    with np.errstate(over="ignore"):  # FNV wraps (seen without the JIT)
        expected = _fnv1a(*strings)
        hashes = _code_hashes(types.weinberg, types.code_offsets, types.computed)
    np.testing.assert_array_equal(hashes, expected)
    assert len(set(expected.tolist())) == 6


def test_types_of_no_grains_is_an_empty_table_with_the_usual_columns(tmp_path):
    empty = tmp_path / "empty.txt"
    empty.write_text("")
    with pytest.warns(EmptyInputWarning, match="empty.txt: no grains"):
        result = CliRunner().invoke(cli, ["types", str(empty), "--format", "csv"])
    assert result.exit_code == 0, result.output
    header = "weinberg,n_faces,p_vector,class,split,penalty,symmetry,count,fraction"
    assert result.stdout.splitlines() == [header]


def test_types_refuses_a_table_classified_without_types(tmp_path):
    plain = tmp_path / "plain.parquet"
    runner = CliRunner()
    result = runner.invoke(cli, ["classify", INPUTS[0], "-o", str(plain), "--no-types", "-q"])
    assert result.exit_code == 0
    result = runner.invoke(cli, ["types", str(plain)])
    assert result.exit_code == 1
    assert f"{plain}: ok grains without a Weinberg vector" in result.stderr


def test_types_and_summarize_refuse_a_parquet_file_that_is_not_a_grain_table(tmp_path):
    summary = tmp_path / "classes.parquet"
    runner = CliRunner()
    result = runner.invoke(cli, ["summarize", INPUTS[0], "--table", "classes", "-o", str(summary)])
    assert result.exit_code == 0
    for command in ("types", "summarize"):
        result = runner.invoke(cli, [command, str(summary)])
        assert result.exit_code == 1
        assert f"{summary}: not a grainclass per-grain table: no column" in result.stderr


def test_a_grain_table_saved_again_from_pandas_reads_as_before(tmp_path):
    """pandas writes a column of None alone (``boundary`` of planar_code input) as Arrow's null
    type: summarize crashed on it. Integer flags and float counts are taken as well."""
    import pandas as pd
    import pyarrow.parquet as pq

    runner = CliRunner()
    table = tmp_path / "grains.parquet"
    bad = str(EXAMPLES / "bad-grains.txt")  # rows without a class, and with errors
    assert runner.invoke(cli, ["classify", *INPUTS, bad, "-o", str(table), "-q"]).exit_code == 0
    frame = pd.read_parquet(table)
    assert frame["boundary"].isna().all()
    assert frame["class"].isna().any()
    frame.to_parquet(tmp_path / "again.parquet")
    assert str(pq.read_schema(tmp_path / "again.parquet").field("boundary").type) == "null"
    frame.assign(boundary=0, n_faces=frame["n_faces"].astype(float)).to_parquet(
        tmp_path / "retyped.parquet"
    )
    want = runner.invoke(cli, ["summarize", str(table), "--format", "json"])
    assert want.exit_code == 0
    for name in ("again", "retyped"):
        for command in ("summarize", "types"):
            got = runner.invoke(
                cli, [command, str(tmp_path / f"{name}.parquet"), "--format", "json"]
            )
            assert got.exit_code == 0, got.output
            original = runner.invoke(cli, [command, str(table), "--format", "json"])
            assert got.stdout == original.stdout


def test_a_grain_table_without_the_columns_added_later_is_summarized(tmp_path):
    import pyarrow.parquet as pq

    runner = CliRunner()
    table = tmp_path / "grains.parquet"
    assert runner.invoke(cli, ["classify", *INPUTS, "-o", str(table), "-q"]).exit_code == 0
    pq.write_table(pq.read_table(table).drop(["boundary", "weinberg"]), tmp_path / "old.parquet")
    args = ["summarize", "--format", "json"]
    want = json.loads(runner.invoke(cli, [*args, str(table)]).stdout)
    got = json.loads(runner.invoke(cli, [*args, str(tmp_path / "old.parquet")]).stdout)
    assert want["headline"]["types"] == 245
    assert got["headline"]["types"] is None  # without Weinberg vectors: not known
    assert got["classes"] == want["classes"]


def test_a_word_the_summaries_do_not_know_is_named(tmp_path):
    """A status written as OK was counted as no status at all: 'ok 0', exit 0."""
    import pandas as pd

    runner = CliRunner()
    table = tmp_path / "grains.parquet"
    assert runner.invoke(cli, ["classify", INPUTS[0], "-o", str(table), "-q"]).exit_code == 0
    frame = pd.read_parquet(table)
    frame.assign(status=frame["status"].str.upper()).to_parquet(tmp_path / "upper.parquet")
    for command in ("summarize", "types"):
        result = runner.invoke(cli, [command, str(tmp_path / "upper.parquet")])
        assert result.exit_code == 1
        assert "column status holds 'OK', not one of ok, degenerate" in result.stderr


def test_arrow_reads_grain_tables_itself(tmp_path, monkeypatch):
    """Read through Python, the bytes were let go by Arrow's decoding threads just after a row
    group came, under the GIL: a refused table ended the process then, and now and then it
    aborted (exit 134, "terminate called without an active exception") instead of exit 1."""
    import grainclass.parquet as parquet

    table = tmp_path / "grains.parquet"
    assert CliRunner().invoke(cli, ["classify", INPUTS[0], "-o", str(table), "-q"]).exit_code == 0

    def python_open(*args, **kwargs):
        raise AssertionError("a grain table read through Python")

    monkeypatch.setattr(parquet, "open", python_open, raising=False)
    rows = sum(len(t) for t in parquet.iter_grain_tables(str(table), ["status"]))
    assert rows == 13


def test_a_damaged_grain_table_is_named_not_a_traceback(tmp_path):
    table = tmp_path / "grains.parquet"
    runner = CliRunner()
    assert runner.invoke(cli, ["classify", INPUTS[1], "-o", str(table), "-q"]).exit_code == 0
    data = bytearray(table.read_bytes())
    data[200:1200] = bytes(b ^ 0x5A for b in data[200:1200])  # inside the first row group
    table.write_bytes(bytes(data))
    for command in ("types", "summarize"):
        result = runner.invoke(cli, [command, str(table)])
        assert result.exit_code == 1
        assert f"{table}: row group 0 cannot be read" in result.stderr


def test_types_as_markdown_and_latex_leave_missing_cells_empty():
    # The tetrahedron is stacked: no split, no penalty.
    runner = CliRunner()
    tetrahedron = "(1,2,3,1,3,4,1,4,2,4,3,2,1)"
    markdown = runner.invoke(cli, ["types", INPUTS[0], "--n", "4", "--format", "markdown"])
    assert markdown.exit_code == 0, markdown.output
    assert f"| {tetrahedron} | 4 | (4) | stacked |  |  | 24 | 1 | 1.0 |" in markdown.stdout
    latex = runner.invoke(cli, ["types", INPUTS[0], "--n", "4", "--format", "latex"])
    assert latex.exit_code == 0, latex.output
    assert f"{tetrahedron} & 4 & (4) & stacked &  &  & 24 & 1 & 1.0 \\\\" in latex.stdout


def test_types_as_text_puts_the_long_codes_last():
    """Weinberg codes first and right-aligned pushed every other column off the screen. Of the
    13 examples, the two dodecahedra are the most frequent type: 2 / 13 to six digits."""
    result = CliRunner().invoke(cli, ["types", INPUTS[0], "--top", "1"])
    assert result.exit_code == 0, result.output
    header, row = result.stdout.splitlines()[1:]
    assert header.split() == [
        "n_faces", "p_vector", "class", "split", "penalty", "symmetry", "count", "fraction",
        "weinberg",
    ]  # fmt: skip
    *columns, code = row.split()
    assert columns == ["12", "(0,0,12)", "flag", "0:8", "0", "120", "2", "0.153846"]
    assert len(code.strip("()").split(",")) == 2 * 30 + 1  # a walk over the 30 edges twice
