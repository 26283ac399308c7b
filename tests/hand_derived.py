"""Hand-derived expected classification values for the grains in examples/polytopes.txt.

Derived by hand from the definitions in Lutz, Mason, Lazar, MacPherson, "Roundness of grains in
cellular microstructures" (sections 2-3 and the appendix "Algorithmic Aspects"), NOT by running
grainclass. Work in the dual triangulation T: one vertex per face, the degree of a vertex is the
number of edges of that face.

* Reverse truncation = delete a degree-3 vertex of T (collapse a triangular face); stop at the
  tetrahedron (stacked, n-4 truncations) or when no degree-3 vertex is left (fundamental).
* A fundamental grain other than the tetrahedron is flag if T has no empty triangle (3-cycle that
  is not a face), sc otherwise.
* A 4-belt = chordless (induced) 4-cycle of T. In a triangulated sphere both sides of a chordless
  4-cycle contain >= 1 vertex (a side without vertices would need a chord), so every 4-belt has a
  type k:m with 1 <= k <= m, k + m = n - 4. Split type = largest k; 0:(n-4) if there is no 4-belt.
* Penalty P = n * sum over 4-belts of k * (n - k - 4).
* trees: a tree is "(" + sorted children + ")", forest sorted by (length, string) joined by "+";
  "" for a fundamental grain, None for stacked. depth = longest root path in nodes.

Split/belt/penalty entries are given only for class ``flag`` (None otherwise).
"""

