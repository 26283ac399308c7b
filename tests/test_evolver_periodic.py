"""Periodic foams whose cells meet their own images, and files that are not 3D foams."""

from __future__ import annotations

import math
import random

import pyarrow as pa
import pytest

from conftest import EVOLVER_DATA
from evolver_expected import FOAMS
from grainclass import classify, read_dataset

DATA = EVOLVER_DATA
# Hand-made files whose cells meet their own periodic images, and the volume of their box
# (|det periods|): a 4 x 4 x 4 cube, the primitive cell of its BCC lattice, a 2 x 2 x 2 cube.
OWN_IMAGES = {
    "kelvin_bcc_torus.fe": 64.0,
    "kelvin_one_cell.fe": 32.0,
    "kelvin_one_cell_fans.fe": 32.0,
    "cube_one_cell.fe": 8.0,
}


def _rows(*paths, **kwargs) -> list[dict]:
    batches = read_dataset([str(p) for p in paths], **kwargs)
    return pa.concat_tables(classify(b) for b in batches).to_pylist()


def _bodies(path):
    """The lines of a datafile before its bodies section, and the bodies' lines."""
    head, bodies = path.read_text().split("\nbodies\n")
    return head, [line for line in bodies.splitlines() if line.strip()]


@pytest.mark.parametrize("name", sorted(OWN_IMAGES))
def test_a_cell_that_meets_its_own_image_is_one_grain(name):
    rows = _rows(DATA / name)
    expected = FOAMS[name]["bodies"]
    stem = name.removesuffix(".fe")
    assert [r["grain_id"] for r in rows] == (
        [stem] if len(expected) == 1 else [str(b) for b in expected]
    )
    for row, want in zip(rows, expected.values(), strict=True):
        assert row["status"] == "ok", row["error"]
        got = (row["n_faces"], tuple(row["p_vector"]), row["class"], row["truncations"])
        assert got == (want["n_faces"], want["p_vector"], want["class"], want["truncations"])
        assert row["symmetry"] == want["symmetry"]
        assert row["volume"] == pytest.approx(want["volume"], rel=1e-12)
        assert row["area"] == pytest.approx(want["area"], rel=1e-8)
        assert row["boundary"] is False


@pytest.mark.parametrize("name", sorted(OWN_IMAGES))
def test_the_cells_of_a_periodic_box_fill_it(name):
    rows = _rows(DATA / name)
    assert sum(r["volume"] for r in rows) == pytest.approx(OWN_IMAGES[name], rel=1e-12)


@pytest.mark.parametrize("name", sorted(OWN_IMAGES))
def test_order_and_direction_of_a_body_list_do_not_matter(tmp_path, name):
    """The same cells with each body's facets listed in another order, and with every sign
    turned (facets listed inwards: volumes come out positive all the same)."""
    head, lines = _bodies(DATA / name)
    rng = random.Random(name)
    shuffled, inward = [], []
    for line in lines:
        body, facets = line.split("\t")
        ids = facets.split()
        rng.shuffle(ids)
        shuffled.append(f"{body}\t{' '.join(ids)}")
        inward.append(f"{body}\t{' '.join(str(-int(f)) for f in facets.split())}")
    want = [(r["n_faces"], r["p_vector"], r["symmetry"], r["volume"]) for r in _rows(DATA / name)]
    for variant, body_lines in (("shuffled", shuffled), ("inward", inward)):
        path = tmp_path / f"{variant}.fe"
        path.write_text(head + "\nbodies\n" + "\n".join(body_lines) + "\n")
        got = [(r["n_faces"], r["p_vector"], r["symmetry"], r["volume"]) for r in _rows(path)]
        assert [g[:3] for g in got] == [w[:3] for w in want], variant
        assert [g[3] for g in got] == pytest.approx([w[3] for w in want], rel=1e-12)


def test_a_facet_listed_twice_the_same_way_is_reported(tmp_path):
    head, lines = _bodies(DATA / "kelvin_one_cell.fe")
    body, facets = lines[0].split("\t")
    ids = facets.split()
    assert ids[-1] == "-1"
    path = tmp_path / "same-way.fe"
    path.write_text(head + f"\nbodies\n{body}\t{' '.join([*ids[:-1], '1'])}\n")
    (row,) = _rows(path)
    assert row["status"] == "invalid"
    assert "body 1 lists facet 1 twice the same way" in row["error"]


# A slab that goes around a 1 x 1 x 2 box in x and y: its surface is two tori (a top and a
# bottom facet, each a square whose edges are one x and one y edge, wrapping), not a sphere.
SLAB = """\
TORUS_FILLED
periods
1 0 0
0 1 0
0 0 2
vertices
1 0 0 0
2 0 0 1
edges
1 1 1 + * *
2 1 1 * + *
3 2 2 + * *
4 2 2 * + *
5 1 2 * * *
faces
1 1 2 -1 -2
2 3 4 -3 -4
bodies
1 -1 2
2 1 -2
"""


def test_a_cell_that_goes_around_the_box_is_not_a_grain(tmp_path):
    path = tmp_path / "slabs.fe"
    path.write_text(SLAB)
    rows = _rows(path)
    assert [r["status"] for r in rows] == ["invalid", "invalid"]
    assert (
        "unwrapped across the periodic box, the surface of body 1 does not close"
        in (rows[0]["error"])
    )


