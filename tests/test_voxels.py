"""Grains from label images (grainclass.voxels): hand-made images with hand-derived rows, the
BCC lattice against Voro++'s cells of the same seeds, and the pass's invariances."""

from __future__ import annotations

import numpy as np
import pyarrow as pa
import pytest
from click.testing import CliRunner

import grainclass.voxels as voxels
from grainclass import classify, read_dataset
from grainclass.cli import cli
from grainclass.options import ReadOptions
from grainclass.readers.label_image import in_memory
from voxel_images import bcc_seeds, nearest_seed


def rows(labels: np.ndarray, **settings) -> list[dict]:
    """The rows of an image in memory, read as ``settings`` say."""
    image = in_memory("image", labels)
    table = pa.concat_tables(
        classify(batch) for batch in voxels.read_image(image, ReadOptions(**settings))
    )
    return table.to_pylist()


def test_voxels_a_grain_in_a_box_is_a_boundary_grain():
    (row,) = rows(np.full((4, 5, 6), 7, np.uint8))
    assert row["grain_id"] == "7"
    assert row["boundary"] is True
    assert row["status"] == "invalid"
    assert "boundary grain" in row["error"]
    assert row["voxels"] == 120
    assert row["volume"] == 120.0
    assert row["area"] is None
    assert row["isoperimetric"] is None


def test_voxels_spacing_scales_the_volume():
    (row,) = rows(np.full((2, 2, 2), 1, np.uint8), spacing=(0.5, 2.0, 3.0))
    assert row["volume"] == pytest.approx(8 * 3.0)


def test_voxels_a_grain_filling_a_periodic_image_is_a_three_torus():
    (row,) = rows(np.full((3, 3, 3), 1, np.uint8), periodic="xyz")
    assert row["boundary"] is False
    assert "Euler characteristic 0" in row["error"]


def test_voxels_two_grains_side_by_side_in_a_box():
    labels = np.ones((4, 4, 6), np.uint16)
    labels[:, :, 3:] = 2
    first, second = rows(labels)
    assert [first["grain_id"], second["grain_id"]] == ["1", "2"]
    assert [first["voxels"], second["voxels"]] == [48, 48]
    assert first["boundary"]
    assert second["boundary"]


def test_voxels_two_slabs_of_a_periodic_image_are_no_solid_grains():
    """A slab wrapping x and y is a torus times an interval: Euler characteristic 0."""
    labels = np.ones((4, 4, 4), np.uint16)
    labels[2:] = 2
    for row in rows(labels, periodic="xyz"):
        assert not row["boundary"]
        assert "Euler characteristic 0" in row["error"]


def test_voxels_a_grain_in_two_pieces_and_with_components():
    """Label 2 is two cubes apart inside label 1: Euler characteristic 2 (two balls); with
    --components each piece is a grain of its own, with its label."""
    labels = np.ones((8, 8, 8), np.uint8)
    labels[1:3, 1:3, 1:3] = 2
    labels[5:7, 5:7, 5:7] = 2
    outer, split = rows(labels)
    assert outer["boundary"]
    assert not split["boundary"]
    assert "Euler characteristic 2" in split["error"]
    assert "several pieces" in split["error"]
    pieces = rows(labels, components=True)
    assert [row["grain_id"] for row in pieces] == ["1", "2", "3"]
    assert [row["label"] for row in pieces] == ["1", "2", "2"]
    assert [row["voxels"] for row in pieces] == [512 - 16, 8, 8]
    # Each cube alone inside label 1's piece: enclosed.
    assert all("enclosed by grain 1" in row["error"] for row in pieces[1:])


def test_voxels_components_joined_across_a_side_that_wraps():
    labels = np.ones((4, 4, 6), np.uint8)
    labels[:, :, 0] = 2
    labels[:, :, 5] = 2  # one slab through the periodic x side
    assert len(rows(labels, components=True, periodic="x")) == 2
    assert len(rows(labels, components=True)) == 3


def test_voxels_a_shell_around_a_cavity_encloses_a_grain():
    """Grain 3 inside grain 2, a hollow cube (Euler characteristic 1 + 1: a ball's boundary
    twice), inside grain 1."""
    labels = np.ones((9, 9, 9), np.uint8)
    labels[2:7, 2:7, 2:7] = 2
    labels[3:6, 3:6, 3:6] = 3
    outer, shell, inner = rows(labels)
    assert outer["boundary"]
    assert "Euler characteristic 2" in shell["error"]
    assert "encloses grain 3" in shell["error"]
    assert "enclosed by grain 2" in inner["error"]
    assert inner["voxels"] == 27


def test_voxels_background_labels_make_boundary_grains_and_no_rows():
    labels = np.ones((6, 6, 6), np.uint8)
    labels[0] = 0
    got = rows(labels, background=(0,), periodic="xyz")
    assert [row["grain_id"] for row in got] == ["1"]
    assert got[0]["boundary"]


def _bcc_image() -> np.ndarray:
    return nearest_seed(bcc_seeds(3), 36).astype(np.uint16)


