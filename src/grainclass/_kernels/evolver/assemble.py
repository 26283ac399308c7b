"""Entries to grains: :func:`_assemble` turns the entries of every file that
:func:`~.tokenize._tokenize` read (slow numbers filled in) into :class:`Grains`, one per body or
one for a file that is not read, and the :class:`Surfaces` of the grains that are.

Per file it builds the tables (``tables.py``), then each body's grain (``body.py``) into one
:class:`~.body.BodyOut`, which is copied onto the ends of the growing surfaces.
"""

from typing import NamedTuple

import numpy as np

from grainclass._kernels.evolver.body import _body, _new_out
from grainclass._kernels.evolver.codes import (
    BODY,
    ENTRY_OK,
    FACET,
    FILE_OK,
    GRAIN_BODY_LINE,
    GRAIN_FILE,
    GRAIN_NO_BODIES,
    GRAIN_OK,
)
from grainclass._kernels.evolver.periodic import Geometry
from grainclass._kernels.evolver.tables import _file_tables, _new_scratch
from grainclass._numba import njit


class Grains(NamedTuple):
    """Per grain: a body, or a file that is not read."""

    file: np.ndarray
    """int64[G]: the file, by its place in the group"""
    body: np.ndarray
    """int64[G]: the body's id (0: a file)"""
    line: np.ndarray
    """int64[G]: the body's line (1: a file)"""
    code: np.ndarray
    """int64[G]: GRAIN_OK, or why it is not a grain"""
    params: np.ndarray
    """int64[G, 5]: the code's params"""
    volume: np.ndarray
    """float64[G]: the volume the body gives (nan: none)"""
    given: np.ndarray
    """bool[G]: whether it gives one"""
    boundary: np.ndarray
    """int8[G]: on the sample's boundary: 1, 0, -1 unknown"""
    n_faces: np.ndarray
    """int64[G]: its number of faces (0 unless GRAIN_OK)"""


class Surfaces(NamedTuple):
    """The surfaces of the grains that are GRAIN_OK, one after another."""

    nbr_counts: np.ndarray
    """int64[faces]: each face's number of neighbours"""
    neighbours: np.ndarray
    """int32[neighbours]: the neighbours of each face (0-based faces of its grain)"""
    position: np.ndarray
    """float64[corners, 3]: each corner's position (x, y, z one after another as the grains
    are kept; in rows once returned)"""
    corners: np.ndarray
    """int64[darts]: each patch's corners in order (rows of ``position``)"""
    loop_sizes: np.ndarray
    """int64[patches]: each patch's number of corners"""
    loop_grain: np.ndarray
    """int64[patches]: each patch's grain"""


