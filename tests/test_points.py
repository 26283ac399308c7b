"""grainclass voronoi --points: Voronoi and Laguerre cells of given points, against the voro++
program, on lattices, from every points format, and refusing bad input."""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import numpy as np
import pyarrow as pa
import pyarrow.compute as pc
import pyarrow.parquet as pq
import pytest
from click.testing import CliRunner

from grainclass import classify, read_dataset
from grainclass.cli import cli

KEYS = ["grain_id", "n_faces", "p_vector", "weinberg", "symmetry", "boundary"]
needs_voro = pytest.mark.skipif(
    shutil.which("voro++") is None,
    reason="the voro++ program is not installed (Debian's voro++ package; make test installs it "
    "as root)",
)


def _run(*args: str) -> object:
    result = CliRunner().invoke(cli, ["voronoi", *args])
    return result


def _ours(tmp_path: Path, *args: str) -> pa.Table:
    out = tmp_path / "ours.parquet"
    result = _run(*args, "-o", str(out), "-q")
    assert result.exit_code == 0, result.output
    table = pq.read_table(out)
    return table.take(pc.sort_indices(table, [("grain_id", "ascending")]))


def _theirs(tmp_path: Path, points: Path, *flags: str, box=(0, 1, 0, 1, 0, 1)) -> pa.Table:
    """The cells of the voro++ program on ``points``, through the Voro++ reader, by id."""
    subprocess.run(
        ["voro++", *flags, "-c", "%i %v %F %n %t", *map(str, box), str(points)], check=True
    )
    table = pa.concat_tables(classify(b) for b in read_dataset(f"{points}.vol"))
    return table.take(pc.sort_indices(table, [("grain_id", "ascending")]))


def _voro_points(path: Path, xyz: np.ndarray, radii: np.ndarray | None = None) -> Path:
    columns = [np.arange(len(xyz)), xyz] + ([radii] if radii is not None else [])
    fmt = "%d" + " %.17g" * (3 + (radii is not None))
    np.savetxt(path, np.column_stack(columns), fmt=fmt)
    return path


def _same_cells(ours: pa.Table, theirs: pa.Table) -> None:
    assert ours.column("status").to_pylist() == ["ok"] * len(ours)
    assert ours.select(KEYS).equals(theirs.select(KEYS))
    np.testing.assert_allclose(ours["volume"].to_numpy(), theirs["volume"].to_numpy(), rtol=1e-5)
    np.testing.assert_allclose(ours["area"].to_numpy(), theirs["area"].to_numpy(), rtol=1e-5)


@needs_voro
def test_periodic_cells_are_those_of_the_voro_program(tmp_path):
    xyz = np.random.default_rng(1).random((500, 3))
    points = _voro_points(tmp_path / "points", xyz)
    ours = _ours(tmp_path, "--points", str(points), "--box", "1", "--periodic", "xyz")
    theirs = _theirs(tmp_path, points, "-p")
    assert not pc.any(ours["boundary"]).as_py()
    _same_cells(ours, theirs.set_column(2, "boundary", ours["boundary"]))


@needs_voro
def test_walled_cells_are_those_of_the_voro_program_and_boundary(tmp_path):
    xyz = np.random.default_rng(2).random((500, 3)) * [2, 1, 1]
    points = _voro_points(tmp_path / "points", xyz)
    ours = _ours(tmp_path, "--points", str(points), "--box", "0,2,0,1,0,1", "--periodic", "none")
    theirs = _theirs(tmp_path, points, box=(0, 2, 0, 1, 0, 1))
    _same_cells(ours, theirs)
    assert 0 < pc.sum(ours["boundary"]).as_py() < 500


@needs_voro
def test_laguerre_cells_are_those_of_the_voro_program(tmp_path):
    rng = np.random.default_rng(3)
    xyz, radii = rng.random((400, 3)), rng.uniform(0.0, 0.06, 400)
    points = _voro_points(tmp_path / "points", xyz, radii)
    ours = _ours(tmp_path, "--points", str(points), "--periodic", "xy")
    theirs = _theirs(tmp_path, points, "-r", "-px", "-py")
    _same_cells(ours, theirs)
    plain = _ours(tmp_path, "--points", str(_voro_points(tmp_path / "plain", xyz)))
    assert not plain.select(["weinberg"]).equals(ours.select(["weinberg"]))


