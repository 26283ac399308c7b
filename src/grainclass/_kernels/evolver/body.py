"""One body to one grain: :func:`_body` runs the steps from the body's list of facets to its
faces' neighbour lists, each step a function of its own, and stops at the first that finds the
body is not a grain.

The steps pass named structures: the file's :class:`~.tables.FileTables`, the body's
:class:`~.patches.Patches` and :class:`~.patches.Darts` (``patches.py``), the
:class:`~.periodic.Corners` they make (``periodic.py``), and the faces (``faces.py``). The
grain goes into a :class:`BodyOut`, made once per file and filled again for each body.
"""

from typing import NamedTuple

import numpy as np

from grainclass._kernels.evolver.codes import GRAIN_AROUND, GRAIN_EULER, GRAIN_OK, GRAIN_PIECES
from grainclass._kernels.evolver.faces import Across, _across, _join_faces, _normals, _walk_faces
from grainclass._kernels.evolver.patches import (
    _check_closed,
    _check_patches,
    _darts,
    _patches,
    _undefined_vertex,
)
from grainclass._kernels.evolver.periodic import (
    _corners,
    _pair_ambiguous,
    _place_corners,
    _translations,
)
from grainclass._numba import njit


class BodyOut(NamedTuple):
    """A body's grain, each array long enough for twice the file's sides."""

    params: np.ndarray
    """int64[5]: the params of the body's GRAIN_ code"""
    counts: np.ndarray
    """int64[6]: faces, neighbours, corners, darts (corner uses), patches, and whether the
    grain is on the sample's boundary (1, 0, -1 unknown)"""
    nbr_counts: np.ndarray
    """int64[room]: each face's number of neighbours"""
    neighbours: np.ndarray
    """int64[room]: the neighbours, face after face"""
    position: np.ndarray
    """float64[room, 3]: each corner's position"""
    corners: np.ndarray
    """int64[room]: each patch's corners in order (rows of ``position``), patch after patch"""
    sizes: np.ndarray
    """int64[room]: each patch's number of corners"""


@njit(inline="always")
def _new_out(tables):
    room = 2 * tables.sides.start[-1] + 1
    return BodyOut(
        np.zeros(5, np.int64),
        np.zeros(6, np.int64),
        np.empty(room, np.int64),
        np.empty(room, np.int64),
        np.empty((room, 3)),
        np.empty(room, np.int64),
        np.empty(room, np.int64),
    )


@njit
def _body(j, entries, tables, geometry, scratch, out):
    """The grain of body ``j`` of a file into ``out``: returns its GRAIN_ code, with the code's
    params in ``out.params``. ``scratch`` rows stamped by another body count as empty."""
    stamp = j + 1
    params = out.params
    for k in range(5):
        params[k] = 0
    periodic = geometry.periodic
    patches = _patches(entries, tables.bodies.last[j], tables.facets.map, scratch, stamp)
    code = _check_patches(patches, periodic, tables, scratch, params)
    if code != GRAIN_OK:
        return code
    darts, body_edges, ambiguous = _darts(patches, tables.sides, scratch, stamp)
    code = _check_closed(patches, darts, body_edges, periodic, tables, params)
    if code != GRAIN_OK:
        return code
    if ambiguous:
        code = _pair_ambiguous(patches, darts, body_edges, tables, scratch, stamp, geometry, params)
        if code != GRAIN_OK:
            return code
    shift, pieces, disagrees = _translations(darts, tables.sides.edge_shift)
    if disagrees >= 0:
        params[0] = tables.edges.id[darts.edge[disagrees]]
        return GRAIN_AROUND
    n_darts = darts.patch.shape[0]
    m = patches.slot.shape[0]
    corners = _corners(darts, shift, scratch, stamp, out.corners[:n_darts])
    n_corners = corners.key.shape[0]
    euler = n_corners - n_darts // 2 + m
    if euler != 2:
        params[0] = euler
        return GRAIN_EULER
    if pieces > 1:
        return GRAIN_PIECES
    key = _place_corners(corners, tables.vertices, geometry, out.position)
    if key >= 0:
        return _undefined_vertex(key, tables, darts.edge, params)
    bodies, outside = _across(patches, j, tables.facets, scratch)
    normal = _normals(darts, corners, out.position, tables.marked)
    face, n_faces = _join_faces(darts, Across(bodies, outside, normal), tables)
    code, n_nbrs = _walk_faces(darts, corners, face, n_faces, out)
    if code != GRAIN_OK:
        return code
    boundary = -1
    if periodic:
        boundary = 0
    elif tables.bodies.last.shape[0] > 1:  # a patch shared with no other body is outside
        boundary = 0
        for o in range(m):
            if outside[o]:
                boundary = 1
    for o in range(m):
        out.sizes[o] = darts.start[o + 1] - darts.start[o]
    counts = out.counts
    counts[0], counts[1], counts[2], counts[3] = n_faces, n_nbrs, n_corners, n_darts
    counts[4], counts[5] = m, boundary
    return GRAIN_OK