@njit
def _assemble(entries, files):
    """The grains of the files, and their surfaces: ``(Grains, Surfaces)``."""
    n_files = files.status.shape[0]
    cap = n_files
    for i in range(entries.kind.shape[0]):
        cap += entries.kind[i] == BODY
    grains = Grains(
        np.empty(cap, np.int64),
        np.zeros(cap, np.int64),
        np.ones(cap, np.int64),
        np.zeros(cap, np.int64),
        np.zeros((cap, 5), np.int64),
        np.full(cap, np.nan),
        np.zeros(cap, np.bool_),
        np.full(cap, -1, np.int8),
        np.zeros(cap, np.int64),
    )
    surfaces = Surfaces(
        np.empty(1024, np.int64),
        np.empty(4096, np.int32),
        np.empty(3 * 1024, np.float64),
        np.empty(4096, np.int64),
        np.empty(1024, np.int64),
        np.empty(1024, np.int64),
    )
    filled = np.zeros(5, np.int64)  # faces, neighbours, corners, darts, patches
    n_g = 0
    for f in range(n_files):
        if files.status[f] != FILE_OK:
            grains.file[n_g], grains.code[n_g] = f, GRAIN_FILE
            n_g += 1
            continue
        tables = _file_tables(entries, files.entry_start[f], files.entry_end[f])
        nb = tables.bodies.last.shape[0]
        if nb == 0:
            _no_bodies(grains, n_g, f, entries, files)
            n_g += 1
            continue
        scratch = _new_scratch(tables)
        out = _new_out(tables)
        geometry = Geometry(entries.xyz, files.periods[f], files.periodic[f])
        for j in range(nb):
            i = tables.bodies.last[j]
            grains.file[n_g], grains.body[n_g], grains.line[n_g] = f, entries.id[i], entries.line[i]
            if tables.bodies.any_bad[j]:
                grains.code[n_g] = GRAIN_BODY_LINE
                n_g += 1
                continue
            code = _body(j, entries, tables, geometry, scratch, out)
            grains.code[n_g] = code
            for k in range(5):
                grains.params[n_g, k] = out.params[k]
            if code == GRAIN_OK:
                if entries.flag[i]:
                    grains.volume[n_g], grains.given[n_g] = entries.xyz[i, 0], True
                grains.boundary[n_g] = out.counts[5]
                grains.n_faces[n_g] = out.counts[0]
                surfaces = _keep(surfaces, filled, out, n_g)
            n_g += 1
    n_f, n_nb, n_pos, n_c, n_loops = filled[0], filled[1], filled[2], filled[3], filled[4]
    return (
        Grains(
            grains.file[:n_g],
            grains.body[:n_g],
            grains.line[:n_g],
            grains.code[:n_g],
            grains.params[:n_g],
            grains.volume[:n_g],
            grains.given[:n_g],
            grains.boundary[:n_g],
            grains.n_faces[:n_g],
        ),
        Surfaces(
            surfaces.nbr_counts[:n_f],
            surfaces.neighbours[:n_nb],
            surfaces.position[: 3 * n_pos].reshape((n_pos, 3)),
            surfaces.corners[:n_c],
            surfaces.loop_sizes[:n_loops],
            surfaces.loop_grain[:n_loops],
        ),
    )


@njit(inline="always")
def _no_bodies(grains, g, f, entries, files):
    """Grain ``g``: file ``f``, which has no bodies, with what the reader's message needs: the
    line of its facets section (a film) and its first unreadable entry."""
    grains.file[g], grains.code[g] = f, GRAIN_NO_BODIES
    grains.params[g, 1] = -1
    for i in range(files.entry_start[f], files.entry_end[f]):
        if entries.kind[i] == FACET:
            grains.params[g, 0] = max(files.facets_line[f], 1)  # a film: facets, no bodies
        if entries.status[i] != ENTRY_OK and grains.params[g, 1] < 0:
            grains.params[g, 1], grains.params[g, 2] = entries.kind[i], entries.line[i]


@njit(inline="always")
def _keep(surfaces, filled, out, g):
    """``surfaces`` with grain ``g``'s from ``out`` after the ``filled`` ones (grown as
    needed); ``filled`` counts them in."""
    counts = out.counts
    faces, nbrs, points, uses, patches = counts[0], counts[1], counts[2], counts[3], counts[4]
    n_f, n_nb, n_pos, n_c, n_loops = filled[0], filled[1], filled[2], filled[3], filled[4]
    nbr_counts = _reserve(surfaces.nbr_counts, n_f + faces)
    for k in range(faces):
        nbr_counts[n_f + k] = out.nbr_counts[k]
    neighbours = _reserve(surfaces.neighbours, n_nb + nbrs)
    for k in range(nbrs):
        neighbours[n_nb + k] = out.neighbours[k]
    position = _reserve(surfaces.position, 3 * (n_pos + points))
    for k in range(points):
        for x in range(3):
            position[3 * (n_pos + k) + x] = out.position[k, x]
    corners = _reserve(surfaces.corners, n_c + uses)
    for k in range(uses):
        corners[n_c + k] = out.corners[k] + n_pos
    loop_sizes = _reserve(surfaces.loop_sizes, n_loops + patches)
    loop_grain = _reserve(surfaces.loop_grain, n_loops + patches)
    for k in range(patches):
        loop_sizes[n_loops + k] = out.sizes[k]
        loop_grain[n_loops + k] = g
    for k in range(5):
        filled[k] += out.counts[k]
    return Surfaces(nbr_counts, neighbours, position, corners, loop_sizes, loop_grain)


@njit
def _reserve(a, need):
    """``a``, or a copy twice as long, so that it holds ``need`` items."""
    if a.shape[0] >= need:
        return a
    b = np.empty(max(need, 2 * a.shape[0]), a.dtype)
    for i in range(a.shape[0]):
        b[i] = a[i]
    return b
