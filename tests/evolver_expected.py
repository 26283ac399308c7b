"""Expected values for the Surface Evolver datafile reader.

``FIXTURES``: the grain-growth grain files in tests/data/evolver/grain3d/ (one body each,
triangulated faces, ``color red`` triple-line edges). ``FOAMS``: the hand-made files in
tests/data/evolver/.

Plain data, no grainclass imports: the reviewed ground truth, kept as a literal table. It is
derived from the datafiles alone by tests/evolver_derivation.py (numpy, networkx and the oracle
of tests/reference.py, NOT grainclass code; its docstring gives the method and its
cross-checks), and tests/test_evolver_expected.py checks that the derivation finds every entry,
key by key, floats to the 9 significant digits kept here. ``python tests/evolver_derivation.py
FILE...`` prints the counts the comments quote (facets, wrap marks, sides per face, truncation
trees). In all ten fixtures the body facet signs as given yield a positive volume (outward
normals): the derivation keeps the sign, and nothing is flipped.

Keys: ``n_faces``; ``p_vector`` (counts of faces with 3, 4, 5, ... sides, up to the largest; None
for degenerate grains); ``status`` ("ok" / "degenerate"); ``class`` and ``truncations`` (None for
degenerate grains); ``n_two_gons`` (degenerate grains only); ``volume``; ``area``; and the extra
cross-check counts ``n_corners`` and ``n_triple_lines``. The bodies of ``FOAMS`` have
``symmetry`` too (the order of the grain's symmetry group, as grainclass's ``symmetry``).
"""

