"""scripts/voxel_study.py: the label images of the resolution study, its naive rule and its
shares, each against a value worked out apart from the code (a brute-force nearest seed, a
cube of voxels, a truncated octahedron's edge, shares counted by hand)."""

from __future__ import annotations

import math
import shutil

import numpy as np
import pyarrow as pa
import pyarrow.parquet as pq
import pytest

from voxel_study import compare, naive_adjacency, shortest_edges, voxelize

# The cube's canonical Weinberg vector, as docs/definitions.md gives it.
CUBE = "(1,2,3,4,1,4,5,6,1,6,7,2,7,8,3,8,5,8,7,6,5,4,3,2,1)"


@pytest.mark.parametrize(("n_seeds", "resolution"), [(1, 4), (5, 9), (40, 14)])
def test_voxelize_labels_each_voxel_with_its_nearest_seed(n_seeds, resolution):
    xyz = np.random.default_rng(n_seeds).random((n_seeds, 3))
    image = voxelize(xyz, resolution, jobs=2)
    centres = (np.arange(resolution) + 0.5) / resolution
    z, y, x = np.meshgrid(centres, centres, centres, indexing="ij")
    offsets = np.stack([x, y, z], axis=-1)[..., None, :] - xyz
    offsets -= np.round(offsets)  # the nearest periodic image
    nearest = (offsets**2).sum(axis=-1).argmin(axis=-1) + 1
    assert image.dtype == np.uint32
    assert np.array_equal(image, nearest)


def _cube_image(block: int) -> np.ndarray:
    """3 x 3 x 3 blocks of ``block`` voxels: grain 1 the centre block, a face block on each of
    its sides (2: -x, 3: +x, 4: -y, 5: +y, 6: -z, 7: +z), and every edge or corner block taking
    the label of the x side it lies on, else the y side, so that each lattice edge of the cube
    has exactly three labels around it."""
    labels = np.zeros((3, 3, 3), dtype=np.uint32)
    for bz in range(3):
        for by in range(3):
            for bx in range(3):
                if bx != 1:
                    labels[bz, by, bx] = 2 if bx == 0 else 3
                elif by != 1:
                    labels[bz, by, bx] = 4 if by == 0 else 5
                elif bz != 1:
                    labels[bz, by, bx] = 6 if bz == 0 else 7
                else:
                    labels[bz, by, bx] = 1
    return np.repeat(np.repeat(np.repeat(labels, block, 0), block, 1), block, 2)


def test_naive_rule_reads_a_cube_of_voxels_as_a_cube(tmp_path):
    from grainclass import read_grains

    lines = naive_adjacency(_cube_image(3))
    text = tmp_path / "cube.txt"
    text.write_text("\n".join(lines) + "\n")
    grains = read_grains(str(text)).set_index("grain_id")
    assert grains.loc["1", "status"] == "ok"
    assert grains.loc["1", "n_faces"] == 6
    assert grains.loc["1", "weinberg"] == CUBE


@pytest.mark.skipif(shutil.which("voro++") is None, reason="needs the voro++ program")
def test_shortest_edge_of_the_bcc_cells_is_the_truncated_octahedrons():
    # Body-centred cubic seeds: every cell a truncated octahedron with 14 faces and every edge
    # sqrt(2)/4 of the cube's side.
    faces, shortest, neighbors = shortest_edges(np.array([[0.25, 0.25, 0.25], [0.75, 0.75, 0.75]]))
    assert list(faces) == [14, 14]
    # 8 hexagons face the other seed's images, 6 squares the seed's own.
    assert neighbors == [[1] * 6 + [2] * 8, [1] * 8 + [2] * 6]
    assert shortest == pytest.approx([math.sqrt(2) / 4] * 2, rel=1e-5)


def test_compare_counts_shares_by_hand(tmp_path):
    truth = pa.table(
        {
            "grain_id": ["1", "2", "3", "4"],
            "n_faces": pa.array([6, 6, 5, 4], pa.int32()),
            "weinberg": ["a", "b", "c", "d"],
            "shortest_edge_voxels": [0.5, 1.5, 2.5, 3.5],
        }
    )
    result = pa.table(
        {
            "grain_id": ["1", "2", "3"],  # grain 4 is missing: wrong
            "status": ["ok", "ok", "invalid"],  # 3 has the type's string but is not ok: wrong
            "n_faces": pa.array([6, 7, 5], pa.int32()),
            "weinberg": ["a", "x", "c"],
        }
    )
    pq.write_table(truth, tmp_path / "truth.parquet")
    pq.write_table(result, tmp_path / "result.parquet")
    shares = compare(tmp_path / "result.parquet", tmp_path / "truth.parquet")
    assert (shares["grains"], shares["found"], shares["ok"]) == (4, 3, 2)
    assert shares["exact_type"] == 1 / 4
    assert shares["right_n"] == 2 / 4  # grains 1 and 3
    assert (shares["edge_ge_1_grains"], shares["edge_ge_1_exact_type"]) == (3, 0.0)
    assert (shares["edge_ge_3_grains"], shares["edge_ge_3_exact_type"]) == (1, 0.0)
