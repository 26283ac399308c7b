"""Neper tessellation files (.tess): hand-written unit cubes in Neper's documented layout."""

from __future__ import annotations

import io
import re
from pathlib import Path

import numpy as np
import pytest

from grainclass import classify
from grainclass.errors import InputError
from grainclass.readers import neper
from grainclass.readers.neper import looks_like_neper, read_neper

DATA = Path(__file__).parent / "data" / "neper"
CUBE = {"status": "ok", "class": "flag", "n_faces": 6, "p_vector": [0, 6], "penalty": 18}


def _rows(path: Path, chunk_size: int = 1000) -> list[dict]:
    with path.open("rb") as f:
        return [row for batch in read_neper(f, str(path), chunk_size) for row in _classify(batch)]


def _classify(batch) -> list[dict]:
    return classify(batch).to_pylist()


def _rows_of(text: str) -> list[dict]:
    return [
        row for b in read_neper(io.BytesIO(text.encode()), "t.tess", 1000) for row in _classify(b)
    ]


def _line_of(path: Path, entry: str) -> int:
    return path.read_text().splitlines().index(entry) + 1


def test_a_unit_cube():
    (row,) = _rows(DATA / "cube.tess")
    assert {key: row[key] for key in CUBE} == CUBE
    assert row["grain_id"] == "1"
    assert row["volume"] == pytest.approx(1.0)
    assert row["area"] == pytest.approx(6.0)
    assert row["boundary"] is True
    assert row["error"] is None


@pytest.mark.parametrize("chunk_size", [1, 1000])
def test_two_cubes_sharing_a_face(chunk_size):
    rows = _rows(DATA / "two_cells.tess", chunk_size)
    assert [row["grain_id"] for row in rows] == ["1", "2"]
    for row in rows:
        assert {key: row[key] for key in CUBE} == CUBE
        assert row["volume"] == pytest.approx(1.0)
        assert row["area"] == pytest.approx(6.0)
        assert row["boundary"] is True


@pytest.mark.parametrize("name", ["cube.tess", "two_cells.tess"])
def test_loops_turn_the_same_way_and_face_outwards(monkeypatch, name):
    """Faces with negative ids are reversed: every edge is walked once each way, and the loops
    enclose a positive volume (measured from a point outside, so that no face drops out)."""
    seen = []
    real = neper.batch_from_loops

    def spy(rows, *args, **kwargs):
        seen.extend(rows)
        return real(rows, *args, **kwargs)

    monkeypatch.setattr(neper, "batch_from_loops", spy)
    path = DATA / name
    _rows(path)
    with path.open("rb") as f:
        coords, _ = neper._vertices(neper._Sections(f, name))
    outside = np.array([-5.0, -7.0, -11.0])
    assert seen
    for _, _, loops, _, _, error in seen:
        assert error is None
        directed = [
            (u, v) for loop in loops for u, v in zip(loop, loop[1:] + loop[:1], strict=True)
        ]
        assert sorted(directed) == sorted((v, u) for u, v in directed)
        volume = 0.0
        for loop in loops:
            p = coords[loop] - outside
            volume += sum(np.dot(p[0], np.cross(p[i], p[i + 1])) for i in range(1, len(p) - 1))
        assert volume / 6 == pytest.approx(1.0)


def test_a_polyhedron_with_a_missing_face_is_an_invalid_row():
    path = DATA / "bad_face.tess"
    line = _line_of(path, "    2 6 -2 7 8 9 10 12")
    rows = _rows(path)
    assert [row["status"] for row in rows] == ["ok", "invalid"]
    assert rows[0]["error"] is None
    assert rows[1]["grain_id"] == "2"
    assert rows[1]["error"] == f"{path}:{line}: polyhedron 2: face 12 does not exist"


TWO = (DATA / "two_cells.tess").read_text()
POLY2 = "    2 6 -2 7 8 9 10 11\n"
FACE11 = "   11 4 8 9 12 11\n     4 -18 -15 -19 7\n"


# A square pyramid whose faces Neper numbers 11 (the base) to 15: its apex is a corner of four
# faces, 12 to 15, each listed with its vertices outward.
PYRAMID = """***tess
 **format
   3.4
 **general
   3 standard
 **vertex
 5
    1  0 0 0     0
    2  1 0 0     0
    3  1 1 0     0
    4  0 1 0     0
    5  0.5 0.5 1     0
 **edge
 8
    1  1 2 0
    2  2 3 0
    3  3 4 0
    4  4 1 0
    5  1 5 0
    6  2 5 0
    7  3 5 0
    8  4 5 0
 **face
 5
   11 4 1 4 3 2
     4 -4 -3 -2 -1
    0 0 0 0
     0 0 0 0 0
   12 3 1 2 5
     3 1 6 -5
    0 0 0 0
     0 0 0 0 0
   13 3 2 3 5
     3 2 7 -6
    0 0 0 0
     0 0 0 0 0
   14 3 3 4 5
     3 3 8 -7
    0 0 0 0
     0 0 0 0 0
   15 3 4 1 5
     3 4 5 -8
    0 0 0 0
     0 0 0 0 0
 **polyhedron
 1
    1 5 11 12 13 14 15
***end
"""


def test_messages_name_faces_by_their_ids_in_the_file():
    (row,) = _rows_of(PYRAMID)
    assert row["status"] == "non_simple"
    assert row["volume"] == pytest.approx(1 / 3, rel=1e-12)
    assert re.search(r"a corner where 4 faces meet \(face (12|13|14|15) is one of them\)$",
                     row["error"]), row["error"]  # fmt: skip