def test_a_facet_whose_wrap_marks_do_not_add_up_is_named(tmp_path):
    """Facet 1 of the one-cube torus runs -y, +z, +y, -z; made -y, +z, -y, -z, its edges still
    join up (the box has one vertex) but it ends two periods from where it starts."""
    text = (DATA / "cube_one_cell.fe").read_text()
    assert "\n1\t-1 2 1 -2\n" in text
    path = tmp_path / "wraps.fe"
    path.write_text(text.replace("\n1\t-1 2 1 -2\n", "\n1\t-1 2 -1 -2\n"))
    (row,) = _rows(path)
    assert row["status"] == "invalid"
    assert "facet 1 goes around the periodic box" in row["error"]


def test_a_facet_whose_edges_do_not_join_up_is_named(tmp_path):
    text = (DATA / "two_cubes.fe").read_text()
    assert "\n7\t13\t14\t15\t16\n" in text
    path = tmp_path / "open-facet.fe"
    path.write_text(text.replace("\n7\t13\t14\t15\t16\n", "\n7\t13\t15\t14\t16\n"))
    rows = _rows(path)
    assert [r["status"] for r in rows] == ["ok", "invalid"]
    assert "body 2: facet 7 is not a closed loop of edges" in rows[1]["error"]


def test_a_facet_listed_against_the_others_is_named(tmp_path):
    head, lines = _bodies(DATA / "two_cubes.fe")
    assert lines[0] == "1\t1 2 3 4 5 6"
    path = tmp_path / "flipped.fe"
    path.write_text(head + "\nbodies\n1\t1 2 3 -4 5 6\n" + lines[1] + "\n")
    first, second = _rows(path)
    assert (first["status"], second["status"]) == ("invalid", "ok")
    assert "not an oriented surface: facets" in first["error"]
    assert "of body 1 both run along edge" in first["error"]


# Files that are not 3D foams: a row each, which says why in the user's terms.
SQUARE = "vertices\n1 0 0\n2 1 0\n3 1 1\n4 0 1\nedges\n1 1 2\n2 2 3\n3 3 4\n4 4 1\n"
CUBE_FILM = (DATA / "two_cubes.fe").read_text().split("\nbodies\n")[0] + "\n"


@pytest.mark.parametrize(
    ("text", "line", "message"),
    [
        (
            "// a 2D foam\nSTRING\nSPACE_DIMENSION 2\n" + SQUARE + "faces\n1 1 2 3 4\n",
            3,
            "a 2D file: grainclass reads 3D bodies",
        ),
        ("SPACE_DIMENSION 2\n" + SQUARE, 1, "a 2D file: grainclass reads 3D bodies"),
        ("STRING\n" + SQUARE, 1, "a string model: grainclass reads 3D bodies"),
        (
            "SIMPLEX_REPRESENTATION\nSPACE_DIMENSION 4\nSURFACE_DIMENSION 3\n"
            "vertices\n1 0 0 0 0\n2 1 0 0 0\n3 0 1 0 0\n4 0 0 1 0\n5 0 0 0 1\n"
            "faces\n1 1 2 3 4\n2 2 3 4 5\nbodies\n1 1 2\n",
            2,
            "a file in 4-space: grainclass reads 3D bodies",
        ),
        (
            "SIMPLEX_REPRESENTATION\nvertices\n1 0 0 0\n2 1 0 0\n3 0 1 0\nfaces\n1 1 2 3\n",
            1,
            "facets given by their vertices (simplex_representation)",
        ),
        (
            'SYMMETRY_GROUP "torus"\n' + CUBE_FILM + "bodies\n1 1 2 3 4 5 6\n",
            1,
            "a quotient space (symmetry_group)",
        ),
        (CUBE_FILM, CUBE_FILM.split("\n").index("faces") + 1, "a film without bodies"),
    ],
    ids=["2D string", "2D", "string", "4-space", "simplex", "quotient", "film"],
)
def test_a_file_that_is_not_a_3d_foam_says_what_it_is(tmp_path, text, line, message):
    path = tmp_path / "other.fe"
    path.write_text(text)
    (row,) = _rows(path)
    assert row["status"] == "invalid"
    assert row["error"].startswith(f"{path}:{line}: {message}")


def test_kelvin_cells_in_a_torus_have_the_areas_of_the_formula():
    """12 + 24 sqrt(3) for edge sqrt(2): 6 squares of area 2, 8 regular hexagons of 3 sqrt(3)."""
    for row in _rows(DATA / "kelvin_bcc_torus.fe"):
        assert row["area"] == pytest.approx(12 + 24 * math.sqrt(3), rel=1e-12)


def test_an_edge_of_no_length_where_a_cell_meets_its_image_is_named(tmp_path):
    """Edge 1 of the one-cell cube cut down to a loop at vertex 1 (no wrap marks): pairing the
    patches around it divided by its length, and the reader ended in a ZeroDivisionError."""
    text = (DATA / "cube_one_cell.fe").read_text()
    assert "\n1\t1\t1\t*\t+\t*\n" in text
    path = tmp_path / "point_edge.fe"
    path.write_text(text.replace("\n1\t1\t1\t*\t+\t*\n", "\n1\t1\t1\n"))
    (row,) = _rows(path)
    assert row["status"] == "invalid"
    assert "uses edge 1 8 times" in row["error"]
    assert "the edge has no length" in row["error"]