FIXTURES = {
    # 21000-00000006.fe: 394 facets, 199 vertices, 591 edges; 126 edges carry wrap marks (in y and
    # z). 16 faces, 28 corners (3 red edges and 3 faces each), 42 triple lines: 28 - 42 + 16 = 2.
    # Sides per face: 3, 4, 4, 4, 5, 5, 5, 5, 5, 5, 5, 6, 6, 7, 7, 8. 1 reverse truncation(s) reach
    # a fundamental grain with 15 faces and no empty triangle; 1 truncation tree(s) (): flag+1.
    # Volume positive with the file's body facet signs.
    "21000-00000006.fe": {
        "n_faces": 16,
        "p_vector": (1, 3, 7, 2, 2, 1),
        "status": "ok",
        "class": "flag+1",
        "truncations": 1,
        "volume": 0.00533810358,
        "area": 0.170809902,
        "n_corners": 28,
        "n_triple_lines": 42,
    },
    # 21000-00000007.fe: 284 facets, 144 vertices, 426 edges; no wrap marks. 13 faces, 22 corners (3
    # red edges and 3 faces each), 33 triple lines: 22 - 33 + 13 = 2. Sides per face: 4, 4, 4, 5, 5,
    # 5, 5, 5, 5, 5, 6, 6, 7. No triangular face: fundamental; no empty triangle: flag. Volume
    # positive with the file's body facet signs.
    "21000-00000007.fe": {
        "n_faces": 13,
        "p_vector": (0, 3, 7, 2, 1),
        "status": "ok",
        "class": "flag",
        "truncations": 0,
        "volume": 0.00258432491,
        "area": 0.101248303,
        "n_corners": 22,
        "n_triple_lines": 33,
    },
    # 21000-00000014.fe: 418 facets, 211 vertices, 627 edges; no wrap marks. 15 faces, 26 corners (3
    # red edges and 3 faces each), 39 triple lines: 26 - 39 + 15 = 2. Sides per face: 4, 4, 4, 4, 4,
    # 4, 5, 5, 5, 6, 6, 6, 7, 7, 7. No triangular face: fundamental; no empty triangle: flag. Volume
    # positive with the file's body facet signs.
    "21000-00000014.fe": {
        "n_faces": 15,
        "p_vector": (0, 6, 3, 3, 3),
        "status": "ok",
        "class": "flag",
        "truncations": 0,
        "volume": 0.00621144777,
        "area": 0.184556932,
        "n_corners": 26,
        "n_triple_lines": 39,
    },
    # 21000-00000019.fe: 350 facets, 177 vertices, 525 edges; no wrap marks. 15 faces, 26 corners (3
    # red edges and 3 faces each), 39 triple lines: 26 - 39 + 15 = 2. Sides per face: 4, 4, 4, 4, 5,
    # 5, 5, 5, 5, 5, 6, 6, 6, 7, 7. No triangular face: fundamental; no empty triangle: flag. Volume
    # positive with the file's body facet signs.
    "21000-00000019.fe": {
        "n_faces": 15,
        "p_vector": (0, 4, 6, 3, 2),
        "status": "ok",
        "class": "flag",
        "truncations": 0,
        "volume": 0.00400544029,
        "area": 0.141655655,
        "n_corners": 26,
        "n_triple_lines": 39,
    },
    # 21000-00000023.fe: 164 facets, 84 vertices, 246 edges; 37 edges carry wrap marks (in x and z).
    # 9 faces, 14 corners (3 red edges and 3 faces each), 21 triple lines: 14 - 21 + 9 = 2. Sides
    # per face: 3, 3, 4, 4, 4, 5, 5, 7, 7. 3 reverse truncation(s) reach a fundamental grain with 6
    # faces and no empty triangle; 2 truncation tree(s) ()+(()): flag>=3. Volume positive with the
    # file's body facet signs.
    "21000-00000023.fe": {
        "n_faces": 9,
        "p_vector": (2, 3, 2, 0, 2),
        "status": "ok",
        "class": "flag>=3",
        "truncations": 3,
        "volume": 0.000254032495,
        "area": 0.0254221108,
        "n_corners": 14,
        "n_triple_lines": 21,
    },
    # 21000-00000025.fe: 224 facets, 114 vertices, 336 edges; no wrap marks. 10 faces, 16 corners (3
    # red edges and 3 faces each), 24 triple lines: 16 - 24 + 10 = 2. Sides per face: 2, 3, 3, 3, 3,
    # 4, 7, 7, 8, 8. 1 face with 2 sides (two faces share two triple lines): degenerate. Volume
    # positive with the file's body facet signs.
    "21000-00000025.fe": {
        "n_faces": 10,
        "p_vector": None,
        "status": "degenerate",
        "class": None,
        "truncations": None,
        "n_two_gons": 1,
        "volume": 0.000934736884,
        "area": 0.0572450072,
        "n_corners": 16,
        "n_triple_lines": 24,
    },
    # 21000-00000028.fe: 392 facets, 198 vertices, 588 edges; no wrap marks. 15 faces, 26 corners (3
    # red edges and 3 faces each), 39 triple lines: 26 - 39 + 15 = 2. Sides per face: 4, 4, 4, 5, 5,
    # 5, 5, 5, 5, 6, 6, 6, 6, 6, 6. No triangular face: fundamental; no empty triangle: flag. Volume
    # positive with the file's body facet signs.
    "21000-00000028.fe": {
        "n_faces": 15,
        "p_vector": (0, 3, 6, 6),
        "status": "ok",
        "class": "flag",
        "truncations": 0,
        "volume": 0.00505632362,
        "area": 0.159303778,
        "n_corners": 26,
        "n_triple_lines": 39,
    },
    # 21000-00000029.fe: 240 facets, 122 vertices, 360 edges; no wrap marks. 10 faces, 16 corners (3
    # red edges and 3 faces each), 24 triple lines: 16 - 24 + 10 = 2. Sides per face: 4, 4, 4, 4, 5,
    # 5, 5, 5, 6, 6. No triangular face: fundamental; no empty triangle: flag. Volume positive with
    # the file's body facet signs.
    "21000-00000029.fe": {
        "n_faces": 10,
        "p_vector": (0, 4, 4, 2),
        "status": "ok",
        "class": "flag",
        "truncations": 0,
        "volume": 0.00126280492,
        "area": 0.0654182288,
        "n_corners": 16,
        "n_triple_lines": 24,
    },
    # 21000-00000030.fe: 460 facets, 232 vertices, 690 edges; 98 edges carry wrap marks (in y). 17
    # faces, 30 corners (3 red edges and 3 faces each), 45 triple lines: 30 - 45 + 17 = 2. Sides per
    # face: 4, 4, 4, 4, 5, 5, 5, 5, 5, 5, 6, 6, 6, 6, 6, 6, 8. No triangular face: fundamental; no
    # empty triangle: flag. Volume positive with the file's body facet signs.
    "21000-00000030.fe": {
        "n_faces": 17,
        "p_vector": (0, 4, 6, 6, 0, 1),
        "status": "ok",
        "class": "flag",
        "truncations": 0,
        "volume": 0.00951004855,
        "area": 0.243238834,
        "n_corners": 30,
        "n_triple_lines": 45,
    },
    # 21000-00000053.fe: 86 facets, 45 vertices, 129 edges; 8 edges carry wrap marks (in x; vertices
    # 44, 45 are stored at x < 0). 5 faces, 6 corners (3 red edges and 3 faces each), 9 triple
    # lines: 6 - 9 + 5 = 2. Sides per face: 2, 3, 3, 5, 5. 1 face with 2 sides (two faces share two
    # triple lines): degenerate. Volume positive with the file's body facet signs.
    "21000-00000053.fe": {
        "n_faces": 5,
        "p_vector": None,
        "status": "degenerate",
        "class": None,
        "truncations": None,
        "n_two_gons": 1,
        "volume": 4.29914939e-05,
        "area": 0.00789146284,
        "n_corners": 6,
        "n_triple_lines": 9,
    },
}