def _lattice(basis: list[tuple[float, float, float]], k: int) -> np.ndarray:
    cells = np.stack(np.meshgrid(*[np.arange(k)] * 3, indexing="ij"), -1).reshape(-1, 3)
    return (cells[:, None, :] + np.asarray(basis)[None]).reshape(-1, 3)


def test_bcc_points_give_truncated_octahedra(tmp_path):
    points = tmp_path / "bcc.npy"
    np.save(points, _lattice([(0, 0, 0), (0.5, 0.5, 0.5)], 3) + 0.25)
    table = _ours(tmp_path, "--points", str(points), "--box", "3")
    assert len(table) == 54
    assert set(table["status"].to_pylist()) == {"ok"}
    assert set(table["n_faces"].to_pylist()) == {14}
    assert {tuple(p) for p in table["p_vector"].to_pylist()} == {(0, 6, 0, 8)}
    assert set(table["symmetry"].to_pylist()) == {48}
    np.testing.assert_allclose(table["volume"].to_numpy(), 0.5)


def test_fcc_points_give_rhombic_dodecahedra(tmp_path):
    points = tmp_path / "fcc.npy"
    basis = [(0, 0, 0), (0.5, 0.5, 0), (0.5, 0, 0.5), (0, 0.5, 0.5)]
    np.save(points, _lattice(basis, 2) + 0.25)
    out = tmp_path / "fcc.parquet"
    result = _run("--points", str(points), "--box", "2", "-o", str(out))
    assert result.exit_code == 0, result.output
    assert "cells with a corner not of three faces: 32" in result.stderr
    table = pq.read_table(out)
    assert set(table["status"].to_pylist()) == {"non_simple"}
    assert set(table["n_faces"].to_pylist()) == {12}
    np.testing.assert_allclose(table["volume"].to_numpy(), 0.25)


POINTS = np.random.default_rng(4).random((200, 3)) * [10, 10, 5]
RADII = np.random.default_rng(5).uniform(0.1, 0.4, 200)


def _formats(tmp_path: Path) -> dict[str, list[str]]:
    """The same points (ids 1..200) with radii, in a box 10 x 10 x 5 periodic in x and y, in
    every format: the file's own box where it has one, else --box and --periodic."""
    ids = np.arange(1, 201)
    box = ["--box", "0,10,0,10,0,5", "--periodic", "xy"]
    lammps = tmp_path / "points.dump"
    lammps.write_text(
        "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n200\nITEM: BOX BOUNDS pp pp ff\n"
        "0 10\n0 10\n0 5\nITEM: ATOMS id type x y z radius\n"
        + "".join(
            f"{i} 1 {x!r} {y!r} {z!r} {r!r}\n"
            for i, (x, y, z), r in zip(ids, POINTS.tolist(), RADII.tolist(), strict=True)
        )
    )
    xyz = tmp_path / "points.xyz"
    xyz.write_text(
        '200\nLattice="10 0 0 0 10 0 0 0 5" Properties=species:S:1:pos:R:3:radius:R:1 '
        'pbc="T T F"\n'
        + "".join(
            f"Fe {x!r} {y!r} {z!r} {r!r}\n"
            for (x, y, z), r in zip(POINTS.tolist(), RADII.tolist(), strict=True)
        )
    )
    csv = tmp_path / "points.csv"
    csv.write_text(
        "id,x,y,z,size\n"
        + "".join(
            f"{i},{x!r},{y!r},{z!r},{r!r}\n"
            for i, (x, y, z), r in zip(ids, POINTS.tolist(), RADII.tolist(), strict=True)
        )
    )
    voro = tmp_path / "points.txt"
    np.savetxt(voro, np.column_stack([ids, POINTS, RADII]), fmt="%d %.17g %.17g %.17g %.17g")
    npy = tmp_path / "points.npy"
    np.save(npy, np.column_stack([POINTS, RADII]))
    return {
        "lammps": ["--points", str(lammps)],
        "xyz": ["--points", str(xyz)],
        "csv": ["--points", str(csv), "--radius-column", "size", *box],
        "voro": ["--points", str(voro), *box],
        "npy": ["--points", str(npy), *box],
    }


