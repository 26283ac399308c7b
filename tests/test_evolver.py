"""The Surface Evolver reader on the grain-growth fixtures and on hand-made foams."""

from __future__ import annotations

import shutil
from pathlib import Path

import pyarrow as pa
import pytest
from click.testing import CliRunner

from conftest import EVOLVER_DATA, EVOLVER_FIXTURES, ctrl_c_at_a_terminal
from evolver_expected import FIXTURES, FOAMS
from grainclass import classify, read_dataset
from grainclass.cli import cli
from grainclass.readers import sniff

FIXTURE_DIR = EVOLVER_FIXTURES
DATA = EVOLVER_DATA


def _rows(*paths, **kwargs) -> list[dict]:
    batches = read_dataset([str(p) for p in paths], **kwargs)
    return pa.concat_tables(classify(b) for b in batches).to_pylist()


@pytest.fixture(scope="module")
def fixture_rows() -> dict[str, dict]:
    return {row["grain_id"] + ".fe": row for row in _rows(FIXTURE_DIR)}


def test_folder_reads_every_fixture_as_one_grain(fixture_rows):
    assert sorted(fixture_rows) == sorted(FIXTURES)
    assert {Path(r["source"]).parent for r in fixture_rows.values()} == {FIXTURE_DIR}


@pytest.mark.parametrize("name", sorted(FIXTURES))
def test_fixture_grain_matches_independent_derivation(fixture_rows, name):
    row, expected = fixture_rows[name], FIXTURES[name]
    assert row["status"] == expected["status"]
    assert row["n_faces"] == expected["n_faces"]
    assert row["volume"] == pytest.approx(expected["volume"], rel=1e-8)
    assert row["area"] == pytest.approx(expected["area"], rel=1e-8)
    if expected["status"] == "ok":
        assert tuple(row["p_vector"]) == expected["p_vector"]
        assert row["class"] == expected["class"]
        assert row["truncations"] == expected["truncations"]
        # Euler: corners - triple lines + faces = 2, and every corner has three faces.
        edges = sum(k * c for k, c in enumerate(row["p_vector"], 3)) // 2
        assert edges == expected["n_triple_lines"] == 3 * row["n_faces"] - 6
        assert 2 * edges // 3 == expected["n_corners"]
    else:
        assert "2-gon" in row["error"]
        assert row["error"].startswith(f"{FIXTURE_DIR / name}:")


def test_fixtures_listed_one_by_one_equal_the_folder(fixture_rows):
    files = sorted(FIXTURE_DIR.glob("*.fe"))
    rows = _rows(*files, chunk_size=3)
    assert {r["grain_id"] + ".fe": r for r in rows} == fixture_rows


def test_other_triple_edge_attribute_is_configurable(tmp_path):
    text = (FIXTURE_DIR / "21000-00000029.fe").read_text().replace("color red", "color green")
    path = tmp_path / "green.fe"
    path.write_text(text)
    row = _rows(path, triple_edges=("color", "green"))[0]
    assert (row["class"], row["n_faces"]) == ("flag", 10)


@pytest.mark.parametrize("name", ["two_cubes.fe", "kelvin_foam.fe"])
def test_whole_foam_file_makes_every_body_a_grain(name):
    rows = _rows(DATA / name)
    expected = FOAMS[name]["bodies"]
    assert [r["grain_id"] for r in rows] == [str(b) for b in expected]
    for row in rows:
        want = expected[int(row["grain_id"])]
        assert row["status"] == "ok"
        got = (row["n_faces"], tuple(row["p_vector"]), row["class"], row["truncations"])
        assert got == (want["n_faces"], want["p_vector"], want["class"], want["truncations"])
        assert row["symmetry"] == want["symmetry"]
        assert row["volume"] == pytest.approx(want["volume"], rel=1e-9)
        assert row["area"] == pytest.approx(want["area"], rel=1e-8)
        assert row["isoperimetric"] == pytest.approx(
            36 * 3.141592653589793 * want["volume"] ** 2 / want["area"] ** 3
        )