# The truncated octahedron of edge sqrt(2) (the BCC Voronoi cell of cube side 4): 24 corners of
# 3 faces, 36 edges, 14 faces: 24 - 36 + 14 = 2; p = (0, 6, 0, 8); the dual (tetrakis
# hexahedron) has no degree-3 vertex and no empty triangle: flag. Volume 4**3 / 2 = 32, area
# 6 * 2 + 8 * (3 * sqrt(3)) = 12 + 24 sqrt(3) = 53.569219381653056. Symmetry 48: the full
# octahedral group (24 rotations, each with its mirror image).
KELVIN = {
    "n_faces": 14,
    "p_vector": (0, 6, 0, 8),
    "class": "flag",
    "truncations": 0,
    "symmetry": 48,
    "volume": 32.0,
    "area": 53.5692194,
}

# Hand-made files in tests/data/evolver/, generated from explicit geometry by a throwaway script and
# checked by the same derivation as above (foam_file_values in tests/evolver_derivation.py:
# closure, volume by the divergence theorem, area, corners, Euler characteristic, classification;
# a cell that meets its own periodic image unwrapped first, by unwrap_cell). In these files every
# polygon facet is one grain face: each lies between two bodies (two_cubes' shared square, every
# Kelvin facet; in a small periodic box the two may be one body and its image) or on the
# outside, where no two facets of a body are coplanar; kelvin_one_cell_fans.fe marks its
# faces' edges color red instead.
FOAMS = {
    # Two unit cubes sharing the facet x = 1 (facet 2: +2 in body 1, -2 in body 2). Non-torus file,
    # so no wrap marks on edges. 12 vertices, 20 edges, 11 quadrilateral facets. Per cube: 6
    # squares, 8 corners of 3 faces, 12 edges: 8 - 12 + 6 = 2; dual = octahedron, no degree-3
    # vertex, no empty triangle: flag. Volume exactly 1, area exactly 6 (outward signs).
    "two_cubes.fe": {
        "status": "ok",
        "bodies": {
            1: {
                "n_faces": 6,
                "p_vector": (0, 6),
                "class": "flag",
                "truncations": 0,
                "symmetry": 48,
                "volume": 1.0,
                "area": 6.0,
            },
            2: {
                "n_faces": 6,
                "p_vector": (0, 6),
                "class": "flag",
                "truncations": 0,
                "symmetry": 48,
                "volume": 1.0,
                "area": 6.0,
            },
        },
    },
    # Periodic Kelvin foam, periods = cube of side 8: the bcc Voronoi cells of the 16 points
    # (0,0,0) + (4i, 4j, 4k) and (2,2,2) + (4i, 4j, 4k), i, j, k in {0, 1}, each a truncated
    # octahedron (6 squares, 8 regular hexagons, edge sqrt(2)). In a box of side 8 a cell never
    # touches its own periodic image, so every facet lies between two different bodies and every
    # body has 24 corners of 3 faces, 36 edges, 14 faces: 24 - 36 + 14 = 2; p = (0, 6, 0, 8);
    # the dual (tetrakis hexahedron) has no degree-3 vertex and no empty triangle: flag.
    # Volume 32 = 8**3 / 16: the cell KELVIN above.
    "kelvin_foam.fe": {
        "status": "ok",
        "bodies": {body: KELVIN for body in range(1, 17)},
    },
    # Kelvin's foam in the smallest periodic box of its BCC lattice's cube: periods = cube of
    # side 4, the Voronoi cells of (1, 1, 1) and (3, 3, 3). 12 vertices, 24 edges, 14 facets
    # (8 hexagons, each between the two bodies, and 3 squares per body, each between the body
    # and its own image: the body lists it once each way). Each cell, unwrapped: 14 patches,
    # 24 corners, 36 edges, the same truncated octahedron as above, so the same row; the two
    # volumes, 32 each, fill the box (4**3 = 64).
    "kelvin_bcc_torus.fe": {
        "status": "ok",
        "bodies": {1: KELVIN, 2: KELVIN},
    },
    # One truncated octahedron filling a torus whose periods are the primitive vectors of the
    # same lattice, (-2, 2, 2), (2, -2, 2), (2, 2, -2) (volume |det| = 32): 6 vertices, 12
    # edges, 7 facets (4 hexagons, 3 squares), each listed once each way; every edge is a
    # triple line where three faces of the one cell meet, so the body uses it 6 times, at
    # three places. Unwrapped: the Kelvin cell above, volume 32 = the box.
    "kelvin_one_cell.fe": {
        "status": "ok",
        "bodies": {1: KELVIN},
    },
    # The cell of kelvin_one_cell.fe with each face cut into triangles around its centre
    # (13 vertices: 6 corners and 7 face centres; 48 edges: the 12 triple-line edges, marked
    # color red, and 36 spokes; 36 triangles, each listed once each way). The triangles of a
    # face join across its spokes into the 14 faces above: the same row.
    "kelvin_one_cell_fans.fe": {
        "status": "ok",
        "bodies": {1: KELVIN},
    },
    # A cube of side 2 filling the cubic torus of side 2: one vertex, three edges (one along
    # each axis, wrapping once), three facets (one per coordinate plane, each running along
    # two of the edges twice, once each way) listed once each way. Unwrapped: 6 squares, 8
    # corners, 12 edges, 8 - 12 + 6 = 2; the dual is the octahedron: flag, symmetry 48.
    # Volume 8 = the box, area 24.
    "cube_one_cell.fe": {
        "status": "ok",
        "bodies": {
            1: {
                "n_faces": 6,
                "p_vector": (0, 6),
                "class": "flag",
                "truncations": 0,
                "symmetry": 48,
                "volume": 8.0,
                "area": 24.0,
            },
        },
    },
    # Unit cube without its top facet (z = 1): 5 quadrilateral facets, outward signs. Edges 1, 7,
    # 10, 11 (the top rim) are each used by only one facet of the body: not closed -> invalid.
    "open_surface.fe": {
        "status": "invalid",
        "reason": "not closed",
        "open_edges": (1, 7, 10, 11),
    },
    # Square pyramid, base the unit square at z = 0, apex (0.5, 0.5, 1): 4 triangles + 1 square,
    # outward signs, closed: 5 - 8 + 5 = 2. The 4 base corners have 3 faces each, the apex has
    # 4 faces (dual vertex figure not a triangle) -> non_simple. Volume 1/3, area 1 + sqrt(5).
    "four_face_corner.fe": {
        "status": "non_simple",
        "reason": "corner of 4 faces",
        "n_faces": 5,
        "max_faces_at_corner": 4,
        "volume": 0.333333333,
        "area": 3.23606798,
    },
}