def test_every_points_format_gives_the_same_table(tmp_path):
    tables = {name: _ours(tmp_path, *args) for name, args in _formats(tmp_path).items()}
    lammps = tables.pop("lammps")
    assert len(lammps) == 200
    assert 0 < pc.sum(lammps["boundary"]).as_py() < 200  # walls at z = 0 and 5
    for name, table in tables.items():
        assert table.select([*KEYS, "volume"]).equals(lammps.select([*KEYS, "volume"])), name


def _refused(tmp_path: Path, text: str, *args: str, name: str = "points.txt") -> str:
    points = tmp_path / name
    points.write_text(text)
    out = tmp_path / "out.parquet"
    result = _run("--points", str(points), *args, "-o", str(out))
    assert result.exit_code == 1, result.output
    assert not out.exists()
    assert [p.name for p in tmp_path.iterdir()] == [name]
    return result.stderr.replace(str(points), "FILE")


@pytest.mark.parametrize(
    ("text", "args", "message"),
    [
        ("1 0.5 0.5 0.5\n2 0.2 1.5 0.5\n", ["--periodic", "xz"], "FILE:2: point 2 at (0.2, 1.5, "),
        ("1 0.5 0.5 0.5\n\n2 0.2 0.2 0.2\n3 0.5 0.5 0.5\n", [], "FILE:4: point 3 is at the same"),
        ("1 0.5 0.5 0.5 0.1\n2 0.2 0.2 0.2 -0.1\n", [], "FILE:2: point 2 has a negative radius"),
        ("1 0.5 0.5 0.5\n2 0.2 zero 0.2\n", [], "FILE:2: cannot read this point: y is 'zero'"),
        ("1 0.5 0.5 0.5\n2 0.2 0.2\n", [], "FILE:2: cannot read this point: expected 4 values"),
        ("1 0.5 0.5 0.5\n1 0.2 0.2 0.2\n", [], "FILE:2: point id 1 is given twice"),
        ("\n\n", [], "FILE: no points in the file"),
        ("1 0.5 0.5 0.5\n2 0.5 0.5 0.5000000001\n", [], "point 2 is closer than Voro++ can sep"),
    ],
)
def test_bad_points_exit_1_with_file_and_line_and_no_output(tmp_path, text, args, message):
    assert message in _refused(tmp_path, text, *args)


def test_an_unreadable_box_names_its_line(tmp_path):
    dump = "ITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS xy xz yz pp pp pp\n0 1 0\n0 1\n0 1 0\n"
    dump += "ITEM: ATOMS id x y z\n1 0.5 0.5 0.5\n"
    assert "FILE:5: cannot read the box: expected low high tilt" in _refused(
        tmp_path, dump, name="p.dump"
    )


def test_laguerre_points_without_a_cell_are_named(tmp_path):
    points = tmp_path / "points.txt"
    points.write_text("1 0.5 0.5 0.5 0.45\n2 0.51 0.5 0.5 0.0\n3 0.1 0.1 0.1 0.1\n")
    result = _run("--points", str(points), "-o", str(tmp_path / "out.parquet"))
    assert result.exit_code == 0, result.output
    assert "1 point without a cell (hidden by their neighbours' radii)" in result.stderr
    assert pq.read_table(tmp_path / "out.parquet")["grain_id"].to_pylist() == ["1", "3"]


def test_voro_reader_marks_cells_with_a_wall_face_as_boundary():
    # voro++ -c "%i %v %F %n %t" 0 1 0 1 0 1 on 300 random points: walls all round.
    path = Path(__file__).resolve().parent / "data" / "voro" / "walled-300.vol"
    table = pa.concat_tables(classify(b) for b in read_dataset(str(path)))
    assert pc.sum(table["boundary"]).as_py() == 183
    inner = table.filter(pc.invert(table["boundary"]))
    # Cells away from the walls are whole Poisson-Voronoi cells (about 15.5 faces, not 13).
    assert pc.mean(inner["n_faces"]).as_py() > 14


