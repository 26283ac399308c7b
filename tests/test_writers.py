"""Grains written back (``grainclass.writers``) read as they were: adjacency text and
planar_code, against the readers and an independent byte-by-byte planar_code reader."""

from __future__ import annotations

import dataclasses
import io

import numpy as np

from conftest import EXAMPLES
from grainclass import GrainBatch, read_dataset
from grainclass.batch import offsets_from_counts
from grainclass.readers.adjacency import read_adjacency
from grainclass.readers.planar_code import read_planar_code
from grainclass.writers import PLANAR_CODE_HEADER, adjacency_text, planar_code
from strategies import bipyramid
from test_properties import _read_planar_code


def _grains(batch: GrainBatch) -> list[list[list[int]]]:
    return [
        [
            batch.neighbors[batch.nbr_offsets[f] : batch.nbr_offsets[f + 1]].tolist()
            for f in range(batch.face_offsets[g], batch.face_offsets[g + 1])
        ]
        for g in range(len(batch))
    ]


def _ids(batch: GrainBatch) -> list[str]:
    ids = batch.grain_id
    return [str(i) for i in (ids.to_pylist() if hasattr(ids, "to_pylist") else ids)]


def test_adjacency_text_reads_back_as_it_was():
    text = (
        b"a\t1 2 3;0 3 2;0 1 3;0 2 1\tvolume=0.1\tarea=2.5\tboundary=0\tphase=x y\n"
        b"b\t1 2 3;0 3 2;0 1 3;0 2 1\tlabel=7\n"
        b"c\t1 2;0\n"
        b"d\t1 x 3\tvolume=3\n"
    )
    (batch,) = read_adjacency(io.BytesIO(text), "in", 100)
    (again,) = read_adjacency(io.BytesIO(adjacency_text(batch)), "out", 100)
    assert _ids(again) == _ids(batch)
    assert _grains(again) == _grains(batch)
    np.testing.assert_array_equal(again.volume, batch.volume)
    np.testing.assert_array_equal(again.area, batch.area)
    np.testing.assert_array_equal(again.boundary, batch.boundary)
    assert again.attributes == batch.attributes
    assert sorted(again.parse_errors) == sorted(batch.parse_errors) == [3]


def test_adjacency_text_of_the_examples_is_their_file_without_its_comments():
    path = EXAMPLES / "polytopes.txt"
    lines = [line for line in path.read_bytes().splitlines(True) if not line.startswith(b"#")]
    assert adjacency_text(next(read_dataset(str(path)))) == b"".join(lines)


def test_adjacency_text_writes_a_cells_measures_and_boundary_as_voronoi_has_them():
    # What `grainclass voronoi` writes for its cells: volume and area with every digit, the
    # boundary flag as 1/0, none where unknown.
    tetrahedron = [[1, 2, 3], [0, 3, 2], [0, 1, 3], [0, 2, 1]]
    batch = dataclasses.replace(
        GrainBatch.from_lists([tetrahedron] * 3, grain_id=["7", "8", "9"]),
        volume=np.array([0.1, 1 / 3, np.nan]),
        area=np.array([2.5, 1e-20, np.nan]),
        boundary=np.array([1, 0, -1], np.int8),
    )
    faces = "1 2 3;0 3 2;0 1 3;0 2 1"
    assert adjacency_text(batch).decode() == (
        f"7\t{faces}\tvolume=0.1\tarea=2.5\tboundary=1\n"
        f"8\t{faces}\tvolume=0.3333333333333333\tarea=1e-20\tboundary=0\n"
        f"9\t{faces}\n"
    )


def test_planar_code_reads_back_as_it_was():
    data = (EXAMPLES / "plantri-10.pc").read_bytes()
    batch = next(read_dataset(str(EXAMPLES / "plantri-10.pc")))
    assert PLANAR_CODE_HEADER + planar_code(batch) == data


def test_planar_code_beyond_255_faces_in_two_byte_entries():
    big = bipyramid(300)  # 302 vertices: 2-byte entries
    small = bipyramid(5)
    batch = GrainBatch.from_lists([small, big, small])
    data = planar_code(batch)
    assert data[0] == 7
    (again,) = read_planar_code(io.BytesIO(PLANAR_CODE_HEADER + data), "out", 10)
    assert _grains(again) == [small, big, small]
    assert _read_planar_code(planar_code(GrainBatch.from_lists([small]))) == [small]


def test_a_record_that_could_not_be_read_is_left_out_of_planar_code():
    records = planar_code(GrainBatch.from_lists([bipyramid(4)]))
    cut = PLANAR_CODE_HEADER + records + records[:-3]
    batches = list(read_planar_code(io.BytesIO(cut), "in", 10))
    assert [len(b) for b in batches] == [1, 1]
    assert list(batches[1].parse_errors) == [0]
    assert planar_code(batches[1]) == b""
    # A batch with a grain the reader could not parse (no faces) between two that it could.
    two = GrainBatch.from_lists([bipyramid(4), bipyramid(5)])
    faces = two.face_offsets
    mixed = dataclasses.replace(
        two,
        grain_id=["1", "2", "3"],
        location=np.arange(1, 4),
        face_offsets=offsets_from_counts([faces[1], 0, faces[2] - faces[1]]),
        parse_errors={1: "cut off"},
    )
    assert planar_code(mixed) == planar_code(two)
