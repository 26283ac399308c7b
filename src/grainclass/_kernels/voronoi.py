"""Voronoi cells as grains: face adjacency, corners and areas from Voro++'s face loops.

Voro++ gives each cell's faces as loops of cell-local corner ids with the neighbouring seed
behind each face. Corner positions are not needed from it: a corner of the cell of seed s is
the centre of the sphere through s and the three seeds behind the faces that meet there.
"""

import numpy as np

from grainclass._kernels.loops import OPEN, _clear, _grain_adjacency, _tables
from grainclass._numba import njit, njit_leaf

# Flags per cell, besides loops.BAD_CORNER and loops.OPEN.
WALL = 4  # a face on the container wall: the slab was too thin for this cell
OUTSIDE = 8  # a corner's empty sphere reaches beyond the slab's seeds: the cell may be wrong
GEOMETRY = 16  # the corners' volume disagrees with Voro++'s: the corner positions are wrong


@njit_leaf
def _toward(s, t, points, side):
    """Seed t relative to seed s, x and y at the periodic image nearest to s."""
    dx = points[t, 0] - points[s, 0]
    dy = points[t, 1] - points[s, 1]
    dx -= side * np.round(dx / side)
    dy -= side * np.round(dy / side)
    return dx, dy, points[t, 2] - points[s, 2]


@njit_leaf
def _corner(s, t1, t2, t3, points, side, out):
    """The point equidistant from seeds s, t1, t2, t3, relative to s, in ``out``: it solves
    d_i . x = |d_i|^2 / 2 for the three d_i = t_i - s, so x = sum r_i (d_j x d_k) / det.
    False if the seeds are coplanar."""
    ax, ay, az = _toward(s, t1, points, side)
    bx, by, bz = _toward(s, t2, points, side)
    cx, cy, cz = _toward(s, t3, points, side)
    ra = 0.5 * (ax * ax + ay * ay + az * az)
    rb = 0.5 * (bx * bx + by * by + bz * bz)
    rc = 0.5 * (cx * cx + cy * cy + cz * cz)
    bc = (by * cz - bz * cy, bz * cx - bx * cz, bx * cy - by * cx)
    ca = (cy * az - cz * ay, cz * ax - cx * az, cx * ay - cy * ax)
    ab = (ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx)
    det = ax * bc[0] + ay * bc[1] + az * bc[2]
    if det == 0.0:
        return False
    for k in range(3):
        out[k] = (ra * bc[k] + rb * ca[k] + rc * ab[k]) / det
    return True


@njit
def _voronoi_grains(
    cell_seed,
    face_offsets,
    adjacent,
    loop_offsets,
    loop_corners,
    points,
    side,
    z_low,
    z_high,
    volume,
    nbr_offsets,
    neighbors,
    area,
    flags,
):
    """Grain c (the cell of seed ``cell_seed[c]``, a row of ``points``) has faces
    ``face_offsets[c]:face_offsets[c + 1]``; face f lies against seed ``adjacent[f]`` (negative:
    a wall) and has the corners ``loop_corners[loop_offsets[f]:loop_offsets[f + 1]]`` (numbered
    from 0 in each cell, as Voro++ does).

    Writes the faces' neighbour lists in cyclic order (``loops._grain_adjacency``: local face
    indices, CSR in ``nbr_offsets`` / ``neighbors``, sized like the loops), the surface area and
    the flags above. Seeds from ``z_low`` to ``z_high`` are all present (a slab; x and y
    periodic with period ``side``): a corner whose empty sphere leaves that range is flagged.
    ``volume`` is Voro++'s, to check the corners against.
    """
    size = 64
    tables = _tables(size)
    position = np.zeros((size, 3))
    point = np.empty(3)
    bad = np.empty(3, np.int64)
    m = 0
    nbr_offsets[0] = 0
    for c in range(cell_seed.shape[0]):
        s = cell_seed[c]
        f0, f1 = face_offsets[c], face_offsets[c + 1]
        corners = 0
        for i in range(loop_offsets[f0], loop_offsets[f1]):
            corners = max(corners, loop_corners[i] + 1)
        if corners > size:
            size = corners
            tables = _tables(size)
            position = np.zeros((size, 3))
        m, flag = _grain_adjacency(
            f0, f1, loop_offsets, loop_corners, size, tables, nbr_offsets, neighbors, m, bad
        )
        corner_faces, on_faces = tables[3], tables[4]
        for f in range(f0, f1):
            if adjacent[f] < 0:
                flag |= WALL
        # Corners from the seeds behind their faces; then area, volume and the slab check.
        if flag & (WALL | OPEN) == 0:
            for u in range(corners):
                if on_faces[u] < 3 or not _corner(
                    s,
                    adjacent[corner_faces[u, 0]],
                    adjacent[corner_faces[u, 1]],
                    adjacent[corner_faces[u, 2]],
                    points,
                    side,
                    point,
                ):
                    flag |= GEOMETRY
                    continue
                radius = np.sqrt(point[0] ** 2 + point[1] ** 2 + point[2] ** 2)
                z = points[s, 2] + point[2]
                if z - radius < z_low or z + radius > z_high:
                    flag |= OUTSIDE
                position[u] = point
            total_area = 0.0
            total_volume = 0.0
            for f in range(f0, f1):
                a, b = loop_offsets[f], loop_offsets[f + 1]
                p = position[loop_corners[a]]
                for i in range(a + 1, b - 1):
                    q, r = position[loop_corners[i]], position[loop_corners[i + 1]]
                    cx = (q[1] - p[1]) * (r[2] - p[2]) - (q[2] - p[2]) * (r[1] - p[1])
                    cy = (q[2] - p[2]) * (r[0] - p[0]) - (q[0] - p[0]) * (r[2] - p[2])
                    cz = (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])
                    total_area += 0.5 * np.sqrt(cx * cx + cy * cy + cz * cz)
                    total_volume += (p[0] * cx + p[1] * cy + p[2] * cz) / 6.0
            area[c] = total_area
            if abs(abs(total_volume) - volume[c]) > 1e-9 * volume[c]:
                flag |= GEOMETRY
        else:
            area[c] = np.nan
        flags[c] = flag
        _clear(f0, f1, loop_offsets, loop_corners, size, tables)
