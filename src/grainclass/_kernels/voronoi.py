"""Voronoi cells as grains: face adjacency, corners and areas from Voro++'s face loops.

Voro++ gives each cell's faces as loops of cell-local corner ids with the neighbouring seed
behind each face. Corner positions are not needed from it: a corner of the cell of seed s is
the centre of the sphere through s and the three seeds behind the faces that meet there.
"""

import numpy as np

from grainclass._numba import njit

# Flags per cell.
BAD_CORNER = 1  # a corner not on exactly three faces
OPEN = 2  # an edge not on exactly two faces: the loops do not close into a surface
WALL = 4  # a face on the container wall: the slab was too thin for this cell
OUTSIDE = 8  # a corner's empty sphere reaches beyond the slab's seeds: the cell may be wrong
GEOMETRY = 16  # the corners' volume disagrees with Voro++'s: the corner positions are wrong


@njit
def _toward(s, t, points, side):
    """Seed t relative to seed s, x and y at the periodic image nearest to s."""
    dx = points[t, 0] - points[s, 0]
    dy = points[t, 1] - points[s, 1]
    dx -= side * np.round(dx / side)
    dy -= side * np.round(dy / side)
    return dx, dy, points[t, 2] - points[s, 2]


@njit
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
    a wall) and has the corners ``loop_corners[loop_offsets[f]:loop_offsets[f + 1]]``.

    Writes the faces' neighbour lists in cyclic order (local face indices, CSR in
    ``nbr_offsets`` / ``neighbors``, sized like the loops), the surface area and the flags
    above. Seeds from ``z_low`` to ``z_high`` are all present (a slab; x and y periodic with
    period ``side``): a corner whose empty sphere leaves that range is flagged. ``volume`` is
    Voro++'s, to check the corners against. Neighbour lists follow
    :func:`grainclass.readers.loops.adjacency_from_loops`: consecutive edges to the same face
    count once across a corner on two faces only.
    """
    n_cells = cell_seed.shape[0]
    size = 64
    first = np.full(size * size, -1, np.int32)
    second = np.full(size * size, -1, np.int32)
    on_faces = np.zeros(size, np.int32)
    corner_faces = np.zeros((size, 3), np.int32)
    position = np.zeros((size, 3))
    edge_nbrs = np.empty(256, np.int32)
    point = np.empty(3)
    m = 0
    nbr_offsets[0] = 0
    for c in range(n_cells):
        s = cell_seed[c]
        f0, f1 = face_offsets[c], face_offsets[c + 1]
        corners = 0
        for i in range(loop_offsets[f0], loop_offsets[f1]):
            corners = max(corners, loop_corners[i] + 1)
        if corners > size:
            size = corners
            first = np.full(size * size, -1, np.int32)
            second = np.full(size * size, -1, np.int32)
            on_faces = np.zeros(size, np.int32)
            corner_faces = np.zeros((size, 3), np.int32)
            position = np.zeros((size, 3))
        flag = 0
        for f in range(f0, f1):
            if adjacent[f] < 0:
                flag |= WALL
            a, b = loop_offsets[f], loop_offsets[f + 1]
            for i in range(a, b):
                u, v = loop_corners[i], loop_corners[i + 1 if i + 1 < b else a]
                key = min(u, v) * size + max(u, v)
                if first[key] < 0:
                    first[key] = f - f0
                elif second[key] < 0:
                    second[key] = f - f0
                else:
                    flag |= OPEN
                if on_faces[u] < 3:
                    corner_faces[u, on_faces[u]] = f
                on_faces[u] += 1
        for u in range(corners):
            if on_faces[u] != 3:
                flag |= BAD_CORNER
        # Neighbours in the loops' order; edges with no second face leave the cell open.
        for f in range(f0, f1):
            a, b = loop_offsets[f], loop_offsets[f + 1]
            if b - a > edge_nbrs.shape[0]:
                edge_nbrs = np.empty(b - a, np.int32)
            for i in range(a, b):
                u, v = loop_corners[i], loop_corners[i + 1 if i + 1 < b else a]
                key = min(u, v) * size + max(u, v)
                other = second[key] if first[key] == f - f0 else first[key]
                if other < 0 or other == f - f0:
                    flag |= OPEN
                edge_nbrs[i - a] = other
            kept = 0
            for i in range(a, b):
                previous = edge_nbrs[(i - a - 1) % (b - a)]
                if edge_nbrs[i - a] != previous or on_faces[loop_corners[i]] > 2:
                    neighbors[m] = edge_nbrs[i - a]
                    m += 1
                    kept += 1
            if kept == 0:
                neighbors[m] = edge_nbrs[0]
                m += 1
            nbr_offsets[f + 1] = m
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
        for f in range(f0, f1):  # reset the tables for the next cell
            a, b = loop_offsets[f], loop_offsets[f + 1]
            for i in range(a, b):
                u, v = loop_corners[i], loop_corners[i + 1 if i + 1 < b else a]
                first[min(u, v) * size + max(u, v)] = -1
                second[min(u, v) * size + max(u, v)] = -1
                on_faces[u] = 0