@pytest.mark.parametrize("edges", ["-15 -19 7 -18", "7 -18 -15 -19"])
def test_a_face_may_list_its_edges_from_another_vertex(edges):
    """Neper writes some faces' edges starting at another vertex than their vertices: the
    same sides, so the same two unit cubes."""
    rows = _rows_of(TWO.replace(FACE11, f"   11 4 8 9 12 11\n     4 {edges}\n"))
    assert [(r["status"], r["n_faces"]) for r in rows] == [("ok", 6), ("ok", 6)]
    assert [r["volume"] for r in rows] == pytest.approx([1.0, 1.0], rel=1e-12)


@pytest.mark.parametrize(
    ("old", "new", "message"),
    [
        (POLY2, "    2 6 -2 7 8 9 10 x\n", "bad polyhedron entry: expected integers"),
        (POLY2, "    2x 6 -2 7 8 9 10 11\n", "bad polyhedron entry: expected integers"),
        (POLY2, "    2\n", "bad polyhedron entry: the number of faces is missing"),
        (POLY2, "    2 5 -2 7 8 9 10 11\n", "bad polyhedron entry: announces 5 faces but lists 6"),
        (POLY2, "    2 6 -2 7 8 9 10 10\n", "polyhedron 2: a face is listed twice"),
        (POLY2, "    2 3 -2 7 8\n", "polyhedron 2: 3 faces (a polyhedron has at least 4)"),
        (POLY2, "    2 6 -2 7 8 9 10 0\n", "polyhedron 2: face 0 does not exist"),
        (POLY2, "    2 6 -2 7 8 9 10 -11\n", "both run from vertex"),
        (POLY2, "    2 6 2 7 8 9 10 11\n", "both run from vertex"),
        (POLY2, "    1 6 -2 7 8 9 10 11\n", "bad polyhedron entry: polyhedron 1 appears twice"),
        (FACE11, "   11 4 8 9 99 11\n     4 -18 -15 -19 7\n", "face 11: vertex 99 does not exist"),
        (FACE11, "   11 4 8 9 12 11\n     4 -18 -15 -19 6\n", "edge 6 does not join vertices 11"),
        (FACE11, "   11 4 8 9 12 11\n     3 -18 -15 -19\n", "face 11 has 4 vertices but 3 edges"),
    ],
)
def test_malformed_entries_make_the_second_cube_invalid(old, new, message):
    assert old in TWO
    rows = _rows_of(TWO.replace(old, new))
    assert rows[0]["status"] == "ok"
    assert rows[1]["status"] == "invalid"
    assert rows[1]["boundary"] is None  # no faces to tell
    line = TWO.splitlines().index(POLY2.rstrip("\n")) + 1
    assert rows[1]["error"].startswith(f"t.tess:{line}: ")
    assert message in rows[1]["error"]


@pytest.mark.parametrize(
    ("old", "new", "message"),
    [
        ("***tess", "***tesr", "expected ***tess"),
        ("   3 standard", "   2 standard", "only 3D tessellations"),
        (" **polyhedron\n 2\n", " **polyhedron\n 3\n", "announces 3 polyhedra but has 2"),
        (" **vertex\n 12\n", " **vertex\n 13\n", "**vertex announces 13 entries but has 12"),
        (" **edge\n 20\n", " **edge\n 0\n", "**edge announces 0 entries but has 20"),
        (" **face\n 11\n", " **face\n 12\n", "**face: the section ends inside"),
        (" **face\n 11\n", " **face\n 10\n", "**face announces 10 faces but has more"),
        (FACE11, "   11 4 8 9 12 11\n     4 -18 -15 -19 7.5\n", "expected integers in face 11"),
        (FACE11, "   11 -4 8 9 12 11\n     4 -18 -15 -19 7\n", "face 11: a count of -4"),
        (" **edge\n 20\n", " **edge\n -20\n", "**edge: expected the number of entries"),
        ("   12  2.0000", "   12  x.0000", "bad vertex 12"),
        ("   12  2.0000", "   13  2.0000", "id 13 is not between 1 and 12"),
        ("   12  2.0000", "   12.0  2.0000", "the id '12.0' is not a whole number"),
        ("   20  6 5 0", "   19  6 5 0", "id 19 appears twice"),
        (" **polyhedron", " **polyhedra", "no **polyhedron section"),
        (" **edge", " **vertex", "section **vertex appears twice"),
    ],
)
def test_unreadable_sections_raise(old, new, message):
    assert old in TWO
    with pytest.raises(InputError, match=message.replace("*", r"\*").replace(".", r"\.")):
        _rows_of(TWO.replace(old, new))


def test_sniffing():
    assert looks_like_neper((DATA / "cube.tess").read_bytes()[:4096])
    assert looks_like_neper(b"\n  \n***tess\n **format\n")
    assert not looks_like_neper(b"***tesr\n")
    assert not looks_like_neper(b"***tessellation\n")
    assert not looks_like_neper(b"1\t1 2 3;4 5 6\n")


def test_neper_files_are_sniffed_by_read_dataset():
    from grainclass import read_dataset

    rows = classify(next(read_dataset(str(DATA / "two_cells.tess")))).to_pylist()
    assert [(r["grain_id"], r["class"], r["boundary"]) for r in rows] == [
        ("1", "flag", True),
        ("2", "flag", True),
    ]


def test_periodic_tessellation_leaves_boundary_unknown(tmp_path):
    text = (DATA / "cube.tess").read_text().replace("***end", " **periodic\n  1 1 1\n***end")
    path = tmp_path / "periodic.tess"
    path.write_text(text)
    with open(path, "rb") as stream:
        (row,) = classify(next(read_neper(stream, str(path), 10))).to_pylist()
    assert (row["class"], row["boundary"]) == ("flag", None)