EXPECTED = {
    # Tetrahedron: T = K4, 4 triangles. It is the end point of reverse truncation itself:
    # stacked, 0 = n - 4 truncations, round_k 0. Fundamental polytope = itself (4 faces).
    "tetrahedron": {
        "n_faces": 4,
        "p_vector": (4,),
        "family": "stacked",
        "class": "stacked",
        "truncations": 0,
        "fundamental_faces": 4,
        "trees": None,
        "depth": None,
        "round_k": 0,
        "split_k": None,
        "split_m": None,
        "belts4": None,
        "penalty": None,
    },
    # Triangular prism: 2 triangles + 3 rectangles. T = triangular bipyramid (degrees 3,3,4,4,4).
    # Deleting one apex (degree 3) leaves K4 = tetrahedron: stacked, 1 = n - 4 truncation.
    "triangular_prism": {
        "n_faces": 5,
        "p_vector": (2, 3),
        "family": "stacked",
        "class": "stacked",
        "truncations": 1,
        "fundamental_faces": 4,
        "trees": None,
        "depth": None,
        "round_k": 1,
        "split_k": None,
        "split_m": None,
        "belts4": None,
        "penalty": None,
    },
    # Cube: 6 squares, T = octahedron (all degrees 4 -> fundamental, not the tetrahedron).
    # 3-cliques of the octahedron are exactly its 8 faces -> no empty triangle -> flag.
    # 4-belts: 4 of the 6 vertices. Leaving out an antipodal pair gives an equator (chordless
    # 4-cycle, one pole on each side: 1:1); leaving out an adjacent pair leaves K4 minus an edge
    # (has chords). So 3 belts (the 3 equators = rings of 4 squares), all 1:1.
    # split 1:1; P = 6 * 3 * 1 * (6 - 1 - 4) = 18.
    "cube": {
        "n_faces": 6,
        "p_vector": (0, 6),
        "family": "flag",
        "class": "flag",
        "truncations": 0,
        "fundamental_faces": 6,
        "trees": "",
        "depth": 0,
        "round_k": 0,
        "split_k": 1,
        "split_m": 1,
        "belts4": 3,
        "penalty": 18,
    },
    # Pentagonal prism: 5 squares + 2 pentagons. T = pentagonal bipyramid: apexes N, S (degree 5),
    # equator C5 (degree 4) -> no degree-3 vertex, fundamental. Triangles: an apex with two
    # consecutive equator vertices (faces); C5 has no triangle; N, S not adjacent -> flag.
    # Chordless 4-cycles: C5 has no 4-cycle; N-e_i-e_{i+1}-e_{i+2} has the chord N-e_{i+1};
    # N-e_i-S-e_j is chordless iff e_i, e_j are non-adjacent on C5: 5 such pairs. Each separates
    # the remaining 3 equator vertices into 1 and 2 -> 5 belts of type 1:2 (pentagon, square,
    # pentagon, non-adjacent square). split 1:2; P = 7 * 5 * 1 * (7 - 1 - 4) = 70.
    "pentagonal_prism": {
        "n_faces": 7,
        "p_vector": (0, 5, 2),
        "family": "flag",
        "class": "flag",
        "truncations": 0,
        "fundamental_faces": 7,
        "trees": "",
        "depth": 0,
        "round_k": 0,
        "split_k": 1,
        "split_m": 2,
        "belts4": 5,
        "penalty": 70,
    },
    # Dodecahedron: 12 pentagons, T = icosahedron (all degrees 5) -> fundamental. Its 3-cliques
    # are its 20 faces (the link of every vertex is an induced 5-cycle) -> flag.
    # 4-belts: a chordless 4-cycle a-b-c-d needs a, c at distance 2 with two NON-adjacent common
    # neighbours; in the icosahedron two vertices at distance 2 have exactly 2 common neighbours
    # and they are adjacent (consecutive on the link pentagon of a); antipodes have none.
    # -> no 4-belt, split 0:8 (the paper: the dodecahedron is THE 0:8 flag grain), P = 0.
    "dodecahedron": {
        "n_faces": 12,
        "p_vector": (0, 0, 12),
        "family": "flag",
        "class": "flag",
        "truncations": 0,
        "fundamental_faces": 12,
        "trees": "",
        "depth": 0,
        "round_k": 0,
        "split_k": 0,
        "split_m": 8,
        "belts4": 0,
        "penalty": 0,
    },
    # Kelvin cell (truncated octahedron): 6 squares + 8 hexagons. T = tetrakis hexahedron: the 8
    # hexagons are the cube vertices (degree 6: 3 cube edges + 3 apexes), the 6 squares are the
    # pyramid apexes over the cube faces (degree 4); edges 12 + 24 = 36 = 3*14 - 6.
    # No degree 3 -> fundamental. Triangles: the cube graph is bipartite (triangle-free) and
    # apexes are pairwise non-adjacent, so a triangle is an apex plus a cube edge of its face =
    # a face of T -> no empty triangle -> flag.
    # Chordless 4-cycles, by number of apexes (apexes cannot be consecutive: 0, 1 or 2 of them):
    #  0 apexes: 4-cycles of the cube graph Q3 = its 6 square faces; the diagonals are not edges
    #    of T and the apex is not in the set, so each is chordless. It separates its apex (the
    #    square) from the other 9 vertices: the ring of 4 hexagons around a square, type 1:9.
    #  1 apex a: a-u-w-v with u, v on a's cube face; u-v a cube edge is impossible (w would close
    #    a triangle in Q3), so u, v are diagonal, and their common cube neighbours are the other
    #    two corners of the same face, which are adjacent to a -> chord a-w. None.
    #  2 apexes a, b: a-u-b-v with u, v in both cube faces; opposite faces share nothing,
    #    adjacent faces share one cube edge, so u-v is a chord. None.
    # -> 6 belts, all 1:9; split 1:9; P = 14 * 6 * 1 * (14 - 1 - 4) = 14 * 6 * 9 = 756.
    "kelvin": {
        "n_faces": 14,
        "p_vector": (0, 6, 0, 8),
        "family": "flag",
        "class": "flag",
        "truncations": 0,
        "fundamental_faces": 14,
        "trees": "",
        "depth": 0,
        "round_k": 0,
        "split_k": 1,
        "split_m": 9,
        "belts4": 6,
        "penalty": 756,
    },
    # Weaire-Phelan pentagonal dodecahedron: combinatorially the dodecahedron (different labels
    # in the example file), so exactly the same values: flag, no 4-belt, 0:8, P = 0.
    "weaire_phelan_12": {
        "n_faces": 12,
        "p_vector": (0, 0, 12),
        "family": "flag",
        "class": "flag",
        "truncations": 0,
        "fundamental_faces": 12,
        "trees": "",
        "depth": 0,
        "round_k": 0,
        "split_k": 0,
        "split_m": 8,
        "belts4": 0,
        "penalty": 0,
    },
    # Weaire-Phelan 14-hedron: 12 pentagons + 2 non-adjacent hexagons. T = bicapped hexagonal
    # antiprism: poles N, S (degree 6), rings t_0..t_5 and b_0..b_5 (degree 5: 2 ring neighbours,
    # 2 in the other ring, 1 pole). Fundamental. Triangles: pole + consecutive ring pair, or the
    # antiprism triangles t_i t_{i+1} b_i / b_i b_{i+1} t_{i+1} -- all faces; the 6-cycles and
    # N, S (non-adjacent, no common neighbour) give no others -> flag.
    # Chordless 4-cycles: through N: N-t_i-x-t_j with t_i, t_j non-adjacent; a common neighbour
    # x in the t-ring is t between them (chord N-x), a b_k sees only adjacent t's -> none (same
    # for S; N-x-S-y impossible). Inside the band: ordering t_0 b_0 t_1 b_1 ... as z_0..z_11, the
    # band graph is C12 squared (z_k ~ z_{k+1}, z_{k+2}); a 4-cycle spans an arc of < 12, and its
    # first vertex z on that arc has both cycle neighbours in {z+1, z+2}, which are adjacent ->
    # chord. So no 4-belt: split 0:10 (as the paper says for the WP 14-hedron), P = 0.
    "weaire_phelan_14": {
        "n_faces": 14,
        "p_vector": (0, 0, 12, 2),
        "family": "flag",
        "class": "flag",
        "truncations": 0,
        "fundamental_faces": 14,
        "trees": "",
        "depth": 0,
        "round_k": 0,
        "split_k": 0,
        "split_m": 10,
        "belts4": 0,
        "penalty": 0,
    },
    # Cube with one corner truncated: new triangle; the 3 faces at that corner become pentagons,
    # the other 3 stay squares -> p = (1, 3, 3), n = 7. Collapsing the triangle (the only
    # degree-3 vertex of T) gives the octahedron (all degrees 4): 1 truncation from the cube
    # (flag, 6 faces). Forest = one single-node tree "()", depth 1, class flag+1, round_k 1.
    "cube_truncated_1": {
        "n_faces": 7,
        "p_vector": (1, 3, 3),
        "family": "flag",
        "class": "flag+1",
        "truncations": 1,
        "fundamental_faces": 6,
        "trees": "()",
        "depth": 1,
        "round_k": 1,
        "split_k": None,
        "split_m": None,
        "belts4": None,
        "penalty": None,
    },
    # Cube with both ends of one edge truncated: the 2 faces containing that edge each lose 2
    # corners -> hexagons; the 2 faces at the ends contain one corner each -> pentagons; the 2
    # remaining faces stay squares; 2 triangles -> p = (2, 2, 2, 2), n = 8 (check: sum of
    # degrees 6+8+10+12 = 36 = 2*(3*8-6)). The two triangles do not touch (the shortened edge
    # separates them), so each is a degree-3 vertex of T whose link avoids the other; collapse
    # both -> cube. Two separate single-node trees: "()+()", depth 1, flag+1+1, round_k 2.
    "cube_truncated_2_adjacent": {
        "n_faces": 8,
        "p_vector": (2, 2, 2, 2),
        "family": "flag",
        "class": "flag+1+1",
        "truncations": 2,
        "fundamental_faces": 6,
        "trees": "()+()",
        "depth": 1,
        "round_k": 2,
        "split_k": None,
        "split_m": None,
        "belts4": None,
        "penalty": None,
    },
    # Cube with two antipodal corners truncated: every cube face contains exactly one of the
    # two corners -> 6 pentagons + 2 triangles, p = (2, 0, 6), n = 8. Triangles are far apart;
    # collapse both -> cube: "()+()", depth 1, flag+1+1, round_k 2.
    "cube_truncated_2_opposite": {
        "n_faces": 8,
        "p_vector": (2, 0, 6),
        "family": "flag",
        "class": "flag+1+1",
        "truncations": 2,
        "fundamental_faces": 6,
        "trees": "()+()",
        "depth": 1,
        "round_k": 2,
        "split_k": None,
        "split_m": None,
        "belts4": None,
        "penalty": None,
    },
    # Truncate a cube corner (triangle T1; its 3 faces -> pentagons), then truncate one of T1's
    # corners (new triangle T2): T1 -> 4-gon, the two faces at that corner -> hexagons, so
    # p = (1, 4, 1, 2): T2 (3); T1 + 3 far squares (4); one pentagon; two hexagons. n = 8.
    # Reverse: only T2 has degree 3; collapsing it makes T1 a triangle again; collapsing T1
    # gives the cube. The second truncation cut a vertex created by the first, so one tree,
    # root with one child: "(())", depth 2, class flag+2, round_k 2.
    "cube_truncated_twice_one_corner": {
        "n_faces": 8,
        "p_vector": (1, 4, 1, 2),
        "family": "flag",
        "class": "flag+2",
        "truncations": 2,
        "fundamental_faces": 6,
        "trees": "(())",
        "depth": 2,
        "round_k": 2,
        "split_k": None,
        "split_m": None,
        "belts4": None,
        "penalty": None,
    },
    # Smallest severely constricted grain: T = two octahedra glued along a face abc (abc is then
    # no longer a face). a, b, c have 2 + 2 + 2 = 6 neighbours (hexagons); the 3 + 3 other
    # vertices keep degree 4 (squares): p = (0, 6, 0, 3), n = 9. No degree-3 vertex ->
    # fundamental, 0 truncations. abc is a 3-cycle that is not a face (it separates the two
    # triples) -> empty triangle -> sc (the non-trivial 3-belt a, b, c). Class sc, trees "",
    # depth 0, round_k None (sc is not k-round for any k).
    "smallest_sc": {
        "n_faces": 9,
        "p_vector": (0, 6, 0, 3),
        "family": "sc",
        "class": "sc",
        "truncations": 0,
        "fundamental_faces": 9,
        "trees": "",
        "depth": 0,
        "round_k": None,
        "split_k": None,
        "split_m": None,
        "belts4": None,
        "penalty": None,
    },
}