def test_voxels_bcc_lattice_gives_truncated_octahedra_as_voro_does(tmp_path):
    """Every grain of the voxelized BCC lattice (12 voxels a cubic cell) has 6 squares and 8
    hexagons, and the type of the Voronoi cells Voro++ computes for the same seeds."""
    seeds = bcc_seeds(3)
    points = tmp_path / "bcc.txt"
    np.savetxt(points, np.column_stack([np.arange(1, 55), seeds]), fmt="%d %.17g %.17g %.17g")
    cells = tmp_path / "cells.parquet"
    result = CliRunner().invoke(
        cli, ["voronoi", "--points", str(points), "--box", "1", "-o", str(cells), "-q"]
    )
    assert result.exit_code == 0, result.output
    exact = set(pa.parquet.read_table(cells)["weinberg"].to_pylist())
    assert len(exact) == 1
    got = rows(_bcc_image(), periodic="xyz")
    assert len(got) == 54
    assert {row["status"] for row in got} == {"ok"}
    assert {row["n_faces"] for row in got} == {14}
    assert {tuple(row["p_vector"]) for row in got} == {(0, 6, 0, 8)}
    assert {row["weinberg"] for row in got} == exact
    assert {row["voxels"] for row in got} == {36**3 // 54}


def test_voxels_faces_lists_are_in_cyclic_order():
    """The truncated octahedron's neighbour lists come out in cyclic order: each pair of
    consecutive neighbours of a face are neighbours themselves."""
    image = in_memory("bcc", _bcc_image())
    batch = next(voxels.read_image(image, ReadOptions(periodic="xyz")))
    for g in range(len(batch)):
        f0, f1 = batch.face_offsets[g], batch.face_offsets[g + 1]
        lists = [
            batch.neighbors[batch.nbr_offsets[f] : batch.nbr_offsets[f + 1]].tolist()
            for f in range(f0, f1)
        ]
        for face, around in enumerate(lists):
            for a, b in zip(around, around[1:] + around[:1], strict=True):
                assert b in lists[a]
                assert face in lists[a]


def test_voxels_same_grains_whatever_the_slabs_and_threads(monkeypatch):
    """The slab depth and the number of threads do not change a thing."""
    from grainclass import parallel

    labels = nearest_seed(np.random.default_rng(3).random((40, 3)), 30)
    expected = rows(labels, periodic="xyz")
    monkeypatch.setattr(voxels, "SLAB_DEPTH", 1)
    assert rows(labels, periodic="xyz") == expected
    monkeypatch.setattr(voxels, "SLAB_DEPTH", 7)
    jobs = parallel.get_jobs()
    try:
        parallel.set_jobs(1)
        assert rows(labels, periodic="xyz") == expected
        parallel.set_jobs(3)
        assert rows(labels, periodic="xyz") == expected
    finally:
        parallel.set_jobs(jobs)


def test_voxels_relabelling_keeps_the_types():
    """Labels are names: adding 1000 to each changes grain ids and nothing else."""
    labels = nearest_seed(np.random.default_rng(4).random((30, 3)), 28)
    plain = rows(labels, periodic="xyz")
    shifted = rows(labels + 1000, periodic="xyz")
    assert [int(r["grain_id"]) + 1000 for r in plain] == [int(r["grain_id"]) for r in shifted]
    assert [r["weinberg"] for r in plain] == [r["weinberg"] for r in shifted]


def test_voxels_labels_past_the_tables_keep_their_values():
    """Labels past MAX_LABEL, as a Potts run's site ids (and past int32): the rows of the same
    image with small labels, under the large labels, in their order; the background and
    --components's label column by their values too."""
    labels = nearest_seed(np.random.default_rng(4).random((30, 3)), 28)
    values = np.arange(31, dtype=np.int64) * (1 << 34) + 5  # labels 1..30 -> values[1..30]
    plain = rows(labels, periodic="xyz")
    large = rows(values[labels], periodic="xyz")
    assert [values[int(r["grain_id"])] for r in plain] == [int(r["grain_id"]) for r in large]
    assert [r["weinberg"] for r in plain] == [r["weinberg"] for r in large]
    assert [r["voxels"] for r in plain] == [r["voxels"] for r in large]
    without = rows(values[labels], periodic="xyz", background=[int(values[1])])
    assert [int(r["grain_id"]) for r in without] == values[2:].tolist()
    assert sum(r["boundary"] for r in without) == sum(
        r["boundary"] for r in rows(labels, periodic="xyz", background=[1])
    )
    pieces = rows(values[labels], periodic="xyz", components=True)
    assert sorted(int(r["label"]) for r in pieces) == values[1:].tolist()


def test_voxels_read_dataset_reads_an_npy_file(tmp_path):
    path = tmp_path / "bcc.npy"
    np.save(path, _bcc_image())
    batches = list(read_dataset(str(path), periodic="xyz"))
    assert sum(len(b) for b in batches) == 54
    assert batches[0].source == str(path)