def test_open_surface_is_reported_not_crashed_on():
    (row,) = _rows(DATA / "open_surface.fe")
    assert row["status"] == "invalid"
    assert "not a closed surface: edge 1 lies on 1 facet" in row["error"]


def test_corner_of_four_faces_is_non_simple():
    (row,) = _rows(DATA / "four_face_corner.fe")
    want = FOAMS["four_face_corner.fe"]
    assert row["status"] == "non_simple"
    assert f"a corner where {want['max_faces_at_corner']} faces meet" in row["error"]
    assert row["volume"] == pytest.approx(want["volume"], rel=1e-8)


def test_body_whose_surface_touches_itself_is_not_a_grain(tmp_path):
    """The first cube of two_cubes.fe with its opposite corners 1 and 6 made one vertex: every
    edge still lies on two facets and the faces touch as a cube's do, but the surface is pinched
    at vertex 1 (V - E + F = 7 - 12 + 6 = 1)."""
    text = (DATA / "two_cubes.fe").read_text()
    head, _ = text.split("\nbodies\n")
    for edge, pinched in (("5\t5\t6", "5\t5\t1"), ("6\t6\t7", "6\t1\t7"), ("12\t6\t3", "12\t1\t3")):
        assert edge in head
        head = head.replace(edge, pinched)
    path = tmp_path / "pinched.fe"
    path.write_text(head + "\nbodies\n1\t1 2 3 4 5 6\n")
    (row,) = _rows(path)
    assert row["status"] == "invalid"
    assert "not a sphere: the surface of body 1 has vertices - edges + facets = 1" in row["error"]


@pytest.mark.parametrize(
    ("volume", "error"),
    [
        ("1", None),
        ("0.5", None),  # a body's own volume wins over the geometry's
        ("nan", "body 1: volume nan: expected a finite number, 0 or more"),
        ("inf", "body 1: volume inf: expected a finite number, 0 or more"),
        ("-1", "body 1: volume -1: expected a finite number, 0 or more"),
        # A ball of area 6 holds sqrt(6^3 / (36 pi)) = 1.38: a unit cube's surface cannot hold 2.
        ("2", "body 1: volume 2 is more than a surface of area 6 can hold (36 pi V^2 > S^3)"),
    ],
)
def test_given_volume_is_checked_as_in_adjacency_text(tmp_path, volume, error):
    text = (DATA / "two_cubes.fe").read_text()
    head, _ = text.split("\nbodies\n")
    path = tmp_path / "given.fe"
    path.write_text(head + f"\nbodies\n1\t1 2 3 4 5 6 volume {volume}\n2\t-2 7 8 9 10 11\n")
    first, second = _rows(path)
    assert second["status"] == "ok"
    assert second["volume"] == pytest.approx(1)
    if error is None:
        assert first["status"] == "ok"
        assert first["volume"] == float(volume)
    else:
        assert first["status"] == "invalid"
        assert error in first["error"]


def test_body_touching_its_own_periodic_image_is_reported(tmp_path):
    # Two bodies sharing facet 1 become one body using it twice.
    text = (DATA / "two_cubes.fe").read_text()
    head, bodies = text.split("\nbodies\n")
    lines = [line for line in bodies.splitlines() if line.strip()]
    merged = "1\t" + " ".join(lines[0].split()[1:] + lines[1].split()[1:])
    path = tmp_path / "self.fe"
    path.write_text(head + "\nbodies\n" + merged + "\n")
    (row,) = _rows(path)
    assert row["status"] == "invalid"
    assert "touches its own periodic image" in row["error"]


def test_malformed_file_is_one_bad_grain_among_good_ones(tmp_path):
    shutil.copy(FIXTURE_DIR / "21000-00000029.fe", tmp_path / "a.fe")
    (tmp_path / "b.fe").write_text("vertices\n1 0 0 zero\n")
    rows = _rows(tmp_path)
    assert [(r["grain_id"], r["status"]) for r in rows] == [("a", "ok"), ("b", "invalid")]
    assert rows[1]["error"] == f"{tmp_path / 'b.fe'}:2: cannot read this vertex line"


