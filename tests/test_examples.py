"""The hand-built polytopes of examples/polytopes.txt against values derived by hand."""

from __future__ import annotations

import pyarrow as pa
import pytest

import reference
from conftest import EXAMPLES
from grainclass import GrainBatch, classify, read_dataset
from hand_derived import EXPECTED

FIELDS = [
    "n_faces",
    "p_vector",
    "family",
    "class",
    "truncations",
    "fundamental_faces",
    "trees",
    "depth",
    "round_k",
    "split_k",
    "split_m",
    "belts4",
    "penalty",
]


def _rows() -> dict[str, dict]:
    table = pa.concat_tables(classify(b) for b in read_dataset(str(EXAMPLES / "polytopes.txt")))
    return {row["grain_id"]: row for row in table.to_pylist()}


ROWS = _rows()


def test_examples_cover_every_hand_derived_grain():
    assert set(ROWS) == set(EXPECTED)


@pytest.mark.parametrize("grain_id", sorted(EXPECTED))
def test_classify_example_matches_hand_derivation(grain_id):
    row = ROWS[grain_id]
    assert row["status"] == "ok"
    assert row["error"] is None
    got = {f: tuple(row[f]) if f == "p_vector" else row[f] for f in FIELDS}
    assert got == EXPECTED[grain_id]


@pytest.mark.parametrize("grain_id", sorted(EXPECTED))
def test_reference_oracle_matches_hand_derivation(grain_id):
    # Guards the oracle that the property tests rely on.
    lines = (EXAMPLES / "polytopes.txt").read_text().splitlines()
    faces = next(line.split("\t")[1] for line in lines if line.startswith(grain_id + "\t"))
    lists = [[int(x) for x in face.split()] for face in faces.split(";")]
    assert reference.classify(lists) == EXPECTED[grain_id]


def test_classify_example_volume_and_area_give_isoperimetric_quotient(tmp_path):
    # A unit cube: V = 1, S = 6, Q = 36 pi / 216 = pi / 6.
    path = tmp_path / "cube.txt"
    path.write_text(
        "cube\t1 2 3 4;0 4 5 2;0 1 5 3;0 2 5 4;0 3 5 1;1 4 3 2\tvolume=1\tarea=6\tphase=b\n"
    )
    row = classify(next(read_dataset(str(path)))).to_pylist()[0]
    assert row["volume"] == 1.0
    assert row["area"] == 6.0
    assert row["isoperimetric"] == pytest.approx(3.141592653589793 / 6)
    assert row["phase"] == "b"


def test_trees_of_the_papers_figure_4_grain():
    # The cube (dual: octahedron) truncated seven times as the paper's Fig. 4 draws it: two
    # single truncations, a tree of two and a path of three. Built by stacking into faces of
    # the octahedron, each child into a triangle made by its parent.
    faces = {(0, 1, 2), (0, 2, 3), (0, 3, 4), (0, 4, 1), (5, 2, 1), (5, 3, 2), (5, 4, 3), (5, 1, 4)}
    v = 6

    def stack(face):
        nonlocal v
        a, b, c = face
        faces.remove(face)
        faces.update({(a, b, v), (b, c, v), (c, a, v)})
        v += 1
        return (a, b, v - 1)  # a triangle made by this truncation

    stack((0, 1, 2))
    stack((5, 3, 2))
    stack(stack((0, 3, 4)))
    stack(stack(stack((5, 1, 4))))
    from strategies import rotation_lists

    row = classify(GrainBatch.from_lists([rotation_lists(faces, v)])).to_pylist()[0]
    assert (row["n_faces"], row["class"], row["truncations"]) == (13, "flag>=3", 7)
    assert (row["trees"], row["depth"], row["round_k"]) == ("()+()+(())+((()))", 3, 7)
