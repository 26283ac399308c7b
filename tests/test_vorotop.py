"""Weinberg vectors, symmetry, chirality and type counts against VoroTop's own output for the
same 500 periodic points (tests/data/vorotop/README.md), through every reader with geometry."""

from __future__ import annotations

import itertools
import re
from pathlib import Path

import numpy as np
import pyarrow as pa
import pyarrow.parquet as pq
from click.testing import CliRunner

from grainclass import classify, read_dataset
from grainclass.cli import cli

DATA = Path(__file__).parent / "data" / "vorotop"
POINTS = DATA / "poisson500"  # VoroTop's input: a LAMMPS dump, periodic unit cube
VECTORS = DATA / "poisson500.vectors"  # VoroTop poisson500 -vt
DISTRIBUTION = DATA / "poisson500.distribution"  # VoroTop poisson500 -d
CELLS = DATA / "cells-1-40.vol"  # voro++ -p -c "%i %P %t", the cells of points 1 to 40


def _vorotop_cells() -> dict[str, tuple[str, int, int]]:
    """VoroTop's ``-vt`` rows by id: (Weinberg vector, symmetry order, chirality). Its columns
    are id, faces, p-vector, Weinberg vector, symmetry order, chirality (and a trailing TAB)."""
    rows = {}
    for line in VECTORS.read_text().splitlines():
        fields = line.split("\t")
        rows[fields[0]] = (fields[3], int(fields[4]), int(fields[5]))
    return rows


def _types(table: pa.Table) -> dict[str, tuple[str, int, int]]:
    assert set(table.column("status").to_pylist()) == {"ok"}
    return {
        row["grain_id"]: (row["weinberg"], row["symmetry"], row["chirality"])
        for row in table.select(["grain_id", "weinberg", "symmetry", "chirality"]).to_pylist()
    }


def _invoke(*args: str) -> None:
    result = CliRunner().invoke(cli, [*args, "-q"])
    assert result.exit_code == 0, result.output


def test_the_data_has_chiral_cells_of_both_signs():
    # Else a sign convention could be wrong and every test here pass.
    signs = [chirality for _, _, chirality in _vorotop_cells().values()]
    assert len(signs) == 500
    assert signs.count(-1) > 100
    assert signs.count(1) > 100
    assert signs.count(0) > 10


def test_voronoi_cells_of_the_points_are_vorotops(tmp_path):
    # The box and its periodicity come from the dump, as VoroTop reads them.
    _invoke("voronoi", "--points", str(POINTS), "-o", str(tmp_path / "cells.parquet"))
    assert _types(pq.read_table(tmp_path / "cells.parquet")) == _vorotop_cells()
    # Written as adjacency text and read back: the lists keep their sense.
    _invoke("voronoi", "--points", str(POINTS), "-o", str(tmp_path / "cells.txt"))
    _invoke("classify", str(tmp_path / "cells.txt"), "-o", str(tmp_path / "again.parquet"))
    assert _types(pq.read_table(tmp_path / "again.parquet")) == _vorotop_cells()


def test_types_writes_what_vorotop_d_writes(tmp_path, monkeypatch):
    # VoroTop's first line names the file it read, as named on its command line; grainclass's
    # names the grains it read: given the same name, the files are the same byte for byte.
    monkeypatch.chdir(tmp_path)
    _invoke("voronoi", "--points", str(POINTS), "-o", "poisson500")
    _invoke("types", "poisson500", "--vorotop", "poisson500.distribution", "-o", "types.csv")
    assert Path("poisson500.distribution").read_bytes() == DISTRIBUTION.read_bytes()


def test_types_names_the_grains_it_read_and_writes_the_rest_as_vorotop(tmp_path):
    cells = tmp_path / "cells.parquet"
    _invoke("voronoi", "--points", str(POINTS), "-o", str(cells))
    out = tmp_path / "cells.distribution"
    _invoke("types", str(cells), "--vorotop", str(out), "-o", str(tmp_path / "types.csv"))
    ours, theirs = out.read_text().splitlines(), DISTRIBUTION.read_text().splitlines()
    assert ours[0] == f"#\tDISTRIBUTION CREATED FROM {cells}"
    assert ours[1:] == theirs[1:]
    # What makes the order: 500 cells, a few types more than once, ties by the integers.
    counts = [int(line.split("\t")[1]) for line in theirs[4:]]
    assert counts[:6] == [3, 2, 2, 2, 2, 2]
    assert set(counts[6:]) == {1}
    as_strings = sorted(theirs[10:], key=lambda line: line.split("\t")[0])
    assert as_strings != theirs[10:]  # label 10 sorts after 9, not after 1


def _cells() -> list[tuple[str, np.ndarray, list[list[int]]]]:
    """The cells of CELLS: id, corner positions, face loops (Voro++'s corner indices)."""
    cells = []
    for line in CELLS.read_text().splitlines():
        cell_id, rest = line.split(" ", 1)
        groups = re.findall(r"\(([^)]*)\)", rest)
        positions = np.array([[float(x) for x in g.split(",")] for g in groups if "." in g])
        loops = [[int(v) for v in g.split(",")] for g in groups if "." not in g]
        assert max(map(max, loops)) == len(positions) - 1  # no position read as a loop
        cells.append((cell_id, positions, loops))
    return cells