def test_a_digit_that_int_cannot_read_is_no_entry(tmp_path):
    """'²' is a digit to str.isdigit() but not to int(): taken for an entry id, it crashed."""
    path = tmp_path / "sup.fe"
    path.write_text(
        (DATA / "two_cubes.fe").read_text().replace("\n12\t2\t0\t1", "\n\u00b2\t2\t0\t1")
    )
    rows = _rows(path)
    assert [(r["grain_id"], r["status"]) for r in rows] == [("1", "ok"), ("2", "invalid")]
    assert "body 2: edge 15 names vertex 12, which the file does not define" in rows[1]["error"]


@pytest.mark.parametrize(
    ("line", "changed", "message"),
    [
        ("\n2\t-2 7 8", "\n2\t-2 70 8", "body 2: its list of facets names facet 70, which"),
        ("\n7\t13\t14", "\n7\t13\t40", "body 2: facet 7 names edge 40, which"),
        ("\n10\t2\t1\t0", "\n30\t2\t1\t0", "body 2: edge 13 names vertex 10, which"),
    ],
)
def test_an_undefined_entry_is_named_with_what_refers_to_it(tmp_path, line, changed, message):
    text = (DATA / "two_cubes.fe").read_text()
    assert line in text
    path = tmp_path / "undefined.fe"
    path.write_text(text.replace(line, changed))
    rows = _rows(path)
    assert [(r["grain_id"], r["status"]) for r in rows] == [("1", "ok"), ("2", "invalid")]
    assert message in rows[1]["error"]


def test_an_id_too_long_for_int_is_an_invalid_row(tmp_path):
    path = tmp_path / "long.fe"
    path.write_text("vertices\n" + "1" * 5000 + " 0 0 0\nbodies\n1 1\n")
    (row,) = _rows(path)
    assert row["status"] == "invalid"
    assert "vertex id 11111111111111111111... is too long" in row["error"]


def test_file_without_bodies_keeps_its_row(tmp_path):
    """An empty dump, or one cut off before its bodies, among good ones: a row each, invalid."""
    good = (FIXTURE_DIR / "21000-00000029.fe").read_text()
    shutil.copy(FIXTURE_DIR / "21000-00000029.fe", tmp_path / "a.fe")
    (tmp_path / "b.fe").write_text(good[: good.lower().index("bodies")])
    (tmp_path / "c.fe").write_text("")
    rows = _rows(tmp_path)
    assert [(r["grain_id"], r["status"]) for r in rows] == [
        ("a", "ok"),
        ("b", "invalid"),
        ("c", "invalid"),
    ]
    assert rows[2]["error"].startswith(f"{tmp_path / 'c.fe'}:1: no bodies")


def test_evolver_is_sniffed_without_the_extension(tmp_path):
    path = tmp_path / "grain.txt"
    shutil.copy(FIXTURE_DIR / "21000-00000007.fe", path)
    assert sniff(path.read_bytes()[:4096]) == "evolver"
    assert _rows(path)[0]["class"] == "flag"


def test_cli_classifies_a_folder(tmp_path):
    out = tmp_path / "g.parquet"
    result = CliRunner().invoke(cli, ["classify", str(FIXTURE_DIR), "-o", str(out)])
    assert result.exit_code == 0
    assert "10 grains classified (8 ok, 2 degenerate)" in result.stderr


