"""Volumes, areas and normals of polytopes given as polygon loops (`grainclass.geometry`)."""

from __future__ import annotations

import numpy as np
import pytest

from grainclass.geometry import loop_arrays, polytope_measures, unit_normals

CUBE = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float)
CUBE_FACES = [[0, 1, 3, 2], [4, 6, 7, 5], [0, 4, 5, 1], [2, 3, 7, 6], [0, 2, 6, 4], [1, 5, 7, 3]]


def test_a_cube_far_from_the_origin_keeps_its_volume():
    """Relative to the cube's first corner the volume keeps its digits; relative to the origin
    the triangles' terms are about 1e18 and their sum loses them all (-121.9 for 0.125)."""
    far = 0.5 * CUBE + (1e6 + 0.1)
    volume, area = polytope_measures(far, *loop_arrays(CUBE_FACES), np.zeros(6, np.int64), 1)
    assert volume.tolist() == [0.125]
    assert area.tolist() == [1.5]


def test_polytopes_sharing_positions_and_listed_in_any_order():
    """Two cubes, one turned inside out (negative volume), their polygons interleaved, and a
    polytope without polygons."""
    positions = np.vstack([CUBE, 2 * CUBE + 5])
    loops = [face for pair in zip(CUBE_FACES, CUBE_FACES, strict=True) for face in pair]
    loops = [
        loop if k % 2 == 0 else [v + 8 for v in reversed(loop)] for k, loop in enumerate(loops)
    ]
    polytope = np.array([0, 2] * 6)
    volume, area = polytope_measures(positions, *loop_arrays(loops), polytope, 3)
    assert volume == pytest.approx([1.0, 0.0, -8.0])
    assert area == pytest.approx([6.0, 0.0, 24.0])


def test_unit_normals_point_out_of_a_cube_and_a_degenerate_polygon_has_none():
    normals = unit_normals(CUBE, *loop_arrays([*CUBE_FACES, [0, 1, 0]]))
    assert normals.tolist() == [
        [-1.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, -1.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, 0.0],
    ]