def _signed_volume(positions: np.ndarray, loops: list[list[int]]) -> float:
    """By the divergence theorem over the loops' fans: positive when they turn
    counter-clockwise seen from outside."""
    total = 0.0
    for loop in loops:
        a = positions[loop[0]]
        for b, c in itertools.pairwise(loop[1:]):
            total += np.dot(a, np.cross(positions[b], positions[c])) / 6
    return total


def _subset(ids) -> dict[str, tuple[str, int, int]]:
    theirs = _vorotop_cells()
    return {i: theirs[i] for i in ids}


def test_voro_output_reads_as_vorotop(tmp_path):
    # The same cells as voro++ -p -c "%i %t" writes them: positions dropped.
    voro = tmp_path / "cells.vol"
    voro.write_text(
        "".join(
            re.sub(r" \([^)]*\.[^)]*\)", "", line) + "\n" for line in CELLS.read_text().splitlines()
        )
    )
    table = pa.concat_tables(classify(b) for b in read_dataset(str(voro)))
    ids = [cell_id for cell_id, _, _ in _cells()]
    assert _types(table) == _subset(ids)


def test_evolver_bodies_read_as_vorotop(tmp_path):
    # One file per cell, a facet per face, every edge a triple line. Voro++'s loops turn
    # clockwise seen from outside: reversed, each facet's normal (right-hand rule) points out.
    folder = tmp_path / "cells"
    folder.mkdir()
    for cell_id, positions, loops in _cells():
        outward = [loop[::-1] for loop in loops]
        assert _signed_volume(positions, outward) > 0 > _signed_volume(positions, loops)
        edges: dict[tuple[int, int], int] = {}
        facets = []
        for loop in outward:
            signed = []
            for u, v in zip(loop, loop[1:] + loop[:1], strict=True):
                e = edges.setdefault((min(u, v), max(u, v)), len(edges) + 1)
                signed.append(e if u < v else -e)
            facets.append(signed)
        text = [
            "vertices",
            *(f"{i + 1} {x} {y} {z}" for i, (x, y, z) in enumerate(positions)),
        ]
        text += ["", "edges", *(f"{e} {u + 1} {v + 1} color red" for (u, v), e in edges.items())]
        text += ["", "faces", *(f"{i + 1} " + " ".join(map(str, f)) for i, f in enumerate(facets))]
        text += ["", "bodies", "1 " + " ".join(str(i + 1) for i in range(len(facets)))]
        (folder / f"{cell_id}.fe").write_text("\n".join(text) + "\n")
    table = pa.concat_tables(classify(b) for b in read_dataset(str(folder)))
    assert _types(table) == _subset(cell_id for cell_id, _, _ in _cells())


def test_neper_polyhedra_read_as_vorotop(tmp_path):
    # Faces as Voro++ loops them, clockwise seen from outside: each polyhedron lists them with
    # a negative id (Neper: a face's normal, right-handed along its loop, points out for +id).
    vertices, edges, faces, polyhedra = [], {}, [], []
    for cell_id, positions, loops in _cells():
        assert _signed_volume(positions, loops) < 0
        base = len(vertices)
        vertices.extend(positions)
        ids = []
        for loop in loops:
            corners = [base + v + 1 for v in loop]
            signed = []
            for u, v in zip(corners, corners[1:] + corners[:1], strict=True):
                e = edges.setdefault((min(u, v), max(u, v)), len(edges) + 1)
                signed.append(e if u < v else -e)
            faces.append((corners, signed))
            ids.append(-len(faces))
        polyhedra.append((cell_id, ids))
    text = [" ***tess", "  **format", "   3.4", "  **general", "   3 standard"]
    text += ["  **vertex", f" {len(vertices)}"]
    text += [f" {i + 1} {x} {y} {z} 0" for i, (x, y, z) in enumerate(vertices)]
    text += ["  **edge", f" {len(edges)}", *(f" {e} {u} {v} 0" for (u, v), e in edges.items())]
    text += ["  **face", f" {len(faces)}"]
    for i, (corners, signed) in enumerate(faces):
        text += [f" {i + 1} {len(corners)} " + " ".join(map(str, corners))]
        text += [f"  {len(signed)} " + " ".join(map(str, signed)), "  0 0 0 0", "  0 0 0 0 0"]
    text += ["  **polyhedron", f" {len(polyhedra)}"]
    text += [f" {p} {len(ids)} " + " ".join(map(str, ids)) for p, ids in polyhedra]
    tess = tmp_path / "cells.tess"
    tess.write_text("\n".join([*text, " ***end"]) + "\n")
    table = pa.concat_tables(classify(b) for b in read_dataset(str(tess)))
    assert _types(table) == _subset(cell_id for cell_id, _, _ in _cells())


def test_mirrored_points_flip_every_chirality(tmp_path):
    # The sign is a handedness: the points mirrored (x -> 1 - x) have every chirality negated,
    # the vectors and symmetry orders kept.
    lines = POINTS.read_text().splitlines()
    head, atoms = lines[:9], lines[9:]
    mirrored = []
    for line in atoms:
        fields = line.split()
        fields[1] = f"{1 - float(fields[1]):.8f}"
        mirrored.append(" ".join(fields))
    points = tmp_path / "mirrored"
    points.write_text("\n".join([*head, *mirrored]) + "\n")
    _invoke("voronoi", "--points", str(points), "-o", str(tmp_path / "cells.parquet"))
    theirs = {i: (w, s, -c) for i, (w, s, c) in _vorotop_cells().items()}
    assert _types(pq.read_table(tmp_path / "cells.parquet")) == theirs