def _tilted_dump(path: Path, xyz: np.ndarray, tilt: tuple[float, float, float], radii=None):
    """A LAMMPS dump of points in the tilted box from 0 with sides 1 and tilts xy, xz, yz."""
    xy, xz, yz = tilt
    radius = " radius" if radii is not None else ""
    lines = [
        "ITEM: TIMESTEP",
        "0",
        "ITEM: NUMBER OF ATOMS",
        str(len(xyz)),
        "ITEM: BOX BOUNDS xy xz yz pp pp pp",
        f"{min(0, xy, xz, xy + xz)} {1 + max(0, xy, xz, xy + xz)} {xy}",
        f"{min(0, yz)} {1 + max(0, yz)} {xz}",
        f"0 1 {yz}",
        f"ITEM: ATOMS id x y z{radius}",
    ]
    for i, point in enumerate(xyz.tolist()):
        extra = f" {float(radii[i])!r}" if radii is not None else ""
        lines.append(f"{i} {point[0]!r} {point[1]!r} {point[2]!r}{extra}")
    path.write_text("\n".join(lines) + "\n")
    return path


@pytest.mark.parametrize("with_radii", [False, True])
def test_a_tilted_box_of_the_same_lattice_gives_the_same_cells(tmp_path, with_radii):
    """Edges (1, 0, 0), (1, 1, 0), (1, 1, 1) span the unit cube's lattice: the same points, in
    either box, have the same periodic cells."""
    rng = np.random.default_rng(6)
    xyz = rng.random((300, 3))
    radii = rng.uniform(0.0, 0.05, 300) if with_radii else None
    cube = _ours(tmp_path, "--points", str(_voro_points(tmp_path / "cube", xyz, radii)))
    tilted = _ours(
        tmp_path, "--points", str(_tilted_dump(tmp_path / "t.dump", xyz, (1, 1, 1), radii))
    )
    assert cube.select(KEYS).equals(tilted.select(KEYS))
    np.testing.assert_allclose(tilted["volume"].to_numpy(), cube["volume"].to_numpy(), rtol=1e-9)


def test_a_tilted_box_with_walls_is_refused(tmp_path):
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    dump = _tilted_dump(elsewhere / "t.dump", np.full((1, 3), 0.5), (0.5, 0, 0)).read_text()
    dump = dump.replace("pp pp pp", "pp pp ff")
    shutil.rmtree(elsewhere)
    message = _refused(tmp_path, dump, name="p.dump")
    assert "FILE:5: a tilted box with walls" in message


def test_bcc_points_in_a_tilted_box_give_truncated_octahedra(tmp_path):
    # Edges (2, 0, 0), (1, 2, 0), (0, 1, 2) are translations of the BCC lattice of side 1.
    points = _lattice([(0, 0, 0), (0.5, 0.5, 0.5)], 7) - 3 + 0.1
    matrix = np.array([[2.0, 1.0, 0.0], [0.0, 2.0, 1.0], [0.0, 0.0, 2.0]])
    fractions = np.linalg.solve(matrix, points.T).T
    inside = points[((fractions >= 0) & (fractions < 1)).all(axis=1)] / 2
    dump = _tilted_dump(tmp_path / "bcc.dump", inside, (0.5, 0.0, 0.5))
    table = _ours(tmp_path, "--points", str(dump))
    assert len(table) == 16
    assert set(table["n_faces"].to_pylist()) == {14}
    assert set(table["symmetry"].to_pylist()) == {48}
    np.testing.assert_allclose(table["volume"].to_numpy(), 1 / 16)


def test_points_on_the_upper_walls_have_cells(tmp_path):
    """As in a LAMMPS box shrunk to its atoms: Voro++ alone would drop the point at x = 1."""
    points = tmp_path / "points.txt"
    points.write_text("1 1.0 0.5 0.5\n2 0.2 0.2 0.2\n3 0 0 1\n")
    table = _ours(tmp_path, "--points", str(points), "--periodic", "none")
    assert table["grain_id"].to_pylist() == ["1", "2", "3"]
    assert pc.sum(table["volume"]).as_py() == pytest.approx(1.0, rel=1e-9)
