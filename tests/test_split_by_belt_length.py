"""The split type of l-belts, k:l:m for l = 5..10, in ``summarize --table split --belt-length L``
and ``types --belt-length L``, from raw input and from a Parquet table, against brute force
(``tests/reference.py``) on the bundled polytopes and on plantri's triangulations.

By the paper's Def. of split type a flag* grain has the type of its most balanced l-belt, and
0:l:(n - l) without one; a grain of fewer than l faces has none (0:l:(n - l) would leave a disc
of n - l < 0 faces and break the definition's k <= m), so it is in no column of the split table
and has no ``split`` in ``types``: no path prints a negative m.
"""

from __future__ import annotations

import csv
import io
import re
from collections import Counter
from pathlib import Path

import pytest
from click.testing import CliRunner

import reference
from conftest import EXAMPLES
from grainclass.cli import cli
from test_properties import _read_planar_code

LENGTHS = range(5, 11)


def _adjacency_lists(path: Path) -> list[list[list[int]]]:
    """The grains of an adjacency-text file without comments or fields, in plain Python."""
    grains = []
    for line in path.read_text().splitlines():
        if line.strip() and not line.startswith("#"):
            faces = line.split("\t")[1].split(";")
            grains.append([[int(x) for x in face.split()] for face in faces])
    return grains


class Grain:
    """A grain by brute force: its faces, whether it is flag*, its Weinberg vector as
    ``types`` writes it, and the k of its split type for each l = 3..10 (None: no type)."""

    def __init__(self, lists: list[list[int]]) -> None:
        self.n = len(lists)
        self.flag = reference.classify(lists)["class"] == "flag"
        code, _, _ = reference.weinberg(lists)
        self.weinberg = "(" + ",".join(map(str, code)) + ")"
        profile = reference.belt_profile(lists, max(LENGTHS)) if self.flag else {}
        self.split = {length: split_k for length, (_, split_k, _) in profile.items()}


@pytest.fixture(scope="module")
def inputs(plantri_output) -> list[Path]:
    """The bundled polytopes (4 to 14 faces), every triangulation with 4 to 9 vertices, and the
    4-connected ones (the flag triangulations) with 10 and 11."""
    return [
        EXAMPLES / "polytopes.txt",
        *(plantri_output(n) for n in range(4, 10)),
        *(plantri_output(n, "-c4") for n in (10, 11)),
    ]


@pytest.fixture(scope="module")
def grains(inputs) -> list[Grain]:
    lists = _adjacency_lists(inputs[0])
    for path in inputs[1:]:
        lists += _read_planar_code(path.read_bytes())
    return [Grain(g) for g in lists]


@pytest.fixture(scope="module")
def table(inputs, tmp_path_factory) -> Path:
    """The inputs classified with belts up to length 10."""
    out = tmp_path_factory.mktemp("belts") / "grains.parquet"
    result = CliRunner().invoke(
        cli, ["classify", *map(str, inputs), "--belts", "--belt-lengths", "10", "-o", str(out)]
    )
    assert result.exit_code == 0, result.output
    return out


def _run(*args: str) -> str:
    result = CliRunner().invoke(cli, [*args, "-q"])
    assert result.exit_code == 0, result.output
    return result.stdout


def test_the_inputs_hold_flag_grains_both_sides_of_each_length(grains):
    # Otherwise the tests below would not tell a grain with no type from one of type 0: flag
    # grains of 6 (the cube, the smallest) to 11 faces and of 14, so for each l = 7..10 some of
    # fewer than l faces, and for each l some of l or l + 1 (no l-belt fits: type 0) and more.
    assert {g.n for g in grains if g.flag} >= {*range(6, 12), 14}


@pytest.mark.parametrize("length", LENGTHS)
@pytest.mark.parametrize("source", ["raw", "parquet"])
def test_summarize_counts_flag_grains_by_the_split_type_of_their_l_belts(
    length, source, inputs, grains, table
):
    paths = map(str, inputs) if source == "raw" else [str(table)]
    text = _run("summarize", *paths, "--table", "split", "--belt-length", str(length),
                "--format", "csv")  # fmt: skip
    rows = list(csv.reader(io.StringIO(text)))
    counted = {
        (int(row[0]), int(k)): int(count)
        for row in rows[1:]
        for k, count in zip(rows[0][1:], row[1:], strict=True)
        if int(count)
    }
    expected = Counter(
        (g.n, g.split[length]) for g in grains if g.flag and g.split[length] is not None
    )
    assert counted == dict(expected)


@pytest.mark.parametrize("length", LENGTHS)
@pytest.mark.parametrize("source", ["raw", "parquet"])
def test_types_give_each_flag_type_its_split_type_of_l_belts(length, source, inputs, grains, table):
    paths = map(str, inputs) if source == "raw" else [str(table)]
    text = _run("types", *paths, "--belt-length", str(length), "--format", "csv")
    got = {row["weinberg"]: row["split"] for row in csv.DictReader(io.StringIO(text))}
    expected = {}
    for g in grains:
        k = g.split.get(length)
        expected[g.weinberg] = "" if k is None else f"{k}:{length}:{g.n - length - k}"
    assert got == expected


@pytest.mark.parametrize("length", [8, 10])
def test_no_split_table_cell_has_a_negative_side(length, inputs):
    text = _run("summarize", *map(str, inputs), "--table", "split", "--belt-length", str(length))
    cells = [word for word in text.split() if re.fullmatch(r"-?\d+:-?\d+:-?\d+", word)]
    assert cells
    for cell in cells:
        k, belt, m = map(int, cell.split(":"))
        assert (belt, 0 <= k <= m) == (length, True), cell