@pytest.mark.parametrize("jobs", [1, 2])
def test_groups_of_files_read_on_threads_give_the_same_grains_in_order(
    fixture_rows, monkeypatch, jobs
):
    """Two files to a kernel call: five groups, read on one thread or two, in order."""
    from grainclass.parallel import get_jobs, set_jobs

    monkeypatch.setattr("grainclass.readers.evolver.PART_FILES", 2)
    before = get_jobs()
    set_jobs(jobs)
    try:
        rows = _rows(FIXTURE_DIR)
    finally:
        set_jobs(before)
    assert [r["grain_id"] for r in rows] == sorted(r[:-3] for r in FIXTURES)
    assert {r["grain_id"] + ".fe": r for r in rows} == fixture_rows


@pytest.mark.parametrize("forced", [False, True])
def test_standard_input_is_refused_with_a_reason(forced):
    """Sniffed or named with --format, an Evolver datafile on standard input gets the same
    message (it is read by file: a folder is a dataset)."""
    text = (FIXTURE_DIR / "21000-00000029.fe").read_text()
    options = ["--format", "evolver"] if forced else []
    result = CliRunner().invoke(cli, ["classify", *options, "-", "-o", "-"], input=text)
    assert result.exit_code == 1
    assert "-: Surface Evolver input must be a file or a folder" in result.stderr


@pytest.mark.parametrize(
    ("spoil", "bad_body", "message"),
    [
        (("2\t-2 7 8 9 10 11", "2\t-2 7 8 9 10 11 volume"), "2", "cannot read this body line"),
        (("2\t-2 7 8 9 10 11", "2\tx7 8 9 10 11"), "2", "cannot read this body line"),
        (
            ("12\t2\t0\t1", "12\t2\tzero\t1"),
            "2",
            "body 2: cannot read the line of its vertex 12 (line 18)",
        ),
    ],
    ids=["volume without value", "no facets", "vertex line"],
)
def test_one_bad_line_of_a_whole_foam_fails_only_the_bodies_that_need_it(
    tmp_path, spoil, bad_body, message
):
    text = (DATA / "two_cubes.fe").read_text()
    assert text.count(spoil[0]) == 1
    path = tmp_path / "foam.fe"
    path.write_text(text.replace(*spoil))
    rows = _rows(path)
    assert [(r["grain_id"], r["status"]) for r in rows] == [("1", "ok"), ("2", "invalid")]
    assert message in rows[1]["error"]


def test_ctrl_c_at_a_terminal_stops_the_readers_quietly(tmp_path):
    """Ctrl-C while the reader's threads are at work (the first batches written, many files
    still to read): the run exits 130 without a traceback, and leaves no output behind."""
    folder = tmp_path / "dump"
    folder.mkdir()
    source = next(FIXTURE_DIR.glob("*.fe")).read_bytes()
    for k in range(3000):
        (folder / f"{k:04d}.fe").write_bytes(source)
    out = tmp_path / "out.parquet"

    def writing(pid: int) -> bool:
        return any(p.name != "dump" for p in tmp_path.iterdir())

    code, err = ctrl_c_at_a_terminal(
        "classify", str(folder), "-o", str(out), "-q", "--chunk-size", "64", when=writing
    )
    assert code == 130
    assert "Traceback" not in err
    assert [p.name for p in tmp_path.iterdir()] == ["dump"]


@pytest.mark.parametrize(
    "damaged", ["7\tx13\t14\t15\t16", "7\t13\tx14\t15\t16", "7\t13\t14\t15\t16.0"]
)
def test_a_damaged_facet_line_is_named(tmp_path, damaged):
    """Its ids were read up to the damage and the rest taken for attributes: the body came out
    'not a closed surface', its line never named."""
    text = (DATA / "two_cubes.fe").read_text()
    line = "\n7\t13\t14\t15\t16\n"
    assert line in text
    path = tmp_path / "damaged.fe"
    path.write_text(text.replace(line, f"\n{damaged}\n"))
    number = text[: text.index(line) + 1].count("\n") + 1
    rows = _rows(path)
    assert [(r["grain_id"], r["status"]) for r in rows] == [("1", "ok"), ("2", "invalid")]
    assert rows[1]["error"].endswith(f"body 2: cannot read the line of its facet 7 (line {number})")
